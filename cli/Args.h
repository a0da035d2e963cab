// Parsing of command-line values (numbers, triples, eps with %) into typed values; throws InputError.
#pragma once

#include "vots/fit/EpsSpec.h"

#include <array>
#include <string>

namespace vots::cli {

/// A finite number; `what` names the option in the error ("--eps").
double parseNumber(const std::string& text, const std::string& what);

/// "a,b,c" as three finite numbers.
std::array<double, 3> parseTriple(const std::string& text, const std::string& what);

/// "X,Y,Z" as three integers >= 1.
std::array<int, 3> parseDims(const std::string& text, const std::string& what);

/// Parses and checks an eps argument (> 0 unless allowZero, finite), numbers as parseNumber reads them.
fit::EpsSpec parseEps(const std::string& text, const std::string& what, bool allowZero = false);

/// Human-friendly number: up to `digits` significant digits, no exponent for everyday sizes.
std::string formatNumber(double value, int digits = 6);

/// Newlines and tabs replaced by spaces, so an error stays on one line.
std::string oneLine(std::string text);

/// Integer with thousands separators ("1,234,567").
std::string formatCount(unsigned long long value);

} // namespace vots::cli
