// Enum <-> name tables: one table per enum beside it, names and further spellings, errors listing the names.
#include "vots/fit/EnumNames.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>

namespace vots::fit {
namespace {

TEST(EnumNames, EveryValueHasANameThatParsesBackToIt) {
    for (const auto& row : SCALAR_TYPE_NAMES.rows)
        EXPECT_EQ(parseName<ScalarType>(nameOf(row.value)), row.value) << row.name;
    for (const auto& row : CERTIFY_NAMES.rows)
        EXPECT_EQ(parseName<Certify>(nameOf(row.value)), row.value) << row.name;
    for (const auto& row : FIT_METHOD_NAMES.rows)
        EXPECT_EQ(parseName<FitMethod>(nameOf(row.value)), row.value) << row.name;
}

TEST(EnumNames, TheFirstRowNamesAValueAndLaterRowsAreFurtherSpellings) {
    static_assert(nameOf(ScalarType::Int16) == "int16");
    static_assert(nameOf(Certify::Cells) == "cells");
    EXPECT_EQ(findNamed<ScalarType>("short"), ScalarType::Int16);
    EXPECT_EQ(findNamed<ScalarType>("unsigned char"), ScalarType::UInt8);
    EXPECT_EQ(findNamed<ScalarType>("Short"), std::nullopt) << "the table holds normalised spellings only";
    EXPECT_EQ(knownNames<ScalarType>(), "uint8, int8, uint16, int16, uint32, int32, float32, float64");
    EXPECT_EQ(knownNames<FitMethod>(), "paper, fast");
}

TEST(EnumNames, AnUnknownNameIsAnInputErrorListingTheNames) {
    try {
        parseName<Certify>("voxels");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "unknown certification 'voxels' (known: samples, cells)");
    }
    try {
        parseScalarType("quaternion");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(),
                     "unknown sample type 'quaternion' (known: uint8, int8, uint16, int16, uint32, int32, float32, "
                     "float64)");
    }
    EXPECT_EQ(parseScalarType("  Unsigned   Short "), ScalarType::UInt16) << "header text is normalised first";
}

} // namespace
} // namespace vots::fit
