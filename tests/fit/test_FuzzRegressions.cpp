// Replays the fuzz seeds and every crash found by fuzzing through the readers: each loads or throws
// InputError.
#include "FuzzCorpus.h"
#include "TempDir.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace {

using vots::test::fuzzInputs;

// Only InputError may escape; anything else (or a crash under the sanitizers) fails the test.
void expectLoadsOrInputError(const std::string& target, const std::string& extension,
                             const std::function<void(const std::string&)>& load) {
    const auto inputs = fuzzInputs(target);
    ASSERT_FALSE(inputs.empty()) << "no seeds for " << target;
    for (const auto& [name, bytes] : inputs) {
        SCOPED_TRACE(target + "/" + name);
        const vots::test::TempDir dir;
        const std::string path = dir.write("input" + extension, bytes);
        try {
            load(path);
        } catch (const vots::fit::InputError&) {
        }
    }
}

// As expectLoadsOrInputError for the 4D targets (fuzz_nifti2, fuzz_mgh): byte 0 picks the frame.
void expectFrameLoadsOrInputError(const std::string& target, const std::string& extension,
                                  const std::function<void(const std::string&, int)>& load) {
    const auto inputs = fuzzInputs(target);
    ASSERT_FALSE(inputs.empty()) << "no seeds for " << target;
    for (const auto& [name, bytes] : inputs) {
        SCOPED_TRACE(target + "/" + name);
        if (bytes.empty()) continue; // the target ignores it
        const vots::test::TempDir dir;
        const std::string path = dir.write("input" + extension, bytes.substr(1));
        try {
            load(path, static_cast<unsigned char>(bytes[0]) % 4);
        } catch (const vots::fit::InputError&) {
        }
    }
}

void decodeOrInputError(const std::vector<std::uint8_t>& bytes) {
    try {
        const auto space = vots::meta::decodeVotSpace(bytes.data(), bytes.size());
        (void)vots::fit::encodeVotSpace(space);
    } catch (const vots::fit::InputError&) {
    }
}

TEST(FuzzRegressions, VotSpaceReader) {
    const auto inputs = fuzzInputs("fuzz_votspace_reader");
    ASSERT_FALSE(inputs.empty());
    for (const auto& [name, text] : inputs) {
        SCOPED_TRACE(name);
        std::vector<std::uint8_t> bytes(text.begin(), text.end());
        decodeOrInputError(bytes);
        if (bytes.size() < 4) continue;
        // As fuzz_votspace_reader does: also with the trailing CRC-32 repaired.
        const std::size_t at = bytes.size() - 4;
        const auto crc =
            static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data(), static_cast<uInt>(at)));
        for (int i = 0; i < 4; ++i)
            bytes[at + i] = static_cast<std::uint8_t>(crc >> (8 * i));
        decodeOrInputError(bytes);
    }
}

TEST(FuzzRegressions, Nrrd) {
    expectLoadsOrInputError("fuzz_nrrd", ".nrrd", [](const std::string& p) { (void)vots::fit::loadNrrd(p); });
}

TEST(FuzzRegressions, Nifti) {
    expectLoadsOrInputError("fuzz_nifti", ".nii",
                            [](const std::string& p) { (void)vots::fit::loadNifti(p); });
}

TEST(FuzzRegressions, NiftiTwoFrames) {
    expectFrameLoadsOrInputError("fuzz_nifti2", ".nii", [](const std::string& p, int frame) {
        (void)vots::fit::loadNifti(p, vots::fit::SampleStorage::Source, frame);
    });
}

TEST(FuzzRegressions, MghFrames) {
    expectFrameLoadsOrInputError("fuzz_mgh", ".mgz", [](const std::string& p, int frame) {
        (void)vots::fit::loadMgh(p, vots::fit::SampleStorage::Source, frame);
    });
}

TEST(FuzzRegressions, DicomFolder) {
    // As fuzz_dicom: the input alone in a folder, read as a series; also every seed cut at several
    // lengths, where GDCM itself aborts (caught by its child process, DicomChild.h).
    const auto inputs = fuzzInputs("fuzz_dicom");
    ASSERT_FALSE(inputs.empty());
    for (const auto& [name, bytes] : inputs)
        for (const std::size_t cut : {bytes.size(), std::size_t{140}, std::size_t{300}, bytes.size() / 2,
                                      bytes.size() - 60, bytes.size() - 1}) {
            SCOPED_TRACE(name + " cut at " + std::to_string(cut));
            const vots::test::TempDir dir;
            dir.write("input.dcm", bytes.substr(0, std::min(cut, bytes.size())));
            try {
                (void)vots::fit::loadVolume(dir.path().string());
            } catch (const vots::fit::InputError&) {
            }
        }
}

TEST(FuzzRegressions, MetaImage) {
    expectLoadsOrInputError("fuzz_metaimage", ".mha",
                            [](const std::string& p) { (void)vots::fit::loadMetaImage(p); });
}

} // namespace

namespace {

// Found by fuzz_nrrd: "<min> <max> <step>" at the limits of long long overflowed (UB) computing the
// file count; now refused with the usual message, and a range ending at LLONG_MAX still works.
TEST(FuzzRegressions, NrrdPatternAtLongLongLimits) {
    const vots::test::TempDir dir;
    const std::string head =
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 1\nencoding: raw\ndata file: s%d.raw ";
    const std::string huge = dir.write("huge.nhdr", head + "-9223372036854775808 9223372036854775807 1\n");
    EXPECT_THROW(
        {
            try {
                (void)vots::fit::loadNrrd(huge);
            } catch (const vots::fit::InputError& e) {
                EXPECT_NE(std::string(e.what()).find("pattern needs <min> <max> <step>"), std::string::npos)
                    << e.what();
                throw;
            }
        },
        vots::fit::InputError);
    dir.write("s9223372036854775807.raw", std::string(12, '\7'));
    const auto volume =
        vots::fit::loadNrrd(dir.write("edge.nhdr", head + "9223372036854775807 9223372036854775807 1\n"));
    EXPECT_EQ(volume.values.size(), 12u);
}

} // namespace
