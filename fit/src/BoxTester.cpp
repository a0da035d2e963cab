// Cache-aware box acceptance: an exact cached error answers a uniform eps without any scan; minimax
// acceptance keeps a BoxRecord per box instead.
#include "BoxTester.h"

namespace vots::fit {

BoxOutcome BoxTester::test(const Box& box) const {
    if (mFitter.norm() == FitNorm::Minimax) {
        BoxRecord record;
        if (mCache) mCache->find(box, record);
        const BoxOutcome o = mFitter.decide(box, mEps, record, mCounters, mMinimax);
        if (mCache && record.changed) mCache->store(box, record);
        return o;
    }
    const bool singleCell = box.cellCount() == 1;
    std::optional<CachedBox> cached;
    if (mCache) cached = mCache->find(box);
    if (cached) {
        BoxOutcome o = cached->outcome;
        const float epsMin = mEps.minOverBox(box);
        const float epsMax = mEps.maxOverBox(box);
        if (singleCell ? o.exact : o.errCriterionBound <= epsMin) {
            mCounters.addCacheHit();
            o.accepted = true;
            return o;
        }
        if (o.errCriterion > epsMax) {
            mCounters.addCacheHit();
            o.accepted = false;
            return o;
        }
        if (cached->hasCoefficients) {
            // Between the bounds only a scan with the stored coefficients can decide.
            mCounters.addCacheHit();
            mFitter.certify(box, mEps, o, mCounters);
            if (o.exact || o.accepted) mCache->store(box, CachedBox{o, true});
            return o;
        }
    }
    BoxOutcome o = mFitter.fit(box, mEps, mCounters);
    if (mCache) {
        // A scan that stopped early still fitted the coefficients; an RSS reject did too, but its
        // error is only a lower bound, which is all a later, larger eps needs to know.
        mCache->store(box, CachedBox{o, true});
    }
    return o;
}

} // namespace vots::fit
