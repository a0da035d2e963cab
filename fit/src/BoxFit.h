// Least-squares Vot for one box (DESIGN §3): rank-adaptive basis, scaled coordinates, LDLT, float certify.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Vot.h"

#include <array>
#include <atomic>
#include <cstddef>

namespace vots::fit {

/// Counters shared by the fitting threads.
struct FitCounters {
    std::atomic<std::size_t> fits{0};
    std::atomic<std::size_t> scans{0};
    std::atomic<std::size_t> cacheHits{0};
};

/// Result of testing one box against the eps field.
struct BoxOutcome {
    bool accepted = false;
    bool exact = false;       // errCriterion is the exact maximum (the scan ran to the end)
    float errCriterion = 0.f; // max |residual| over the certified points; a lower bound when !exact
    float errSamples = 0.f;   // max |residual| over grid samples (what the file records)
    std::array<float, 3> p{}; // expansion point (box centre), index space
    std::array<float, MONOMIAL_COUNT> c{}; // index-unit coefficients, float as stored
};

/// Fits boxes of one volume at one requested degree. Stateless apart from the volume; thread-safe.
class BoxFitter {
public:
    BoxFitter(const Volume& volume, int degree, Certify certify)
        : mVolume(volume), mDegree(degree), mCertify(certify) {}

    /// Solves the least-squares problem on the box and certifies the float coefficients.
    /// A single-cell box is always accepted: its 8-term trilinear basis is exact (DESIGN §2/§3).
    BoxOutcome fit(const Box& box, const EpsField& eps, FitCounters& counters) const;
    /// Certifies given coefficients on the box (for reuse from a cache); fills err*, accepted, exact.
    void certify(const Box& box, const EpsField& eps, BoxOutcome& outcome, FitCounters& counters) const;

    int degree() const { return mDegree; }

private:
    const Volume& mVolume;
    int mDegree;
    Certify mCertify;
};

/// The monomials a box can determine: degree <= N and a_axis < points along that axis; a one-cell
/// box always gets the 8-term trilinear basis whatever N. Returns a bit mask over MONOMIAL_EXPONENTS.
std::uint32_t basisMask(const Box& box, int degree);

} // namespace vots::fit
