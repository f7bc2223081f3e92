#pragma once
// The vocabulary of the deck schema's table (io/deck_schema.cpp): a row is
// {path, type, default, meaning}, written with the helpers below so that the
// table reads as one. Internal to io/: deck_schema.cpp writes the rows, and
// deck_schema_index.cpp turns them into the DeckKeys of io/deck_schema.hpp.

#include "io/deck_names.hpp"
#include "io/deck_schema.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace iga::io::schema_rows {

struct Row;

/// What a row's key holds.
struct Type {
    KeyKind kind = KeyKind::value;
    ValueType value = ValueType::none;
    Range range{};
    std::vector<std::string> (*words)() = nullptr;  ///< choice: its spellings
    std::string_view text{};                        ///< the docs' name of the type, where it is not generated
    const Row* group = nullptr;                     ///< a map or list whose keys are a shared group
    std::size_t group_size = 0;
    std::string_view group_name{};

    /// The same type, named `name` in the docs.
    constexpr Type shown_as(std::string_view name) const
    {
        Type t = *this;
        t.text = name;
        return t;
    }
};

struct Default {
    Presence presence = Presence::optional;
    std::string_view text{};
};

struct Row {
    std::string_view path;  ///< relative to the group, for the rows of a group
    Type type;
    Default value;
    std::string_view meaning;
};

template <class E>
std::vector<std::string> spellings()
{
    std::vector<std::string> out;
    for (const auto& entry : DeckNames<E>::all)
        out.emplace_back(entry.name);
    return out;
}

constexpr Range above(double x, std::string_view why = {})
{
    return {Range::Kind::above, x, 0.0, why};
}
constexpr Range at_least(double x, std::string_view why = {})
{
    return {Range::Kind::at_least, x, 0.0, why};
}
constexpr Range inside(double low, double high)
{
    return {Range::Kind::open_interval, low, high, {}};
}

constexpr Type map()
{
    return {KeyKind::map};
}
constexpr Type list()
{
    return {KeyKind::list};
}
template <std::size_t N>
constexpr Type map_of(const Row (&group)[N], std::string_view name)
{
    return {KeyKind::map, ValueType::none, {}, nullptr, {}, group, N, name};
}
template <std::size_t N>
constexpr Type list_of(const Row (&group)[N], std::string_view name)
{
    return {KeyKind::list, ValueType::none, {}, nullptr, {}, group, N, name};
}
constexpr Type integer(Range range = {})
{
    return {KeyKind::value, ValueType::integer, range};
}
constexpr Type number(Range range = {})
{
    return {KeyKind::value, ValueType::number, range};
}
constexpr Type number_or_auto(Range range)
{
    return {KeyKind::value, ValueType::number_or_auto, range};
}
constexpr Type boolean()
{
    return {KeyKind::value, ValueType::boolean};
}
/// A string; `name` says what kind ("word", "path", ...).
constexpr Type text(std::string_view name = "string")
{
    return {KeyKind::value, ValueType::string, {}, nullptr, name};
}
template <class E>
constexpr Type choice()
{
    return {KeyKind::value, ValueType::choice, {}, &spellings<E>};
}
constexpr Type integers(std::string_view name, Range range = {})
{
    return {KeyKind::value, ValueType::integers, range, nullptr, name};
}
constexpr Type numbers(std::string_view name, Range range = {})
{
    return {KeyKind::value, ValueType::numbers, range, nullptr, name};
}
/// A value the reader reads by hand (a side, a list of lists, ...).
constexpr Type other(std::string_view name)
{
    return {KeyKind::value, ValueType::other, {}, nullptr, name};
}

inline constexpr Default required{Presence::required, "—"};
constexpr Default fallback(std::string_view text)
{
    return {Presence::optional, text};
}
/// Required in the case `when` only (the reader checks it).
constexpr Default needed(std::string_view when)
{
    return {Presence::conditional, when};
}

/// The rows of the deck, top level first; a row of a map or list may include a group.
std::span<const Row> deck_table();

}  // namespace iga::io::schema_rows
