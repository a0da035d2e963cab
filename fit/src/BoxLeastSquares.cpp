// Least-squares fit of a box from separable moment sums, its normal matrix factored once per box shape.
#include "BoxFit.h"

#include "SampleAccess.h"

#include <Eigen/Dense>
#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vots::fit {
namespace {

constexpr std::size_t MAX_CACHED_FACTORS = 4096; // box shapes per thread (~3.5 KB each)

} // namespace

BoxOutcome BoxFitter::leastSquares(const Box& box, double epsMax, bool& rssRejected) const {
    rssRejected = false;
    const std::uint32_t mask = basisMask(box, mDegree);
    std::array<int, MONOMIAL_COUNT> basis{};
    int nb = 0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (mask & (1u << i)) basis[static_cast<std::size_t>(nb++)] = static_cast<int>(i);

    // Scaled coordinates u = (x - centre) / half-extent in [-1, 1] keep the normal matrix well conditioned.
    std::array<double, 3> centre{}, half{};
    for (int a = 0; a < 3; ++a) {
        centre[a] = 0.5 * (box.lo[a] + box.hi[a]);
        half[a] = 0.5 * (box.hi[a] - box.lo[a]);
    }
    // 1D power sums S_a[k] = sum u^k (k <= 6) give the normal matrix without touching the samples.
    std::array<std::array<double, 7>, 3> powerSums{};
    // Reused per thread: small boxes are the common case and allocation would dominate them.
    thread_local std::array<std::vector<std::array<double, 4>>, 3> powers;
    for (int a = 0; a < 3; ++a) {
        powers[a].resize(static_cast<std::size_t>(box.points(a)));
        for (int i = 0; i < box.points(a); ++i) {
            const double u = (box.lo[a] + i - centre[a]) / half[a];
            powers[a][static_cast<std::size_t>(i)] = {1.0, u, u * u, u * u * u};
            double pk = 1.0;
            for (int k = 0; k <= 6; ++k, pk *= u)
                powerSums[a][k] += pk;
        }
    }
    // Right-hand side b_a = sum f u^ax v^ay w^az, accumulated separably row by row.
    double moments[4][4][4] = {};
    double sumSquares = 0.0;
    const int nx = box.points(0);
    const auto& ux = powers[0];
    visitSamples(mVolume, [&](const auto* values) {
        for (int k = 0; k < box.points(2); ++k) {
            double slab[4][4] = {};
            for (int j = 0; j < box.points(1); ++j) {
                const auto* row = values + mVolume.indexOf(box.lo[0], box.lo[1] + j, box.lo[2] + k);
                double r0 = 0, r1 = 0, r2 = 0, r3 = 0;
                for (int i = 0; i < nx; ++i) {
                    const double f = sampleAsFloat(row[i]);
                    const auto& u = ux[static_cast<std::size_t>(i)];
                    r0 += f;
                    r1 += f * u[1];
                    r2 += f * u[2];
                    r3 += f * u[3];
                    sumSquares += f * f;
                }
                const auto& v = powers[1][static_cast<std::size_t>(j)];
                const double rs[4] = {r0, r1, r2, r3};
                for (int p = 0; p < 4; ++p)
                    for (int q = 0; q < 4; ++q)
                        slab[p][q] += rs[p] * v[q];
            }
            const auto& w = powers[2][static_cast<std::size_t>(k)];
            for (int p = 0; p < 4; ++p)
                for (int q = 0; q < 4; ++q)
                    for (int s = 0; s < 4; ++s)
                        moments[p][q][s] += slab[p][q] * w[s];
        }
    });

    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 20, 20>; // on the stack
    using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 20, 1>;
    Vector rhs(nb);
    for (int r = 0; r < nb; ++r) {
        const auto& ea = MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis[static_cast<std::size_t>(r)])];
        rhs(r) = moments[ea[0]][ea[1]][ea[2]];
    }
    auto factorNormalMatrix = [&] {
        Matrix normal(nb, nb);
        for (int r = 0; r < nb; ++r) {
            const auto& ea = MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis[static_cast<std::size_t>(r)])];
            for (int s = 0; s < nb; ++s) {
                const auto& eb =
                    MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis[static_cast<std::size_t>(s)])];
                normal(r, s) =
                    powerSums[0][ea[0] + eb[0]] * powerSums[1][ea[1] + eb[1]] * powerSums[2][ea[2] + eb[2]];
            }
        }
        return Eigen::LDLT<Matrix>(normal);
    };
    // The normal matrix depends only on the box's point counts and basis, not on where the box is or
    // on the data, and a fit visits the same few hundred shapes over and over: factor each shape once
    // per thread. Same factors, so the same solutions.
    const bool cacheable = box.points(0) <= 255 && box.points(1) <= 255 && box.points(2) <= 255;
    Vector solution;
    if (cacheable) {
        thread_local absl::flat_hash_map<std::uint64_t, Eigen::LDLT<Matrix>> factors;
        const std::uint64_t key = std::uint64_t{mask} << 24 | std::uint64_t(box.points(0)) << 16 |
                                  std::uint64_t(box.points(1)) << 8 | std::uint64_t(box.points(2));
        auto it = factors.find(key);
        if (it == factors.end()) {
            if (factors.size() >= MAX_CACHED_FACTORS) factors.clear();
            it = factors.emplace(key, factorNormalMatrix()).first;
        }
        solution = it->second.solve(rhs);
    } else {
        solution = factorNormalMatrix().solve(rhs);
    }

    BoxOutcome outcome;
    for (int a = 0; a < 3; ++a)
        outcome.p[a] = static_cast<float>(centre[a]);
    double halfPower[3][4];
    for (int a = 0; a < 3; ++a) {
        halfPower[a][0] = 1.0;
        for (int k = 1; k < 4; ++k)
            halfPower[a][k] = halfPower[a][k - 1] * half[a];
    }
    for (int r = 0; r < nb; ++r) {
        const auto& e = MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis[static_cast<std::size_t>(r)])];
        const double scale = halfPower[0][e[0]] * halfPower[1][e[1]] * halfPower[2][e[2]];
        outcome.c[static_cast<std::size_t>(basis[static_cast<std::size_t>(r)])] =
            static_cast<float>(solution(r) / scale);
    }

    // RSS = sum f^2 - c.b for the least-squares solution; rms > eps proves some residual exceeds eps.
    if (!isSingleCell(box)) {
        const double rss = std::max(0.0, sumSquares - solution.dot(rhs));
        const double m = static_cast<double>(box.pointCount());
        if (rss > m * epsMax * epsMax * (1.0 + 1e-6) + 1e-9 * sumSquares) {
            outcome.accepted = false;
            outcome.exact = false;
            outcome.errCriterion = static_cast<float>(std::sqrt(rss / m));
            rssRejected = true;
        }
    }
    return outcome;
}

} // namespace vots::fit
