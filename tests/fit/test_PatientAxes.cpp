// Grid directions in patient space (LPS) from each reader's header fields, and their normalising.
#include "vots/fit/Error.h"
#include "vots/fit/PatientAxes.h"
#include "vots/fit/VolumeLoad.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace vots::fit;
using vots::test::encode;
using vots::test::niftiHeader;
using vots::test::nrrdHeader;
using vots::test::TempDir;

namespace {

const std::string INT16_DATA = encode(vots::test::fixtureValues(ScalarType::Int16), ScalarType::Int16, false);

Volume nrrdWith(const TempDir& dir, const std::string& lines) {
    return loadVolume(dir.write(
        "v.nrrd",
        nrrdHeader("int16", "raw", std::string("endian: little\n").append(lines).append("\n")) + INT16_DATA));
}

Volume metaWith(const TempDir& dir, const std::string& lines) {
    dir.write("v.raw", INT16_DATA);
    return loadVolume(
        dir.write("v.mhd", std::string("ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\n").append(lines) +
                               "ElementType = MET_SHORT\nElementDataFile = v.raw\n"));
}

} // namespace

TEST(PatientAxes, NormalisesSnapsAndRejectsDegenerateDirections) {
    const auto axes = normalizedPatientAxes({{{0, 0, 2.5}, {-0.9999999, 1e-8, 0}, {0, 3, 0}}});
    ASSERT_TRUE(axes);
    EXPECT_EQ(*axes, (PatientAxes{{{0, 0, 1}, {-1, 0, 0}, {0, 1, 0}}}));
    EXPECT_TRUE(isAxisAligned(*axes));
    const double h = std::sqrt(0.5);
    const auto oblique = normalizedPatientAxes({{{1, 1, 0}, {-1, 1, 0}, {0, 0, 1}}});
    ASSERT_TRUE(oblique);
    EXPECT_NEAR((*oblique)[0][0], h, 1e-15);
    EXPECT_FALSE(isAxisAligned(*oblique));
    EXPECT_EQ(patientDirectionName((*oblique)[0]), "");
    EXPECT_EQ(patientDirectionName({0, -1, 0}), "A");
    EXPECT_FALSE(normalizedPatientAxes({{{1, 0, 0}, {2, 0, 0}, {0, 0, 1}}})); // collinear
    EXPECT_FALSE(normalizedPatientAxes({{{1, 0, 0}, {0, 0, 0}, {0, 0, 1}}})); // zero
    EXPECT_FALSE(
        normalizedPatientAxes({{{std::numeric_limits<double>::quiet_NaN(), 0, 0}, {0, 1, 0}, {0, 0, 1}}}));
}

TEST(PatientAxes, NrrdSpaceNamesTurnIntoLps) {
    const TempDir dir;
    const std::string directions = "space directions: (0,2,0) (-1,0,0) (0,0,3)\nspace origin: (10,20,30)\n";
    const Volume lps = nrrdWith(dir, "space: left-posterior-superior\n" + directions);
    EXPECT_TRUE(lps.orientationKnown);
    EXPECT_EQ(lps.patientAxes, (PatientAxes{{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}}));
    EXPECT_EQ(lps.origin, (std::array<double, 3>{10, 20, 30}));
    const Volume ras = nrrdWith(dir, "space: RAS\n" + directions);
    EXPECT_EQ(ras.patientAxes, (PatientAxes{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}}));
    EXPECT_EQ(ras.origin, (std::array<double, 3>{-10, -20, 30}));
    const Volume las = nrrdWith(dir, "space: left-anterior-superior\n" + directions);
    EXPECT_EQ(las.patientAxes, (PatientAxes{{{0, -1, 0}, {-1, 0, 0}, {0, 0, 1}}}));
    // No patient meaning, or spacings only (like data/cranium.nhdr): index space, as before.
    EXPECT_FALSE(nrrdWith(dir, "space: 3D-right-handed\n" + directions).orientationKnown);
    EXPECT_FALSE(nrrdWith(dir, "spacings: 1 2 3\n").orientationKnown);
    EXPECT_FALSE(nrrdWith(dir, "space directions: (1,0,0) (0,1,0) (0,0,1)\n").orientationKnown);
    EXPECT_THROW(nrrdWith(dir, "space: LPS\nspace directions: (1,0,0) (2,0,0) (0,0,1)\n"), InputError);
}

TEST(PatientAxes, NiftiQformQuaternionAndQfac) {
    const TempDir dir;
    vots::test::NiftiSpec spec;
    spec.qformCode = 1;
    spec.quatern = {0.f, 0.f, 1.f}; // 180 degrees about z: RAS x, y flipped, i.e. LPS itself
    const Volume lps = loadVolume(dir.write("q.nii", niftiHeader(spec) + INT16_DATA));
    EXPECT_TRUE(lps.orientationKnown);
    EXPECT_EQ(lps.patientAxes, IDENTITY_PATIENT_AXES);
    spec.qfac = -1.f; // the third axis flips: slices run from head to feet
    const Volume down = loadVolume(dir.write("f.nii", niftiHeader(spec) + INT16_DATA));
    EXPECT_EQ(down.patientAxes, (PatientAxes{{{1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}));
    spec.qformCode = 0; // method 1: nothing known
    EXPECT_FALSE(loadVolume(dir.write("n.nii", niftiHeader(spec) + INT16_DATA)).orientationKnown);
}

TEST(PatientAxes, MetaImageTransformMatrixWinsOverAnatomicalOrientation) {
    const TempDir dir;
    const Volume both = metaWith(dir, "TransformMatrix = 0 1 0 1 0 0 0 0 1\nAnatomicalOrientation = RAI\n");
    EXPECT_TRUE(both.orientationKnown);
    EXPECT_EQ(both.patientAxes, (PatientAxes{{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}}));
    // ITK's letters: RAI is the identity in LPS (x from right to left, y from anterior, z from inferior).
    EXPECT_EQ(metaWith(dir, "AnatomicalOrientation = RAI\n").patientAxes, IDENTITY_PATIENT_AXES);
    EXPECT_EQ(metaWith(dir, "AnatomicalOrientation = LPS\n").patientAxes,
              (PatientAxes{{{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}}}));
    EXPECT_FALSE(metaWith(dir, "AnatomicalOrientation = ???\n").orientationKnown);
    EXPECT_FALSE(metaWith(dir, "").orientationKnown);
    EXPECT_THROW(metaWith(dir, "AnatomicalOrientation = RLI\n"), InputError);
}
