// The float32 residual certification scan of a box: its samples, and with Certify::Cells its cell points;
// the range of the residuals over the same points.
#include "BoxFit.h"

#include "FloatBounds.h"
#include "SampleAccess.h"

#include <algorithm>
#include <cmath>

namespace vots::fit {
namespace {

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

/// Calls visit(x, y, z, residual), residual = P - sample, at the box's samples (x fastest) while it returns
/// true; false when a visit stopped the walk.
template <typename Visit>
bool visitSampleResiduals(const Volume& volume, const Box& box, const BoxOutcome& o, Visit&& visit) {
    const double px = o.p[0], py = o.p[1], pz = o.p[2];
    return visitSamples(volume, [&](const auto* values) {
        for (int z = box.lo[2]; z <= box.hi[2]; ++z) {
            const SliceCoefficients q = sliceCoefficients(o.c, z - pz);
            for (int y = box.lo[1]; y <= box.hi[1]; ++y) {
                const auto r = rowCoefficients(q, y - py);
                const auto* row = values + volume.indexOf(0, y, z);
                for (int x = box.lo[0]; x <= box.hi[0]; ++x)
                    if (!visit(x, y, z, horner(r, x - px) - static_cast<double>(sampleAsFloat(row[x]))))
                        return false;
            }
        }
        return true;
    });
}

/// The same at the cell points Certify::Cells checks, against their trilinear value (docs/DESIGN.md §3):
/// edge midpoints and cell centres, walked on the half-integer lattice so each slice and row polynomial is
/// built once.
template <typename Visit>
bool visitCellPointResiduals(const Volume& v, const Box& box, const BoxOutcome& o, Visit&& visit) {
    const double px = o.p[0], py = o.p[1], pz = o.p[2];
    const int n[3] = {2 * box.cells(0), 2 * box.cells(1), 2 * box.cells(2)};
    return visitSamples(v, [&](const auto* values) {
        for (int zi = 0; zi <= n[2]; ++zi) {
            const double z = box.lo[2] + 0.5 * zi;
            const int z0 = box.lo[2] + zi / 2, zh = zi & 1;
            const SliceCoefficients q = sliceCoefficients(o.c, z - pz);
            for (int yi = 0; yi <= n[1]; ++yi) {
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
                    if (!visit(x, y, z, horner(r, x - px) - reference)) return false;
                }
            }
        }
        return true;
    });
}

} // namespace

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
    double maxSample = 0.0;
    double maxCriterion = 0.0;
    bool violated = false;

    auto allowed = [&](double x, double y, double z, double absResidual) {
        if (absResidual <= epsMin) return true;
        return varies && absResidual <= eps.at(x, y, z);
    };

    // The sample scan ends before the last sample at the first violation when scanOnTo is 0.
    const bool stopped =
        !visitSampleResiduals(mVolume, box, outcome, [&](int x, int y, int z, double residual) {
            const double res = std::abs(residual);
            maxSample = std::max(maxSample, res);
            if (alwaysAccept || allowed(x, y, z, res)) return true;
            violated = true;
            // A violation is above eps >= 0, so scanOnTo 0 stops at the first one.
            return res <= scanOnTo;
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
        visitCellPointResiduals(mVolume, box, outcome, [&](double x, double y, double z, double residual) {
            const double res = std::abs(residual);
            maxCriterion = std::max(maxCriterion, res);
            if (alwaysAccept || allowed(x, y, z, res)) return true;
            violated = true;
            return false;
        });
    }
    outcome.accepted = !violated;
    outcome.exact = !violated && !cellsBounded;
    outcome.errSamples = roundUpToFloat(maxSample);
    outcome.errCriterion = roundUpToFloat(maxCriterion);
    if (outcome.exact) outcome.errCriterionBound = outcome.errCriterion;
}

ResidualRange BoxFitter::residualRange(const Box& box, const BoxOutcome& outcome) const {
    ResidualRange range;
    auto widen = [&](auto, auto, auto, double residual) {
        range.low = std::min(range.low, residual);
        range.high = std::max(range.high, residual);
        return true;
    };
    visitSampleResiduals(mVolume, box, outcome, widen);
    if (mCertify == Certify::Cells) visitCellPointResiduals(mVolume, box, outcome, widen);
    return range;
}

} // namespace vots::fit
