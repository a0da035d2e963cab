// `vots render --slab-sweep` end to end: a DICOM series in, a derived series out that the project's reader
// and GDCM read back (count, geometry, HU against the grid renderer, the tags a PACS needs); PNGs; bad input.
#include "CliExpect.h"
#include "CliRunner.h"
#include "DicomTags.h"
#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include "vots/fit/DicomSeries.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

namespace vots::test {
namespace {

constexpr double EPS = 20.0; // the fit's bound, HU
constexpr double AIR = -1000.0;

/// A bright ball in air, 24 x 20 x 16 samples, 18 mm deep along z.
fit::Volume ball() {
    return sampleVolume({24, 20, 16},
                        [](int x, int y, int z) {
                            const double r = std::hypot(x - 11.5, y - 9.5, (z - 7.5) * 1.5);
                            return r < 7 ? 900.0 - 20.0 * r : AIR;
                        },
                        {0.8, 0.8, 1.2});
}

/// The ball as a CT stores it, oriented like the Cranium's series (rows reversed, slices rising to superior).
std::string writeSource(const TempDir& dir) {
    DicomWriteOptions o;
    o.storeSigned = false;
    o.bitsStored = 12;
    o.intercept = -1024;
    o.orientation = {1, 0, 0, 0, -1, 0};
    o.slicesAlongNormal = false;
    o.origin = {-9.2, 7.6, -40.0};
    const std::string folder = dir.file("ct");
    writeDicomSeries(ball(), folder, o);
    return folder;
}

std::vector<std::string> sweepArgs(const std::string& input, const std::string& output) {
    return {"render", input,   "--view", "inferior",          "--slab-sweep", "10,5",
            "--size", "48x40", "--eps",  std::to_string(EPS), "-o",           output};
}

std::vector<std::string> filesIn(const std::string& folder) {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(CliSlabSweep, WritesADerivedSeriesInTheSourcesStudy) {
    TempDir dir;
    const std::string source = writeSource(dir);
    std::filesystem::create_directories(dir.path() / "vots");
    std::filesystem::create_directories(dir.path() / "grid");
    const CliResult vots = runVots(sweepArgs(source, dir.file("vots/%03d.dcm")));
    ASSERT_EQ(vots.exitCode, 0) << vots.err;
    std::vector<std::string> gridArgs = sweepArgs(source, dir.file("grid/%03d.dcm"));
    gridArgs.insert(gridArgs.end(), {"--renderer", "grid"});
    const CliResult grid = runVots(gridArgs);
    ASSERT_EQ(grid.exitCode, 0) << grid.err;

    // 18 mm along the inferior view: 1 + ceil((18 - 10) / 5) = 3 slabs, named from 0.
    const std::vector<std::string> files = filesIn(dir.file("vots"));
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(files.front(), dir.file("vots/000.dcm"));

    const fit::Volume derived = fit::loadDicomSeries(dir.file("vots"));
    const fit::Volume exact = fit::loadDicomSeries(dir.file("grid"));
    ASSERT_EQ(derived.dims, (std::array<int, 3>{48, 40, 3}));
    // The inferior view: patient left on image right, anterior at the top, looking towards superior.
    const std::array<std::array<double, 3>, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(derived.patientAxes[a][c], axes[a][c], 1e-6) << a << "," << c;
    EXPECT_NEAR(derived.spacing[2], 5.0, 1e-6);
    // Square pixels: the bounding sphere of the volume's box (2R mm) across the image height.
    const double diagonal = std::sqrt(std::pow(23 * 0.8, 2) + std::pow(19 * 0.8, 2) + std::pow(15 * 1.2, 2));
    EXPECT_NEAR(derived.spacing[0], diagonal / 40, 1e-5);
    EXPECT_NEAR(derived.spacing[1], diagonal / 40, 1e-5);
    // The slabs are centred on the volume: the middle one's plane holds the volume's centre.
    const double centreZ = -40.0 + 0.5 * 15 * 1.2;
    EXPECT_NEAR(derived.origin[2] + derived.spacing[2], centreZ, 1e-4);
    EXPECT_EQ(derived.origin, exact.origin);

    // HU: the analytic slab MIP from the Vots against the exact one of the grid, within eps (+ rounding).
    std::size_t compared = 0;
    double brightest = -1e9;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 48; ++x) {
                const double v = derived.at(x, y, z), g = exact.at(x, y, z);
                brightest = std::max(brightest, v);
                if (v == -32768.0) { // no Vot: outside the volume, or air the fit left out as background
                    EXPECT_TRUE(g == -32768.0 || g < AIR + 0.01 * 1900 + EPS) << x << "," << y << "," << z;
                    continue;
                }
                ASSERT_NE(g, -32768.0) << x << "," << y << "," << z;
                EXPECT_NEAR(v, g, EPS + 1.0) << x << "," << y << "," << z;
                ++compared;
            }
    EXPECT_GT(compared, 300u);
    EXPECT_NEAR(brightest, ball().valueRange()[1], EPS + 1.0); // the middle slab holds the ball's centre

    const DicomTags sourceFile(filesIn(source).front());
    std::set<std::string> sops;
    for (std::size_t k = 0; k < files.size(); ++k) {
        const DicomTags t(files[k]);
        EXPECT_EQ(t.text(0x0010, 0x0020), sourceFile.text(0x0010, 0x0020));
        EXPECT_EQ(t.text(0x0010, 0x0020), "VOTS-PHANTOM-1");
        EXPECT_EQ(t.text(0x0010, 0x0010), "Vots^Phantom");
        EXPECT_EQ(t.text(0x0020, 0x000d), sourceFile.text(0x0020, 0x000d));
        EXPECT_EQ(t.text(0x0020, 0x0052), sourceFile.text(0x0020, 0x0052));
        EXPECT_NE(t.text(0x0020, 0x000e), sourceFile.text(0x0020, 0x000e));
        EXPECT_EQ(t.text(0x0020, 0x000e), DicomTags(files[0]).text(0x0020, 0x000e));
        EXPECT_EQ(t.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.2"); // CT Image Storage, as the source
        EXPECT_EQ(t.text(0x0008, 0x0008), "DERIVED\\SECONDARY");
        EXPECT_EQ(t.text(0x0008, 0x103e), "MIP 10 mm / 5 mm axial");
        EXPECT_EQ(t.text(0x0018, 0x0050), "10");
        EXPECT_EQ(t.text(0x0018, 0x0088), "5");
        EXPECT_EQ(t.text(0x0020, 0x0037), "1\\0\\0\\0\\1\\0");
        EXPECT_EQ(t.text(0x0020, 0x0013), std::to_string(k + 1));
        sops.insert(t.text(0x0008, 0x0018));
    }
    EXPECT_EQ(sops.size(), files.size());
    EXPECT_EQ(sops.count(sourceFile.text(0x0008, 0x0018)), 0u);
}

// A .vots file knows no patient: with its DICOM volume the series joins the source's study; alone it is a
// new study stored as Secondary Capture.
TEST(CliSlabSweep, AVotsInputTakesItsIdentityFromItsVolume) {
    TempDir dir;
    const std::string source = writeSource(dir);
    const std::string vots = dir.file("ct.vots");
    ASSERT_EQ(runVots({"fit", source, "-o", vots, "--eps", "20"}).exitCode, 0);
    std::filesystem::create_directories(dir.path() / "with");
    std::filesystem::create_directories(dir.path() / "alone");
    std::vector<std::string> with = sweepArgs(vots, dir.file("with/%d.dcm"));
    with.insert(with.end(), {"--volume", source});
    const CliResult joined = runVots(with);
    ASSERT_EQ(joined.exitCode, 0) << joined.err;
    const CliResult alone = runVots(sweepArgs(vots, dir.file("alone/%d.dcm")));
    ASSERT_EQ(alone.exitCode, 0) << alone.err;

    const DicomTags sourceFile(filesIn(source).front());
    const DicomTags withFile(dir.file("with/0.dcm")), aloneFile(dir.file("alone/0.dcm"));
    EXPECT_EQ(withFile.text(0x0020, 0x000d), sourceFile.text(0x0020, 0x000d));
    EXPECT_EQ(withFile.text(0x0010, 0x0020), "VOTS-PHANTOM-1");
    EXPECT_EQ(withFile.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.2");
    EXPECT_NE(aloneFile.text(0x0020, 0x000d), sourceFile.text(0x0020, 0x000d));
    EXPECT_NE(aloneFile.text(0x0020, 0x000d), "");
    EXPECT_EQ(aloneFile.text(0x0010, 0x0020), "");
    EXPECT_EQ(aloneFile.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.7"); // Secondary Capture
    // The same Vots drawn either way: the same slabs at the same places.
    EXPECT_EQ(filesIn(dir.file("with")).size(), 3u);
    EXPECT_EQ(withFile.text(0x0020, 0x0032), aloneFile.text(0x0020, 0x0032));
}

TEST(CliSlabSweep, WritesDisplayImagesAsPngs) {
    TempDir dir;
    const std::string source = writeSource(dir);
    std::filesystem::create_directories(dir.path() / "png");
    std::vector<std::string> args = sweepArgs(source, dir.file("png/slab-%d.png"));
    args.insert(args.end(), {"--mode", "minip", "--window", "-500,1000"});
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::string> files = filesIn(dir.file("png"));
    ASSERT_EQ(files.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        const std::string bytes = slurpText(dir.file("png/slab-" + std::to_string(k) + ".png"));
        EXPECT_EQ(bytes.substr(1, 3), "PNG");
    }
}

TEST(CliSlabSweep, BadInputWritesNothing) {
    TempDir dir;
    const std::string source = writeSource(dir);
    TempDir out;
    std::filesystem::create_directories(out.path() / "s");
    const std::string pattern = out.file("s/%03d.dcm");
    const auto with = [&](std::vector<std::string> extra, const std::string& output = {}) {
        std::vector<std::string> args = sweepArgs(source, output.empty() ? pattern : output);
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const auto bad = [&](std::vector<std::string> args, const std::string& needle) {
        expectBadInput(out, args, needle);
        EXPECT_TRUE(std::filesystem::is_empty(out.path() / "s")) << needle;
    };
    auto zeroThickness = with({});
    zeroThickness[5] = "0,5";
    bad(zeroThickness, "is not THICKNESS,STEP");
    auto negativeStep = with({});
    negativeStep[5] = "10,-5";
    bad(negativeStep, "is not THICKNESS,STEP");
    bad(with({"--turntable", "4"}), "--slab-sweep or --turntable");
    bad(with({}, out.file("s/slab.dcm")), "one %d");
    bad(with({}, out.file("s/%03d.jpg")), "must end in .dcm");
    bad(with({}, out.file("s%d/x.dcm")), "in the file name");
    bad(with({}, out.file("missing/%03d.dcm")), "does not exist");
    out.write("file", "not a folder");
    bad(with({}, out.file("file/%03d.dcm")), "does not exist");
    bad(with({"--slab", "0,10"}), "leave out --slab");
    bad(with({"--mode", "density"}), "density");
    auto perspective = with({});
    perspective[3] = "az=0,el=-90,proj=persp";
    perspective[2] = "--cam";
    bad(perspective, "orthographic");
    auto tooMany = with({});
    tooMany[5] = "0.001,0.001";
    bad(tooMany, "at most");
    std::filesystem::remove(out.file("file"));
}

} // namespace
} // namespace vots::test
