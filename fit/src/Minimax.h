// The minimax (L-infinity) polynomial of one box by an exchange method (docs/DESIGN.md §3, "Minimax").
#pragma once

#include "vots/fit/Box.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Monomials.h"
#include "vots/fit/Volume.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

namespace vots::fit {

/// The exchange stops when the worst residual of its polynomial is within this fraction of the lower
/// bound (plus a tiny absolute slack): the polynomial is then the minimax one to 0.1 %.
inline constexpr double MINIMAX_TOLERANCE = 1e-3;
/// It gives up (a reject) after this many scans of the box or this many simplex pivots.
inline constexpr int MINIMAX_MAX_SCANS = 40;
inline constexpr int MINIMAX_MAX_PIVOTS = 600;

/// A box of at most this many samples holds its points in one matrix; a larger one is scanned for its worst
/// residuals, which feed a pool of candidate points.
inline constexpr std::int64_t MINIMAX_DENSE_POINTS = 256;

/// With Certify::Cells the minimax polynomial is fitted at the face centres too, which certification does
/// not test: a polynomial held within eps at every point of the half-integer lattice overshoots less
/// between them (docs/DESIGN.md §3, "Minimax").
inline constexpr bool MINIMAX_FACE_CENTRES = true;

/// The points the minimax polynomial is fitted on: the box's grid samples and, with Certify::Cells, its
/// edge midpoints, face centres (MINIMAX_FACE_CENTRES) and cell centres.
std::int64_t pointsToFit(const Box& box, Certify points);

struct MinimaxSolution {
    enum class Result : std::uint8_t {
        Converged, // `scaled` is the minimax polynomial (to MINIMAX_TOLERANCE), its error `maxResidual`
        Found,     // `scaled` was within the target's acceptBelow, and its `accept` took it
        Above,     // the lower bound passed stopAbove: no polynomial of the basis is within it
        GaveUp,    // no convergence within the scan or pivot limit (or a singular basis)
        NotFound   // the least-change search of a small box met no polynomial within the target (proves
                   // nothing)
    };
    Result result = Result::GaveUp;
    /// No polynomial of the basis has a largest |residual| over the points below this (the dual LP's value).
    double lowerBound = 0.0;
    double maxResidual = INFINITY; // of `scaled` over the points (Converged, Found)
    /// The smallest largest residual over the samples of the polynomials met before the last: a target
    /// whose acceptBelow is under it stops the search no sooner, and the search is the same up to there.
    double minEarlier = INFINITY;
    /// Coefficients over the scaled coordinates u = (x - centre) / half-extent, canonical monomial order.
    std::array<double, MONOMIAL_COUNT> scaled{};
    int scans = 0;
    int pivots = 0;
};

/// When the search may stop before the minimax polynomial.
struct MinimaxTarget {
    /// Once the lower bound exceeds this, no polynomial is within it: the search ends with Above.
    double stopAbove = INFINITY;
    /// A polynomial whose largest residual is within this is offered to `accept` (at most
    /// MINIMAX_MAX_OFFERS times); the search ends with Found when it takes it.
    double acceptBelow = -1.0;
    std::function<bool(const std::array<double, MONOMIAL_COUNT>& scaled)> accept;
};
inline constexpr int MINIMAX_MAX_OFFERS = 2;

/// The polynomial of the basis (a basisMask) that minimises the largest |value - P| over the box's grid
/// samples and, with Certify::Cells, over its cell centres and edge midpoints (their trilinear value), or
/// the first one met within the target. `start` (scaled coordinates, e.g. the least-squares solution)
/// only picks the first reference points. The sequence of polynomials met depends only on the box and the
/// start; the target only says where it stops.
MinimaxSolution fitMinimax(const Volume& volume, const Box& box, std::uint32_t basisMask, Certify points,
                           const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target);

} // namespace vots::fit
