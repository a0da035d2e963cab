// The meta block's fields: written by buildFitMeta, restored by every .vots read, absent in old files.
#include "vots/meta/FitMeta.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include "TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace vots::meta {

namespace {

fit::Volume smallVolume() {
    fit::Volume volume;
    volume.dims = {2, 2, 2};
    volume.name = "small";
    volume.values.assign(8, -1000.f);
    return volume;
}

// A Vot-Space with a -983.9 threshold whose meta block records `fill` (and the volume's orientation),
// written to a file and read back.
fit::VotSpace throughAFile(std::optional<float> fill, const fit::Volume& volume = smallVolume()) {
    FitProvenance record;
    record.sourcePath = "/data/small.nrrd";
    record.volume = &volume;
    record.options.background = -983.9f;
    record.backgroundFill = fill;
    fit::VotSpace space;
    space.dims = volume.dims;
    space.background = -983.9f;
    space.backgroundFill = fill;
    space.metaJson = buildFitMeta(record);
    const test::TempDir dir;
    const std::string path = dir.file("small.vots");
    fit::writeVotSpaceFile(path, space);
    return readVotSpaceFile(path); // the header has neither fill nor axes: the meta block has them
}

TEST(FitMeta, TheBackgroundFillSurvivesAFileBitForBit) {
    const float fill = std::nextafter(-1000.1f, 0.f); // a float that no short decimal names
    const fit::VotSpace read = throughAFile(fill);
    ASSERT_TRUE(read.backgroundFill);
    EXPECT_EQ(*read.backgroundFill, fill);
    EXPECT_EQ(read.omittedCellValue(), fill);
    EXPECT_EQ(nlohmann::json::parse(read.metaJson)["background_fill"].get<double>(), double{fill});
}

TEST(FitMeta, AFitThatOmittedNothingWritesNoFillAndCountsTheThreshold) {
    const fit::VotSpace read = throughAFile(std::nullopt);
    EXPECT_FALSE(nlohmann::json::parse(read.metaJson).contains("background_fill"));
    EXPECT_FALSE(read.backgroundFill);
    EXPECT_EQ(read.omittedCellValue(), -983.9f);
}

TEST(FitMeta, AFileReadBackKnowsItsPatientAxes) {
    fit::Volume volume = smallVolume();
    volume.orientationKnown = true;
    volume.patientAxes = {{{-1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0}}}; // a sagittal-ish grid
    const fit::VotSpace read = throughAFile(std::nullopt, volume);
    EXPECT_TRUE(read.orientationKnown);
    EXPECT_EQ(read.patientAxes, volume.patientAxes);
    const fit::VotSpace unoriented = throughAFile(std::nullopt);
    EXPECT_FALSE(unoriented.orientationKnown);
    EXPECT_EQ(unoriented.patientAxes, fit::IDENTITY_PATIENT_AXES);
}

TEST(FitMeta, OldOrForeignBlocksGiveNoFill) {
    // Files from before the key, and keys that are not a finite float, fall back to the threshold.
    for (const char* meta : {"{}", "not json", R"({"background_fill": null})",
                             R"({"background_fill": "-1000"})", R"({"background_fill": [1]})",
                             R"({"background_fill": 1e300})", R"({"fit": {"background_fill": 3}})"}) {
        fit::VotSpace space;
        space.dims = {2, 2, 2};
        space.background = -983.9f;
        space.backgroundFill = 5.f; // whatever it held before: the block decides
        space.metaJson = meta;
        const std::vector<std::uint8_t> bytes = encodeVotSpace(space);
        const fit::VotSpace read = decodeVotSpace(bytes.data(), bytes.size());
        EXPECT_FALSE(read.backgroundFill) << meta;
        EXPECT_EQ(read.omittedCellValue(), -983.9f) << meta;
        EXPECT_FALSE(read.orientationKnown) << meta;
    }
    EXPECT_EQ(readFitMeta(R"({"background_fill": -1000})").backgroundFill, -1000.f);
}

} // namespace
} // namespace vots::meta
