// The --memory-budget option shared by `fit`, `render` and `serve`; the header-only check before loading.
#include "MemoryBudgetOption.h"

#include "vots/fit/Error.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"

#include <CLI/CLI.hpp>

namespace vots::cli {

void addMemoryBudgetOption(CLI::App& command, std::string& text) {
    command.add_option(
        "--memory-budget", text,
        "Most memory to use, e.g. 8G, 512M or bytes; a volume whose load and fit would need more "
        "(estimated from its header) is refused before it is read. Default: 80 % of the memory "
        "available at start (MemAvailable, or the cgroup's headroom)");
}

std::uint64_t resolveMemoryBudget(const std::string& text) {
    return text.empty() ? fit::defaultMemoryBudget() : fit::parseMemorySize(text, "--memory-budget");
}

void checkVolumeFitsBudget(const std::string& path, const std::optional<fit::RawLayout>& raw,
                           const std::string& budgetText, const std::string& dicomSeries) {
    const std::uint64_t budget = resolveMemoryBudget(budgetText);
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(path, raw, dicomSeries);
    const std::uint64_t needed = fit::estimateLoadAndFitBytes(header);
    const std::uint64_t held = fit::residentBytes();
    const std::uint64_t left = budget > held ? budget - held : 0;
    if (needed <= left) return;
    throw fit::InputError(path + ": " + header.describe() + " needs about " + fit::formatBytes(needed) +
                          " of memory to load and fit, more than the memory budget of " +
                          fit::formatBytes(budget) + (budgetText.empty() ? " (the default)" : "") +
                          " leaves (" + fit::formatBytes(left) +
                          "); give a larger --memory-budget or use a smaller volume");
}

} // namespace vots::cli
