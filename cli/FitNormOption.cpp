// The --fit-norm option shared by `fit` and `render`.
#include "FitNormOption.h"

#include "vots/fit/Fitter.h"

#include <CLI/CLI.hpp>

namespace vots::cli {

void addFitNormOption(CLI::App& command, std::string& norm) {
    command
        .add_option("--fit-norm", norm,
                    "minimax: a box is kept when some polynomial of the degree is within eps there (fewer, "
                    "larger Vots); lsq: only when the least-squares one is (the paper's method). Either way "
                    "the stored coefficients are certified the same way")
        ->check(CLI::IsMember(fit::acceptedNames<fit::FitNorm>()))
        ->capture_default_str();
}

} // namespace vots::cli
