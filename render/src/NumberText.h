// Private to render: the "A,B" number pairs of slab and sweep requests, read the one way.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace vots::render::detail {

/// A finite decimal number spelled in at most 32 characters; nullopt for anything else.
std::optional<double> parseFinite(std::string_view text);

/// "A,B": two finite numbers, each at most 1e9 in magnitude (millimetres no volume reaches); nullopt for
/// anything else. The callers check signs and name the fields in their own messages.
std::optional<std::array<double, 2>> parseFinitePair(std::string_view text);

} // namespace vots::render::detail
