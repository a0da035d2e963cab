// Decides whether a box fits within eps, consulting the FitCache before solving and scanning.
#pragma once

#include "BoxFit.h"
#include "FitCacheImpl.h"

namespace vots::fit {

class BoxTester {
public:
    BoxTester(const BoxFitter& fitter, const EpsField& eps, FitCounters& counters, FitCache::Impl* cache)
        : mFitter(fitter), mEps(eps), mCounters(counters), mCache(cache) {}

    /// Accepted outcomes carry coefficients and certified errors; rejected ones may not.
    BoxOutcome test(const Box& box) const;
    /// A hint: box will be tested soon.
    void willTest(const Box& box) const {
        if (mCache) mCache->prefetch(box);
    }
    const EpsField& eps() const { return mEps; }

private:
    const BoxFitter& mFitter;
    const EpsField& mEps;
    FitCounters& mCounters;
    FitCache::Impl* mCache;
};

/// A box chosen (or proposed) for the cover, with its certified fit.
struct FittedBox {
    Box box;
    BoxOutcome outcome;
};

} // namespace vots::fit
