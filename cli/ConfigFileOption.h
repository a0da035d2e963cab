// --config FILE: a command's options read from an INI/TOML file by CLI11's reader; the command line wins.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// Adds --config FILE to a command; `path` stays empty when it is not given.
void addConfigFileOption(CLI::App& command, std::string& path);

/// Gives every option of `command` that the command line left out its value from the file at `path`:
/// top-level `key = value` lines, the keys being the options' long names without "--" (TOML arrays or
/// repeated keys for repeatable options, true/false for flags). Throws one-line InputError (exit 2) for
/// an unreadable file, a malformed line, an unknown or repeated key, a value the option refuses, or an
/// option left without the one it needs.
void applyConfigFile(CLI::App& command, const std::string& path);

} // namespace vots::cli
