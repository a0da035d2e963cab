// CacheMeta: the server's use of fit's meta schema, with the FitKey text as the cache key.
#include "CacheMeta.h"

#include "vots/server/FitMeta.h"

#include <filesystem>

namespace vots::server {

std::string cacheMetaFor(const FitKey& key, const Dataset& dataset, const fit::FitStats& stats,
                         const fit::VotSpace& space) {
    FitProvenance fit;
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(dataset.path, ec);
    fit.sourcePath = ec ? dataset.path.string() : absolute.lexically_normal().string();
    fit.volume = dataset.volume.get();
    fit.options = fitOptionsFor(key);
    fit.stats = stats;
    fit.maxError = maxStoredError(space);
    fit.cacheKey = key.text();
    fit.backgroundFill = space.backgroundFill;
    return buildFitMeta(fit);
}

bool carriesKey(const fit::VotSpace& space, const std::string& keyText) {
    return readFitMeta(space.metaJson).cacheKey == keyText;
}

double fitSecondsOf(const fit::VotSpace& space) {
    return readFitMeta(space.metaJson).fitSeconds.value_or(0.0);
}

} // namespace vots::server
