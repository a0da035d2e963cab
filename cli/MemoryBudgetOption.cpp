// The --memory-budget option shared by `fit`, `render` and `serve`; the header-only check before loading.
#include "MemoryBudgetOption.h"

#include "vots/fit/Error.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumePlanes.h"

#include <CLI/CLI.hpp>

#include <algorithm>

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

namespace {

// `header`: what will be held (the whole volume, or one rank's planes). Empty when it fits.
std::string budgetRefusal(const std::string& path, const fit::VolumeHeaderInfo& header,
                          const std::string& budgetText, fit::SampleStorage storage) {
    const std::uint64_t budget = resolveMemoryBudget(budgetText);
    const std::uint64_t needed = fit::estimateLoadAndFitBytes(header, storage);
    const std::uint64_t held = fit::residentBytes();
    const std::uint64_t left = budget > held ? budget - held : 0;
    if (needed <= left) return {};
    return path + ": " + header.describe() + " needs about " + fit::formatBytes(needed) +
           " of memory to load and fit, more than the memory budget of " + fit::formatBytes(budget) +
           (budgetText.empty() ? " (the default)" : "") + " leaves (" + fit::formatBytes(left) +
           "); give a larger --memory-budget or use a smaller volume";
}

} // namespace

void checkHeaderFitsBudget(const std::string& name, const fit::VolumeHeaderInfo& header,
                           const std::string& budgetText, fit::SampleStorage storage) {
    const std::string refusal = budgetRefusal(name, header, budgetText, storage);
    if (!refusal.empty()) throw fit::InputError(refusal);
}

void checkVolumeFitsBudget(const std::string& path, const std::optional<fit::RawLayout>& raw,
                           const std::string& budgetText, const std::string& dicomSeries,
                           fit::SampleStorage storage) {
    checkHeaderFitsBudget(path, fit::volumeHeaderInfo(path, raw, dicomSeries), budgetText, storage);
}

std::string planesBudgetRefusal(const std::string& path, const std::optional<fit::RawLayout>& raw,
                                const std::string& budgetText, const std::string& dicomSeries,
                                std::uint64_t planes, fit::SampleStorage storage) {
    fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(path, raw, dicomSeries);
    // Otherwise the whole is loaded before its planes are cut: its estimate stays, an upper bound.
    if (fit::readsOnlyPlanes(path, raw)) header.dims[2] = std::min(header.dims[2], planes);
    return budgetRefusal(path, header, budgetText, storage);
}

void checkPlanesFitBudget(const std::string& path, const std::optional<fit::RawLayout>& raw,
                          const std::string& budgetText, const std::string& dicomSeries, std::uint64_t planes,
                          fit::SampleStorage storage) {
    const std::string refusal = planesBudgetRefusal(path, raw, budgetText, dicomSeries, planes, storage);
    if (!refusal.empty()) throw fit::InputError(refusal);
}

} // namespace vots::cli
