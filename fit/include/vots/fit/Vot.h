// One Vot: a Taylor polynomial of degree <= 3 around an expansion point, valid in a box (docs/DESIGN.md §1).
#pragma once

#include "vots/fit/Box.h"
#include "vots/fit/Monomials.h"

#include <array>

namespace vots::fit {

/// Plain data as stored in the Vot-Space file (docs/DESIGN.md §8, record of 120 bytes).
struct Vot {
    Box box;                               // validity box, grid index space, closed, lo < hi
    std::array<float, 3> p{0.f, 0.f, 0.f}; // expansion point P, grid index space
    float err = 0.f;                       // max |residual| over the grid samples in the box, data units
    std::array<float, MONOMIAL_COUNT> c{}; // Taylor coefficients c_a for d = X - P (index units)

    /// f~(X) at a point X given in grid index space, evaluated in double.
    double evaluate(const std::array<double, 3>& xIndex) const;
    /// Gradient of f~ at X (index space).
    std::array<double, 3> computeGradient(const std::array<double, 3>& xIndex) const;
    /// Hessian of f~ at X, row-major 3x3.
    std::array<double, 9> computeHessian(const std::array<double, 3>& xIndex) const;
    /// Third-derivative tensor T_ijk (constant for degree <= 3), flattened as [i*9 + j*3 + k].
    std::array<double, 27> thirdDerivatives() const;
    /// Highest total degree with a nonzero coefficient (0 for an all-zero Vot).
    int effectiveDegree() const;
};

/// d^a for all 20 monomials at local offset d.
std::array<double, MONOMIAL_COUNT> evaluateMonomials(const std::array<double, 3>& d);

} // namespace vots::fit
