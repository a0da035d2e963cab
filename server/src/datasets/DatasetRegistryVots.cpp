// Vot-Space files as datasets: the name, the memory a load takes, and the load with its derived fields.
#include "datasets/DatasetRegistryVots.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr float CT_MIN_HU = -900.f; // as for volumes: a minimum this low means CT

/// source.value_range of a meta block `vots fit` or the server wrote: the range percentages of eps
/// were resolved against, so a request's "2%" means what it meant for the fit.
std::optional<std::array<float, 2>> sourceValueRange(const std::string& metaJson) {
    const auto meta = nlohmann::json::parse(metaJson, nullptr, /*allow_exceptions=*/false);
    const nlohmann::json::json_pointer where("/source/value_range");
    if (!meta.is_object() || !meta.contains(where)) return std::nullopt;
    const auto& range = meta.at(where);
    if (!range.is_array() || range.size() != 2 || !range[0].is_number() || !range[1].is_number())
        return std::nullopt;
    const std::array<float, 2> out{range[0].get<float>(), range[1].get<float>()};
    if (!std::isfinite(out[0]) || !std::isfinite(out[1]) || out[0] > out[1]) return std::nullopt;
    return out;
}

/// The values the Vots take at their box corners: a file of another tool has no meta range, and the
/// corners bound what a MIP shows closely enough for windows and presets.
std::array<float, 2> cornerValueRange(const fit::VotSpace& space) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const fit::Vot& vot : space.vots)
        for (int corner = 0; corner < 8; ++corner) {
            std::array<double, 3> x{};
            for (int a = 0; a < 3; ++a)
                x[a] = (corner >> a & 1) ? vot.box.hi[a] : vot.box.lo[a];
            const double value = vot.evaluate(x);
            lo = std::min(lo, value);
            hi = std::max(hi, value);
        }
    if (!(lo <= hi)) return {0.f, 0.f};
    return {static_cast<float>(lo), static_cast<float>(hi)};
}

} // namespace

std::string votsStem(const fs::path& file) {
    const std::string name = file.filename().string();
    const std::string ext = ".vots";
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0)
        return name.substr(0, name.size() - ext.size());
    return {};
}

std::uint64_t estimateVotsLoadBytes(std::uint64_t fileBytes) {
    const std::uint64_t records = fileBytes / fit::VOTS_RECORD_BYTES;
    return fileBytes + records * sizeof(fit::Vot);
}

std::shared_ptr<const Dataset> loadVotsDataset(const std::string& name, const fs::path& path) {
    auto space = std::make_shared<fit::VotSpace>(meta::readVotSpaceFile(path.string()));
    auto dataset = std::make_shared<Dataset>();
    dataset->name = name;
    dataset->path = path;
    dataset->kind = DatasetKind::Vots;
    dataset->range = sourceValueRange(space->metaJson).value_or(cornerValueRange(*space));
    dataset->background = space->background;
    dataset->defaultEps = space->eps;
    dataset->isCt = dataset->range[0] <= CT_MIN_HU;
    dataset->presets = windowPresets(dataset->range, dataset->isCt);
    std::error_code ec;
    const auto bytes = fs::file_size(path, ec);
    dataset->loadAndFitBytes = ec ? 0 : estimateVotsLoadBytes(bytes);
    dataset->fitBytes = 0; // never fitted
    dataset->space = std::move(space);
    return dataset;
}

} // namespace vots::server
