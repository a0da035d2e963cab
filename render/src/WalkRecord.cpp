// Packing a Vot into the walk's 64-byte record: re-expansion around the box centre, box coordinates,
// 16-bit higher-order terms.
#include "WalkRecord.h"

#include "ShaderContract.h"

#include "VotWalkGrid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace vots::render {

namespace {

constexpr double BINOMIAL[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
constexpr std::size_t FIRST_QUANTISED = 4; // monomials 4..19: degree 2 and 3
constexpr double QUANTUM_STEPS = 32767.0;  // the largest term is +-32767 q
// The shader clips rays to the box grown by CLIP_SLACK cells; on a box side of one cell that takes |u| to
// 1 + 2 CLIP_SLACK, and a cubic monomial to (1 + 2 CLIP_SLACK)^3, which CLIP_GROWTH must cover.
constexpr double CLIP_GROWTH = 1.001;
static_assert((1.0 + 2.0 * CLIP_SLACK) * (1.0 + 2.0 * CLIP_SLACK) * (1.0 + 2.0 * CLIP_SLACK) <= CLIP_GROWTH);

std::uint32_t floatBits(float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits;
}

float bitsFloat(std::uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

// The coefficients of `vot` around its box centre m in box units u = (X - m) / h, h the half sides.
std::array<double, fit::MONOMIAL_COUNT> boxUnitCoefficients(const fit::Vot& vot) {
    // X - p = h u + delta with delta = m - p: each (h u + delta)^e expands binomially, per axis.
    double hPow[3][4], deltaPow[3][4];
    bool centred = true;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const double lo = vot.box.lo[axis], hi = vot.box.hi[axis];
        const double h = 0.5 * (hi - lo), delta = 0.5 * (lo + hi) - double(vot.p[axis]);
        centred = centred && delta == 0.0;
        hPow[axis][0] = deltaPow[axis][0] = 1.0;
        for (int e = 1; e < 4; ++e) {
            hPow[axis][e] = hPow[axis][e - 1] * h;
            deltaPow[axis][e] = deltaPow[axis][e - 1] * delta;
        }
    }
    std::array<double, fit::MONOMIAL_COUNT> d{};
    // Unrolled over the monomials at compile time, as in VotBounds.cpp: an upload packs every Vot.
    auto addMonomial = [&]<std::size_t A>(std::integral_constant<std::size_t, A>) {
        constexpr auto e = fit::MONOMIAL_EXPONENTS[A];
        const double c = vot.c[A];
        if (centred) { // the fast fit's Vots: only the scaling
            d[A] += c * hPow[0][e[0]] * hPow[1][e[1]] * hPow[2][e[2]];
            return;
        }
        for (int k = 0; k <= e[2]; ++k)
            for (int j = 0; j <= e[1]; ++j)
                for (int i = 0; i <= e[0]; ++i)
                    d[static_cast<std::size_t>(fit::monomialIndex(i, j, k))] +=
                        c * BINOMIAL[e[0]][i] * hPow[0][i] * deltaPow[0][e[0] - i] * BINOMIAL[e[1]][j] *
                        hPow[1][j] * deltaPow[1][e[1] - j] * BINOMIAL[e[2]][k] * hPow[2][k] *
                        deltaPow[2][e[2] - k];
    };
    [&]<std::size_t... A>(std::index_sequence<A...>) {
        (addMonomial(std::integral_constant<std::size_t, A>{}), ...);
    }
    (std::make_index_sequence<fit::MONOMIAL_COUNT>{});
    return d;
}

} // namespace

WalkRecord makeWalkRecord(const fit::Vot& vot) {
    const std::array<double, fit::MONOMIAL_COUNT> d = boxUnitCoefficients(vot);
    WalkRecord record;
    auto& w = record.words;
    packBoxCorners(w.data(), vot.box.lo, vot.box.hi);
    for (std::size_t k = 0; k < FIRST_QUANTISED; ++k)
        w[3 + k] = floatBits(static_cast<float>(d[k]));
    double largest = 0.0;
    for (std::size_t k = FIRST_QUANTISED; k < fit::MONOMIAL_COUNT; ++k)
        largest = std::max(largest, std::abs(d[k]));
    // The float quantum itself is what the shader multiplies by; the steps are rounded against it.
    const float quantum = static_cast<float>(largest / QUANTUM_STEPS);
    w[7] = floatBits(quantum);
    const double perQuantum = quantum > 0.f ? 1.0 / double(quantum) : 0.0;
    double error = 0.0;
    for (std::size_t k = FIRST_QUANTISED; k < fit::MONOMIAL_COUNT; ++k) {
        const double steps = std::clamp(std::nearbyint(d[k] * perQuantum), -32767.0, 32767.0);
        error += std::abs(d[k] - steps * quantum);
        const std::size_t slot = k - FIRST_QUANTISED;
        w[8 + slot / 2] |= (static_cast<std::uint32_t>(static_cast<int>(steps)) & 0xffffu)
                           << (16 * (slot % 2));
    }
    record.maxError = error * CLIP_GROWTH;
    return record;
}

std::array<double, fit::MONOMIAL_COUNT> walkRecordCoefficients(const WalkRecord& record) {
    const auto& w = record.words;
    std::array<double, fit::MONOMIAL_COUNT> d{};
    for (std::size_t k = 0; k < FIRST_QUANTISED; ++k)
        d[k] = bitsFloat(w[3 + k]);
    const double quantum = bitsFloat(w[7]);
    for (std::size_t k = FIRST_QUANTISED; k < fit::MONOMIAL_COUNT; ++k) {
        const std::size_t slot = k - FIRST_QUANTISED;
        const auto half = static_cast<std::uint16_t>(w[8 + slot / 2] >> (16 * (slot % 2)));
        d[k] = static_cast<std::int16_t>(half) * quantum;
    }
    return d;
}

} // namespace vots::render
