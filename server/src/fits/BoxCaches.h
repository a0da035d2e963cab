// The fitter's box caches, one per (dataset, frame, degree), shared by fits and warm-ups; a few kept.
#pragma once

#include "vots/fit/Fitter.h"

#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace vots::server {

/// Thread-safe.
class BoxCaches {
public:
    /// Each can grow large: beyond this many, another one is dropped (a running fit keeps its own alive).
    static constexpr std::size_t MAX_KEPT = 4;

    /// The cache for fits of this dataset's frame (of a 4D one; else 0) at this degree, made on first use.
    std::shared_ptr<fit::FitCache> forFits(const std::string& dataset, int frame, int degree);

private:
    std::mutex mMutex;
    std::map<std::string, std::shared_ptr<fit::FitCache>> mCaches; // "dataset/frame/degree"
};

} // namespace vots::server
