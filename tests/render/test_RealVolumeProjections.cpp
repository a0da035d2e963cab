// MIP, MinIP and average of the fitted Cranium CT, Vots against the exact grid renderer, with and without
// a thick slab: the error the tests report is the Vots' own.
#include "RenderTestSupport.h"

#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace vots;
using namespace vots::render;

namespace {

const test::FittedVolume& cranium() {
    static const test::FittedVolume fitted = test::fitForImages(VOTS_CRANIUM_HEADER, 0.02f);
    return fitted;
}

// How many compared pixels lie within eps + allowance of the grid, and the worst difference.
struct Agreement {
    std::size_t compared = 0, within = 0;
    double worst = 0;
};

} // namespace

TEST(RealVolumeProjections, VotsMatchTheExactGridInEveryModeWithAndWithoutASlab) {
    test::glContext();
    const test::FittedVolume& f = cranium();
    VotRenderer vots;
    vots.upload(f.space);
    GridRenderer grid;
    grid.upload(f.volume);
    const float background = f.space.background;
    // What the agreement of the mean below rests on: the fill lies between the data's min and the threshold.
    ASSERT_TRUE(f.space.backgroundFill);
    EXPECT_LT(*f.space.backgroundFill, background);
    EXPECT_GE(*f.space.backgroundFill, f.volume.valueRange()[0]);
    // Beyond eps: float evaluation and the 16-bit higher terms of the walk records (well under a grey
    // level of this range), nothing for interpolation: the grid is exact.
    const double allowance = 1e-3 * (f.volume.valueRange()[1] - f.volume.valueRange()[0]);
    // The slab lies 25 mm behind the centre as the camera sees it: through the back of the skull.
    for (const char* cam : {"anterior", "az=30,el=20"})
        for (const std::optional<Slab>& slab :
             {std::optional<Slab>{}, std::optional<Slab>{Slab{-25.0, 30.0}}})
            for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip}) {
                const Camera camera = parseCamera(cam);
                const RenderOptions options{mode, slab};
                const FloatImage a = vots.render(camera, 256, 256, options);
                // The Vots count background cells as the fill, the mean of the data over them: both lie
                // in [min, threshold), 1 % of the range apart at most, under eps (2 %), so the mean of
                // every ray stays within eps of the data's and compares against the data itself too.
                const FloatImage b = grid.render(camera, 256, 256, options);
                Agreement agreement, outside; // pixels above the background threshold, and below it
                for (std::size_t i = 0; i < a.pixels.size(); ++i) {
                    const float ref = b.pixels[i], vot = a.pixels[i];
                    if (!std::isfinite(ref)) {
                        EXPECT_FALSE(std::isfinite(vot)) << cam << " pixel " << i;
                        continue;
                    }
                    // Below the threshold the fit left the cells out (MIP: no Vot; MinIP: background), so
                    // the Vots can only say "background": at most background + eps, and for the min never
                    // below the data by more than eps. A whole-ray MinIP of a CT is all such pixels (air).
                    if (mode != RenderMode::Aip && ref <= background) {
                        ++outside.compared;
                        const bool low = !std::isfinite(vot) || vot <= background + f.eps + allowance;
                        const bool high = mode != RenderMode::MinIp || vot >= ref - f.eps - allowance;
                        if (low && high) ++outside.within;
                        continue;
                    }
                    ++agreement.compared;
                    const double diff = std::isfinite(vot) ? std::abs(double(vot) - ref) : 1e30;
                    agreement.worst = std::max(agreement.worst, diff);
                    if (diff <= f.eps + allowance) ++agreement.within;
                }
                const std::string what = std::string(renderModeName(mode)) + " " + cam +
                                         (slab ? " slab " + formatSlab(*slab) : std::string(" whole"));
                if (mode != RenderMode::MinIp || slab) {
                    ASSERT_GT(agreement.compared, a.pixels.size() / 20) << what;
                }
                if (agreement.compared > 0) {
                    EXPECT_GE(double(agreement.within) / double(agreement.compared), 0.999)
                        << what << ": worst " << agreement.worst;
                }
                if (outside.compared > 0) {
                    EXPECT_GE(double(outside.within) / double(outside.compared), 0.999)
                        << what << " background";
                }
                std::cout << what << ": " << agreement.compared << " pixels, "
                          << 100.0 * double(agreement.within) /
                                 double(std::max<std::size_t>(agreement.compared, 1))
                          << " % within eps " << f.eps << " + " << allowance << ", worst " << agreement.worst
                          << "; " << outside.compared << " below the background threshold, "
                          << 100.0 * double(outside.within) /
                                 double(std::max<std::size_t>(outside.compared, 1))
                          << " % as background\n";
            }
}

TEST(RealVolumeProjections, MinNeverAboveMeanNeverAboveMax) {
    test::glContext();
    const test::FittedVolume& f = cranium();
    VotRenderer vots;
    vots.upload(f.space);
    for (const std::optional<Slab>& slab : {std::optional<Slab>{}, std::optional<Slab>{Slab{-10.0, 15.0}}}) {
        const Camera camera = parseCamera("az=-40,el=15,proj=persp,zoom=1.2");
        const FloatImage lo = vots.render(camera, 192, 192, RenderOptions{RenderMode::MinIp, slab});
        const FloatImage mean = vots.render(camera, 192, 192, RenderOptions{RenderMode::Aip, slab});
        const FloatImage hi = vots.render(camera, 192, 192, RenderOptions{RenderMode::Mip, slab});
        std::size_t ordered = 0;
        for (std::size_t i = 0; i < lo.pixels.size(); ++i) {
            if (!std::isfinite(mean.pixels[i])) continue;
            // The mean's float sum of integrals rounds; a hundredth of a grey level of slack.
            EXPECT_LE(lo.pixels[i], mean.pixels[i] + 0.01f) << i;
            // The max leaves background cells out (a ray through air alone meets nothing), so where it is
            // below the background value the mean, which counts them, may lie above it.
            if (hi.pixels[i] >= f.space.background) {
                EXPECT_LE(mean.pixels[i], hi.pixels[i] + 0.01f) << i;
            }
            ++ordered;
        }
        EXPECT_GT(ordered, lo.pixels.size() / 10);
    }
}
