// Enum <-> name: each enum's table of names beside the enum, and the one nameOf/parseName that read them.
#pragma once

#include "vots/fit/Error.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vots::fit {

/// One spelling of an enum value. A table's first row for a value is its name; later rows for the same
/// value are further spellings parseName accepts ("gray" for grey).
template <class E> struct NamedValue {
    E value;
    std::string_view name;
};

/// An enum's names and what the names are of ("colormap", for "unknown colormap 'x'"). A table is found
/// by argument-dependent lookup: beside the enum, `constexpr const auto& namesOf(E) { return TABLE; }`.
template <class E, std::size_t N> struct NameTable {
    std::string_view what;
    std::array<NamedValue<E>, N> rows;
};

/// A table from rows written out in place: nameTable<Colormap>("colormap", {{Colormap::Grey, "grey"}, ...}).
template <class E, std::size_t N>
constexpr NameTable<E, N> nameTable(std::string_view what, const NamedValue<E> (&rows)[N]) {
    NameTable<E, N> table{what, {}};
    for (std::size_t i = 0; i < N; ++i)
        table.rows[i] = rows[i];
    return table;
}

/// The name of `value` (its table's first row for it); "unknown" for a value the table lacks.
template <class E> constexpr std::string_view nameOf(E value) {
    for (const NamedValue<E>& row : namesOf(value).rows)
        if (row.value == value) return row.name;
    return "unknown";
}

/// The value spelt `name`, nullopt when no row spells it.
template <class E> constexpr std::optional<E> findNamed(std::string_view name) {
    for (const NamedValue<E>& row : namesOf(E{}).rows)
        if (row.name == name) return row.value;
    return std::nullopt;
}

/// The names (not the further spellings) in table order, "a, b, c".
template <class E> std::string knownNames() {
    const auto& table = namesOf(E{});
    std::string out;
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        bool first = true;
        for (std::size_t j = 0; j < i; ++j)
            first = first && table.rows[j].value != table.rows[i].value;
        if (!first) continue;
        if (!out.empty()) out += ", ";
        out += table.rows[i].name;
    }
    return out;
}

/// Every spelling parseName accepts, in table order (for a command line's list of choices).
template <class E> std::vector<std::string> acceptedNames() {
    std::vector<std::string> names;
    for (const NamedValue<E>& row : namesOf(E{}).rows)
        names.emplace_back(row.name);
    return names;
}

/// The value spelt `name`; throws InputError "unknown <what> '<name>' (known: <knownNames>)".
template <class E> E parseName(std::string_view name) {
    if (const auto value = findNamed<E>(name)) return *value;
    throw InputError("unknown " + std::string(namesOf(E{}).what) + " '" + std::string(name) +
                     "' (known: " + knownNames<E>() + ")");
}

} // namespace vots::fit
