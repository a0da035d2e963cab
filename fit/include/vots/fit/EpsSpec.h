// An error bound as a person writes it: data units ("20") or a percentage of the value range ("2%").
#pragma once

#include <limits>
#include <optional>
#include <string_view>

namespace vots::fit {

/// The bound a fit gets when nobody names one (the viewer's first fit, `vots render` of a volume).
inline constexpr double DEFAULT_EPS_PERCENT = 2.0;

struct EpsSpec {
    double value = DEFAULT_EPS_PERCENT;
    bool isPercent = true;

    /// The bound in data units for a volume whose values span [lo, hi]. Computed in double; a caller
    /// that needs the fitter's float rounds once, so every caller gets the same float for the same text.
    double resolve(double lo, double hi) const { return isPercent ? value / 100.0 * (hi - lo) : value; }
    friend bool operator==(const EpsSpec&, const EpsSpec&) = default;
};

/// Why a text is not an acceptable eps; the callers word the message (an option name, a parameter).
enum class EpsProblem {
    None,
    NotANumber,     // the part before an optional '%' is not a finite number
    NotPositive,    // < 0, or 0 where zero is not allowed
    PercentTooLarge // a percentage above EpsRules::maxPercent
};

/// A finite decimal number that takes the whole text: no whitespace, no '+', no hex (the HTTP API's
/// grammar); nullopt otherwise.
std::optional<double> readDecimal(std::string_view text);

struct EpsRules {
    bool allowZero = false;
    double maxPercent = std::numeric_limits<double>::infinity();
    /// The grammar of the number part; nullopt when it is not a finite number.
    std::optional<double> (*readNumber)(std::string_view) = readDecimal;
};

struct EpsParse {
    EpsSpec spec;
    EpsProblem problem = EpsProblem::None;
    std::string_view numberText; // the text without its '%', as the messages quote it
};

/// Splits an optional trailing '%' off, reads the number and checks it against the rules.
EpsParse parseEps(std::string_view text, const EpsRules& rules = {});

} // namespace vots::fit
