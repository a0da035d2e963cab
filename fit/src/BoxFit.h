// Least-squares Vot for one box (docs/DESIGN.md §3): rank-adaptive basis, scaled coordinates, float certify.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Vot.h"

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>

namespace vots::fit {

/// What the fitting threads did, for FitStats. Each thread counts in its own cache line: two threads
/// adding to one shared line would make every cache hit wait for that line.
class FitCounters {
public:
    void addFit() { mine().fits.fetch_add(1, std::memory_order_relaxed); }
    void addScan() { mine().scans.fetch_add(1, std::memory_order_relaxed); }
    void addCacheHit() { mine().cacheHits.fetch_add(1, std::memory_order_relaxed); }
    std::size_t fits() const { return total(&Slot::fits); }
    std::size_t scans() const { return total(&Slot::scans); }
    std::size_t cacheHits() const { return total(&Slot::cacheHits); }

private:
    struct alignas(64) Slot {
        std::atomic<std::size_t> fits{0};
        std::atomic<std::size_t> scans{0};
        std::atomic<std::size_t> cacheHits{0};
    };
    // Threads get slots in the order they first count; threads that share a slot still count right.
    static constexpr std::size_t SLOTS = 16;
    Slot& mine();
    std::size_t total(std::atomic<std::size_t> Slot::*counter) const {
        std::size_t sum = 0;
        for (const Slot& slot : mSlots)
            sum += (slot.*counter).load(std::memory_order_relaxed);
        return sum;
    }
    std::array<Slot, SLOTS> mSlots;
};

/// Result of testing one box against the eps field.
struct BoxOutcome {
    bool accepted = false;
    bool exact = false;                 // errCriterion is the exact maximum (the scan ran to the end)
    float errCriterion = 0.f;           // max |residual| over the certified points; a lower bound when !exact
    float errCriterionBound = INFINITY; // an upper bound of that maximum; errCriterion itself when exact
    float errSamples = 0.f;             // max |residual| over grid samples (what the file records)
    std::array<float, 3> p{};           // expansion point (box centre), index space
    std::array<float, MONOMIAL_COUNT> c{}; // index-unit coefficients, float as stored
};

/// Fits boxes of one volume at one requested degree. Stateless apart from the volume; thread-safe.
class BoxFitter {
public:
    BoxFitter(const Volume& volume, int degree, Certify certify)
        : mVolume(volume), mDegree(degree), mCertify(certify), mHasNoData(volume.nonFiniteCount() > 0) {}

    /// Solves the least-squares problem on the box and certifies the float coefficients.
    /// A single-cell box is always accepted: its 8-term trilinear basis is exact (docs/DESIGN.md §2).
    BoxOutcome fit(const Box& box, const EpsField& eps, FitCounters& counters) const;
    /// Certifies given coefficients on the box (for reuse from a cache); fills err*, accepted, exact.
    void certify(const Box& box, const EpsField& eps, BoxOutcome& outcome, FitCounters& counters) const;

    int degree() const { return mDegree; }

private:
    /// A box holding a NaN or Inf sample is rejected whatever eps (its error counts as infinite), so the
    /// generators split it until no Vot holds one (docs/DESIGN.md §4 "Non-finite samples").
    bool holdsNoData(const Box& box) const;

    const Volume& mVolume;
    int mDegree;
    Certify mCertify;
    bool mHasNoData; // any sample of the volume is NaN or Inf
};

/// The monomials a box can determine: degree <= N and a_axis < points along that axis; a one-cell
/// box always gets the 8-term trilinear basis whatever N. Returns a bit mask over MONOMIAL_EXPONENTS.
std::uint32_t basisMask(const Box& box, int degree);

} // namespace vots::fit
