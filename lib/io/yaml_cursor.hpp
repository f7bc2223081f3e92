#pragma once
// Cursor: a YAML node together with its key path in the deck (--set syntax:
// `materials.steel.nu`, `loads.0.force`), its path in the deck schema (list items
// as `*`: `materials.*.nu`, io/deck_schema.hpp) and its source (file:line:col, or
// "<command line>" for a node that --set put in). The deck reader reads every
// value through a Cursor, so every problem it finds is located
// (docs/deck.md "General rules"), and takes the keys each map allows, and the
// type and range of the simple values, from the schema.
//
// Problems are recorded in an IssueList instead of thrown, so one pass reports
// all independent issues; the reader throws a single DeckError at the end.
// Typed reads return std::nullopt after recording an issue.
// yaml-cpp marks are 0-based; SourceLocation is 1-based (0 = unknown).
// Internal to io/: this header exposes yaml-cpp, which nothing else includes.

#include "core/error.hpp"
#include "io/deck_names.hpp"
#include "io/deck_schema.hpp"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace iga::io {

/// File label of values given with --set.
inline constexpr std::string_view command_line_file = "<command line>";

/// Where a YAML tree came from: the deck's file label, and the nodes that --set
/// wrote into it (a node and everything below it count as command-line values).
class DeckSource {
public:
    explicit DeckSource(std::string file) : file_(std::move(file)) {}
    const std::string& file() const { return file_; }
    void add_command_line_node(const YAML::Node& node) { command_line_nodes_.push_back(node); }
    bool is_command_line_node(const YAML::Node& node) const;

private:
    std::string file_;
    std::vector<YAML::Node> command_line_nodes_;
};

/// The issues found so far, in the order found.
class IssueList {
public:
    void add(DeckIssue issue) { issues_.push_back(std::move(issue)); }
    bool empty() const { return issues_.empty(); }
    const std::vector<DeckIssue>& issues() const { return issues_; }
    /// Throws one DeckError carrying every issue, if there are any.
    void throw_if_any() const;

private:
    std::vector<DeckIssue> issues_;
};

/// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(std::string_view a, std::string_view b);
/// " (did you mean 'x'?)" for the candidate closest to `word` when it is close
/// enough to be a typo (distance <= max(2, |word|/3)); "" otherwise.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);
/// did_you_mean(word, names), or else " (<what>: a, b, c)" listing the choices.
std::string hint_or_list(std::string_view word, const std::vector<std::string>& names, std::string_view what);
/// "a, b, c"
std::string join_names(const std::vector<std::string>& names);
/// A double as the shortest text that reads back to the same value, always with a
/// '.' so that every YAML reader takes it for a float ("1000.0", "1.0e-10").
std::string format_number(double value);
/// Parses a YAML scalar as a double: decimal or exponent notation, and YAML's
/// .inf/.nan spellings (returned as inf/NaN so the caller can reject them).
std::optional<double> parse_number(std::string_view text);

class Cursor {
public:
    /// The root of a tree read from `source`.
    Cursor(const YAML::Node& root, const DeckSource& source, IssueList& issues);

    const std::string& path() const { return path_; }
    /// The path in the deck schema: list items written `*` ("materials.*.nu").
    const std::string& schema_path() const { return schema_path_; }
    /// The key is present and its value is not null (`key:` with nothing counts as absent).
    bool exists() const { return present_ && !node_.IsNull(); }
    bool is_map() const { return exists() && node_.IsMap(); }
    bool is_list() const { return exists() && node_.IsSequence(); }
    bool has(std::string_view key) const { return child(key).exists(); }
    std::size_t size() const { return is_list() || is_map() ? node_.size() : 0; }

    /// The value of `key` in this map (absent if there is none; then located here).
    Cursor child(std::string_view key) const;
    /// Item i of this list; its path uses the item's `name` if it has one, else i.
    Cursor item(std::size_t i) const;
    std::vector<Cursor> items() const;

    SourceLocation location() const;
    bool from_command_line() const { return command_line_; }
    /// The value as written: a scalar verbatim, a list in flow style (shortened),
    /// nothing for a map.
    std::string value_text() const;

    /// Records an issue at this node, quoting its value.
    void fail(const std::string& reason) const;
    /// Records an issue at this node without quoting a value.
    void fail_here(const std::string& reason) const;
    /// Records "missing required key '<key>'" at this map.
    void fail_missing(std::string_view key) const;

    /// Checks that this is a map (records an issue if not).
    bool expect_map() const;
    /// Checks that this is a list (records an issue if not).
    bool expect_list() const;
    /// Checks that this is a map whose keys are all keys of its map in the deck
    /// schema: records an issue for each unknown key (with "did you mean").
    bool check_keys() const;
    /// Records an issue at every key that repeats an earlier key of the same map, in
    /// this node and everything below it (YAML readers keep the first and drop the
    /// rest without a word; yaml-cpp keeps both, so they can be found here).
    void check_duplicate_keys() const;
    /// The scalar keys of this map, in file order (empty for anything else).
    std::vector<std::string> keys() const;

    // This node converted; on failure an issue is recorded here and nullopt returned.
    // Numbers must be finite. Integers may be written 3 or 3.0.
    std::optional<double> to_number() const;
    std::optional<int> to_integer() const;
    std::optional<bool> to_bool() const;
    std::optional<std::string> to_string() const;
    /// A flow or block list of numbers; `n` > 0 demands exactly n of them.
    std::optional<std::vector<double>> to_numbers(std::size_t n = 0) const;
    std::optional<std::vector<int>> to_integers(std::size_t n = 0) const;
    template <class E>
    std::optional<E> to_enum() const;

    template <class T>
    std::optional<T> to() const;

    /// The value of `key` read as the deck schema describes it: of its type (T must
    /// be that type), within its range, and "missing required key" when it is absent
    /// and the schema requires it. Lists of numbers: `count` > 0 demands that many.
    template <class T>
    std::optional<T> read(std::string_view key, std::size_t count = 0) const
    {
        return read_value<T>(key, count, false);
    }
    /// read(), or `fallback` when the key is absent or invalid (after recording the issue).
    template <class T>
    T read_or(std::string_view key, T fallback) const
    {
        return read_value<T>(key, 0, false).value_or(std::move(fallback));
    }
    /// read() of a key that the schema requires only in some cases, one of which the caller has found.
    template <class T>
    std::optional<T> read_required(std::string_view key, std::size_t count = 0) const
    {
        return read_value<T>(key, count, true);
    }

private:
    Cursor(const YAML::Node& node, bool present, std::string path, std::string schema_path, const YAML::Mark& mark,
           bool command_line, const DeckSource& source, IssueList& issues);
    /// The schema's entry for `key` of this map; checks that it holds a value of `type` (a reader bug otherwise).
    const DeckKey& schema_key(std::string_view key, ValueType type) const;
    template <class T>
    std::optional<T> read_value(std::string_view key, std::size_t count, bool required) const;
    std::optional<std::string> scalar(const char* expected) const;
    std::optional<std::string> name_of_item() const;

    YAML::Node node_;
    bool present_ = true;
    std::string path_;
    std::string schema_path_;
    YAML::Mark mark_;
    bool command_line_ = false;
    const DeckSource* source_;
    IssueList* issues_;
};

template <class E>
std::optional<E> Cursor::to_enum() const
{
    std::vector<std::string> names;
    for (const auto& entry : DeckNames<E>::all)
        names.emplace_back(entry.name);
    const auto text = scalar(nullptr);
    if (text)
        for (const auto& entry : DeckNames<E>::all)
            if (entry.name == *text)
                return entry.value;
    fail("expected one of " + join_names(names) + (text ? did_you_mean(*text, names) : std::string()));
    return std::nullopt;
}

/// The schema's type of a value the reader reads as T.
template <class T>
constexpr ValueType value_type_of()
{
    if constexpr (std::is_same_v<T, double>)
        return ValueType::number;
    else if constexpr (std::is_same_v<T, int>)
        return ValueType::integer;
    else if constexpr (std::is_same_v<T, bool>)
        return ValueType::boolean;
    else if constexpr (std::is_same_v<T, std::string>)
        return ValueType::string;
    else if constexpr (std::is_same_v<T, std::vector<double>>)
        return ValueType::numbers;
    else if constexpr (std::is_same_v<T, std::vector<int>>)
        return ValueType::integers;
    else if constexpr (std::is_enum_v<T>)
        return ValueType::choice;
    else
        static_assert(std::is_same_v<T, void>, "value_type_of: unsupported type");
}

template <class T>
std::optional<T> Cursor::read_value(std::string_view key, std::size_t count, bool required) const
{
    const DeckKey& entry = schema_key(key, value_type_of<T>());
    if constexpr (std::is_enum_v<T>) {
        std::vector<std::string> words;
        for (const auto& e : DeckNames<T>::all)
            words.emplace_back(e.name);
        IGA_CHECK(entry.words == words, "deck schema: '" + entry.path + "' is read with other words");
    }
    const Cursor c = child(key);
    if (!c.exists()) {
        if (required || entry.presence == Presence::required)
            fail_missing(key);
        return std::nullopt;
    }
    std::optional<T> value;
    if constexpr (std::is_same_v<T, std::vector<double>>)
        value = c.to_numbers(count);
    else if constexpr (std::is_same_v<T, std::vector<int>>)
        value = c.to_integers(count);
    else
        value = c.to<T>();
    if (!value)
        return std::nullopt;
    if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int>) {
        if (!entry.range.admits(*value)) {
            c.fail(entry.range.failure());
            return std::nullopt;
        }
    } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<int>>) {
        bool ok = true;
        for (std::size_t i = 0; i < value->size(); ++i)
            if (!entry.range.admits((*value)[i])) {
                c.item(i).fail(entry.range.failure());
                ok = false;
            }
        if (!ok)
            return std::nullopt;
    }
    return value;
}

template <class T>
std::optional<T> Cursor::to() const
{
    if constexpr (std::is_same_v<T, double>)
        return to_number();
    else if constexpr (std::is_same_v<T, int>)
        return to_integer();
    else if constexpr (std::is_same_v<T, bool>)
        return to_bool();
    else if constexpr (std::is_same_v<T, std::string>)
        return to_string();
    else if constexpr (std::is_same_v<T, std::vector<double>>)
        return to_numbers();
    else if constexpr (std::is_same_v<T, std::vector<int>>)
        return to_integers();
    else if constexpr (std::is_enum_v<T>)
        return to_enum<T>();
    else
        static_assert(std::is_same_v<T, void>, "Cursor::to: unsupported type");
}

}  // namespace iga::io
