// The dense method of a minimax fit: a small box's points in one matrix, kept per thread for its shape.
#include "MinimaxSearch.h"

#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace vots::fit::minimax {
namespace {

// Shapes of at most this many samples keep their point matrix per thread, in at most this many bytes.
constexpr std::int64_t MINIMAX_SHAPE_CACHE_SAMPLES = MINIMAX_DENSE_POINTS;
constexpr std::size_t MINIMAX_SHAPE_CACHE_BYTES = std::size_t{16} << 20; // per thread, while the fit runs

using ColumnPoints = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;

/// The points of one box shape (point counts per axis, basis, certified points): their basis values in
/// one matrix and their doubled coordinates from twice the low corner. The same for every box of the
/// shape, so small shapes are kept per thread, as BoxFitter keeps its factors. The cell points' rows (seven
/// for each sample) are filled only when a search first prices them (fillCellRows).
struct ShapePoints {
    ColumnPoints phi; // points x n, column by column: the samples' rows first
    std::vector<std::array<int, 3>> offsets;
    int samples = 0;
    bool cellRowsFilled = false;
    std::optional<Whitening> whitening; // of the samples' rows, once a least-change search needs it
    void row(int point, double* out) const {
        for (Eigen::Index j = 0; j < phi.cols(); ++j)
            out[j] = phi(point, j);
    }
};

void fillRows(const Geometry& g, ShapePoints& shape, int begin, int end) {
    const Box& box = g.box();
    for (int row = begin; row < end; ++row) {
        const auto& o = shape.offsets[static_cast<std::size_t>(row)];
        const Point p = g.point({2 * box.lo[0] + o[0], 2 * box.lo[1] + o[1], 2 * box.lo[2] + o[2]}, 0.0);
        for (int j = 0; j < g.n(); ++j)
            shape.phi(row, j) = p.phi[static_cast<std::size_t>(j)];
    }
}

/// The shape's points and the samples' rows.
void buildShape(const Geometry& g, Certify points, ShapePoints& out) {
    const Box& box = g.box();
    const auto count = static_cast<Eigen::Index>(pointsToFit(box, points));
    out.phi.resize(count, g.n());
    out.offsets.resize(static_cast<std::size_t>(count));
    out.samples = static_cast<int>(box.pointCount());
    out.cellRowsFilled = count == out.samples;
    out.whitening.reset();
    std::size_t row = 0;
    // The grid samples first, then (Certify::Cells) the edge midpoints and cell centres.
    for (int pass = 0; pass < (points == Certify::Cells ? 2 : 1); ++pass)
        for (int z = 0; z <= 2 * box.cells(2); ++z)
            for (int y = 0; y <= 2 * box.cells(1); ++y)
                for (int x = 0; x <= 2 * box.cells(0); ++x) {
                    const int halves = (x & 1) + (y & 1) + (z & 1);
                    if (pass == 0 ? halves != 0 : !isCellPoint(halves)) continue;
                    out.offsets[row++] = {x, y, z};
                }
    fillRows(g, out, 0, out.samples);
}

void fillCellRows(const Geometry& g, ShapePoints& shape) {
    if (shape.cellRowsFilled) return;
    fillRows(g, shape, shape.samples, static_cast<int>(shape.offsets.size()));
    shape.cellRowsFilled = true;
}

ShapePoints& shapeOf(const Geometry& g, Certify points) {
    const Box& box = g.box();
    thread_local ShapePoints scratch;
    if (box.pointCount() > MINIMAX_SHAPE_CACHE_SAMPLES || box.points(0) > 255 || box.points(1) > 255 ||
        box.points(2) > 255) {
        buildShape(g, points, scratch);
        return scratch;
    }
    thread_local absl::flat_hash_map<std::uint64_t, std::unique_ptr<ShapePoints>> shapes;
    thread_local std::size_t shapeBytes = 0;
    const std::uint64_t key = std::uint64_t{g.mask()} << 26 | std::uint64_t{points == Certify::Cells} << 24 |
                              std::uint64_t(box.points(0)) << 16 | std::uint64_t(box.points(1)) << 8 |
                              std::uint64_t(box.points(2));
    auto it = shapes.find(key);
    if (it == shapes.end()) {
        auto shape = std::make_unique<ShapePoints>();
        buildShape(g, points, *shape);
        const std::size_t bytes = static_cast<std::size_t>(shape->phi.size()) * sizeof(double) +
                                  shape->offsets.size() * sizeof(shape->offsets[0]) + sizeof(Whitening);
        if (shapeBytes + bytes > MINIMAX_SHAPE_CACHE_BYTES) {
            shapes.clear();
            shapeBytes = 0;
        }
        shapeBytes += bytes;
        it = shapes.emplace(key, std::move(shape)).first;
    }
    return *it->second;
}

/// The values at the shape's points [begin, end) in this box: the samples, or the trilinear values at cell
/// points.
void gatherValues(const Volume& volume, const Box& box, const ShapePoints& shape, int begin, int end,
                  Eigen::VectorXd& f) {
    visitSamples(volume, [&](const auto* values) {
        for (int k = begin; k < end; ++k) {
            const auto& o = shape.offsets[static_cast<std::size_t>(k)];
            f(k) = latticeValue(volume, values, 2 * box.lo[0] + o[0], 2 * box.lo[1] + o[1],
                                2 * box.lo[2] + o[2]);
        }
    });
}

/// The largest |v_i| and the first i that holds it, as maxCoeff(&i) finds them, but in a vectorised pass and
/// a scan that stops there.
template <typename V> double largestMagnitude(const V& v, Eigen::Index& at) {
    const double largest = v.cwiseAbs().maxCoeff();
    at = 0;
    while (at + 1 < v.size() && !(std::abs(v(at)) == largest))
        ++at;
    return largest;
}

/// The dense method's points as Exchange::start reads candidates: rows of the shape in a given order.
struct RowList {
    const ShapePoints& shape;
    const Box& box;
    const Eigen::VectorXd& values;
    const std::vector<int>& order;
    int count;
    int size() const { return count; }
    void phi(int k, double* out) const { shape.row(order[static_cast<std::size_t>(k)], out); }
    double f(int k) const { return values(order[static_cast<std::size_t>(k)]); }
    std::uint64_t key(int k) const { return rowKey(order[static_cast<std::size_t>(k)]); }
    std::uint64_t rowKey(int row) const {
        const auto& o = shape.offsets[static_cast<std::size_t>(row)];
        return keyOf({2 * box.lo[0] + o[0], 2 * box.lo[1] + o[1], 2 * box.lo[2] + o[2]});
    }
};

/// Up to `most` of the points [0, r.size()) whose |r| passes `level`, worst first (ties: the lower index).
int worstBeyond(const Eigen::VectorXd& r, double level, int most, int* out) {
    double magnitude[LEAST_CHANGE_PINS_PER_ROUND];
    int count = 0;
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const double a = std::abs(r(i));
        if (!(a > level) || (count == most && a <= magnitude[count - 1])) continue;
        int at = count < most ? count++ : count - 1;
        for (; at > 0 && magnitude[at - 1] < a; --at) {
            magnitude[at] = magnitude[at - 1];
            out[at] = out[at - 1];
        }
        magnitude[at] = a;
        out[at] = static_cast<int>(i);
    }
    return count;
}

/// A small box's points: its shape's rows (per thread) and the values there, the cell points' gathered
/// only once something prices them.
struct DenseBox {
    ShapePoints& shape;
    Eigen::VectorXd& f;
    bool cellsGathered;
    std::function<void()> gatherCells;

    DenseBox(const Volume& volume, const Geometry& g, Certify points)
        : shape(shapeOf(g, points)), f(values()), cellsGathered(false) {
        const Box& box = g.box();
        const int m = static_cast<int>(shape.offsets.size());
        const int ms = shape.samples;
        f.resize(m);
        gatherValues(volume, box, shape, 0, ms, f);
        cellsGathered = m == ms;
        gatherCells = [this, &volume, &g, m, ms] {
            if (cellsGathered) return;
            fillCellRows(g, shape);
            gatherValues(volume, g.box(), shape, ms, m, f);
            cellsGathered = true;
        };
    }
    DenseBox(const DenseBox&) = delete; // (gatherCells points at this one)
    DenseBox& operator=(const DenseBox&) = delete;
    /// The tolerances' scale, 1 + the largest |f| (a trilinear value at a cell point is a mean of samples:
    /// the samples hold the largest).
    double scale() const { return 1.0 + f.head(shape.samples).cwiseAbs().maxCoeff(); }

private:
    static Eigen::VectorXd& values() {
        thread_local Eigen::VectorXd f;
        return f;
    }
};

/// A small box's points for the least-change search: every residual in one product, as the exchange prices.
class DensePricing final : public LeastChangePricing {
public:
    DensePricing(const Geometry& g, DenseBox& box)
        : mG(g), mShape(box.shape), mF(box.f), mGatherCells(box.gatherCells), mScale(box.scale()) {}

    int beyond(const double* coefficients, double level, Point* out, double& largest) override {
        const int n = mG.n();
        const int ms = mShape.samples;
        const int m = static_cast<int>(mShape.offsets.size());
        const Eigen::Map<const Eigen::VectorXd> c(coefficients, n);
        thread_local Eigen::VectorXd r;
        r.noalias() = mF.head(ms) - mShape.phi.topRows(ms) * c;
        int rows[LEAST_CHANGE_PINS_PER_ROUND];
        int count = worstBeyond(r, level, LEAST_CHANGE_PINS_PER_ROUND, rows);
        largest = r.cwiseAbs().maxCoeff();
        int first = 0;
        if (count == 0 && m > ms && largest + cellBound(mG, coefficients, mScale) > level) {
            mGatherCells();
            r.noalias() = mF.tail(m - ms) - mShape.phi.bottomRows(m - ms) * c;
            count = worstBeyond(r, level, LEAST_CHANGE_PINS_PER_ROUND, rows);
            largest = std::max(largest, r.cwiseAbs().maxCoeff());
            first = ms;
        }
        for (int q = 0; q < count; ++q) {
            const int row = first + rows[q];
            mShape.row(row, out[q].phi.data());
            out[q].f = mF(row);
        }
        return count;
    }

private:
    const Geometry& mG;
    const ShapePoints& mShape;
    const Eigen::VectorXd& mF;
    const std::function<void()>& mGatherCells;
    double mScale;
};

} // namespace

MinimaxSolution findDense(const Volume& volume, const Geometry& g, Certify points,
                          const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target) {
    DenseBox dense(volume, g, points);
    ShapePoints& shape = dense.shape;
    if (!shape.whitening) shape.whitening = whiteningOf(g);
    DensePricing pricing(g, dense);
    return findLeastChange(g, pricing, *shape.whitening, start, target);
}

/// Every point of the box in one matrix: pricing is one product with the coefficients, and the worst
/// point enters.
MinimaxSolution fitDense(const Volume& volume, const Geometry& g, Certify points,
                         const std::array<double, MONOMIAL_COUNT>& start) {
    MinimaxSolution solution;
    const Box& box = g.box();
    const int n = g.n();
    DenseBox dense(volume, g, points);
    ShapePoints& shape = dense.shape;
    Eigen::VectorXd& f = dense.f;
    // The cell points (Certify::Cells: seven for each sample) are gathered only once some step prices them:
    // the first basis is chosen among the samples, and most searches end before the cells matter.
    const int m = static_cast<int>(shape.offsets.size());
    const int ms = shape.samples;
    thread_local Eigen::VectorXd r;
    r.resize(m);
    solution.scans = 1;
    const auto& gatherCells = dense.gatherCells;
    Vector c(n);
    for (int j = 0; j < n; ++j)
        c(j) = start[static_cast<std::size_t>(g.basis(j))];
    r.head(ms).noalias() = f.head(ms) - shape.phi.topRows(ms) * c;
    const double scale = dense.scale();

    // The first basis from the start polynomial's worst samples.
    // The points ranked worst first by |residual|, ties by row: a strict order, so selecting the few worst
    // and sorting them is the same as a partial sort, in time linear in m. Pairs in one array, so the
    // selection compares without reaching into the residuals.
    struct Ranked {
        double magnitude;
        int row;
    };
    auto worstFirst = [](const Ranked& a, const Ranked& b) {
        return a.magnitude != b.magnitude ? a.magnitude > b.magnitude : a.row < b.row;
    };
    thread_local std::vector<Ranked> ranked;
    ranked.resize(static_cast<std::size_t>(ms));
    for (int i = 0; i < ms; ++i)
        ranked[static_cast<std::size_t>(i)] = {std::abs(r(i)), i};
    thread_local std::vector<int> order;
    order.resize(static_cast<std::size_t>(ms));
    const auto rankFirst = [&](int count) {
        for (int i = 0; i < count; ++i)
            order[static_cast<std::size_t>(i)] = ranked[static_cast<std::size_t>(i)].row;
    };
    const int few = std::min(ms, 3 * n + 8);
    std::nth_element(ranked.begin(), ranked.begin() + (few - 1), ranked.end(), worstFirst);
    std::sort(ranked.begin(), ranked.begin() + few, worstFirst);
    rankFirst(few);
    Exchange exchange(n);
    if (!exchange.start(RowList{shape, box, f, order, few})) {
        if (few == ms) return solution;
        std::sort(ranked.begin() + few, ranked.end(), worstFirst);
        rankFirst(ms);
        if (!exchange.start(RowList{shape, box, f, order, ms})) return solution;
    }
    const RowList rows{shape, box, f, order, m};

    for (;;) {
        const double t = exchange.t();
        solution.lowerBound = std::max(solution.lowerBound, t);
        solution.pivots = exchange.pivots();
        const double* y = exchange.coefficients();
        for (int j = 0; j < n; ++j)
            c(j) = y[j];
        // The samples first; the cell points (far more of them) only when no sample is beyond t, and not
        // even then when the curvature bound answers for them. What enters: the worst sample while one is
        // beyond t, else the worst point.
        const double slack = MINIMAX_TOLERANCE * std::max(t, 0.0) + 1e-9 * scale;
        r.head(ms).noalias() = f.head(ms) - shape.phi.topRows(ms) * c;
        Eigen::Index worst = 0;
        const double largestSample = largestMagnitude(r.head(ms), worst);
        const bool samplesDone = largestSample <= t + slack;
        double largest = largestSample; // over every point once the cells are priced, else an upper bound
        if (m > ms && samplesDone) {
            largest = largestSample + cellBound(g, c.data(), scale);
            if (largest > t + slack) {
                gatherCells();
                r.tail(m - ms).noalias() = f.tail(m - ms) - shape.phi.bottomRows(m - ms) * c;
                Eigen::Index worstCell = 0;
                const double largestCell = largestMagnitude(r.tail(m - ms), worstCell);
                largest = std::max(largestSample, largestCell);
                if (largestCell > largestSample) worst = ms + worstCell;
            }
        }
        if (samplesDone && largest <= t + slack) {
            converged(g, c.data(), largest, solution);
            return solution;
        }
        if (exchange.pivots() >= MINIMAX_MAX_PIVOTS) return solution;
        alignas(16) double phi[MONOMIAL_COUNT] = {};
        shape.row(static_cast<int>(worst), phi);
        if (!exchange.pivot(phi, f(worst), rows.rowKey(static_cast<int>(worst)), r(worst), nullptr))
            return solution;
    }
}

} // namespace vots::fit::minimax
