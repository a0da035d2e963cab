// --config FILE: CLI11's INI/TOML reader fills the options the command line did not give.
#include "ConfigFileOption.h"

#include "vots/fit/Error.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vots::cli {
namespace {

std::vector<CLI::ConfigItem> readItems(const CLI::ConfigBase& reader, const std::string& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error))
        throw fit::InputError("cannot read the configuration file " + path + ": it is a folder");
    std::ifstream in(path);
    if (!in)
        throw fit::InputError("cannot read the configuration file " + path + ": " + std::strerror(errno));
    std::stringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw fit::InputError("cannot read the configuration file " + path + ": " + std::strerror(errno));
    try {
        return reader.from_config(text);
    } catch (const CLI::Error& e) {
        throw fit::InputError("configuration file " + path + ": " + e.what());
    }
}

/// "vots serve": the command as typed.
std::string commandPath(const CLI::App& command) {
    const CLI::App* parent = command.get_parent();
    return parent ? commandPath(*parent) + " " + command.get_name() : command.get_name();
}

/// The option a key names, or InputError: only the command's own long options, never --config itself.
CLI::Option* optionOf(CLI::App& command, const CLI::ConfigItem& item, const std::string& path) {
    if (!item.parents.empty())
        throw fit::InputError("configuration file " + path + ": sections are not read ('" + item.fullname() +
                              "'): give the options as top-level keys");
    CLI::Option* option = command.get_option_no_throw("--" + item.name);
    if (!option || !option->get_configurable() || option == command.get_help_ptr())
        throw fit::InputError("configuration file " + path + ": unknown key '" + item.name +
                              "' (the keys are `" + commandPath(command) + "` options without their --)");
    return option;
}

} // namespace

void addConfigFileOption(CLI::App& command, std::string& path) {
    command
        .add_option("--config", path,
                    "INI/TOML file of options as `key = value` (the long names without --, e.g. "
                    "tls-cert = /etc/vots/cert.pem; true/false for flags, [\"a\", \"b\"] for repeatable "
                    "ones); the command line overrides it")
        ->configurable(false);
}

void applyConfigFile(CLI::App& command, const std::string& path) {
    const CLI::ConfigTOML reader; // reads INI files too (`key=value`, ';' comments)
    std::vector<CLI::Option*> filled;
    for (const CLI::ConfigItem& item : readItems(reader, path)) {
        if (item.name == "++" || item.name == "--") continue; // a section's bounds, refused with its keys
        CLI::Option* option = optionOf(command, item, path);
        const bool fromFile = std::find(filled.begin(), filled.end(), option) != filled.end();
        if (option->count() > 0 && !fromFile) continue; // given on the command line
        // CLI11's reader joins a repeated key's values into one item, as it does an array's.
        const bool single = option->get_items_expected_max() <= 1;
        if (single && (fromFile || item.inputs.size() > 1))
            throw fit::InputError("configuration file " + path + ": key '" + item.name +
                                  "' takes one value and has several (given twice, or an array)");
        try {
            if (option->get_expected_min() == 0)
                option->add_result(option->get_flag_value(item.name, reader.to_flag(item)));
            else
                option->add_result(item.inputs);
        } catch (const CLI::Error& e) {
            throw fit::InputError("configuration file " + path + ": " + e.what());
        }
        if (!fromFile) filled.push_back(option);
    }
    for (CLI::Option* option : filled) {
        try {
            option->run_callback(); // checks the value as on the command line, then stores it
        } catch (const CLI::Error& e) {
            throw fit::InputError("configuration file " + path + ": " + e.what());
        }
    }
    // CLI11 checked --x's needs before the file was read.
    for (const CLI::Option* option : command.get_options())
        for (const CLI::Option* needed : option->get_needs())
            if (option->count() > 0 && needed->count() == 0)
                throw fit::InputError(option->get_name() + " needs " + needed->get_name() +
                                      " (on the command line or in " + path + ")");
}

} // namespace vots::cli
