// Parsing and formatting of command-line values; every failure is one line naming the option.
#include "Args.h"

#include "vots/fit/Error.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <vector>

namespace vots::cli {
namespace {

[[noreturn]] void bad(const std::string& what, const std::string& text, const std::string& expected) {
    throw fit::InputError(what + ": '" + text + "' is not " + expected);
}

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts;
    std::string::size_type start = 0;
    while (true) {
        const auto comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

/// The command line's number grammar (strtod's), finite numbers only.
std::optional<double> readNumber(std::string_view view) {
    const std::string text(view);
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    // strtod accepts "nan" and "inf"; a parameter must be an ordinary number.
    if (text.empty() || end != begin + text.size() || errno == ERANGE || !std::isfinite(v))
        return std::nullopt;
    return v;
}

} // namespace

double parseNumber(const std::string& text, const std::string& what) {
    const auto v = readNumber(text);
    if (!v) bad(what, text, "a finite number");
    return *v;
}

std::array<double, 3> parseTriple(const std::string& text, const std::string& what) {
    const auto parts = splitCommas(text);
    if (parts.size() != 3) bad(what, text, "three comma-separated numbers (x,y,z)");
    return {parseNumber(parts[0], what), parseNumber(parts[1], what), parseNumber(parts[2], what)};
}

std::array<int, 3> parseDims(const std::string& text, const std::string& what) {
    const auto parts = splitCommas(text);
    if (parts.size() != 3) bad(what, text, "three comma-separated sizes (X,Y,Z)");
    std::array<int, 3> dims{};
    for (int a = 0; a < 3; ++a) {
        const double v = parseNumber(parts[static_cast<std::size_t>(a)], what);
        if (v < 1 || v > INT_MAX || v != std::floor(v)) bad(what, text, "three whole numbers >= 1");
        dims[static_cast<std::size_t>(a)] = static_cast<int>(v);
    }
    return dims;
}

fit::EpsSpec parseEps(const std::string& text, const std::string& what, bool allowZero) {
    fit::EpsRules rules;
    rules.allowZero = allowZero;
    rules.readNumber = readNumber;
    const fit::EpsParse eps = fit::parseEps(text, rules);
    if (eps.problem == fit::EpsProblem::NotANumber) bad(what, std::string(eps.numberText), "a finite number");
    if (eps.problem != fit::EpsProblem::None)
        throw fit::InputError(what + " must be " + (allowZero ? ">= 0" : "> 0") + ", got '" + text + "'");
    return eps.spec;
}

std::string formatNumber(double value, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    return buf;
}

std::string formatCount(unsigned long long value) {
    const std::string digits = std::to_string(value);
    std::string out; // built forward; std::string::insert trips a GCC 12 -Wrestrict false positive
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string oneLine(std::string text) {
    for (char& ch : text)
        if (ch == '\n' || ch == '\r' || ch == '\t') ch = ' ';
    while (!text.empty() && text.back() == ' ')
        text.pop_back();
    return text;
}

} // namespace vots::cli
