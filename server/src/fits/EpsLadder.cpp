// epsLadder: the E24 percentages of a dataset's range, and the rungs a warm-up fits around an eps.
#include "fits/EpsLadder.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace vots::server {
namespace {

// IEC 60063's E24 series: round values about 10 % apart, so the labels read "2.2 %", "2.4 %".
constexpr std::array<double, 24> E24{1.0, 1.1, 1.2, 1.3, 1.5, 1.6, 1.8, 2.0, 2.2, 2.4, 2.7, 3.0,
                                     3.3, 3.6, 3.9, 4.3, 4.7, 5.1, 5.6, 6.2, 6.8, 7.5, 8.2, 9.1};
constexpr double LOWEST_PERCENT = 0.1;
constexpr double HIGHEST_PERCENT = 50.0;
// A rung this close to the default (relative) is the default: the first fit's eps is on the ladder.
constexpr double SAME_AS_DEFAULT = 0.02;
// Rungs closer than this (relative) to an eps are that eps.
constexpr double SAME_EPS = 1e-3;

// The double nearest the decimal: scaled by an exact power of ten, never by an inexact 0.1.
double threeSignificantDigits(double value) {
    const int digits = 2 - static_cast<int>(std::floor(std::log10(value)));
    const double power = std::pow(10.0, std::abs(digits));
    return digits >= 0 ? std::round(value * power) / power : std::round(value / power) * power;
}

} // namespace

std::vector<double> epsLadder(const Dataset& dataset) {
    const double span = static_cast<double>(dataset.range[1]) - dataset.range[0];
    if (dataset.kind == DatasetKind::Vots || !(span > 0) || !std::isfinite(span)) return {};
    std::vector<double> ladder;
    for (double decade = LOWEST_PERCENT; decade < HIGHEST_PERCENT; decade *= 10)
        for (const double e : E24)
            if (e * decade < HIGHEST_PERCENT * (1 - SAME_EPS))
                ladder.push_back(threeSignificantDigits(e * decade / 100 * span));
    ladder.push_back(threeSignificantDigits(HIGHEST_PERCENT / 100 * span));
    const double def = dataset.defaultEps;
    if (def > 0) {
        std::erase_if(ladder, [&](double rung) { return std::abs(rung / def - 1) < SAME_AS_DEFAULT; });
        ladder.push_back(def);
    }
    std::sort(ladder.begin(), ladder.end());
    ladder.erase(std::unique(ladder.begin(), ladder.end()), ladder.end());
    return ladder;
}

std::vector<double> rungsAround(const std::vector<double>& ladder, double eps, std::size_t count) {
    if (!(eps > 0)) return {};
    // Above: the first rung past eps (and past its own rung); below: the last rung under it.
    auto above = std::upper_bound(ladder.begin(), ladder.end(), eps * (1 + SAME_EPS));
    auto below = std::lower_bound(ladder.begin(), ladder.end(), eps * (1 - SAME_EPS));
    std::vector<double> rungs;
    while (rungs.size() < count && (above != ladder.end() || below != ladder.begin())) {
        const bool takeAbove =
            above != ladder.end() &&
            (below == ladder.begin() || std::log(*above / eps) <= std::log(eps / *(below - 1)) + SAME_EPS);
        rungs.push_back(takeAbove ? *above++ : *--below);
    }
    return rungs;
}

std::optional<double> draftRung(const std::vector<double>& ladder, double eps, double span) {
    if (!(eps > 0) || !(span > 0)) return std::nullopt;
    // A rung's three digits put it up to 0.5 % off its percentage (10 % of 4095 is the rung 410).
    const double cap = DRAFT_EPS_CAP * span * 1.005;
    const double want = std::min(DRAFT_EPS_FACTOR * eps, cap);
    // Nearest on a log scale among the rungs not over the cap.
    std::optional<double> best;
    for (const double rung : ladder)
        if (rung <= cap && (!best || std::abs(std::log(rung / want)) < std::abs(std::log(*best / want))))
            best = rung;
    if (!best || *best < DRAFT_EPS_LEAST * eps) return std::nullopt;
    return best;
}

} // namespace vots::server
