// Parsing of eps texts ("20", "2%") into an EpsSpec, with the reason when a text is refused.
#include "vots/fit/EpsSpec.h"

#include <charconv>
#include <cmath>

namespace vots::fit {

std::optional<double> readDecimal(std::string_view text) {
    if (text.empty() || text.size() > 64) return std::nullopt;
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value, std::chars_format::general);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

EpsParse parseEps(std::string_view text, const EpsRules& rules) {
    EpsParse parse;
    parse.spec.isPercent = !text.empty() && text.back() == '%';
    parse.numberText = parse.spec.isPercent ? text.substr(0, text.size() - 1) : text;
    const auto value = rules.readNumber(parse.numberText);
    if (!value) {
        parse.problem = EpsProblem::NotANumber;
        return parse;
    }
    parse.spec.value = *value;
    if (*value < 0.0 || (!rules.allowZero && *value == 0.0))
        parse.problem = EpsProblem::NotPositive;
    else if (parse.spec.isPercent && *value > rules.maxPercent)
        parse.problem = EpsProblem::PercentTooLarge;
    return parse;
}

} // namespace vots::fit
