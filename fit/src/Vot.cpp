// Evaluation and derivatives of one Vot's Taylor polynomial (docs/DESIGN.md §1), generic over the monomials.
#include "vots/fit/Vot.h"

namespace vots::fit {
namespace {

double power(double base, int exponent) {
    double result = 1.0;
    for (int i = 0; i < exponent; ++i)
        result *= base;
    return result;
}

int fallingFactorial(int n, int k) {
    int result = 1;
    for (int i = 0; i < k; ++i)
        result *= n - i;
    return result;
}

/// d^b/dX^b of the polynomial at local offset d, for a derivative multi-index b.
double derivative(const Vot& vot, const std::array<double, 3>& d, const std::array<int, 3>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& a = MONOMIAL_EXPONENTS[i];
        if (a[0] < b[0] || a[1] < b[1] || a[2] < b[2] || vot.c[i] == 0.f) continue;
        double term = vot.c[i];
        for (int axis = 0; axis < 3; ++axis)
            term *= fallingFactorial(a[axis], b[axis]) * power(d[axis], a[axis] - b[axis]);
        sum += term;
    }
    return sum;
}

std::array<double, 3> localOffset(const Vot& vot, const std::array<double, 3>& xIndex) {
    return {xIndex[0] - vot.p[0], xIndex[1] - vot.p[1], xIndex[2] - vot.p[2]};
}

} // namespace

std::array<double, MONOMIAL_COUNT> evaluateMonomials(const std::array<double, 3>& d) {
    std::array<double, MONOMIAL_COUNT> m{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& a = MONOMIAL_EXPONENTS[i];
        m[i] = power(d[0], a[0]) * power(d[1], a[1]) * power(d[2], a[2]);
    }
    return m;
}

double Vot::evaluate(const std::array<double, 3>& xIndex) const {
    const auto m = evaluateMonomials(localOffset(*this, xIndex));
    double sum = 0.0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        sum += static_cast<double>(c[i]) * m[i];
    return sum;
}

std::array<double, 3> Vot::computeGradient(const std::array<double, 3>& xIndex) const {
    const auto d = localOffset(*this, xIndex);
    return {derivative(*this, d, {1, 0, 0}), derivative(*this, d, {0, 1, 0}),
            derivative(*this, d, {0, 0, 1})};
}

std::array<double, 9> Vot::computeHessian(const std::array<double, 3>& xIndex) const {
    const auto d = localOffset(*this, xIndex);
    std::array<double, 9> h{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            std::array<int, 3> b{0, 0, 0};
            ++b[i];
            ++b[j];
            h[i * 3 + j] = derivative(*this, d, b);
        }
    return h;
}

std::array<double, 27> Vot::thirdDerivatives() const {
    std::array<double, 27> t{};
    const std::array<double, 3> zero{0.0, 0.0, 0.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                std::array<int, 3> b{0, 0, 0};
                ++b[i];
                ++b[j];
                ++b[k];
                t[i * 9 + j * 3 + k] = derivative(*this, zero, b);
            }
    return t;
}

int Vot::effectiveDegree() const {
    int degree = 0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (c[i] != 0.f && monomialDegree(i) > degree) degree = monomialDegree(i);
    return degree;
}

} // namespace vots::fit
