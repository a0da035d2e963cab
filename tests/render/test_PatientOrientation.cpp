// The six views are patient directions whatever the storage order: a phantom with markers at the
// patient's left, anterior and superior, written as NIfTI and NRRD in three storage orders, lands where
// docs/DESIGN.md (coordinates) says, and every order gives the same image.
#include "RenderTestSupport.h"

#include "OrientationPhantom.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

using namespace vots;
using namespace vots::render;

namespace {

constexpr int W = 96, H = 96;

struct Writer {
    const char* name;
    std::function<void(const test::PhantomGrid&, const std::string&)> write;
    const char* extension;
};

// A DICOM series (GDCM's writer): rows along patientAxes[0], columns along [1], slices along [2],
// which is the IOP normal or its opposite.
void writePhantomDicom(const test::PhantomGrid& grid, const std::string& folder) {
    fit::Volume volume;
    volume.dims = grid.dims;
    volume.spacing = grid.spacing;
    volume.values = grid.values;
    const fit::PatientAxes& a = grid.patientAxes;
    test::DicomWriteOptions options;
    options.orientation = {a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2]};
    options.origin = grid.origin;
    const std::array<double, 3> normal{a[0][1] * a[1][2] - a[0][2] * a[1][1],
                                       a[0][2] * a[1][0] - a[0][0] * a[1][2],
                                       a[0][0] * a[1][1] - a[0][1] * a[1][0]};
    options.slicesAlongNormal = normal[0] * a[2][0] + normal[1] * a[2][1] + normal[2] * a[2][2] > 0;
    test::writeDicomSeries(volume, folder, options);
}

const std::vector<Writer>& writers() {
    static const std::vector<Writer> all{
        {"dicom", writePhantomDicom, ""},
        {"nifti", test::writePhantomNifti, ".nii"},
        {"nrrd_lps", [](const auto& g, const auto& p) { test::writePhantomNrrd(g, p, false); }, ".nrrd"},
        {"nrrd_ras", [](const auto& g, const auto& p) { test::writePhantomNrrd(g, p, true); }, ".nrrd"}};
    return all;
}

struct Order {
    const char* name;
    fit::PatientAxes axes;
};
const std::vector<Order> ORDERS{
    {"lps", test::LPS_ORDER}, {"ras", test::RAS_ORDER}, {"permuted", test::PERMUTED_ORDER}};

// Centroid (x, y in pixels, y down) of the pixels showing exactly this marker's value.
std::optional<std::array<double, 2>> markerAt(const FloatImage& image, float value) {
    double sx = 0, sy = 0;
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (std::abs(image.at(x, y) - value) < 0.01f) {
                sx += x;
                sy += y;
                ++n;
            }
    if (n < 4) return std::nullopt;
    return std::array<double, 2>{sx / n, sy / n};
}

fit::Volume loadPhantom(const test::TempDir& dir, const Writer& writer, const Order& order) {
    const std::string path = dir.file(std::string(writer.name) + "_" + order.name + writer.extension);
    writer.write(test::phantomGrid(order.axes), path);
    return fit::loadVolume(path);
}

// Where section 2 of the views' contract puts the markers, in one rendered image.
void expectAnteriorView(const FloatImage& image, const std::string& what) {
    const auto left = markerAt(image, test::LEFT_MARKER);
    const auto anterior = markerAt(image, test::ANTERIOR_MARKER);
    const auto superior = markerAt(image, test::SUPERIOR_MARKER);
    ASSERT_TRUE(left && anterior && superior) << what;
    EXPECT_GT((*left)[0], W * 0.6) << what << ": the patient's left is on the image's right";
    EXPECT_NEAR((*left)[1], H / 2.0, 3.0) << what;
    EXPECT_NEAR((*anterior)[0], W / 2.0, 3.0) << what << ": the face is seen head on";
    EXPECT_NEAR((*anterior)[1], H / 2.0, 3.0) << what;
    EXPECT_LT((*superior)[1], H * 0.4) << what << ": superior is at the top";
    EXPECT_NEAR((*superior)[0], W / 2.0, 3.0) << what;
}

void expectLeftView(const FloatImage& image, const std::string& what) {
    const auto left = markerAt(image, test::LEFT_MARKER);
    const auto anterior = markerAt(image, test::ANTERIOR_MARKER);
    const auto superior = markerAt(image, test::SUPERIOR_MARKER);
    ASSERT_TRUE(left && anterior && superior) << what;
    EXPECT_LT((*anterior)[0], W * 0.4) << what << ": anterior is on the image's left";
    EXPECT_NEAR((*anterior)[1], H / 2.0, 3.0) << what;
    EXPECT_NEAR((*left)[0], W / 2.0, 3.0) << what << ": the left side is seen head on";
    EXPECT_LT((*superior)[1], H * 0.4) << what << ": superior is at the top";
}

FloatImage renderGrid(const fit::Volume& volume, ViewPreset view) {
    GridRenderer renderer;
    renderer.upload(volume);
    return renderer.render(cameraForView(view), W, H);
}

} // namespace

TEST(PatientOrientation, ReadersFillPatientAxesFromEveryStorageOrder) {
    const test::TempDir dir;
    for (const Writer& writer : writers())
        for (const Order& order : ORDERS) {
            const fit::Volume volume = loadPhantom(dir, writer, order);
            ASSERT_TRUE(volume.orientationKnown) << writer.name << " " << order.name;
            EXPECT_EQ(volume.patientAxes, order.axes) << writer.name << " " << order.name;
            const test::PhantomGrid grid = test::phantomGrid(order.axes);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(volume.origin[c], grid.origin[c], 1e-4) << writer.name << " " << order.name;
        }
}

TEST(PatientOrientation, ReferenceViewsAreTheSameForEveryStorageOrder) {
    test::glContext();
    const test::TempDir dir;
    std::optional<FloatImage> anteriorLps, leftLps;
    for (const Writer& writer : writers())
        for (const Order& order : ORDERS) {
            const std::string what = std::string(writer.name) + " stored " + order.name;
            const fit::Volume volume = loadPhantom(dir, writer, order);
            const FloatImage anterior = renderGrid(volume, ViewPreset::Anterior);
            const FloatImage left = renderGrid(volume, ViewPreset::Left);
            expectAnteriorView(anterior, what);
            expectLeftView(left, what);
            if (!anteriorLps) {
                anteriorLps = anterior;
                leftLps = left;
                test::saveForInspection(anterior, "phantom_anterior");
                test::saveForInspection(left, "phantom_left");
                continue;
            }
            // The same samples at the same patient points, traced in another index order: the ray steps
            // fall on other points along each ray, so the thin edges of the balls (where the value changes
            // within one step) may differ. Tolerance: every pixel within 1/4 of the brightest marker, and
            // fewer than 2 % of the pixels more than 0.5 apart.
            for (const auto& [mine, first] :
                 {std::pair{&anterior, &*anteriorLps}, std::pair{&left, &*leftLps}}) {
                const test::ImageComparison cmp = test::compareImages(*mine, *first, 0.5);
                EXPECT_EQ(cmp.finiteMismatch, 0u) << what;
                EXPECT_LT(cmp.worst, test::LEFT_MARKER / 4) << what;
                EXPECT_LT(cmp.beyondTolerance, std::size_t{W * H / 50}) << what;
            }
        }
}

TEST(PatientOrientation, VotViewsPutTheMarkersInPlace) {
    test::glContext();
    const test::TempDir dir;
    for (const Order& order : ORDERS) {
        const fit::Volume volume = loadPhantom(dir, writers()[0], order);
        fit::FitOptions options;
        options.eps = 0.5f;
        options.background = 1.f;
        const fit::VotSpace space = fit::fitVotSpace(volume, options).space;
        ASSERT_TRUE(space.orientationKnown);
        EXPECT_EQ(space.patientAxes, order.axes);
        VotRenderer renderer;
        renderer.upload(space);
        const std::string what = std::string("Vots of nifti stored ") + order.name;
        // Vots reproduce the flat tops within eps, so the markers are found with a tolerance of eps.
        FloatImage anterior = renderer.render(cameraForView(ViewPreset::Anterior), W, H);
        FloatImage left = renderer.render(cameraForView(ViewPreset::Left), W, H);
        for (FloatImage* image : {&anterior, &left})
            for (float& v : image->pixels)
                for (const float marker : {test::LEFT_MARKER, test::ANTERIOR_MARKER, test::SUPERIOR_MARKER})
                    if (std::abs(v - marker) <= options.eps) v = marker;
        expectAnteriorView(anterior, what);
        expectLeftView(left, what);
    }
}

TEST(PatientOrientation, UnorientedVolumeKeepsIndexSpaceAsLps) {
    // A volume whose file says nothing has the identity axes: the same bounds as before orientation.
    fit::Volume volume;
    volume.dims = {10, 20, 30};
    volume.spacing = {1.0, 2.0, 0.5};
    volume.origin = {5.0, -3.0, 7.0};
    const SceneBounds b = sceneBounds(volume);
    EXPECT_FALSE(volume.orientationKnown);
    EXPECT_EQ(b.lo, volume.origin);
    EXPECT_EQ(b.hi, (std::array<double, 3>{5.0 + 9.0, -3.0 + 38.0, 7.0 + 14.5}));
    // A flipped axis widens the box on the other side of the origin.
    volume.patientAxes = test::RAS_ORDER;
    const SceneBounds flipped = sceneBounds(volume);
    EXPECT_EQ(flipped.lo, (std::array<double, 3>{5.0 - 9.0, -3.0 - 38.0, 7.0}));
    EXPECT_EQ(flipped.hi, (std::array<double, 3>{5.0, -3.0, 7.0 + 14.5}));
}
