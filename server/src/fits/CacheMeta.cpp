// CacheMeta: the server's use of fit's meta schema, with the FitKey text as the cache key.
#include "fits/CacheMeta.h"

#include "vots/meta/FitMeta.h"

#include <filesystem>

namespace vots::server {

std::string cacheMetaFor(const FitKey& key, const Dataset& dataset, const fit::FitStats& stats,
                         const fit::VotSpace& space) {
    meta::FitProvenance provenance;
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(dataset.path, ec);
    provenance.sourcePath = ec ? dataset.path.string() : absolute.lexically_normal().string();
    provenance.volume = dataset.volume.get();
    provenance.options = fitOptionsFor(key);
    provenance.stats = stats;
    provenance.maxError = fit::maxStoredError(space);
    provenance.cacheKey = key.text();
    provenance.backgroundFill = space.backgroundFill;
    return meta::buildFitMeta(provenance);
}

bool carriesKey(const fit::VotSpace& space, const std::string& keyText) {
    return meta::readFitMeta(space.metaJson).cacheKey == keyText;
}

double fitSecondsOf(const fit::VotSpace& space) {
    return meta::readFitMeta(space.metaJson).fitSeconds.value_or(0.0);
}

} // namespace vots::server
