// Parsing of command-line values (numbers, triples, eps with %) into typed values; throws InputError.
#pragma once

#include <array>
#include <string>

namespace vots::cli {

/// A finite number; `what` names the option in the error ("--eps").
double parseNumber(const std::string& text, const std::string& what);

/// "a,b,c" as three finite numbers.
std::array<double, 3> parseTriple(const std::string& text, const std::string& what);

/// "X,Y,Z" as three integers >= 1.
std::array<int, 3> parseDims(const std::string& text, const std::string& what);

/// An error bound: a plain value in data units, or a percentage of the value range ("2%").
struct EpsArg {
    double value = 0.0;
    bool isPercent = false;
    /// The bound in data units for a volume whose values span [lo, hi].
    double resolve(double lo, double hi) const { return isPercent ? value / 100.0 * (hi - lo) : value; }
};

/// Parses and checks an eps argument (> 0 unless allowZero, finite).
EpsArg parseEps(const std::string& text, const std::string& what, bool allowZero = false);

/// Human-friendly number: up to `digits` significant digits, no exponent for everyday sizes.
std::string formatNumber(double value, int digits = 6);

/// Newlines and tabs replaced by spaces, so an error stays on one line.
std::string oneLine(std::string text);

/// Integer with thousands separators ("1,234,567").
std::string formatCount(unsigned long long value);

} // namespace vots::cli
