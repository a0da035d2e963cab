// Minimax acceptance of a box (BoxFitter::decide): its least-squares polynomial, else its minimax one.
#include "BoxFit.h"

#include "FloatBounds.h"
#include "Minimax.h"

#include <algorithm>
#include <cmath>

namespace vots::fit {
namespace {

/// half-extent^a of each monomial: coefficients over scaled coordinates are these times those in index units.
std::array<double, MONOMIAL_COUNT> scaledMonomialFactors(const Box& box) {
    double halfPower[3][4];
    for (int a = 0; a < 3; ++a) {
        const double half = 0.5 * (box.hi[a] - box.lo[a]);
        halfPower[a][0] = 1.0;
        for (int k = 1; k < 4; ++k)
            halfPower[a][k] = halfPower[a][k - 1] * half;
    }
    std::array<double, MONOMIAL_COUNT> factors{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        factors[i] = halfPower[0][e[0]] * halfPower[1][e[1]] * halfPower[2][e[2]];
    }
    return factors;
}

/// The field times `factor`, focus included.
EpsField scaledField(const EpsField& field, double factor) {
    std::optional<FocusRegion> focus = field.focus();
    if (focus) focus->epsFocus = static_cast<float>(focus->epsFocus * factor);
    return EpsField(static_cast<float>(field.context() * factor), focus);
}

/// A certification that rejected the coefficients found less than an earlier one of the same coefficients
/// may have (it stopped at the first point over a smaller eps): keep the larger lower bounds.
void keepWhatWasKnown(BoxOutcome& now, const BoxOutcome& before) {
    if (now.accepted) return;
    if (!now.exact && before.errCriterion > now.errCriterion) {
        now.errCriterion = before.errCriterion;
        now.exact = before.exact;
        now.errCriterionBound = before.errCriterionBound;
    }
    if (!now.samplesComplete && (before.samplesComplete || before.errSamples > now.errSamples)) {
        now.errSamples = before.errSamples;
        now.samplesComplete = before.samplesComplete;
    }
}

} // namespace

BoxOutcome BoxFitter::decide(const Box& box, const EpsField& eps, BoxRecord& record, FitCounters& counters,
                             bool minimax) const {
    record.changed = false;
    if (holdsNoData(box)) return rejectedForNoData(box);
    if (decideLeastSquares(box, eps, record, counters, minimax)) return record.lsq;
    if (minimax && decideMinimax(box, eps, record, counters)) return record.minimax;
    BoxOutcome rejected;
    rejected.errCriterion = std::max(record.lowerBound, record.lsq.errCriterion);
    return rejected;
}

bool BoxFitter::decideLeastSquares(const Box& box, const EpsField& eps, BoxRecord& record,
                                   FitCounters& counters, bool minimax) const {
    const bool singleCell = isSingleCell(box);
    const double epsMin = eps.minOverBox(box);
    const double epsMax = eps.maxOverBox(box);
    // The sample scan goes on past eps as far as the gate needs to know the samples' largest error.
    const double scanOnTo = singleCell || !minimax ? 0.0 : MINIMAX_GATE * minimaxTarget() * epsMax;
    BoxOutcome& o = record.lsq;
    if (!record.fitted) {
        counters.addFit();
        bool rssRejected = false;
        o = leastSquares(box, epsMax, rssRejected);
        record.fitted = record.changed = true;
        if (rssRejected) {
            // The least-squares polynomial has the smallest sum of squares: every polynomial's root mean
            // square residual, so its largest one, is at least this.
            record.lowerBound = std::max(record.lowerBound, o.errCriterion);
            return false;
        }
        certify(box, eps, o, counters, scanOnTo);
        return o.accepted;
    }
    if (record.lowerBound > epsMax) {
        counters.addCacheHit();
        return false;
    }
    if (singleCell ? o.exact : o.errCriterionBound <= epsMin) {
        counters.addCacheHit();
        o.accepted = true;
        return true;
    }
    if (o.errCriterion > epsMax) {
        counters.addCacheHit();
        return false;
    }
    // Between the bounds only a scan with the stored coefficients can decide.
    const BoxOutcome before = o;
    certify(box, eps, o, counters, scanOnTo);
    keepWhatWasKnown(o, before);
    record.changed = true;
    return o.accepted;
}

bool BoxFitter::decideCentred(const Box& box, const EpsField& tight, double epsMin, BoxRecord& record,
                              FitCounters& counters) const {
    if (std::isnan(record.centredHalfRange)) {
        const ResidualRange range = residualRange(box, record.lsq);
        record.centredHalfRange = roundUpToFloat(0.5 * (range.high - range.low));
        record.centredConstant = static_cast<float>(record.lsq.c[0] - 0.5 * (range.high + range.low));
        record.changed = true;
    }
    if (record.centredHalfRange > epsMin) return false;
    if (record.state == BoxRecord::Minimax::Centred && record.minimax.errCriterionBound <= epsMin) {
        counters.addCacheHit();
        record.minimax.accepted = true;
        return true;
    }
    // The constant is the monomial 1 (MONOMIAL_EXPONENTS[0]); the float rounding of the moved constant is
    // within what the certification checks.
    BoxOutcome centred = record.lsq;
    centred.c[0] = record.centredConstant;
    certify(box, tight, centred, counters);
    if (!centred.accepted) return false;
    record.state = BoxRecord::Minimax::Centred;
    record.minimax = centred;
    record.changed = true;
    counters.addCentredAccepted();
    return true;
}

bool BoxFitter::decideMinimax(const Box& box, const EpsField& field, BoxRecord& record,
                              FitCounters& counters) const {
    if (isSingleCell(box)) return false; // (the least-squares polynomial is exact there)
    const EpsField& eps = field;
    const double gate = MINIMAX_GATE * minimaxTarget() * field.maxOverBox(box);
    BoxOutcome& lsq = record.lsq;
    if (!lsq.samplesComplete && lsq.errSamples <= gate) {
        // What the last scan of the least-squares polynomial saw (at another eps, or none after an RSS
        // reject) does not settle the gate: scan as far as it needs. The polynomial stays refused: the
        // scan before found it beyond eps.
        const BoxOutcome before = lsq;
        certify(box, eps, lsq, counters, gate);
        keepWhatWasKnown(lsq, before);
        record.changed = true;
        if (lsq.accepted) return false; // not reached; decideLeastSquares has refused these coefficients
    }
    if (lsq.errSamples > gate) return false;

    // A fit certified at the cells holds its minimax polynomials within MINIMAX_CELLS_TARGET eps at every
    // point they are fitted at (the certification itself stays at eps).
    const EpsField tight = minimaxTarget() < 1.0 ? scaledField(field, minimaxTarget()) : field;
    const double epsMin = tight.minOverBox(box);
    const double epsMax = tight.maxOverBox(box);
    // Before the search: least squares with its residuals centred. The least-squares polynomial's mean
    // residual is zero, not the middle of its range, and a box refused for a few large residuals of one sign
    // (a bone edge, a vessel) is often within eps once its constant moves to that middle, at the price of two
    // scans instead of a search (bench/RESULTS.md, "Centred least squares"); what it finds holds at any
    // larger eps, so a cache keeps it.
    if (decideCentred(box, tight, epsMin, record, counters)) return true;

    if (record.lowerBound > epsMax) return false;

    // The least-change search from the stored (float) least-squares coefficients, for a polynomial within
    // eps less a margin for the rounding of its coefficients, which its certification then checks.
    const std::uint32_t mask = basisMask(box, mDegree);
    const auto factors = scaledMonomialFactors(box);
    std::array<double, MONOMIAL_COUNT> start{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (mask & (1u << i)) start[i] = static_cast<double>(lsq.c[i]) * factors[i];
    MinimaxTarget target;
    BoxOutcome found;
    target.acceptBelow = epsMin * (1.0 - MINIMAX_ROUNDING_MARGIN);
    target.accept = [&](const std::array<double, MONOMIAL_COUNT>& scaled) {
        found = BoxOutcome{};
        found.p = lsq.p;
        for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
            if (mask & (1u << i)) found.c[i] = static_cast<float>(scaled[i] / factors[i]);
        certify(box, tight, found, counters);
        return found.accepted;
    };
    const MinimaxSolution solution = findWithinTarget(mVolume, box, mask, mCertify, start, target);
    const bool accepted = solution.result == MinimaxSolution::Result::Found;
    counters.addMinimax(solution.scans, accepted);
    if (!accepted) return false;
    record.state = BoxRecord::Minimax::Found; // (nothing for a cache: it holds at this eps only)
    record.minimax = found;
    return true;
}

} // namespace vots::fit
