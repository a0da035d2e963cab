// The minimax (L-infinity) polynomial of one box by an exchange method, and a polynomial within a target by
// a least-change search (docs/DESIGN.md §3, "Minimax acceptance").
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
/// It gives up after this many scans of the box or this many simplex pivots.
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
        Converged, // fitMinimax: `scaled` is the minimax polynomial (to MINIMAX_TOLERANCE), its error
                   // `maxResidual`
        Found,     // findWithinTarget: `scaled` is within the target, and its `accept` took it
        NotFound,  // findWithinTarget: no polynomial met within the target (this proves nothing)
        GaveUp     // fitMinimax: no convergence within the scan or pivot limit (or a singular basis)
    };
    Result result = Result::GaveUp;
    /// fitMinimax: no polynomial of the basis has a largest |residual| over the points below this (the dual
    /// LP's value).
    double lowerBound = 0.0;
    double maxResidual = INFINITY; // of `scaled` over the points priced (Converged, Found)
    /// Coefficients over the scaled coordinates u = (x - centre) / half-extent, canonical monomial order.
    std::array<double, MONOMIAL_COUNT> scaled{};
    int scans = 0;  // of the box, or rounds of the least-change search
    int pivots = 0; // of the exchange
};

/// The polynomial of the basis (a basisMask) that minimises the largest |value - P| over the box's grid
/// samples and, with Certify::Cells, over its cell centres, face centres and edge midpoints (their
/// trilinear value): the exchange (docs/DESIGN.md §3, "Minimax acceptance", step 5). `start` (scaled
/// coordinates, e.g. the least-squares solution) only picks the first reference points.
MinimaxSolution fitMinimax(const Volume& volume, const Box& box, std::uint32_t basisMask, Certify points,
                           const std::array<double, MONOMIAL_COUNT>& start);

/// What a least-change search looks for: a polynomial within `acceptBelow` at every point, which `accept`
/// (the certification) takes.
struct MinimaxTarget {
    double acceptBelow = 0.0;
    std::function<bool(const std::array<double, MONOMIAL_COUNT>& scaled)> accept;
};

/// The polynomial nearest `start` (scaled coordinates: the least-squares solution) in the least-squares
/// metric that is within the target at the same points as fitMinimax's, when the least-change search finds
/// one and the target takes it (docs/DESIGN.md §3, "Minimax acceptance", step 4).
MinimaxSolution findWithinTarget(const Volume& volume, const Box& box, std::uint32_t basisMask,
                                 Certify points, const std::array<double, MONOMIAL_COUNT>& start,
                                 const MinimaxTarget& target);

} // namespace vots::fit
