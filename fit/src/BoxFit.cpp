// BoxFitter's common steps: the basis rule, the fit of a box, the no-data check, and the per-thread counters.
// The least squares are in BoxLeastSquares.cpp, the certification in BoxCertify.cpp, and minimax acceptance
// (BoxFitter::decide) in BoxMinimaxAcceptance.cpp.
#include "BoxFit.h"

#include <cmath>

namespace vots::fit {

std::uint32_t basisMask(const Box& box, int degree) {
    const int n = isSingleCell(box) ? 3 : degree;
    std::uint32_t mask = 0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& a = MONOMIAL_EXPONENTS[i];
        if (monomialDegree(i) <= n && a[0] < box.points(0) && a[1] < box.points(1) && a[2] < box.points(2))
            mask |= 1u << i;
    }
    return mask;
}

FitCounters::Slot& FitCounters::mine() {
    static std::atomic<std::size_t> nextThread{0};
    thread_local const std::size_t slot = nextThread.fetch_add(1, std::memory_order_relaxed) % SLOTS;
    return mSlots[slot];
}

bool BoxFitter::holdsNoData(const Box& box) const {
    if (!mHasNoData) return false;
    for (int z = box.lo[2]; z <= box.hi[2]; ++z)
        for (int y = box.lo[1]; y <= box.hi[1]; ++y) {
            const float* row = mVolume.values.data() + mVolume.indexOf(0, y, z);
            for (int x = box.lo[0]; x <= box.hi[0]; ++x)
                if (!std::isfinite(row[x])) return true;
        }
    return false;
}

BoxOutcome BoxFitter::rejectedForNoData(const Box& box) {
    BoxOutcome outcome;
    outcome.exact = true; // no eps accepts it: a cache may answer it without a scan
    outcome.errCriterion = outcome.errCriterionBound = outcome.errSamples = INFINITY;
    for (int a = 0; a < 3; ++a)
        outcome.p[a] = 0.5f * static_cast<float>(box.lo[a] + box.hi[a]);
    return outcome;
}

BoxOutcome BoxFitter::fit(const Box& box, const EpsField& eps, FitCounters& counters) const {
    counters.addFit();
    if (holdsNoData(box)) return rejectedForNoData(box);
    bool rssRejected = false;
    BoxOutcome outcome = leastSquares(box, eps.maxOverBox(box), rssRejected);
    if (!rssRejected) certify(box, eps, outcome, counters);
    return outcome;
}

} // namespace vots::fit
