// Private: parsing helpers for text headers (NRRD, MetaImage): trimming, words, strict numbers.
#include "HeaderText.h"

#include "InputFile.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace vots::fit::detail {

namespace {
bool isBlank(char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0;
}
} // namespace

std::string trim(std::string_view text) {
    std::size_t begin = 0;
    std::size_t end = text.size();
    while (begin < end && isBlank(text[begin]))
        ++begin;
    while (end > begin && isBlank(text[end - 1]))
        --end;
    return std::string(text.substr(begin, end - begin));
}

std::string toLower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
    return out;
}

std::vector<std::string> splitWords(std::string_view text) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && isBlank(text[i]))
            ++i;
        const std::size_t start = i;
        while (i < text.size() && !isBlank(text[i]))
            ++i;
        if (i > start) words.emplace_back(text.substr(start, i - start));
    }
    return words;
}

std::optional<long long> parseInteger(std::string_view token) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    long long value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
    return value;
}

std::optional<double> parseReal(std::string_view token) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
    return value;
}

std::vector<long long> parseIntegers(const std::string& path, const std::string& field,
                                     std::string_view value, std::size_t count) {
    const std::vector<std::string> words = splitWords(value);
    if (words.size() != count)
        throwInputError(path, "'" + field + "' needs " + std::to_string(count) + " integers, got '" +
                                  quotable(trim(value)) + "'");
    std::vector<long long> numbers;
    for (const std::string& word : words) {
        const std::optional<long long> number = parseInteger(word);
        if (!number) throwInputError(path, "'" + field + "' has a bad integer '" + quotable(word) + "'");
        numbers.push_back(*number);
    }
    return numbers;
}

std::vector<double> parseReals(const std::string& path, const std::string& field, std::string_view value,
                               std::size_t count) {
    const std::vector<std::string> words = splitWords(value);
    if (words.size() != count)
        throwInputError(path, "'" + field + "' needs " + std::to_string(count) + " numbers, got '" +
                                  quotable(trim(value)) + "'");
    std::vector<double> numbers;
    for (const std::string& word : words) {
        const std::optional<double> number = parseReal(word);
        if (!number) throwInputError(path, "'" + field + "' has a bad number '" + quotable(word) + "'");
        numbers.push_back(*number);
    }
    return numbers;
}

double checkedSpacing(const std::string& path, const std::string& field, double spacing) {
    if (!std::isfinite(spacing) || spacing == 0.0)
        throwInputError(path, "'" + field + "' has a spacing that is zero or not finite");
    return std::fabs(spacing);
}

std::string quotable(std::string_view text) {
    std::string out(text.substr(0, 60));
    for (char& c : out)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    if (text.size() > 60) out += "...";
    return out;
}

HeaderLine lineAt(const std::string& text, std::size_t offset) {
    HeaderLine line;
    const std::size_t newline = text.find('\n', offset);
    const std::size_t end = newline == std::string::npos ? text.size() : newline;
    line.text = text.substr(offset, end - offset);
    if (!line.text.empty() && line.text.back() == '\r') line.text.pop_back();
    line.complete = newline != std::string::npos;
    line.next = line.complete ? newline + 1 : text.size();
    return line;
}

} // namespace vots::fit::detail
