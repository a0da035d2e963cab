// Source-typed samples: a volume read as int16/uint8 (Volume::compact) fits to exactly the Vots of the
// same file read as floats, and the word-counted background mask agrees with counting cell by cell.
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"

#include "CellMask.h"
#include "SampleRange.h"
#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <variant>

namespace {

using namespace vots::fit;
using vots::test::TempDir;

constexpr std::array<int, 3> DIMS{70, 45, 38}; // two zones along x, cut mask words on every side

// A CT-like field: air (-1024) around a noisy object whose values span the int16 range used by CT.
std::vector<double> ctLikeSamples(double lo, double hi) {
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 6.0);
    std::vector<double> values;
    for (int z = 0; z < DIMS[2]; ++z)
        for (int y = 0; y < DIMS[1]; ++y)
            for (int x = 0; x < DIMS[0]; ++x) {
                const double r = std::hypot(x - 35.0, y - 22.0, 0.7 * (z - 19.0));
                double v = r > 20.0 ? lo
                                    : lo + 0.25 * (hi - lo) + 300.0 * std::sin(0.2 * x) * std::cos(0.17 * y) +
                                          40.0 * z + noise(rng);
                values.push_back(std::round(std::clamp(v, lo, hi)));
            }
    return values;
}

// A detached NRRD header beside its raw data file, in the folder `dir`.
std::string writeNrrd(const std::string& dir, const std::string& type, ScalarType scalar,
                      const std::vector<double>& values, bool bigEndian) {
    const std::string name = type + (bigEndian ? "_big" : "_little");
    std::ofstream(dir + "/" + name + ".raw", std::ios::binary)
        << vots::test::encode(values, scalar, bigEndian);
    std::ofstream(dir + "/" + name + ".nhdr")
        << "NRRD0004\ntype: " << type << "\ndimension: 3\nsizes: " << DIMS[0] << " " << DIMS[1] << " "
        << DIMS[2] << "\nspacings: 0.5 0.5 1.25\nendian: " << (bigEndian ? "big" : "little")
        << "\nencoding: raw\ndata file: " << name << ".raw\n";
    return dir + "/" + name + ".nhdr";
}

FitResult fitWith(const Volume& volume, FitMethod method) {
    FitOptions options;
    const auto range = volume.valueRange();
    options.eps = 0.02f * (range[1] - range[0]);
    options.background = defaultBackground(volume);
    options.certify = Certify::Cells;
    options.method = method;
    options.threads = 2;
    return fitVotSpace(volume, options);
}

void expectSameVots(const FitResult& a, const FitResult& b) {
    ASSERT_EQ(a.space.vots.size(), b.space.vots.size());
    for (std::size_t i = 0; i < a.space.vots.size(); ++i) {
        const Vot& x = a.space.vots[i];
        const Vot& y = b.space.vots[i];
        ASSERT_EQ(x.box, y.box) << "Vot " << i;
        // Bit for bit: the same sums in the same order, not merely close.
        ASSERT_EQ(std::memcmp(&x.p, &y.p, sizeof x.p), 0) << "Vot " << i;
        ASSERT_EQ(std::memcmp(&x.c, &y.c, sizeof x.c), 0) << "Vot " << i;
        ASSERT_EQ(std::memcmp(&x.err, &y.err, sizeof x.err), 0) << "Vot " << i;
    }
    EXPECT_EQ(a.stats.boxFits, b.stats.boxFits);
    EXPECT_EQ(a.stats.boxScans, b.stats.boxScans);
    EXPECT_EQ(a.stats.coveredCells, b.stats.coveredCells);
}

struct TypeCase {
    const char* nrrdType;
    ScalarType type;
    double lo, hi;
};

class CompactSamples : public testing::TestWithParam<TypeCase> {};

TEST_P(CompactSamples, FitIsTheSameAsFromFloats) {
    const TypeCase& c = GetParam();
    TempDir dir;
    for (const bool bigEndian : {false, true}) {
        const std::string path =
            writeNrrd(dir.path().string(), c.nrrdType, c.type, ctLikeSamples(c.lo, c.hi), bigEndian);
        const Volume asFloat = loadVolume(path);
        const Volume asSource = loadVolume(path, std::nullopt, SampleStorage::Source);
        ASSERT_FALSE(asFloat.isCompact());
        ASSERT_TRUE(asSource.isCompact()) << c.nrrdType << " should stay in its source type";
        EXPECT_TRUE(asSource.values.empty());
        ASSERT_EQ(asSource.heldSamples(), asFloat.values.size());
        EXPECT_EQ(asSource.valueRange(), asFloat.valueRange());
        EXPECT_EQ(asSource.contentCrc(), asFloat.contentCrc());
        // In runs of planes, as ranks holding different slabs give it together (an empty run included).
        const std::uint64_t planeBytes = std::uint64_t{DIMS[0]} * DIMS[1] * sizeof(float);
        std::uint32_t chained = asSource.gridCrc();
        for (const auto& [first, count] : {std::pair{0, 7}, {7, 0}, {7, 20}, {27, 11}})
            chained = combineCrc(chained, asSource.planesCrc(first, count), planeBytes * count);
        EXPECT_EQ(chained, asFloat.contentCrc());
        EXPECT_NE(combineCrc(asSource.gridCrc(), asSource.planesCrc(0, 37), planeBytes * 37), chained);
        EXPECT_THROW(asSource.planesCrc(30, 9), InputError);
        // The range in runs too: min and max of the runs' is the volume's; an empty run has none.
        const std::size_t plane = std::size_t{DIMS[0]} * DIMS[1];
        std::array<float, 2> runs{INFINITY, -INFINITY};
        for (const auto& [first, count] : {std::pair{0, 7}, {7, 0}, {7, 20}, {27, 11}}) {
            const std::array<float, 2> run = finiteRange(asSource, plane * first, plane * (first + count));
            runs = {std::min(runs[0], run[0]), std::max(runs[1], run[1])};
        }
        EXPECT_EQ(usableRange(runs), asFloat.valueRange());
        EXPECT_GT(finiteRange(asSource, plane * 7, plane * 7)[0],
                  finiteRange(asSource, plane * 7, plane * 7)[1]);
        EXPECT_EQ(usableRange(finiteRange(asSource, plane * 7, plane * 7)), (std::array<float, 2>{0.f, 0.f}));
        EXPECT_EQ(asSource.at(35, 22, 19), asFloat.at(35, 22, 19));
        EXPECT_EQ(asSource.at(69, 44, 37), asFloat.at(69, 44, 37));
        // The fast method only: the paper method fits boxes with the same BoxFitter and reads the same
        // mask (CellMaskWords below), and seeding every cell of this grid would take minutes.
        const FitResult fromFloat = fitWith(asFloat, FitMethod::Fast);
        ASSERT_GT(fromFloat.space.vots.size(), 50u) << "the field should need many Vots";
        expectSameVots(fitWith(asSource, FitMethod::Fast), fromFloat);
    }
}

INSTANTIATE_TEST_SUITE_P(EightAndSixteenBit, CompactSamples,
                         testing::Values(TypeCase{"int16", ScalarType::Int16, -1024.0, 3071.0},
                                         TypeCase{"uint16", ScalarType::UInt16, 0.0, 65535.0},
                                         TypeCase{"uint8", ScalarType::UInt8, 0.0, 255.0},
                                         TypeCase{"int8", ScalarType::Int8, -128.0, 127.0}),
                         [](const testing::TestParamInfo<TypeCase>& p) {
                             return std::string(p.param.nrrdType);
                         });

TEST(CompactSamples, WiderTypesStayFloat) {
    TempDir dir;
    const std::string path =
        writeNrrd(dir.path().string(), "int32", ScalarType::Int32, ctLikeSamples(-1024.0, 3071.0), false);
    const Volume volume = loadVolume(path, std::nullopt, SampleStorage::Source);
    EXPECT_FALSE(volume.isCompact()) << "float is no larger than int32: nothing to save";
    EXPECT_EQ(volume.values.size(), volume.sampleCount());
}

// The word counts against counting isBackground cell by cell, and isBackground against the definition
// (all 8 corners below the threshold), on boxes of every alignment to the mask's 4-cell words.
TEST(CellMaskWords, CountsMatchCellByCell) {
    TempDir dir;
    const std::string path =
        writeNrrd(dir.path().string(), "int16", ScalarType::Int16, ctLikeSamples(-1024.0, 3071.0), false);
    const Volume volume = loadVolume(path, std::nullopt, SampleStorage::Source);
    const float tau = -1000.f;
    const CellMask mask(volume, tau);
    const auto cells = mask.cellDims();
    std::int64_t background = 0;
    for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
            for (int i = 0; i < cells[0]; ++i) {
                bool low = true;
                for (int c = 0; c < 8; ++c)
                    low = low && volume.at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1)) < tau;
                ASSERT_EQ(mask.isBackground(i, j, k), low) << i << "," << j << "," << k;
                background += low ? 1 : 0;
            }
    ASSERT_GT(background, 0);
    ASSERT_LT(background, mask.totalCells());
    EXPECT_EQ(mask.totalForeground(), mask.totalCells() - background);

    std::mt19937 rng(5);
    for (int n = 0; n < 2000; ++n) {
        Box box;
        for (int a = 0; a < 3; ++a) {
            std::uniform_int_distribution<int> pick(0, cells[a]);
            int s = pick(rng), e = pick(rng);
            if (s == e) e = s == cells[a] ? s - 1 : s + 1;
            box.lo[a] = std::min(s, e);
            box.hi[a] = std::max(s, e);
        }
        std::int64_t want = 0;
        for (int k = box.lo[2]; k < box.hi[2]; ++k)
            for (int j = box.lo[1]; j < box.hi[1]; ++j)
                for (int i = box.lo[0]; i < box.hi[0]; ++i)
                    want += mask.isBackground(i, j, k) ? 0 : 1;
        ASSERT_EQ(mask.countForeground(box), want) << "box " << n;
    }
    const CellMask everything(volume, std::nullopt);
    EXPECT_EQ(everything.totalForeground(), everything.totalCells());
}

} // namespace
