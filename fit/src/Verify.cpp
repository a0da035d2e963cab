// Independent verification: evaluates each Vot's full polynomial per sample, no shared code with BoxFit.
#include "vots/fit/Verify.h"

#include "ParallelFor.h"
#include "vots/fit/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vots::fit {
namespace {

struct Partial {
    std::size_t samples = 0, violations = 0;
    double maxError = 0.0, maxCellCentre = 0.0;
    std::string firstProblem;
};

void checkVot(const Vot& vot, std::size_t index, const Volume& volume, const EpsField& eps, Partial& out) {
    const Box& b = vot.box;
    for (int z = b.lo[2]; z <= b.hi[2]; ++z)
        for (int y = b.lo[1]; y <= b.hi[1]; ++y)
            for (int x = b.lo[0]; x <= b.hi[0]; ++x) {
                const double value = volume.at(x, y, z);
                if (!std::isfinite(value)) { // no data: no Vot may hold one (a NaN residual passes no test)
                    ++out.samples;
                    if (out.violations++ == 0)
                        out.firstProblem = "Vot " + std::to_string(index) + " holds the non-finite sample (" +
                                           std::to_string(x) + "," + std::to_string(y) + "," +
                                           std::to_string(z) + ")";
                    continue;
                }
                const double residual = std::abs(vot.evaluate({double(x), double(y), double(z)}) - value);
                const double slack = FLOAT_ALLOWANCE * (1.0 + std::abs(value));
                ++out.samples;
                out.maxError = std::max(out.maxError, residual);
                const bool withinEps = residual <= eps.at(x, y, z) + slack;
                const bool withinRecorded = residual <= static_cast<double>(vot.err) + slack;
                if (!withinEps || !withinRecorded) {
                    if (out.violations++ == 0) {
                        std::ostringstream msg;
                        msg << "Vot " << index << " misses sample (" << x << "," << y << "," << z << ") by "
                            << residual << (withinEps ? " (above its recorded err " : " (above eps ")
                            << (withinEps ? vot.err : eps.at(x, y, z)) << ")";
                        out.firstProblem = msg.str();
                    }
                }
                if (x < b.hi[0] && y < b.hi[1] && z < b.hi[2]) {
                    double trilinear = 0.0;
                    for (int c = 0; c < 8; ++c)
                        trilinear += volume.at(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
                    trilinear /= 8.0;
                    const double centre = vot.evaluate({x + 0.5, y + 0.5, z + 0.5});
                    out.maxCellCentre = std::max(out.maxCellCentre, std::abs(centre - trilinear));
                }
            }
}

} // namespace

VerifyReport verifyVotSpace(const VotSpace& space, const Volume& volume,
                            const std::optional<EpsField>& epsIn) {
    if (space.dims != volume.dims)
        throw InputError("the Vot-Space was not fitted to this volume (dims differ)");
    const EpsField eps = epsIn ? *epsIn : EpsField(space.eps);
    VerifyReport report;

    const std::array<int, 3> cells{volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1};
    auto cellIndex = [&](int i, int j, int k) {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(cells[0]) *
                   (static_cast<std::size_t>(j) + static_cast<std::size_t>(cells[1]) * k);
    };
    std::vector<std::uint8_t> covered(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0);
    for (std::size_t v = 0; v < space.vots.size(); ++v) {
        const Box& b = space.vots[v].box;
        for (int a = 0; a < 3; ++a)
            if (b.lo[a] < 0 || b.hi[a] >= volume.dims[a] || b.lo[a] >= b.hi[a])
                throw InputError("Vot " + std::to_string(v) + " has a box outside the grid or empty");
        for (int k = b.lo[2]; k < b.hi[2]; ++k)
            for (int j = b.lo[1]; j < b.hi[1]; ++j)
                for (int i = b.lo[0]; i < b.hi[0]; ++i)
                    covered[cellIndex(i, j, k)] = 1;
    }
    const float tau = space.background;
    for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
            for (int i = 0; i < cells[0]; ++i) {
                // Background: all corners below the threshold, or any corner NaN or Inf (no data).
                bool allLow = true, anyNoData = false;
                for (int c = 0; c < 8; ++c) {
                    const float corner = volume.at(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
                    allLow = allLow && corner < tau;
                    anyNoData = anyNoData || !std::isfinite(corner);
                }
                if (allLow || anyNoData) continue;
                ++report.nonBackgroundCells;
                if (!covered[cellIndex(i, j, k)] && report.uncoveredCells++ == 0)
                    report.firstProblem = "cell (" + std::to_string(i) + "," + std::to_string(j) + "," +
                                          std::to_string(k) + ") is not background and no Vot covers it";
            }

    const int threads = resolveThreadCount(0);
    std::vector<Partial> partials(static_cast<std::size_t>(threads));
    parallelFor(space.vots.size(), threads, [&](std::size_t v, int t) {
        checkVot(space.vots[v], v, volume, eps, partials[static_cast<std::size_t>(t)]);
    });
    for (const auto& p : partials) {
        report.samplesChecked += p.samples;
        report.violations += p.violations;
        report.maxError = std::max(report.maxError, p.maxError);
        report.maxCellCentreError = std::max(report.maxCellCentreError, p.maxCellCentre);
        if (report.firstProblem.empty() && !p.firstProblem.empty()) report.firstProblem = p.firstProblem;
    }
    report.ok = report.uncoveredCells == 0 && report.violations == 0;
    return report;
}

} // namespace vots::fit
