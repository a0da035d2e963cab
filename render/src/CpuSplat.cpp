// CpuSplat: the frame around the splat kernel: Vot order, footprints on screen, tiles and threads.
#include "CpuSplat.h"

#include "ParallelChunks.h"
#include "ShaderContract.h"
#include "VotOrder.h"

#include "vots/render/Renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace vots::render {
namespace {

// Pixels per side of the tiles whose running minimum of the max so far lets a Vot skip them whole, and
// of the rows of tiles handed to the threads in turn (every thread draws every Vot over its own rows,
// so no pixel has two writers and the threads never wait on each other).
constexpr int TILE = 16;
// Runs of Vots a frame can skip with one test: the Vots by falling bound are cut into levels of
// LEVEL_VOTS, each level put in space order (the records' own order, CpuSplat::upload) and cut into runs of
// RUN_VOTS, whose joint box and largest bound a tile refuses at once. Most Vots of a CT lie inside the
// bright skull's outline, where whole runs are refused; one by one they cost 25-40 ns each a frame
// (bench/RESULTS.md, "The MIP splat").
constexpr std::size_t LEVEL_VOTS = 4096;
constexpr std::size_t RUN_VOTS = 32;
// How many runs a thread draws between two looks at whether the frame is still wanted.
constexpr std::size_t RUNS_PER_LOOK = 64;

// Pixel centres X + 0.5 counted in a footprint lie within this margin of its edge: rounding in the
// projection must never leave out a pixel whose ray meets the box (one too many only costs a clip test).
constexpr double FOOTPRINT_MARGIN = 0.05;

struct Footprint {
    int x0 = 0, x1 = -1, y0 = 0, y1 = -1; // inclusive pixel ranges, window rows (row 0 at the bottom)
};

SplatFrame frameOf(const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                   const std::optional<CellDomain>& domain, const std::array<int, 3>& cells, int width,
                   int height) {
    SplatFrame f;
    f.width = width;
    f.height = height;
    for (std::size_t k = 0; k < 16; ++k)
        f.clipToIndex[k] = static_cast<float>(m.clipToIndex[k]);
    if (slab) {
        f.slabOn = true;
        for (int a = 0; a < 3; ++a)
            f.slabNormal[a] = static_cast<float>(slab->normal[static_cast<std::size_t>(a)]);
        f.slabOffset = static_cast<float>(slab->offset);
        f.slabLo = static_cast<float>(slab->lo);
        f.slabHi = static_cast<float>(slab->hi);
    }
    const CellDomain inGrid = domainInGrid(domain, cells);
    if (inGrid.lo != std::array<int, 3>{0, 0, 0} || inGrid.hi != cells) {
        f.domainOn = true;
        for (std::size_t a = 0; a < 3; ++a) {
            f.domainLo[a] = static_cast<float>(inGrid.lo[a]) - CLIP_SLACK;
            f.domainHi[a] = static_cast<float>(inGrid.hi[a]) + CLIP_SLACK;
        }
    }
    return f;
}

// The pixels whose centres the box can cover: an affine map (orthographic) takes the box's centre and
// half sides; a perspective one its eight corners, or the whole image when a corner is behind the eye.
class FootprintMap {
public:
    FootprintMap(const CameraMatrices& m, int width, int height) : mWidth(width), mHeight(height) {
        const auto& t = m.indexToClip;
        mAffine = t[3] == 0.0 && t[7] == 0.0 && t[11] == 0.0 && t[15] == 1.0;
        for (int k = 0; k < 16; ++k) {
            mToClip[k] = t[static_cast<std::size_t>(k)];
            mToClipF[k] = static_cast<float>(mToClip[k]);
        }
    }

    Footprint of(const CpuSplat::Placement& v) const {
        if (mAffine) {
            float cx = mToClipF[12], cy = mToClipF[13], ex = 0.f, ey = 0.f;
            for (int a = 0; a < 3; ++a) {
                cx += mToClipF[4 * a] * v.centre[a], cy += mToClipF[4 * a + 1] * v.centre[a];
                ex += std::fabs(mToClipF[4 * a]) * v.half[a],
                    ey += std::fabs(mToClipF[4 * a + 1]) * v.half[a];
            }
            return clamped(toPixels(cx - ex, mWidth), toPixels(cx + ex, mWidth), toPixels(cy - ey, mHeight),
                           toPixels(cy + ey, mHeight));
        }
        double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
        for (int k = 0; k < 8; ++k) {
            double p[3];
            for (int a = 0; a < 3; ++a)
                p[a] = double(v.centre[a]) + ((k >> a) & 1 ? v.half[a] : -v.half[a]);
            double clip[4];
            for (int r = 0; r < 4; ++r)
                clip[r] = mToClip[r] * p[0] + mToClip[4 + r] * p[1] + mToClip[8 + r] * p[2] + mToClip[12 + r];
            if (clip[3] <= 1e-9) return {0, mWidth - 1, 0, mHeight - 1};
            const double sx = toPixels(clip[0] / clip[3], mWidth), sy = toPixels(clip[1] / clip[3], mHeight);
            x0 = std::min(x0, sx), x1 = std::max(x1, sx), y0 = std::min(y0, sy), y1 = std::max(y1, sy);
        }
        return clamped(x0, x1, y0, y1);
    }

private:
    static double toPixels(double ndc, int size) { return (ndc * 0.5 + 0.5) * size; }
    Footprint clamped(double x0, double x1, double y0, double y1) const {
        return {firstCentre(x0), std::min(mWidth - 1, lastCentre(x1)), firstCentre(y0),
                std::min(mHeight - 1, lastCentre(y1))};
    }
    // floor and ceil by conversion: the baseline x86-64 has no rounding instruction, and a call each
    // was a fifth of what a Vot the frame skips costs. Arguments are clamped into int's range first.
    static int floorOf(double v) {
        v = std::clamp(v, -1e9, 1e9);
        const int i = static_cast<int>(v);
        return v < i ? i - 1 : i;
    }
    // The first and last pixel whose centre (index + 0.5) lies in [lo, hi], widened by the margin.
    static int firstCentre(double lo) { return std::max(0, -floorOf(-(lo - 0.5 - FOOTPRINT_MARGIN))); }
    static int lastCentre(double hi) { return std::max(-1, floorOf(hi - 0.5 + FOOTPRINT_MARGIN)); }

    double mToClip[16];
    float mToClipF[16]; // the affine map in float: its rounding is far inside FOOTPRINT_MARGIN
    int mWidth, mHeight;
    bool mAffine = true;
};

} // namespace

void CpuSplat::upload(const std::vector<GpuVot>& vots) {
    std::vector<std::size_t> order = boundOrder(vots);
    // The records come in space order (VotRenderer's upload, spatialOrder), so a level's indices in
    // ascending order put its Vots in space order.
    for (std::size_t level = 0; level < order.size(); level += LEVEL_VOTS)
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(level),
                  order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), level + LEVEL_VOTS)));
    mVots.resize(vots.size());
    mPlacements.resize(vots.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const GpuVot& g = vots[order[i]];
        SplatVot& s = mVots[i];
        Placement& place = mPlacements[i];
        for (int a = 0; a < 3; ++a) {
            s.lo[a] = g.lo[a] - CLIP_SLACK;
            s.hi[a] = g.hi[a] + CLIP_SLACK;
            s.p[a] = g.p[a];
            place.centre[a] = 0.5f * (s.lo[a] + s.hi[a]);
            place.half[a] = 0.5f * (s.hi[a] - s.lo[a]);
        }
        std::copy(std::begin(g.c), std::end(g.c), s.c);
        place.upper = g.upperBound;
        place.unused = 0.f;
    }
    mRuns.resize((vots.size() + RUN_VOTS - 1) / RUN_VOTS);
    for (std::size_t r = 0; r < mRuns.size(); ++r) {
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        float upper = -INFINITY;
        for (std::size_t n = r * RUN_VOTS; n < std::min(vots.size(), (r + 1) * RUN_VOTS); ++n) {
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], mVots[n].lo[a]);
                hi[a] = std::max(hi[a], mVots[n].hi[a]);
            }
            upper = std::max(upper, mPlacements[n].upper);
        }
        Placement& run = mRuns[r];
        for (int a = 0; a < 3; ++a) {
            run.centre[a] = 0.5f * (lo[a] + hi[a]);
            // Rounded up: the joint box must hold every box of the run.
            run.half[a] = std::nextafter(0.5f * (hi[a] - lo[a]), INFINITY);
        }
        run.upper = upper;
        run.unused = 0.f;
    }
}

FloatImage CpuSplat::draw(const CameraMatrices& matrices, const std::optional<SlabPlanes>& slab,
                          const std::optional<CellDomain>& domain, const std::array<int, 3>& cells, int width,
                          int height, bool culling, const std::function<bool()>& abandoned,
                          FrameStats& stats) const {
    // Window rows, row 0 at the bottom; flipped into the image at the end.
    std::vector<float> best(static_cast<std::size_t>(width) * height, -INFINITY);
    const CellDomain inGrid = domainInGrid(domain, cells);
    const int tilesX = (width + TILE - 1) / TILE, tileRows = (height + TILE - 1) / TILE;
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, tileRows);
    std::atomic<bool> stop{false};
    std::vector<std::size_t> drawn(threads, 0);
    if (!inGrid.empty()) {
        const SplatFrame frame = frameOf(matrices, slab, domain, cells, width, height);
        const FootprintMap footprints(matrices, width, height);
        parallelTasks(threads, [&](std::size_t part) {
            // Per tile: the least max so far of its pixels (only this thread's rows are kept up to date).
            std::vector<float> tileLeast(static_cast<std::size_t>(tilesX) * tileRows, -INFINITY);
            // Which rows of tiles are this thread's (a table: a division per Vot showed in its cost).
            std::vector<char> mine(static_cast<std::size_t>(tileRows));
            for (int ty = 0; ty < tileRows; ++ty)
                mine[static_cast<std::size_t>(ty)] = static_cast<std::size_t>(ty) % threads == part;
            // Whether a tile of this thread's rows under the footprint is below `upper`.
            auto anyTileBelow = [&](const Footprint& fp, float upper) {
                for (int ty = fp.y0 / TILE; ty <= fp.y1 / TILE; ++ty) {
                    if (!mine[static_cast<std::size_t>(ty)]) continue;
                    for (int tx = fp.x0 / TILE; tx <= fp.x1 / TILE; ++tx)
                        if (tileLeast[static_cast<std::size_t>(ty) * tilesX + tx] < upper) return true;
                }
                return false;
            };
            for (std::size_t r = 0; r < mRuns.size(); ++r) {
                if (r % RUNS_PER_LOOK == 0) {
                    // Only the caller's thread asks: the question need not be thread-safe.
                    if (part == 0 && abandoned && abandoned()) stop = true;
                    if (stop.load(std::memory_order_relaxed)) return;
                }
                const Footprint runPrint = footprints.of(mRuns[r]);
                if (runPrint.x0 > runPrint.x1 || runPrint.y0 > runPrint.y1) continue;
                if (culling && !anyTileBelow(runPrint, mRuns[r].upper)) continue;
                for (std::size_t n = r * RUN_VOTS; n < std::min(mVots.size(), (r + 1) * RUN_VOTS); ++n) {
                    const Placement& place = mPlacements[n];
                    const float upper = culling ? place.upper : INFINITY; // no pixel or tile holds +inf
                    const Footprint fp = footprints.of(place);
                    if (fp.x0 > fp.x1 || fp.y0 > fp.y1) continue;
                    bool touched = false;
                    for (int ty = fp.y0 / TILE; ty <= fp.y1 / TILE; ++ty) {
                        if (!mine[static_cast<std::size_t>(ty)]) continue;
                        const int ya = std::max(fp.y0, ty * TILE), yb = std::min(fp.y1, ty * TILE + TILE - 1);
                        for (int tx = fp.x0 / TILE; tx <= fp.x1 / TILE; ++tx) {
                            float& least = tileLeast[static_cast<std::size_t>(ty) * tilesX + tx];
                            if (least >= upper) continue;
                            touched = true;
                            const int xa = std::max(fp.x0, tx * TILE),
                                      xb = std::min(fp.x1, tx * TILE + TILE - 1);
                            if (!splatVot(frame, mVots[n], upper, best.data(), xa, xb, ya, yb)) continue;
                            float m = INFINITY;
                            for (int y = ty * TILE; y < std::min(height, ty * TILE + TILE); ++y)
                                for (int x = tx * TILE; x < std::min(width, tx * TILE + TILE); ++x)
                                    m = std::min(m, best[static_cast<std::size_t>(y) * width + x]);
                            least = m;
                        }
                    }
                    if (touched) ++drawn[part];
                }
            }
        });
    }
    if (stop) throw FrameAbandoned();
    stats.votsDrawn = *std::max_element(drawn.begin(), drawn.end());
    stats.batches = 0;
    FloatImage image{width, height, std::vector<float>(best.size())};
    for (int y = 0; y < height; ++y)
        std::copy_n(&best[static_cast<std::size_t>(height - 1 - y) * width], width,
                    &image.pixels[static_cast<std::size_t>(y) * width]);
    return image;
}

} // namespace vots::render
