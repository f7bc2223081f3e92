#pragma once
// Cursor: a YAML node together with its key path in the deck (--set syntax:
// `materials.steel.nu`, `loads.0.force`) and its source (file:line:col, or
// "<command line>" for a node that --set put in). The deck reader reads every
// value through a Cursor, so every problem it finds is located
// (docs/deck.md "General rules").
//
// Problems are recorded in an IssueList instead of thrown, so one pass reports
// all independent issues; the reader throws a single DeckError at the end.
// Typed reads return std::nullopt after recording an issue.
// yaml-cpp marks are 0-based; SourceLocation is 1-based (0 = unknown).
// Internal to io/: this header exposes yaml-cpp, which nothing else includes.

#include "core/error.hpp"
#include "io/deck_names.hpp"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <initializer_list>
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
    /// Checks that this is a map whose keys are all in `keys`: records an issue
    /// for each unknown key (with "did you mean").
    bool allow_only(std::initializer_list<std::string_view> keys) const;
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

    /// Required key: records "missing required key" when absent.
    template <class T>
    std::optional<T> get(std::string_view key) const
    {
        const Cursor c = child(key);
        if (!c.exists()) {
            fail_missing(key);
            return std::nullopt;
        }
        return c.to<T>();
    }
    /// Optional key: `fallback` when absent, and also when invalid (after recording the issue).
    template <class T>
    T get_or(std::string_view key, T fallback) const
    {
        const Cursor c = child(key);
        if (!c.exists())
            return fallback;
        return c.to<T>().value_or(std::move(fallback));
    }

    /// Required key holding a number > 0 ("must be > 0" otherwise).
    std::optional<double> positive(std::string_view key) const;
    /// Optional key holding a number > 0: `fallback` when absent or invalid.
    double positive_or(std::string_view key, double fallback) const;
    /// Optional key holding an integer >= `min`: `fallback` when absent or invalid.
    int integer_at_least(std::string_view key, int fallback, int min) const;

private:
    Cursor(const YAML::Node& node, bool present, std::string path, const YAML::Mark& mark, bool command_line,
           const DeckSource& source, IssueList& issues);
    std::optional<std::string> scalar(const char* expected) const;
    std::optional<std::string> name_of_item() const;

    YAML::Node node_;
    bool present_ = true;
    std::string path_;
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
