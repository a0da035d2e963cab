// The --memory-budget option of `fit`, `render` and `serve`, and the check a load makes against it.
#pragma once

#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include <cstdint>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// Adds --memory-budget SIZE to a command; `text` stays empty when it is not given.
void addMemoryBudgetOption(CLI::App& command, std::string& text);

/// The budget in bytes: the option's value, or fit::defaultMemoryBudget() when it is empty.
/// Throws InputError for a malformed size.
std::uint64_t resolveMemoryBudget(const std::string& text);

/// Throws one-line InputError (exit 2) when loading a volume of this announced `header` (named `name` in
/// the message) with `storage` and fitting it would need more than the budget leaves; for inputs whose
/// header comes from elsewhere than a file (a PACS series' metadata).
void checkHeaderFitsBudget(const std::string& name, const fit::VolumeHeaderInfo& header,
                           const std::string& budgetText,
                           fit::SampleStorage storage = fit::SampleStorage::Float);

/// Reads only the volume's header and throws one-line InputError (exit 2) when loading it with
/// `storage` and fitting it would need more than the budget leaves after what this process holds:
/// checked before any of the samples are read, so a header announcing a huge volume costs nothing.
void checkVolumeFitsBudget(const std::string& path, const std::optional<fit::RawLayout>& raw,
                           const std::string& budgetText, const std::string& dicomSeries = {},
                           fit::SampleStorage storage = fit::SampleStorage::Float);

/// The refusal checkPlanesFitBudget would throw, or empty when the planes fit; throws InputError for a
/// malformed header or budget.
std::string planesBudgetRefusal(const std::string& path, const std::optional<fit::RawLayout>& raw,
                                const std::string& budgetText, const std::string& dicomSeries,
                                std::uint64_t planes, fit::SampleStorage storage);

/// The same for one rank under mpirun that loads and fits `planes` z planes: read by offset where the
/// format allows (fit::readsOnlyPlanes), else the whole volume is read before its planes are cut.
void checkPlanesFitBudget(const std::string& path, const std::optional<fit::RawLayout>& raw,
                          const std::string& budgetText, const std::string& dicomSeries, std::uint64_t planes,
                          fit::SampleStorage storage = fit::SampleStorage::Float);

} // namespace vots::cli
