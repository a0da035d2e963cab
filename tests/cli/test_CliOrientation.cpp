// `vots render` of an oriented volume and of its .vots file give the same PNG: the file keeps its place
// in patient space in the meta block (docs/DESIGN.md §8), and views of two storage orders agree.
#include "CliRunner.h"
#include "OrientationPhantom.h"
#include "TempDir.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>

namespace vots::test {
namespace {

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

} // namespace

TEST(CliOrientation, VotsFileRendersLikeItsOrientedVolume) {
    const TempDir dir;
    const std::string volume = dir.file("permuted.nrrd");
    writePhantomNrrd(phantomGrid(PERMUTED_ORDER), volume, /*rasSpace=*/true);
    const std::string vots = dir.file("permuted.vots");
    const std::vector<std::string> fitArgs{"fit", volume, "-o", vots, "--eps", "0.5", "--certify", "cells"};
    const CliResult fit = runVots(fitArgs);
    ASSERT_EQ(fit.exitCode, 0) << describe(fitArgs, fit);

    // The meta block names the axes, rows in grid order, in LPS.
    const nlohmann::json meta = nlohmann::json::parse(meta::readVotSpaceFile(vots).metaJson);
    ASSERT_TRUE(meta["source"].contains("patient_axes")) << meta.dump();
    EXPECT_EQ(meta["source"]["patient_axes"], nlohmann::json(PERMUTED_ORDER));

    for (const std::string view : {"anterior", "left"}) {
        const std::vector<std::string> fromVolume{"render", volume,   "-o",    dir.file("v.png"), "--view",
                                                  view,     "--size", "64x64", "--eps",           "0.5"};
        const std::vector<std::string> fromFile{"render", vots, "-o",     dir.file("f.png"),
                                                "--view", view, "--size", "64x64"};
        const CliResult a = runVots(fromVolume), b = runVots(fromFile);
        ASSERT_EQ(a.exitCode, 0) << describe(fromVolume, a);
        ASSERT_EQ(b.exitCode, 0) << describe(fromFile, b);
        EXPECT_EQ(readBytes(dir.file("v.png")), readBytes(dir.file("f.png"))) << view;
    }
}

TEST(CliOrientation, VotsFileWithoutTheKeyRendersInIndexSpace) {
    // A file written before the key (here: the key removed) still loads and renders, as index space.
    const TempDir dir;
    const std::string volume = dir.file("ras.nii");
    writePhantomNifti(phantomGrid(RAS_ORDER), volume);
    const std::string vots = dir.file("ras.vots");
    ASSERT_EQ(runVots({"fit", volume, "-o", vots, "--eps", "0.5", "--threads", "2"}).exitCode, 0);
    fit::VotSpace space = meta::readVotSpaceFile(vots);
    nlohmann::ordered_json meta = nlohmann::ordered_json::parse(space.metaJson);
    meta["source"].erase("patient_axes");
    space.metaJson = meta.dump();
    const std::string old = dir.file("old.vots");
    fit::writeVotSpaceFile(old, space);
    const std::vector<std::string> args{"render", old,        "-o",     dir.file("o.png"),
                                        "--view", "anterior", "--size", "64x64"};
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << describe(args, r);
    const CliResult oriented =
        runVots({"render", vots, "-o", dir.file("n.png"), "--view", "anterior", "--size", "64x64"});
    ASSERT_EQ(oriented.exitCode, 0);
    // Stored RAS, the old file shows the phantom turned round (viewed from behind): another image.
    EXPECT_NE(readBytes(dir.file("o.png")), readBytes(dir.file("n.png")));
    EXPECT_EQ(runVots({"info", old}).exitCode, 0);
}

} // namespace vots::test
