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
    void addMinimax(int scans, bool accepted) {
        mine().minimaxFits.fetch_add(1, std::memory_order_relaxed);
        mine().minimaxScans.fetch_add(static_cast<std::size_t>(scans), std::memory_order_relaxed);
        if (accepted) mine().minimaxAccepted.fetch_add(1, std::memory_order_relaxed);
    }
    void addCentredAccepted() { mine().centredAccepted.fetch_add(1, std::memory_order_relaxed); }
    std::size_t fits() const { return total(&Slot::fits); }
    std::size_t scans() const { return total(&Slot::scans); }
    std::size_t cacheHits() const { return total(&Slot::cacheHits); }
    std::size_t minimaxFits() const { return total(&Slot::minimaxFits); }
    std::size_t minimaxScans() const { return total(&Slot::minimaxScans); }
    std::size_t minimaxAccepted() const { return total(&Slot::minimaxAccepted); }
    std::size_t centredAccepted() const { return total(&Slot::centredAccepted); }

private:
    struct alignas(64) Slot {
        std::atomic<std::size_t> fits{0};
        std::atomic<std::size_t> scans{0};
        std::atomic<std::size_t> cacheHits{0};
        std::atomic<std::size_t> minimaxFits{0};
        std::atomic<std::size_t> minimaxScans{0};
        std::atomic<std::size_t> minimaxAccepted{0};
        std::atomic<std::size_t> centredAccepted{0};
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
    bool samplesComplete = false;       // errSamples is over every sample (a lower bound when false)
    std::array<float, 3> p{};           // expansion point (box centre), index space
    std::array<float, MONOMIAL_COUNT> c{}; // index-unit coefficients, float as stored
};

/// The smallest and largest residual P - value of a polynomial over a box's certified points.
struct ResidualRange {
    double low = INFINITY;
    double high = -INFINITY;
};

/// Minimax acceptance searches only a box whose least-squares polynomial is within this many times the
/// minimax target (eps, or MINIMAX_CELLS_TARGET eps) at every sample: further out no polynomial is often
/// within it, and the search would mostly fail at the price of its rounds (docs/DESIGN.md §3, "Minimax").
inline constexpr double MINIMAX_GATE = 1.5;
/// With Certify::Cells a box is accepted by its minimax polynomial only when that is within this fraction
/// of eps at the samples and the cell points, face centres included: least squares rarely comes near eps
/// everywhere, minimax does by its nature, and between the certified points a polynomial overshoots what
/// it holds at them. With this margin the Vots' MIP agrees with the exact grid's at least as often as with
/// least squares (docs/DESIGN.md §3, "Minimax"; tests/render/test_RealVolumeProjections.cpp).
inline constexpr double MINIMAX_CELLS_TARGET = 0.9;
/// The least-change search looks for a polynomial within eps less this fraction: the rounding of its
/// coefficients to float must not take it past eps.
inline constexpr double MINIMAX_ROUNDING_MARGIN = 1e-4;

/// What minimax acceptance has learned about one box that holds at any eps, so a FitCache keeps it and a
/// later fit at another eps decides from it as a fresh fit would. The least-change search's polynomial
/// depends on the eps it searched for, so a later eps searches again.
struct BoxRecord {
    enum class Minimax : std::uint8_t {
        NotRun, // `minimax` holds nothing
        Found, // `minimax` holds what the least-change search found at this eps, certified (for no other eps)
        Centred // `minimax` holds the centred least-squares polynomial (below) and its last certification
    };
    BoxOutcome lsq;      // the least-squares coefficients and what their last certification found
    bool fitted = false; // lsq holds coefficients
    /// No polynomial of the basis is within less than this at every certified point: the least-squares
    /// root-mean-square residual.
    float lowerBound = 0.f;
    Minimax state = Minimax::NotRun;
    BoxOutcome minimax;
    /// The least-squares polynomial with its constant moved to the middle of its residuals' range over the
    /// certified points: half that range (rounded up; NaN until computed) and the moved constant.
    float centredHalfRange = NAN;
    float centredConstant = 0.f;
    bool changed = false; // decide() learned something a cache should keep
};

/// Fits boxes of one volume at one requested degree. Stateless apart from the volume; thread-safe.
class BoxFitter {
public:
    BoxFitter(const Volume& volume, int degree, Certify certify, FitNorm norm = FitNorm::Lsq)
        : mVolume(volume), mDegree(degree), mCertify(certify), mNorm(norm),
          mHasNoData(volume.nonFiniteCount() > 0) {}

    /// Solves the least-squares problem on the box and certifies the float coefficients.
    /// A single-cell box is always accepted: its 8-term trilinear basis is exact (docs/DESIGN.md §2).
    BoxOutcome fit(const Box& box, const EpsField& eps, FitCounters& counters) const;
    /// Certifies given coefficients on the box (for reuse from a cache); fills err*, accepted, exact.
    /// scanOnTo > 0: after a sample breaks the bound the scan goes on over the samples while none exceeds
    /// scanOnTo, so that errSamples is their exact maximum when it is at most scanOnTo (samplesComplete).
    void certify(const Box& box, const EpsField& eps, BoxOutcome& outcome, FitCounters& counters,
                 double scanOnTo = 0.0) const;
    /// Minimax acceptance (docs/DESIGN.md §3): the least-squares polynomial when it is certified, else the
    /// minimax one when the least-squares one is within MINIMAX_GATE eps and the minimax one is certified.
    /// `record` is what earlier decisions on this box learned (empty for a fresh box) and is brought up to
    /// date. minimax false: the least-squares polynomial only (as fit() decides).
    BoxOutcome decide(const Box& box, const EpsField& eps, BoxRecord& record, FitCounters& counters,
                      bool minimax = true) const;

    int degree() const { return mDegree; }
    FitNorm norm() const { return mNorm; }

private:
    /// A box holding a NaN or Inf sample is rejected whatever eps (its error counts as infinite), so the
    /// generators split it until no Vot holds one (docs/DESIGN.md §4 "Non-finite samples").
    bool holdsNoData(const Box& box) const;
    /// The outcome of such a box: rejected, with infinite errors.
    static BoxOutcome rejectedForNoData(const Box& box);
    /// The least-squares coefficients (uncertified); rejected when the RSS alone proves that some sample
    /// is beyond epsMax (errCriterion then holds the root-mean-square residual, a lower bound).
    BoxOutcome leastSquares(const Box& box, double epsMax, bool& rssRejected) const;
    bool decideLeastSquares(const Box& box, const EpsField& eps, BoxRecord& record, FitCounters& counters,
                            bool minimax) const;
    bool decideMinimax(const Box& box, const EpsField& eps, BoxRecord& record, FitCounters& counters) const;
    /// The centred least-squares polynomial, tried before any search: accepted when half its residuals'
    /// range is within epsMin (the target's smallest eps over the box) and its certification at `tight`
    /// passes.
    bool decideCentred(const Box& box, const EpsField& tight, double epsMin, BoxRecord& record,
                       FitCounters& counters) const;
    /// The smallest and largest residual of the outcome's coefficients over the points certify() checks.
    ResidualRange residualRange(const Box& box, const BoxOutcome& outcome) const;
    /// The fraction of eps a minimax polynomial must keep to (MINIMAX_CELLS_TARGET with Certify::Cells).
    double minimaxTarget() const { return mCertify == Certify::Cells ? MINIMAX_CELLS_TARGET : 1.0; }

    const Volume& mVolume;
    int mDegree;
    Certify mCertify;
    FitNorm mNorm;
    bool mHasNoData; // any sample of the volume is NaN or Inf
};

/// The monomials a box can determine: degree <= N and a_axis < points along that axis; a one-cell
/// box always gets the 8-term trilinear basis whatever N. Returns a bit mask over MONOMIAL_EXPONENTS.
std::uint32_t basisMask(const Box& box, int degree);

/// A box of one cell, whose trilinear basis is exact.
inline bool isSingleCell(const Box& box) {
    return box.cells(0) == 1 && box.cells(1) == 1 && box.cells(2) == 1;
}

} // namespace vots::fit
