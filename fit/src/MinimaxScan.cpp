// The scan method of a minimax fit: the worst residuals of each scan feed a pool the exchange prices.
#include "MinimaxSearch.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace vots::fit::minimax {
namespace {

constexpr std::size_t POOL_CAPACITY = 128;

/// The largest and smallest residual f - P per region of one scan, and where they are.
struct Extremes {
    double maxAbs = 0.0;
    double maxAbsValue = 0.0; // the largest |f| seen, for the tolerances' scale
    std::array<double, REGION_COUNT> high{}, low{};
    std::array<std::array<int, 3>, REGION_COUNT> highAt{}, lowAt{};
    void reset() {
        maxAbs = 0.0;
        high.fill(-std::numeric_limits<double>::infinity());
        low.fill(std::numeric_limits<double>::infinity());
    }
    void offer(int region, double r, const std::array<int, 3>& twice) {
        const auto k = static_cast<std::size_t>(region);
        if (r > high[k]) {
            high[k] = r;
            highAt[k] = twice;
        }
        if (r < low[k]) {
            low[k] = r;
            lowAt[k] = twice;
        }
    }
    void finish() {
        for (std::size_t k = 0; k < REGION_COUNT; ++k) {
            if (high[k] > -std::numeric_limits<double>::infinity()) maxAbs = std::max(maxAbs, high[k]);
            if (low[k] < std::numeric_limits<double>::infinity()) maxAbs = std::max(maxAbs, -low[k]);
        }
    }
};

/// Residuals of the polynomial at every grid sample of the box.
void scanSamples(const Volume& volume, const Geometry& g, const Tensor& c, bool measureValues,
                 Extremes& out) {
    const Box& box = g.box();
    const int nx = box.points(0), ny = box.points(1), nz = box.points(2);
    thread_local std::vector<double> ux;
    ux.resize(static_cast<std::size_t>(nx));
    for (int i = 0; i < nx; ++i)
        ux[static_cast<std::size_t>(i)] = g.scaled(0, 2 * (box.lo[0] + i));
    // The samples of region rx along x are [segment[rx], segment[rx + 1]).
    std::array<int, REGIONS + 1> segment{};
    for (int r = 0, i = 0; r < REGIONS; ++r) {
        segment[static_cast<std::size_t>(r)] = i;
        while (i < nx && g.region(0, 2 * (box.lo[0] + i)) == r)
            ++i;
        segment[static_cast<std::size_t>(r) + 1] = i;
    }
    out.reset();
    double maxValue = 0.0;
    visitSamples(volume, [&](const auto* values) {
        for (int k = 0; k < nz; ++k) {
            const int z = box.lo[2] + k;
            const double w = g.scaled(2, 2 * z);
            const int rz = g.region(2, 2 * z);
            double q[4][4];
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    q[a][b] = ((c[a][b][3] * w + c[a][b][2]) * w + c[a][b][1]) * w + c[a][b][0];
            for (int j = 0; j < ny; ++j) {
                const int y = box.lo[1] + j;
                const double v = g.scaled(1, 2 * y);
                const int ry = g.region(1, 2 * y);
                double r[4];
                for (int a = 0; a < 4; ++a)
                    r[a] = ((q[a][3] * v + q[a][2]) * v + q[a][1]) * v + q[a][0];
                const auto* row = values + volume.indexOf(box.lo[0], y, z);
                for (int rx = 0; rx < REGIONS; ++rx) {
                    double high = -std::numeric_limits<double>::infinity();
                    double low = std::numeric_limits<double>::infinity();
                    int highI = -1, lowI = -1;
                    for (int i = segment[static_cast<std::size_t>(rx)];
                         i < segment[static_cast<std::size_t>(rx) + 1]; ++i) {
                        const double u = ux[static_cast<std::size_t>(i)];
                        const double f = sampleAsFloat(row[i]);
                        const double res = f - (((r[3] * u + r[2]) * u + r[1]) * u + r[0]);
                        if (measureValues) maxValue = std::max(maxValue, std::abs(f));
                        if (res > high) {
                            high = res;
                            highI = i;
                        }
                        if (res < low) {
                            low = res;
                            lowI = i;
                        }
                    }
                    if (highI < 0) continue;
                    const int region = rx + REGIONS * (ry + REGIONS * rz);
                    out.offer(region, high, {2 * (box.lo[0] + highI), 2 * y, 2 * z});
                    out.offer(region, low, {2 * (box.lo[0] + lowI), 2 * y, 2 * z});
                }
            }
        }
    });
    out.maxAbsValue = maxValue;
    out.finish();
}

/// Residuals against the trilinear value at every cell point of the box (isCellPoint).
void scanCells(const Volume& volume, const Geometry& g, const Tensor& c, Extremes& out) {
    const Box& box = g.box();
    const int n[3] = {2 * box.cells(0), 2 * box.cells(1), 2 * box.cells(2)};
    out.reset();
    visitSamples(volume, [&](const auto* values) {
        for (int zi = 0; zi <= n[2]; ++zi) {
            const int tz = 2 * box.lo[2] + zi;
            const double w = g.scaled(2, tz);
            const int rz = g.region(2, tz);
            double q[4][4];
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    q[a][b] = ((c[a][b][3] * w + c[a][b][2]) * w + c[a][b][1]) * w + c[a][b][0];
            for (int yi = 0; yi <= n[1]; ++yi) {
                const int ty = 2 * box.lo[1] + yi;
                const double v = g.scaled(1, ty);
                const int ry = g.region(1, ty);
                double r[4];
                for (int a = 0; a < 4; ++a)
                    r[a] = ((q[a][3] * v + q[a][2]) * v + q[a][1]) * v + q[a][0];
                for (int xi = 0; xi <= n[0]; ++xi) {
                    if (!isCellPoint((xi & 1) + (yi & 1) + (zi & 1))) continue;
                    const int tx = 2 * box.lo[0] + xi;
                    const double u = g.scaled(0, tx);
                    const double res = latticeValue(volume, values, tx, ty, tz) -
                                       (((r[3] * u + r[2]) * u + r[1]) * u + r[0]);
                    out.offer(g.region(0, tx) + REGIONS * (ry + REGIONS * rz), res, {tx, ty, tz});
                }
            }
        }
    });
    out.finish();
}

/// A scan's worst residual of one sign in one region: how far it reaches in its own direction (r for the
/// highest, -r for the lowest) and where.
struct RankedExtreme {
    double reach;
    std::array<int, 3> twice;
};
using RankedExtremes = std::array<RankedExtreme, 2 * REGION_COUNT>;

/// The extremes that reach past `level`, farthest first (ties by position); their count.
std::size_t rankExtremes(const Extremes& e, double level, RankedExtremes& out) {
    std::size_t count = 0;
    for (std::size_t k = 0; k < REGION_COUNT; ++k) {
        if (e.high[k] > level) out[count++] = {e.high[k], e.highAt[k]};
        if (-e.low[k] > level) out[count++] = {-e.low[k], e.lowAt[k]};
    }
    std::sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count),
              [](const RankedExtreme& a, const RankedExtreme& b) {
                  return a.reach != b.reach ? a.reach > b.reach : keyOf(a.twice) < keyOf(b.twice);
              });
    return count;
}

/// Points of the scan method's pool, as Exchange::start reads candidates.
struct PointList {
    const std::vector<Point>& points;
    int size() const { return static_cast<int>(points.size()); }
    void phi(int k, double* out) const {
        const auto& phi = points[static_cast<std::size_t>(k)].phi;
        std::copy(phi.begin(), phi.end(), out);
    }
    double f(int k) const { return points[static_cast<std::size_t>(k)].f; }
    std::uint64_t key(int k) const { return points[static_cast<std::size_t>(k)].key; }
};

/// Adds the scan's worst points whose residual passes t by more than `slack` to the pool.
void addCandidates(const Volume& volume, const Geometry& g, const Extremes& e, const Exchange& exchange,
                   double slack, std::vector<Point>& pool) {
    auto add = [&](const std::array<int, 3>& twice, double sign) {
        const std::uint64_t key = keyOf(twice);
        if (exchange.inBasis(key, sign)) return;
        for (const Point& p : pool)
            if (p.key == key) return;
        if (pool.size() >= POOL_CAPACITY) pool.erase(pool.begin());
        pool.push_back(g.point(twice, referenceAt(volume, twice)));
    };
    const double t = exchange.t();
    for (std::size_t k = 0; k < REGION_COUNT; ++k) {
        if (e.high[k] > t + slack) add(e.highAt[k], 1.0);
        if (-e.low[k] > t + slack) add(e.lowAt[k], -1.0);
    }
}

/// A large box's points for the least-change search: a scan's worst residual of each sign in each region
/// are the candidates, as they are the exchange's.
class ScanPricing final : public LeastChangePricing {
public:
    ScanPricing(const Volume& volume, const Geometry& g, Certify points)
        : mVolume(volume), mG(g), mPoints(points) {}

    int beyond(const double* c, double level, Point* out, double& largest) override {
        const Tensor tensor = mG.tensor(c);
        const bool first = mScale == 0.0;
        scanSamples(mVolume, mG, tensor, first, mScan);
        if (first) mScale = 1.0 + mScan.maxAbsValue; // (the tolerances' scale, for cellBound)
        largest = mScan.maxAbs;
        if (largest <= level) {
            if (mPoints != Certify::Cells || largest + cellBound(mG, c, mScale) <= level) return 0;
            scanCells(mVolume, mG, tensor, mScan);
            largest = std::max(largest, mScan.maxAbs);
        }
        RankedExtremes ranked;
        const std::size_t taken =
            std::min<std::size_t>(rankExtremes(mScan, level, ranked), LEAST_CHANGE_PINS_PER_ROUND);
        for (std::size_t q = 0; q < taken; ++q)
            out[q] = mG.point(ranked[q].twice, referenceAt(mVolume, ranked[q].twice));
        return static_cast<int>(taken);
    }

private:
    const Volume& mVolume;
    const Geometry& mG;
    Certify mPoints;
    double mScale = 0.0;
    Extremes mScan;
};

} // namespace

MinimaxSolution findByScans(const Volume& volume, const Geometry& g, Certify points,
                            const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target) {
    ScanPricing pricing(volume, g, points);
    return findLeastChange(g, pricing, whiteningOf(g), start, target);
}

MinimaxSolution fitByScans(const Volume& volume, const Geometry& g, Certify points,
                           const std::array<double, MONOMIAL_COUNT>& start) {
    MinimaxSolution solution;
    const Box& box = g.box();
    const int n = g.n();
    // The first reference: the worst residuals of the start polynomial, then a 4x4x4 grid of samples (on
    // which the basis is independent, since a box has more than a_axis points along every axis).
    Extremes extremes;
    {
        Vector c(n);
        for (int j = 0; j < n; ++j)
            c(j) = start[static_cast<std::size_t>(g.basis(j))];
        scanSamples(volume, g, g.tensor(c.data()), true, extremes);
    }
    const double scale = 1.0 + extremes.maxAbsValue;
    const double pivotSlack = 1e-10 * scale;
    std::vector<Point> candidates;
    {
        // (Every extreme: a region's highest and lowest residual are finite once it holds a sample.)
        RankedExtremes ranked;
        const std::size_t count = rankExtremes(extremes, -std::numeric_limits<double>::infinity(), ranked);
        auto add = [&](const std::array<int, 3>& twice) {
            const std::uint64_t key = keyOf(twice);
            for (const Point& p : candidates)
                if (p.key == key) return;
            candidates.push_back(g.point(twice, referenceAt(volume, twice)));
        };
        for (std::size_t k = 0; k < count; ++k)
            add(ranked[k].twice);
        std::array<std::array<int, 4>, 3> grid{};
        std::array<int, 3> gridCount{};
        for (int a = 0; a < 3; ++a) {
            const int pts = box.points(a);
            gridCount[a] = std::min(4, pts);
            for (int k = 0; k < gridCount[a]; ++k)
                grid[a][static_cast<std::size_t>(k)] =
                    box.lo[a] + (pts <= 4 ? k : static_cast<int>(std::lround(k * (pts - 1) / 3.0)));
        }
        for (int k = 0; k < gridCount[2]; ++k)
            for (int j = 0; j < gridCount[1]; ++j)
                for (int i = 0; i < gridCount[0]; ++i)
                    add({2 * grid[0][static_cast<std::size_t>(i)], 2 * grid[1][static_cast<std::size_t>(j)],
                         2 * grid[2][static_cast<std::size_t>(k)]});
    }
    Exchange exchange(n);
    solution.scans = 1;
    if (!exchange.start(PointList{candidates})) return solution;

    std::vector<Point> pool;
    for (;;) {
        solution.lowerBound = std::max(solution.lowerBound, exchange.t());
        solution.pivots = exchange.pivots();
        // Price the pool: the largest reduced cost |r| - t enters.
        double bestGain = pivotSlack;
        std::size_t best = pool.size();
        double bestResidual = 0.0;
        for (std::size_t k = 0; k < pool.size(); ++k) {
            const double r = exchange.residual(pool[k].phi.data(), pool[k].f);
            if (std::abs(r) - exchange.t() > bestGain) {
                bestGain = std::abs(r) - exchange.t();
                best = k;
                bestResidual = r;
            }
        }
        if (best < pool.size()) {
            if (exchange.pivots() >= MINIMAX_MAX_PIVOTS) return solution;
            const Point entering = pool[best];
            pool[best] = pool.back();
            pool.pop_back();
            Point left;
            if (!exchange.pivot(entering.phi.data(), entering.f, entering.key, bestResidual, &left))
                return solution;
            if (pool.size() >= POOL_CAPACITY) pool.erase(pool.begin());
            pool.push_back(left);
            continue;
        }
        // No pool point violates t: scan the box.
        if (solution.scans >= MINIMAX_MAX_SCANS) return solution;
        ++solution.scans;
        const double t = exchange.t();
        const double slack = MINIMAX_TOLERANCE * std::max(t, 0.0) + 1e-9 * scale;
        const Tensor c = g.tensor(exchange.coefficients());
        scanSamples(volume, g, c, false, extremes);
        const bool samplesDone = extremes.maxAbs <= t + slack;
        if (!samplesDone) {
            addCandidates(volume, g, extremes, exchange, pivotSlack, pool);
            continue;
        }
        double worst = extremes.maxAbs;
        Extremes cells;
        if (points == Certify::Cells) {
            // The curvature bound, or else the scan, for the cell points.
            worst = extremes.maxAbs + cellBound(g, exchange.coefficients(), scale);
            if (worst > t + slack) {
                ++solution.scans;
                scanCells(volume, g, c, cells);
                worst = std::max(extremes.maxAbs, cells.maxAbs);
            }
        }
        if (worst <= t + slack) {
            converged(g, exchange.coefficients(), worst, solution);
            return solution;
        }
        addCandidates(volume, g, cells, exchange, pivotSlack, pool);
    }
}

} // namespace vots::fit::minimax
