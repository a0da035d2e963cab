// The --fit-norm option of `fit` and `render`: which polynomial a box is accepted with (docs/DESIGN.md §3).
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// Adds --fit-norm lsq|minimax to a command; `norm` holds the command's default until given.
void addFitNormOption(CLI::App& command, std::string& norm);

} // namespace vots::cli
