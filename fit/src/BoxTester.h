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
    /// The same tester, but a minimax fit's boxes are accepted with their least-squares polynomial only: the
    /// split, where larger boxes accepted by minimax would block more merges than they save
    /// (docs/DESIGN.md §4).
    BoxTester leastSquaresOnly() const {
        BoxTester t = *this;
        t.mMinimax = false;
        return t;
    }
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
    bool mMinimax = true; // (with a FitNorm::Minimax fitter)
};

/// A box chosen (or proposed) for the cover, with its certified fit.
struct FittedBox {
    Box box;
    BoxOutcome outcome;
};

} // namespace vots::fit
