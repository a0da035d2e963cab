// Least-squares fit of a box from separable moment sums, and the float32 residual certification scan.
#include "BoxFit.h"

#include "Minimax.h"
#include "SampleAccess.h"

#include <Eigen/Dense>
#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <cmath>

namespace vots::fit {
namespace {

constexpr std::size_t MAX_CACHED_FACTORS = 4096; // box shapes per thread (~3.5 KB each)

bool isSingleCell(const Box& box) {
    return box.cells(0) == 1 && box.cells(1) == 1 && box.cells(2) == 1;
}

/// The polynomial restricted to a slice z = const: q[k][l] multiplies dx^k dy^l.
using SliceCoefficients = std::array<std::array<double, 4>, 4>;

SliceCoefficients sliceCoefficients(const std::array<float, MONOMIAL_COUNT>& c, double dz) {
    SliceCoefficients q{};
    const double pz[4] = {1.0, dz, dz * dz, dz * dz * dz};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& a = MONOMIAL_EXPONENTS[i];
        q[static_cast<std::size_t>(a[0])][static_cast<std::size_t>(a[1])] +=
            static_cast<double>(c[i]) * pz[a[2]];
    }
    return q;
}

/// Row polynomial in dx for fixed (dy, dz): r[k] = sum_l q[k][l] dy^l.
std::array<double, 4> rowCoefficients(const SliceCoefficients& q, double dy) {
    std::array<double, 4> r{};
    for (std::size_t k = 0; k < 4; ++k)
        r[k] = ((q[k][3] * dy + q[k][2]) * dy + q[k][1]) * dy + q[k][0];
    return r;
}

double horner(const std::array<double, 4>& r, double dx) {
    return ((r[3] * dx + r[2]) * dx + r[1]) * dx + r[0];
}

/// max |Pxx|, |Pyy|, |Pzz| and |Pxx + Pyy + Pzz| over the box. A cubic's second derivatives are affine in
/// position, so each takes its largest magnitude at a corner of the box.
double maxSecondDerivative(const Box& box, const std::array<float, MONOMIAL_COUNT>& c,
                           const std::array<float, 3>& p) {
    // Each second derivative as g0 + gx dx + gy dy + gz dz: row 0..2 for axes x, y, z, row 3 the trace.
    std::array<std::array<double, 4>, 4> g{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        for (int a = 0; a < 3; ++a) {
            if (e[a] < 2) continue;
            // d^2/da^2 of c dx^ex dy^ey dz^ez leaves a term of degree <= 1 (the degree is at most 3).
            std::array<int, 3> rest = e;
            const double factor = static_cast<double>(c[i]) * e[a] * (e[a] - 1);
            rest[a] -= 2;
            const int term = rest[0] ? 1 : rest[1] ? 2 : rest[2] ? 3 : 0;
            g[static_cast<std::size_t>(a)][static_cast<std::size_t>(term)] += factor;
            g[3][static_cast<std::size_t>(term)] += factor;
        }
    }
    double largest = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        double d[3];
        for (int a = 0; a < 3; ++a)
            d[a] = ((corner >> a) & 1 ? box.hi[a] : box.lo[a]) - static_cast<double>(p[a]);
        for (const auto& row : g)
            largest = std::max(largest, std::abs(row[0] + row[1] * d[0] + row[2] * d[1] + row[3] * d[2]));
    }
    return largest;
}

/// The recorded error must stay an upper bound after narrowing to float.
float roundUpToFloat(double value) {
    const float f = static_cast<float>(value);
    return static_cast<double>(f) < value ? std::nextafter(f, INFINITY) : f;
}

/// A lower bound stays one after narrowing to float.
float roundDownToFloat(double value) {
    const float f = static_cast<float>(value);
    return static_cast<double>(f) > value ? std::nextafter(f, -INFINITY) : f;
}

/// half-extent^a of each monomial: coefficients over scaled coordinates are these times those in index units.
std::array<double, MONOMIAL_COUNT> scaledMonomialFactors(const Box& box) {
    double halfPower[3][4];
    for (int a = 0; a < 3; ++a) {
        const double half = 0.5 * (box.hi[a] - box.lo[a]);
        halfPower[a][0] = 1.0;
        for (int k = 1; k < 4; ++k)
            halfPower[a][k] = halfPower[a][k - 1] * half;
    }
    std::array<double, MONOMIAL_COUNT> factors{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        factors[i] = halfPower[0][e[0]] * halfPower[1][e[1]] * halfPower[2][e[2]];
    }
    return factors;
}

/// The field times `factor`, focus included.
EpsField scaledField(const EpsField& field, double factor) {
    std::optional<FocusRegion> focus = field.focus();
    if (focus) focus->epsFocus = static_cast<float>(focus->epsFocus * factor);
    return EpsField(static_cast<float>(field.context() * factor), focus);
}

/// A certification that rejected the coefficients found less than an earlier one of the same coefficients
/// may have (it stopped at the first point over a smaller eps): keep the larger lower bounds.
void keepWhatWasKnown(BoxOutcome& now, const BoxOutcome& before) {
    if (now.accepted) return;
    if (!now.exact && before.errCriterion > now.errCriterion) {
        now.errCriterion = before.errCriterion;
        now.exact = before.exact;
        now.errCriterionBound = before.errCriterionBound;
    }
    if (!now.samplesComplete && (before.samplesComplete || before.errSamples > now.errSamples)) {
        now.errSamples = before.errSamples;
        now.samplesComplete = before.samplesComplete;
    }
}

} // namespace

std::uint32_t basisMask(const Box& box, int degree) {
    const int n = isSingleCell(box) ? 3 : degree;
    std::uint32_t mask = 0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& a = MONOMIAL_EXPONENTS[i];
        if (monomialDegree(i) <= n && a[0] < box.points(0) && a[1] < box.points(1) && a[2] < box.points(2))
            mask |= 1u << i;
    }
    return mask;
}

FitCounters::Slot& FitCounters::mine() {
    static std::atomic<std::size_t> nextThread{0};
    thread_local const std::size_t slot = nextThread.fetch_add(1, std::memory_order_relaxed) % SLOTS;
    return mSlots[slot];
}

bool BoxFitter::holdsNoData(const Box& box) const {
    if (!mHasNoData) return false;
    for (int z = box.lo[2]; z <= box.hi[2]; ++z)
        for (int y = box.lo[1]; y <= box.hi[1]; ++y) {
            const float* row = mVolume.values.data() + mVolume.indexOf(0, y, z);
            for (int x = box.lo[0]; x <= box.hi[0]; ++x)
                if (!std::isfinite(row[x])) return true;
        }
    return false;
}

namespace {

BoxOutcome rejectedForNoData(const Box& box) {
    BoxOutcome outcome;
    outcome.exact = true; // no eps accepts it: a cache may answer it without a scan
    outcome.errCriterion = outcome.errCriterionBound = outcome.errSamples = INFINITY;
    for (int a = 0; a < 3; ++a)
        outcome.p[a] = 0.5f * static_cast<float>(box.lo[a] + box.hi[a]);
    return outcome;
}

} // namespace

BoxOutcome BoxFitter::fit(const Box& box, const EpsField& eps, FitCounters& counters) const {
    counters.addFit();
    if (holdsNoData(box)) return rejectedForNoData(box);
    bool rssRejected = false;
    BoxOutcome outcome = leastSquares(box, eps.maxOverBox(box), rssRejected);
    if (!rssRejected) certify(box, eps, outcome, counters);
    return outcome;
}

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

void BoxFitter::certify(const Box& box, const EpsField& eps, BoxOutcome& outcome, FitCounters& counters,
                        double scanOnTo) const {
    counters.addScan();
    if (holdsNoData(box)) {
        const auto coefficients = outcome.c;
        outcome = rejectedForNoData(box);
        outcome.c = coefficients;
        return;
    }
    const bool alwaysAccept = isSingleCell(box);
    const bool varies = eps.varies();
    const double epsMin = eps.minOverBox(box);
    const double px = outcome.p[0], py = outcome.p[1], pz = outcome.p[2];
    double maxSample = 0.0;
    double maxCriterion = 0.0;
    bool violated = false;
    bool stopped = false; // the sample scan ended before the last sample (at once when scanOnTo is 0)

    auto allowed = [&](double x, double y, double z, double absResidual) {
        if (absResidual <= epsMin) return true;
        return varies && absResidual <= eps.at(x, y, z);
    };

    visitSamples(mVolume, [&](const auto* values) {
        for (int z = box.lo[2]; z <= box.hi[2] && !stopped; ++z) {
            const SliceCoefficients q = sliceCoefficients(outcome.c, z - pz);
            for (int y = box.lo[1]; y <= box.hi[1] && !stopped; ++y) {
                const auto r = rowCoefficients(q, y - py);
                const auto* row = values + mVolume.indexOf(0, y, z);
                for (int x = box.lo[0]; x <= box.hi[0]; ++x) {
                    const double res =
                        std::abs(horner(r, x - px) - static_cast<double>(sampleAsFloat(row[x])));
                    maxSample = std::max(maxSample, res);
                    if (!alwaysAccept && !allowed(x, y, z, res)) {
                        violated = true;
                        // A violation is above eps >= 0, so scanOnTo 0 stops at the first one.
                        if (res > scanOnTo) {
                            stopped = true;
                            break;
                        }
                    }
                }
            }
        }
    });
    maxCriterion = maxSample;
    outcome.samplesComplete = !stopped;

    // At an edge midpoint the trilinear reference is the mean of two samples, so its residual is the
    // mean of theirs minus P''(m)/8 along the edge (exact for a cubic); at a cell centre, the mean of eight
    // minus the Hessian's trace/8. When that bound is within eps everywhere, the cell points cannot fail
    // and need no scan, about four fifths of a certify's work. The margin covers the rounding of the
    // computed residuals (far below 1e-6 of any value here), so the decision is the scan's own.
    bool cellsBounded = false;
    if (!violated && mCertify == Certify::Cells && !alwaysAccept) {
        const double bound = maxSample + maxSecondDerivative(box, outcome.c, outcome.p) / 8.0;
        const double margin = 1e-6 * (1.0 + bound);
        if (bound + margin <= epsMin) {
            cellsBounded = true;
            outcome.errCriterionBound = roundUpToFloat(bound + margin);
        }
    }
    if (!violated && mCertify == Certify::Cells && !cellsBounded) {
        // Trilinear reference at cell centres and edge midpoints (docs/DESIGN.md §3), walked on the
        // half-integer lattice so each slice and row polynomial is built once: h counts the half coordinates.
        const Volume& v = mVolume;
        const int n[3] = {2 * box.cells(0), 2 * box.cells(1), 2 * box.cells(2)};
        visitSamples(v, [&](const auto* values) {
            for (int zi = 0; zi <= n[2] && !violated; ++zi) {
                const double z = box.lo[2] + 0.5 * zi;
                const int z0 = box.lo[2] + zi / 2, zh = zi & 1;
                const SliceCoefficients q = sliceCoefficients(outcome.c, z - pz);
                for (int yi = 0; yi <= n[1] && !violated; ++yi) {
                    const int yh = yi & 1;
                    const double y = box.lo[1] + 0.5 * yi;
                    const int y0 = box.lo[1] + yi / 2;
                    const auto r = rowCoefficients(q, y - py);
                    // Only points with 1 or 3 half coordinates count (h = xh + yh + zh): one parity of xi.
                    const int xhWanted = (yh + zh) % 2 == 0 ? 1 : 0;
                    const bool centres = yh + zh == 2;
                    const auto* c00 = values + v.indexOf(0, y0, z0); // corners (y0|y0+1, z0|z0+1)
                    const auto* c10 = yh ? c00 + v.dims[0] : c00;
                    const auto* c01 = zh ? c00 + v.indexOf(0, 0, 1) : c00;
                    const auto* c11 = zh ? c10 + v.indexOf(0, 0, 1) : c10;
                    for (int xi = xhWanted; xi <= n[0]; xi += 2) {
                        const int x0 = box.lo[0] + xi / 2;
                        double reference = 0.0;
                        // The same sums in the same order (and precision) as evaluating the trilinear
                        // interpolant corner by corner, so the certified errors do not change.
                        if (centres) { // h == 3: mean of the cell's 8 corners, x fastest, then y, then z
                            for (const auto* base : {c00, c10, c01, c11}) {
                                reference += sampleAsFloat(base[x0]);
                                reference += sampleAsFloat(base[x0 + 1]);
                            }
                            reference /= 8.0;
                        } else if (xhWanted) { // edge along x
                            reference = 0.5 * (sampleAsFloat(c00[x0]) + sampleAsFloat(c00[x0 + 1]));
                        } else { // edge along y or z
                            reference = 0.5 * (sampleAsFloat(c00[x0]) + sampleAsFloat(c11[x0]));
                        }
                        const double x = box.lo[0] + 0.5 * xi;
                        const double res = std::abs(horner(r, x - px) - reference);
                        maxCriterion = std::max(maxCriterion, res);
                        if (!alwaysAccept && !allowed(x, y, z, res)) {
                            violated = true;
                            break;
                        }
                    }
                }
            }
        });
    }
    outcome.accepted = !violated;
    outcome.exact = !violated && !cellsBounded;
    outcome.errSamples = roundUpToFloat(maxSample);
    outcome.errCriterion = roundUpToFloat(maxCriterion);
    if (outcome.exact) outcome.errCriterionBound = outcome.errCriterion;
}

BoxOutcome BoxFitter::decide(const Box& box, const EpsField& eps, BoxRecord& record, FitCounters& counters,
                             bool minimax) const {
    record.changed = false;
    if (holdsNoData(box)) return rejectedForNoData(box);
    if (decideLeastSquares(box, eps, record, counters, minimax)) return record.lsq;
    if (minimax && decideMinimax(box, eps, record, counters)) return record.minimax;
    BoxOutcome rejected;
    rejected.errCriterion = std::max(record.lowerBound, record.lsq.errCriterion);
    return rejected;
}

bool BoxFitter::decideLeastSquares(const Box& box, const EpsField& eps, BoxRecord& record,
                                   FitCounters& counters, bool minimax) const {
    const bool singleCell = isSingleCell(box);
    const double epsMin = eps.minOverBox(box);
    const double epsMax = eps.maxOverBox(box);
    // The sample scan goes on past eps as far as the gate needs to know the samples' largest error.
    const double scanOnTo = singleCell || !minimax ? 0.0 : MINIMAX_GATE * minimaxTarget() * epsMax;
    BoxOutcome& o = record.lsq;
    if (!record.fitted) {
        counters.addFit();
        bool rssRejected = false;
        o = leastSquares(box, epsMax, rssRejected);
        record.fitted = record.changed = true;
        if (rssRejected) {
            // The least-squares polynomial has the smallest sum of squares: every polynomial's root mean
            // square residual, so its largest one, is at least this.
            record.lowerBound = std::max(record.lowerBound, o.errCriterion);
            return false;
        }
        certify(box, eps, o, counters, scanOnTo);
        return o.accepted;
    }
    if (record.lowerBound > epsMax) {
        counters.addCacheHit();
        return false;
    }
    if (singleCell ? o.exact : o.errCriterionBound <= epsMin) {
        counters.addCacheHit();
        o.accepted = true;
        return true;
    }
    if (o.errCriterion > epsMax) {
        counters.addCacheHit();
        return false;
    }
    // Between the bounds only a scan with the stored coefficients can decide.
    const BoxOutcome before = o;
    certify(box, eps, o, counters, scanOnTo);
    keepWhatWasKnown(o, before);
    record.changed = true;
    return o.accepted;
}

bool BoxFitter::decideMinimax(const Box& box, const EpsField& field, BoxRecord& record,
                              FitCounters& counters) const {
    if (isSingleCell(box)) return false; // (the least-squares polynomial is exact there)
    const EpsField& eps = field;
    const double gate = MINIMAX_GATE * minimaxTarget() * field.maxOverBox(box);
    BoxOutcome& lsq = record.lsq;
    if (!lsq.samplesComplete && lsq.errSamples <= gate) {
        // What the last scan of the least-squares polynomial saw (at another eps, or none after an RSS
        // reject) does not settle the gate: scan as far as it needs. The polynomial stays refused: the
        // scan before found it beyond eps.
        const BoxOutcome before = lsq;
        certify(box, eps, lsq, counters, gate);
        keepWhatWasKnown(lsq, before);
        record.changed = true;
        if (lsq.accepted) return false; // not reached; decideLeastSquares has refused these coefficients
    }
    if (lsq.errSamples > gate) return false;

    // A fit certified at the cells holds its minimax polynomials within MINIMAX_CELLS_TARGET eps at every
    // point they are fitted at (the certification itself stays at eps).
    const EpsField tight = minimaxTarget() < 1.0 ? scaledField(field, minimaxTarget()) : field;
    const double epsMin = tight.minOverBox(box);
    const double epsMax = tight.maxOverBox(box);
    if (record.lowerBound > epsMax) return false;

    // A polynomial within eps (less a margin for the rounding of its coefficients to float) ends the
    // search when its certification passes. The search meets the same polynomials at any eps, so what an
    // earlier one ended with is this eps's answer when this eps would have ended it there too.
    const double acceptBelow = epsMin * (1.0 - MINIMAX_ROUNDING_MARGIN);
    const bool noEarlierStop = record.minEarlier > acceptBelow;
    switch (record.state) {
    case BoxRecord::Minimax::Found:
        if (noEarlierStop && record.offered <= acceptBelow && record.minimax.errCriterionBound <= epsMin) {
            counters.addCacheHit();
            record.minimax.accepted = true;
            return true;
        }
        break;
    case BoxRecord::Minimax::Converged: {
        if (!noEarlierStop) break;
        BoxOutcome& m = record.minimax;
        if (m.errCriterionBound <= epsMin) {
            counters.addCacheHit();
            m.accepted = true;
            return true;
        }
        if (m.errCriterion > epsMax) {
            counters.addCacheHit();
            return false;
        }
        const BoxOutcome before = m;
        certify(box, tight, m, counters);
        keepWhatWasKnown(m, before);
        record.changed = true;
        return m.accepted;
    }
    case BoxRecord::Minimax::NotRun:
    case BoxRecord::Minimax::Above:
        break;
    }

    // The exchange starts from the stored (float) least-squares coefficients, so a later fit that finds
    // this record in a cache runs it from the same start, to the same polynomial.
    const std::uint32_t mask = basisMask(box, mDegree);
    const auto factors = scaledMonomialFactors(box);
    std::array<double, MONOMIAL_COUNT> start{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (mask & (1u << i)) start[i] = static_cast<double>(lsq.c[i]) * factors[i];
    MinimaxTarget target;
    target.stopAbove = epsMax;
    BoxOutcome found;
    target.acceptBelow = acceptBelow;
    target.accept = [&](const std::array<double, MONOMIAL_COUNT>& scaled) {
        found = BoxOutcome{};
        found.p = lsq.p;
        for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
            if (mask & (1u << i)) found.c[i] = static_cast<float>(scaled[i] / factors[i]);
        certify(box, tight, found, counters);
        return found.accepted;
    };
    const MinimaxSolution solution = fitMinimax(mVolume, box, mask, mCertify, start, target);
    record.changed = true;
    record.lowerBound = std::max(record.lowerBound, roundDownToFloat(solution.lowerBound));
    record.minEarlier = roundDownToFloat(solution.minEarlier);
    record.offered = roundUpToFloat(solution.maxResidual);
    switch (solution.result) {
    case MinimaxSolution::Result::Above:
        counters.addMinimax(solution.scans, false);
        record.state = BoxRecord::Minimax::Above;
        return false;
    case MinimaxSolution::Result::GaveUp:
        counters.addMinimax(solution.scans, false);
        record.state = BoxRecord::Minimax::NotRun; // (another eps may stop it sooner)
        return false;
    case MinimaxSolution::Result::Found:
        counters.addMinimax(solution.scans, true);
        record.state = BoxRecord::Minimax::Found;
        record.minimax = found;
        return true;
    case MinimaxSolution::Result::Converged:
        break;
    }
    record.state = BoxRecord::Minimax::Converged;
    BoxOutcome& m = record.minimax;
    m = BoxOutcome{};
    m.p = lsq.p;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (mask & (1u << i)) m.c[i] = static_cast<float>(solution.scaled[i] / factors[i]);
    certify(box, tight, m, counters);
    counters.addMinimax(solution.scans, m.accepted);
    return m.accepted;
}

} // namespace vots::fit
