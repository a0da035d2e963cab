// Rays cut to z domains of cells: the frames of a Vot-Space split in slabs composite (min, length-weighted
// mean, max) to the undivided frame, with background cells, a --slab and Vots that cross the slab faces.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/CellDomain.h"
#include "vots/render/Slab.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <vector>

using namespace vots;
using namespace vots::render;

namespace {

constexpr int N = 24;
constexpr double AMPLITUDE = 100.0;
constexpr int W = 64, H = 48;
// Far below every value: a cell of another slab counted as background would set the min to it.
constexpr float BACKGROUND = -10.f * float(AMPLITUDE);

// Boxes of 4 cells, a hole of background cells [8, 16)^3 that the slab faces cut, and faces at z = 10 and
// z = 17 that cut boxes too (boxes start at multiples of 4).
fit::VotSpace spaceWithHole() {
    const test::Polynomial p = test::randomPolynomial(3, N, AMPLITUDE, 4242u);
    fit::VotSpace space = test::polynomialVotSpace(p, {N + 1, N + 1, N + 1}, 4, 0.3f);
    std::erase_if(space.vots, [](const fit::Vot& v) {
        for (int a = 0; a < 3; ++a)
            if (v.box.lo[a] < 8 || v.box.hi[a] > 16) return false;
        return true;
    });
    space.background = BACKGROUND;
    return space;
}

struct ZSplit {
    int first, end;
};
const std::vector<ZSplit> SLABS{{0, 10}, {10, 17}, {17, N}};

// The Vots whose box meets the slab's cells, as a rank of `vots render` under mpirun keeps them.
fit::VotSpace votsMeeting(fit::VotSpace space, ZSplit slab) {
    std::erase_if(space.vots,
                  [&](const fit::Vot& v) { return v.box.lo[2] >= slab.end || v.box.hi[2] <= slab.first; });
    return space;
}

struct Frames {
    FloatImage min, mean, max, length;
};

Frames framesOf(VotRenderer& renderer, const Camera& cam, const std::optional<Slab>& slab) {
    return {renderer.render(cam, W, H, RenderOptions{RenderMode::MinIp, slab}),
            renderer.render(cam, W, H, RenderOptions{RenderMode::Aip, slab}),
            renderer.render(cam, W, H, RenderOptions{RenderMode::Mip, slab}),
            renderer.rayLengths(cam, W, H, slab)};
}

// The composite of the slabs' frames, as rank 0 forms it: min and max over the slabs that take anything,
// the mean weighted by each slab's length.
Frames composite(const std::vector<Frames>& parts) {
    Frames out = parts.front();
    for (std::size_t i = 0; i < out.min.pixels.size(); ++i) {
        float lo = INFINITY, hi = -INFINITY, length = 0.f;
        double integral = 0.0, lengthSum = 0.0;
        for (const Frames& f : parts) {
            if (f.min.pixels[i] != -INFINITY) lo = std::min(lo, f.min.pixels[i]);
            hi = std::max(hi, f.max.pixels[i]);
            if (std::isfinite(f.mean.pixels[i]) && f.length.pixels[i] > 0.f) {
                integral += double(f.mean.pixels[i]) * f.length.pixels[i];
                lengthSum += f.length.pixels[i];
            }
            length += f.length.pixels[i];
        }
        out.min.pixels[i] = lo == INFINITY ? -INFINITY : lo;
        out.max.pixels[i] = hi;
        out.mean.pixels[i] = lengthSum > 0.0 ? static_cast<float>(integral / lengthSum) : -INFINITY;
        out.length.pixels[i] = length;
    }
    return out;
}

void expectClose(const FloatImage& got, const FloatImage& want, double tolerance, const char* what) {
    const test::ImageComparison c = test::compareImages(got, want, tolerance);
    EXPECT_EQ(c.finiteMismatch, 0u) << what;
    EXPECT_EQ(c.beyondTolerance, 0u) << what << ": worst " << c.worst;
    std::cout << what << ": " << c.bitIdentical << " of " << want.pixels.size()
              << " pixels bit-identical, worst " << c.worst << "\n";
}

class CellDomains : public ::testing::TestWithParam<Projection> {};

} // namespace

TEST_P(CellDomains, SlabsOfCellsCompositeToTheUndividedFrame) {
    test::glContext();
    const fit::VotSpace whole = spaceWithHole();
    const Camera cam = test::obliqueCamera(GetParam());
    // The max by the walk and by the splat (both cut rays to a domain); the min and mean always walk.
    for (const auto mipBy : {VotRenderer::Strategy::Walk, VotRenderer::Strategy::Splat})
        for (const std::optional<Slab>& slab : {std::optional<Slab>{}, std::optional<Slab>{Slab{1.5, 9.0}}}) {
            VotRenderer renderer;
            renderer.setStrategy(mipBy);
            renderer.upload(whole);
            const Frames undivided = framesOf(renderer, cam, slab);
            std::vector<Frames> parts, leaky;
            for (const ZSplit& s : SLABS) {
                VotRenderer rank;
                rank.setStrategy(mipBy);
                rank.upload(votsMeeting(whole, s));
                leaky.push_back(
                    framesOf(rank, cam, slab)); // whole rays: the other slabs' cells are background
                rank.setRayDomain(CellDomain{{0, 0, s.first}, {N, N, s.end}});
                parts.push_back(framesOf(rank, cam, slab));
            }
            const Frames joined = composite(parts);
            // The min takes each piece's min, and the pieces partition the ray at the same plane crossings;
            // a Vot cut by a face is expanded from the face, not its box entry, which may move a value by a
            // few ulps (values reach 10 amplitudes here).
            expectClose(joined.min, undivided.min, 1e-5 * AMPLITUDE, slab ? "min, slab" : "min");
            expectClose(joined.max, undivided.max, 1e-5 * AMPLITUDE, slab ? "max, slab" : "max");
            // Background x length and the Vots' integrals, split at the faces and summed in another order.
            expectClose(joined.mean, undivided.mean, 1e-5 * AMPLITUDE, slab ? "mean, slab" : "mean");
            expectClose(joined.length, undivided.length, 1e-4, slab ? "length, slab" : "length");
            std::size_t seen = 0;
            for (std::size_t i = 0; i < undivided.mean.pixels.size(); ++i) {
                const bool hit = std::isfinite(undivided.mean.pixels[i]);
                EXPECT_EQ(hit, undivided.length.pixels[i] > 0.f) << i;
                seen += hit ? 1 : 0;
            }
            EXPECT_GT(seen, std::size_t(W * H / 4));
            // Without the cut, each slab's rays count the cells the others hold as background: the test above
            // would fail.
            const Frames leaked = composite(leaky);
            EXPECT_GT(test::compareImages(leaked.min, undivided.min, 1e-5 * AMPLITUDE).beyondTolerance,
                      std::size_t(W * H / 4));
            EXPECT_GT(test::compareImages(leaked.mean, undivided.mean, 1e-4 * AMPLITUDE).beyondTolerance,
                      std::size_t(W * H / 4));
        }
}

TEST_P(CellDomains, SlabsOnBoxFacesGiveTheMinBitForBit) {
    test::glContext();
    const fit::VotSpace whole = spaceWithHole();
    const Camera cam = test::obliqueCamera(GetParam());
    for (const auto mipBy : {VotRenderer::Strategy::Walk, VotRenderer::Strategy::Splat}) {
        VotRenderer renderer;
        renderer.setStrategy(mipBy);
        renderer.upload(whole);
        const Frames undivided = framesOf(renderer, cam, std::nullopt);
        // No box crosses z = 8 or 16 (a fit per slab stops its boxes at the slab faces): each Vot is drawn
        // on one slab only, over all of its part of the ray, with the arithmetic of the undivided frame.
        std::vector<Frames> parts;
        for (const ZSplit& s : std::vector<ZSplit>{{0, 8}, {8, 16}, {16, N}}) {
            VotRenderer rank;
            rank.setStrategy(mipBy);
            rank.upload(votsMeeting(whole, s));
            rank.setRayDomain(CellDomain{{0, 0, s.first}, {N, N, s.end}});
            parts.push_back(framesOf(rank, cam, std::nullopt));
        }
        const Frames joined = composite(parts);
        EXPECT_EQ(test::compareImages(joined.min, undivided.min, 0.0).bitIdentical,
                  undivided.min.pixels.size());
        EXPECT_EQ(test::compareImages(joined.max, undivided.max, 0.0).bitIdentical,
                  undivided.max.pixels.size());
    }
}

INSTANTIATE_TEST_SUITE_P(Projections, CellDomains,
                         ::testing::Values(Projection::Orthographic, Projection::Perspective));

TEST(CellDomain, TheWholeGridAsDomainChangesNoBit) {
    test::glContext();
    VotRenderer renderer;
    renderer.upload(spaceWithHole());
    const Camera cam = test::obliqueCamera(Projection::Perspective);
    for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip}) {
        renderer.setRayDomain(std::nullopt);
        const FloatImage plain = renderer.render(cam, W, H, mode);
        // Larger than the grid: cut to it.
        renderer.setRayDomain(CellDomain{{-5, 0, 0}, {N, N + 7, N}});
        const FloatImage whole = renderer.render(cam, W, H, mode);
        EXPECT_EQ(test::compareImages(whole, plain, 0.0).bitIdentical, plain.pixels.size())
            << renderModeName(mode);
    }
}

TEST(CellDomain, AnEmptyDomainTakesNothingAndBoxesRefuseOne) {
    test::glContext();
    VotRenderer renderer;
    renderer.upload(spaceWithHole());
    renderer.setRayDomain(CellDomain{{0, 0, 12}, {N, N, 12}});
    const Camera cam = test::obliqueCamera(Projection::Orthographic);
    for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip})
        for (float v : renderer.render(cam, W, H, mode).pixels)
            ASSERT_EQ(v, -INFINITY) << renderModeName(mode);
    for (float v : renderer.rayLengths(cam, W, H).pixels)
        ASSERT_EQ(v, 0.f);
    // Density, and a mip drawn by the raster strategy, see boxes, not cells.
    EXPECT_THROW(renderer.render(cam, W, H, RenderMode::Density), fit::InputError);
    renderer.setStrategy(VotRenderer::Strategy::Raster);
    EXPECT_THROW(renderer.render(cam, W, H, RenderMode::Mip), fit::InputError);
    renderer.setRayDomain(std::nullopt);
    EXPECT_NO_THROW(renderer.render(cam, W, H, RenderMode::Mip));
}

TEST(CellDomain, ComputeAndFragmentWalksCutRaysAlike) {
    // GPUs walk in the compute shader: a rank's frame and lengths must not depend on the machine. A size
    // that is no multiple of the 8x8 work groups tests the edges.
    test::glContext();
    const fit::VotSpace space = votsMeeting(spaceWithHole(), {10, 17});
    VotRenderer fragment, compute;
    fragment.setWalkShader(VotRenderer::WalkShader::Fragment);
    compute.setWalkShader(VotRenderer::WalkShader::Compute);
    for (VotRenderer* r : {&fragment, &compute}) {
        r->upload(space);
        r->setRayDomain(CellDomain{{0, 0, 10}, {N, N, 17}});
    }
    const Camera cam = test::obliqueCamera(Projection::Perspective);
    constexpr int w = 61, h = 45;
    for (RenderMode mode : {RenderMode::MinIp, RenderMode::Aip}) {
        const FloatImage a = fragment.render(cam, w, h, mode), b = compute.render(cam, w, h, mode);
        EXPECT_EQ(test::compareImages(a, b, 0.0).bitIdentical, a.pixels.size()) << renderModeName(mode);
    }
    const FloatImage a = fragment.rayLengths(cam, w, h, Slab{1.5, 9.0});
    const FloatImage b = compute.rayLengths(cam, w, h, Slab{1.5, 9.0});
    EXPECT_EQ(test::compareImages(a, b, 0.0).bitIdentical, a.pixels.size());
    std::size_t cut = 0;
    for (float v : a.pixels)
        cut += v > 0.f ? 1 : 0;
    EXPECT_GT(cut, a.pixels.size() / 8); // the slab and the domain leave a band of the image
}
