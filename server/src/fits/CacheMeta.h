// What the server's cache files record in their meta block (fit's one schema) and reads back from it.
#pragma once

#include "datasets/DatasetRegistry.h"
#include "fits/FitKey.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/VotSpace.h"

#include <string>

namespace vots::server {

/// The meta block of a fit of `key` made of the dataset: buildFitMeta (FitMeta.h) with the key as cache key,
/// so `vots info` reads a cache file like a `vots fit` file.
std::string cacheMetaFor(const FitKey& key, const Dataset& dataset, const fit::FitStats& stats,
                         const fit::VotSpace& space);

/// Whether the space's meta block names this key (a copied or renamed file does not).
bool carriesKey(const fit::VotSpace& space, const std::string& keyText);

/// The fit time its meta block records, 0 when absent.
double fitSecondsOf(const fit::VotSpace& space);

} // namespace vots::server
