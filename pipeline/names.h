// One concept, one name: every enum a user can choose or a report prints has one table of names,
// declared beside the enum, and everything that reads or writes a name (scene files, the command
// line's choices, printers, reports, error messages) goes through it. Adding a value means adding its
// row to the table; nothing else spells it.
//
// Beside an enum E (found by argument-dependent lookup):
//   inline constexpr EnumName<E> kENames[] = {{E::A, "a"}, {E::B, "b"}};
//   constexpr std::span<const EnumName<E>> enumNames(E) { return kENames; }
// A table lists every value exactly once, in the order messages and help texts list them.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace facet {

template <class E>
struct EnumName {
    E value;
    std::string_view name;  // as scene files, the command line, printers and reports spell it
};

// The name of `value`; "?" for a value missing from its table (which the tables' tests rule out).
template <class E>
constexpr std::string_view nameOf(E value) {
    for (const EnumName<E>& entry : enumNames(E{}))
        if (entry.value == value) return entry.name;
    return "?";
}

// The value named `text`, or nothing when no value has that name.
template <class E>
constexpr std::optional<E> parseName(std::string_view text) {
    for (const EnumName<E>& entry : enumNames(E{}))
        if (entry.name == text) return entry.value;
    return std::nullopt;
}

// The names in table order, leaving out `except` (values a scene key or an option does not offer).
template <class E>
std::vector<std::string> namesOf(std::initializer_list<E> except = {}) {
    std::vector<std::string> names;
    for (const EnumName<E>& entry : enumNames(E{})) {
        bool left = false;
        for (const E value : except)
            left = left || value == entry.value;
        if (!left) names.emplace_back(entry.name);
    }
    return names;
}

}  // namespace facet
