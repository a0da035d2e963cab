// Private: parsing helpers for text headers (NRRD, MetaImage): trimming, words, strict numbers.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vots::fit::detail {

std::string trim(std::string_view text);
std::string toLower(std::string_view text);
std::vector<std::string> splitWords(std::string_view text);

/// The whole token must be a number; nullopt otherwise (also on overflow).
std::optional<long long> parseInteger(std::string_view token);
std::optional<double> parseReal(std::string_view token);

/// Exactly `count` whitespace-separated numbers for header field `field`; throws InputError otherwise.
std::vector<long long> parseIntegers(const std::string& path, const std::string& field,
                                     std::string_view value, std::size_t count);
std::vector<double> parseReals(const std::string& path, const std::string& field, std::string_view value,
                               std::size_t count);

/// Absolute value of a spacing; throws unless it is finite and non-zero.
double checkedSpacing(const std::string& path, const std::string& field, double spacing);

/// Header text quoted in an error message: at most 60 characters, non-printable bytes as '?'.
std::string quotable(std::string_view text);

/// One line of a text header and where the next one starts.
struct HeaderLine {
    std::string text;      // without the newline and a trailing '\r'
    std::size_t next = 0;  // offset just past the newline
    bool complete = false; // false when the text ran out before a newline
};

/// The line starting at `offset` in `text`.
HeaderLine lineAt(const std::string& text, std::size_t offset);

} // namespace vots::fit::detail
