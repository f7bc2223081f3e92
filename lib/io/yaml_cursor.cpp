#include "io/yaml_cursor.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>

namespace iga::io {

bool DeckSource::is_command_line_node(const YAML::Node& node) const
{
    return std::any_of(command_line_nodes_.begin(), command_line_nodes_.end(),
                       [&](const YAML::Node& n) { return n.is(node); });
}

void IssueList::throw_if_any() const
{
    if (!issues_.empty())
        throw DeckError(issues_);
}

std::size_t edit_distance(std::string_view a, std::string_view b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates)
{
    // A typo changes a character or two; a third of a long word is still a typo.
    const std::size_t max_distance = std::max<std::size_t>(2, word.size() / 3);
    const std::string* best = nullptr;
    std::size_t best_distance = max_distance + 1;
    for (const auto& c : candidates) {
        const std::size_t d = edit_distance(word, c);
        if (d > 0 && d < best_distance) {
            best = &c;
            best_distance = d;
        }
    }
    return best ? " (did you mean '" + *best + "'?)" : std::string();
}

std::string hint_or_list(std::string_view word, const std::vector<std::string>& names, std::string_view what)
{
    const std::string hint = did_you_mean(word, names);
    if (!hint.empty())
        return hint;
    return names.empty() ? " (there are no " + std::string(what) + ")"
                         : " (" + std::string(what) + ": " + join_names(names) + ")";
}

std::string join_names(const std::vector<std::string>& names)
{
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i > 0 ? ", " : "") + names[i];
    return out;
}

std::string format_number(double value)
{
    if (std::isnan(value))
        return ".nan";
    if (std::isinf(value))
        return value > 0 ? ".inf" : "-.inf";
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest round-trip form
    const std::string text(buffer, result.ptr);
    const auto e = text.find('e');
    std::string mantissa = text.substr(0, e);
    if (mantissa.find('.') == std::string::npos)
        mantissa += ".0";
    return e == std::string::npos ? mantissa : mantissa + text.substr(e);
}

std::optional<double> parse_number(std::string_view text)
{
    bool negative = false;
    std::string_view body = text;
    if (!body.empty() && (body.front() == '+' || body.front() == '-')) {
        negative = body.front() == '-';
        body.remove_prefix(1);
    }
    if (body.empty())
        return std::nullopt;
    // YAML 1.2 core schema spellings of infinity and not-a-number.
    if (body == ".inf" || body == ".Inf" || body == ".INF")
        return negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    if (body == ".nan" || body == ".NaN" || body == ".NAN")
        return std::numeric_limits<double>::quiet_NaN();
    if (!(std::isdigit(static_cast<unsigned char>(body.front())) || body.front() == '.'))
        return std::nullopt;
    double value = 0.0;
    const auto result = std::from_chars(body.data(), body.data() + body.size(), value);
    if (result.ptr != body.data() + body.size())
        return std::nullopt;
    if (result.ec == std::errc::result_out_of_range)
        // from_chars leaves `value` untouched here; strtod tells overflow (infinity) from underflow (0).
        value = std::strtod(std::string(body).c_str(), nullptr);
    else if (result.ec != std::errc())
        return std::nullopt;
    return negative ? -value : value;
}

// ---------------------------------------------------------------------------

Cursor::Cursor(const YAML::Node& root, const DeckSource& source, IssueList& issues)
    : Cursor(root, true, std::string(), std::string(), root.Mark(), source.is_command_line_node(root), source, issues)
{
}

Cursor::Cursor(const YAML::Node& node, bool present, std::string path, std::string schema_path,
               const YAML::Mark& mark, bool command_line, const DeckSource& source, IssueList& issues)
    : node_(node), present_(present), path_(std::move(path)), schema_path_(std::move(schema_path)), mark_(mark),
      command_line_(command_line), source_(&source), issues_(&issues)
{
}

namespace {
/// `key` below `path`, dotted.
std::string below(const std::string& path, std::string_view key)
{
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
}  // namespace

Cursor Cursor::child(std::string_view key) const
{
    std::string path = below(path_, key);
    std::string schema_path = below(schema_path_, key);
    if (is_map()) {
        for (auto it = node_.begin(); it != node_.end(); ++it) {
            if (!it->first.IsScalar() || it->first.Scalar() != key)
                continue;
            // `key:` with no value has no useful mark of its own: point at the key.
            const YAML::Mark mark = it->second.IsNull() ? it->first.Mark() : it->second.Mark();
            const bool command_line = command_line_ || source_->is_command_line_node(it->second);
            return Cursor(it->second, true, std::move(path), std::move(schema_path), mark, command_line, *source_,
                          *issues_);
        }
    }
    return Cursor(YAML::Node(), false, std::move(path), std::move(schema_path), mark_, command_line_, *source_,
                  *issues_);
}

std::optional<std::string> Cursor::name_of_item() const
{
    if (!is_map())
        return std::nullopt;
    for (auto it = node_.begin(); it != node_.end(); ++it)
        if (it->first.IsScalar() && it->first.Scalar() == "name" && it->second.IsScalar() &&
            !it->second.Scalar().empty())
            return it->second.Scalar();
    return std::nullopt;
}

Cursor Cursor::item(std::size_t i) const
{
    const YAML::Node node = node_[i];
    const bool command_line = command_line_ || source_->is_command_line_node(node);
    Cursor c(node, true, std::string(), below(schema_path_, "*"), node.Mark(), command_line, *source_, *issues_);
    c.path_ = below(path_, c.name_of_item().value_or(std::to_string(i)));
    return c;
}

std::vector<Cursor> Cursor::items() const
{
    std::vector<Cursor> out;
    if (is_list())
        for (std::size_t i = 0; i < node_.size(); ++i)
            out.push_back(item(i));
    return out;
}

SourceLocation Cursor::location() const
{
    if (command_line_)
        return {std::string(command_line_file), 0, 0};
    if (mark_.line < 0)
        return {source_->file(), 0, 0};
    return {source_->file(), mark_.line + 1, mark_.column + 1};
}

std::string Cursor::value_text() const
{
    // Long lists (control points) are cut: the location already says where they are.
    constexpr std::size_t max_length = 60;
    if (!exists() || node_.IsMap())
        return {};
    if (node_.IsScalar())
        return node_.Scalar();
    YAML::Emitter out;
    out << YAML::Flow << node_;
    std::string text = out.c_str();
    if (text.size() > max_length)
        text = text.substr(0, max_length - 3) + "...";
    return text;
}

void Cursor::fail(const std::string& reason) const
{
    issues_->add(DeckIssue{location(), path_, value_text(), reason});
}

void Cursor::fail_here(const std::string& reason) const
{
    issues_->add(DeckIssue{location(), path_, std::string(), reason});
}

void Cursor::fail_missing(std::string_view key) const
{
    fail_here("missing required key '" + std::string(key) + "'");
}

bool Cursor::expect_map() const
{
    if (is_map())
        return true;
    fail(exists() ? "expected a map of keys" : "expected a map of keys, got nothing");
    return false;
}

bool Cursor::expect_list() const
{
    if (is_list())
        return true;
    fail(exists() ? "expected a list" : "expected a list, got nothing");
    return false;
}

std::vector<std::string> Cursor::keys() const
{
    std::vector<std::string> out;
    if (!is_map())
        return out;
    for (auto it = node_.begin(); it != node_.end(); ++it)
        if (it->first.IsScalar())
            out.push_back(it->first.Scalar());
    return out;
}

bool Cursor::check_keys() const
{
    const std::vector<std::string>& known = map_keys(schema_path_);
    IGA_CHECK(!known.empty(), "the deck schema has no map '" + schema_path_ + "'");
    if (!expect_map())
        return false;
    for (auto it = node_.begin(); it != node_.end(); ++it) {
        const bool command_line = command_line_ || source_->is_command_line_node(it->second);
        const Cursor key_cursor(it->first, true, path_, schema_path_, it->first.Mark(), command_line, *source_,
                                *issues_);
        if (!it->first.IsScalar()) {
            key_cursor.fail_here("keys must be words");
            continue;
        }
        const std::string& key = it->first.Scalar();
        if (std::find(known.begin(), known.end(), key) == known.end()) {
            const std::string hint = did_you_mean(key, known);
            key_cursor.fail_here("unknown key '" + key + "'" +
                                 (hint.empty() ? " (known keys: " + join_names(known) + ")" : hint));
        }
    }
    return true;
}

void Cursor::check_duplicate_keys() const
{
    if (is_list()) {
        for (const Cursor& c : items())
            c.check_duplicate_keys();
        return;
    }
    if (!is_map())
        return;
    std::map<std::string, int> seen;  // key -> line of its first use (a map: a hostile deck may hold many keys)
    for (auto it = node_.begin(); it != node_.end(); ++it) {
        const bool command_line = command_line_ || source_->is_command_line_node(it->second);
        if (!it->first.IsScalar())
            continue;  // check_keys reports it where keys are checked
        const std::string& key = it->first.Scalar();
        const Cursor key_cursor(it->first, true, path_, schema_path_, it->first.Mark(), command_line, *source_,
                                *issues_);
        if (const auto first = seen.find(key); first != seen.end()) {
            key_cursor.fail_here("duplicate key '" + key + "'" +
                                 (first->second > 0 ? " (first given at line " + std::to_string(first->second) + ")"
                                                    : std::string()));
            continue;
        }
        seen.emplace(key, key_cursor.location().line);
        const YAML::Mark mark = it->second.IsNull() ? it->first.Mark() : it->second.Mark();
        Cursor(it->second, true, below(path_, key), below(schema_path_, key), mark, command_line, *source_, *issues_)
            .check_duplicate_keys();
    }
}

std::optional<std::string> Cursor::scalar(const char* expected) const
{
    if (exists() && node_.IsScalar())
        return node_.Scalar();
    if (expected)
        fail(expected);
    return std::nullopt;
}

std::optional<double> Cursor::to_number() const
{
    const auto text = scalar("expected a number");
    if (!text)
        return std::nullopt;
    const auto value = parse_number(*text);
    if (!value) {
        fail("expected a number");
        return std::nullopt;
    }
    if (!std::isfinite(*value)) {
        const bool spelled_infinite = text->find("inf") != std::string::npos || text->find("Inf") != std::string::npos ||
                                      text->find("INF") != std::string::npos || std::isnan(*value);
        fail(spelled_infinite ? "must be a finite number"
                              : "out of range: beyond the largest number a double holds (about 1.8e308)");
        return std::nullopt;
    }
    return value;
}

std::optional<int> Cursor::to_integer() const
{
    const auto text = scalar("expected an integer");
    if (!text)
        return std::nullopt;
    const auto value = parse_number(*text);
    // Accept 3 and 3.0; reject 2.5, NaN and infinity; an integer an int cannot hold is out of range.
    if (!value || !std::isfinite(*value) || *value != std::floor(*value)) {
        fail("expected an integer");
        return std::nullopt;
    }
    constexpr int limit = std::numeric_limits<int>::max();
    if (std::abs(*value) > limit) {
        fail(*value > 0 ? "out of range: an integer here is at most " + std::to_string(limit)
                        : "out of range: an integer here is at least -" + std::to_string(limit));
        return std::nullopt;
    }
    return static_cast<int>(*value);
}

std::optional<bool> Cursor::to_bool() const
{
    const auto text = scalar("expected true or false");
    if (!text)
        return std::nullopt;
    if (*text == "true" || *text == "True" || *text == "TRUE")
        return true;
    if (*text == "false" || *text == "False" || *text == "FALSE")
        return false;
    fail("expected true or false");
    return std::nullopt;
}

std::optional<std::string> Cursor::to_string() const
{
    return scalar("expected a string");
}

namespace {
std::string list_of(std::size_t n, const char* what)
{
    return n > 0 ? "expected a list of " + std::to_string(n) + " " + what : std::string("expected a list of ") + what;
}
}  // namespace

std::optional<std::vector<double>> Cursor::to_numbers(std::size_t n) const
{
    if (!is_list() || (n > 0 && size() != n)) {
        fail(list_of(n, "numbers"));
        return std::nullopt;
    }
    std::vector<double> values;
    bool ok = true;
    for (const Cursor& c : items()) {
        const auto v = c.to_number();
        ok = ok && v.has_value();
        values.push_back(v.value_or(0.0));
    }
    return ok ? std::optional(values) : std::nullopt;
}

std::optional<std::vector<int>> Cursor::to_integers(std::size_t n) const
{
    if (!is_list() || (n > 0 && size() != n)) {
        fail(list_of(n, "integers"));
        return std::nullopt;
    }
    std::vector<int> values;
    bool ok = true;
    for (const Cursor& c : items()) {
        const auto v = c.to_integer();
        ok = ok && v.has_value();
        values.push_back(v.value_or(0));
    }
    return ok ? std::optional(values) : std::nullopt;
}

const DeckKey& Cursor::schema_key(std::string_view key, ValueType type) const
{
    const std::string path = below(schema_path_, key);
    const DeckKey* entry = find_deck_key(path);
    IGA_CHECK(entry != nullptr, "the deck schema has no key '" + path + "'");
    IGA_CHECK(entry->type == type, "the deck schema gives '" + path + "' another type than the reader reads");
    return *entry;
}

}  // namespace iga::io
