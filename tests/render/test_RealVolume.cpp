// Vot MIP of a fitted real CT volume against the reference ray caster in the same run.
#include "RenderTestSupport.h"

#include "vots/fit/Fitter.h"
#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace vots;
using namespace vots::render;

namespace {

// The Cranium CT at a quarter of its in-plane resolution: 64x64x108 int16, 3.83 x 3.83 x 1.5 mm
// (anisotropic).
const test::FittedVolume& headCt() {
    static const test::FittedVolume fitted =
        test::fitForImages(std::string(VOTS_TEST_DATA_DIR) + "/cranium-quarter_64x64x108_int16.nrrd", 0.01f);
    return fitted;
}

} // namespace

TEST(RealVolume, VotMipMatchesReferenceWithinEps) {
    test::glContext();
    const test::FittedVolume& f = headCt();
    VotRenderer vots;
    vots.upload(f.space);
    GridRenderer grid;
    grid.upload(f.volume);
    const float background = fit::defaultBackground(f.volume);
    for (const char* text : {"anterior", "az=30,el=20", "left", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        const FloatImage a = vots.render(cam, 256, 256);
        const FloatImage b = grid.render(cam, 256, 256);
        // Allowance beyond eps: the reference is the exact max of the trilinear interpolant, the Vots are
        // certified at samples and cell centres only, so between those the two reconstructions differ
        // (docs/DESIGN.md §3 overshoot). Pixels whose reference max is below the fitter's background
        // threshold have no Vot by design: compare them as background.
        const double allowance = 0.01 * (f.volume.valueRange()[1] - f.volume.valueRange()[0]);
        std::size_t compared = 0, within = 0, above = 0, below = 0;
        double worst = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
            const float ref = b.pixels[i], vot = a.pixels[i];
            if (!std::isfinite(ref) || ref <= background) {
                EXPECT_TRUE(!std::isfinite(vot) || vot <= background + f.eps) << text << " pixel " << i;
                continue;
            }
            ++compared;
            const double diff = std::isfinite(vot) ? std::abs(double(vot) - ref) : 1e30;
            worst = std::max(worst, diff);
            if (diff > f.eps + allowance) (vot > ref ? ++above : ++below);
            if (diff <= f.eps + allowance) ++within;
        }
        ASSERT_GT(compared, a.pixels.size() / 10) << text;
        EXPECT_GE(double(within) / double(compared), 0.999) << text << ": worst " << worst;
        std::cout << text << ": " << compared << " pixels, " << 100.0 * within / compared << " % within eps "
                  << f.eps << " + " << allowance << ", worst " << worst << " (outside: " << above
                  << " above, " << below << " below the reference)\n";
        test::saveForInspection(a, std::string("cranium_quarter_vot_") +
                                       (text[0] == 'a' && text[1] == 'z' ? "oblique" : text));
        test::saveForInspection(b, std::string("cranium_quarter_ref_") +
                                       (text[0] == 'a' && text[1] == 'z' ? "oblique" : text));
    }
}

TEST(RealVolume, BrightestPixelIsTheDataMaximum) {
    test::glContext();
    const test::FittedVolume& f = headCt();
    VotRenderer vots;
    vots.upload(f.space);
    GridRenderer grid;
    grid.upload(f.volume);
    // Pan an anterior ortho view so the centre pixel of an odd-sized image looks straight through the
    // grid point holding the data maximum (other rays pass between samples and see less).
    const auto maxIt = std::max_element(f.volume.values.begin(), f.volume.values.end());
    const auto flat = static_cast<std::size_t>(maxIt - f.volume.values.begin());
    const int ix = int(flat % f.volume.dims[0]), iz = int(flat / (f.volume.dims[0] * f.volume.dims[1]));
    const SceneBounds b = vots.bounds();
    double radius = 0;
    for (int a = 0; a < 3; ++a)
        radius += (b.hi[a] - b.lo[a]) * (b.hi[a] - b.lo[a]);
    radius = 0.5 * std::sqrt(radius);
    Camera cam = cameraForView(ViewPreset::Anterior);
    cam.zoom = 2;
    const double halfHeight = radius / cam.zoom;
    cam.panX = (b.origin[0] + b.spacing[0] * ix - 0.5 * (b.lo[0] + b.hi[0])) / halfHeight;
    cam.panY = (b.origin[2] + b.spacing[2] * iz - 0.5 * (b.lo[2] + b.hi[2])) / halfHeight;
    const FloatImage a = vots.render(cam, 255, 255);
    const FloatImage r = grid.render(cam, 255, 255);
    EXPECT_NEAR(a.at(127, 127), *maxIt, f.eps);
    EXPECT_NEAR(r.at(127, 127), *maxIt, 1e-3 * *maxIt);
    EXPECT_LE(*std::max_element(a.pixels.begin(), a.pixels.end()), *maxIt + f.eps * 1.0001f);
}

TEST(RealVolume, CullingDoesNotChangeTheImage) {
    test::glContext();
    const test::FittedVolume& f = headCt();
    VotRenderer vots;
    vots.upload(f.space);
    for (const auto strategy :
         {VotRenderer::Strategy::Walk, VotRenderer::Strategy::Raster, VotRenderer::Strategy::Splat}) {
        vots.setStrategy(strategy);
        for (const char* text :
             {"anterior", "az=30,el=20,zoom=2,pan=0.3:-0.2", "az=10,el=5,zoom=3,proj=persp"}) {
            const Camera cam = parseCamera(text);
            vots.setCulling(true);
            const FloatImage culled = vots.render(cam, 200, 150);
            const std::size_t drawn = vots.lastFrameStats().votsDrawn;
            vots.setCulling(false);
            const FloatImage all = vots.render(cam, 200, 150);
            EXPECT_EQ(culled.pixels, all.pixels) << text;
            if (strategy == VotRenderer::Strategy::Raster)
                std::cout << text << ": culling drew " << drawn << " of " << f.space.vots.size() << " Vots\n";
        }
    }
}
