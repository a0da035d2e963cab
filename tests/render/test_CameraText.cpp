// Camera text form: round trip, presets, and strict rejections (NaN, inf, unknown/duplicate keys, ranges,
// length).
#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace vots::render;
using vots::fit::InputError;

TEST(CameraText, ParsesTheDocumentedExample) {
    const Camera c = parseCamera("az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30");
    EXPECT_EQ(c.azimuthDeg, 30.0);
    EXPECT_EQ(c.elevationDeg, 20.0);
    EXPECT_EQ(c.zoom, 1.0);
    EXPECT_EQ(c.projection, Projection::Orthographic);
    EXPECT_EQ(parseCamera("proj=persp,pan=0.25:-1.5").panY, -1.5);
}

TEST(CameraText, ViewNamesGivePresets) {
    EXPECT_EQ(parseCamera("anterior"), cameraForView(ViewPreset::Anterior));
    EXPECT_EQ(parseCamera("left").azimuthDeg, 90.0);
    EXPECT_EQ(parseCamera("superior").elevationDeg, 90.0);
    const Camera c = parseCamera("view=posterior,zoom=2");
    EXPECT_EQ(c.azimuthDeg, 180.0);
    EXPECT_EQ(c.zoom, 2.0);
}

TEST(CameraText, FormatRoundTripsExactly) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> az(-360, 360), el(-90, 90), zoom(0.01, 1000), pan(-100, 100),
        fov(1, 150);
    for (int i = 0; i < 2000; ++i) {
        Camera c;
        c.azimuthDeg = az(rng), c.elevationDeg = el(rng), c.zoom = zoom(rng);
        c.panX = pan(rng), c.panY = pan(rng), c.fovDeg = fov(rng);
        c.projection = i % 2 ? Projection::Perspective : Projection::Orthographic;
        ASSERT_EQ(parseCamera(formatCamera(c)), c) << formatCamera(c);
    }
    EXPECT_EQ(formatCamera(Camera{}), "az=0,el=0,zoom=1,pan=0:0,proj=ortho,fov=30");
}

TEST(CameraText, RejectsMalformedText) {
    const char* bad[] = {"",
                         "az=nan",
                         "az=NaN",
                         "az=inf",
                         "zoom=-inf",
                         "az=1e999",
                         "az=0x10",
                         "az=",
                         "az",
                         "az=1,",
                         ",az=1",
                         "az=1,,el=2",
                         "foo=1",
                         "az=1,az=2",
                         "el=91",
                         "zoom=0",
                         "zoom=1001",
                         "fov=0.5",
                         "pan=1",
                         "pan=1:x",
                         "proj=fisheye",
                         "view=sideways",
                         "view=left,az=3",
                         "az= 1",
                         "az=1 ",
                         "anterior,zoom=2",
                         "az=1\xff"};
    for (const char* text : bad)
        EXPECT_THROW(parseCamera(text), InputError) << "accepted '" << text << "'";
    EXPECT_THROW(parseCamera(std::string(MAX_CAMERA_TEXT + 1, '1')), InputError);
}

TEST(CameraText, MessagesNameTheProblem) {
    try {
        parseCamera("az=1,bogus=2");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bogus"), std::string::npos) << e.what();
    }
    try {
        parseCamera("az=1,az=2");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("twice"), std::string::npos) << e.what();
    }
}
