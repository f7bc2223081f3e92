// The deck schema's table (io/deck_schema.cpp) flattened to full paths, checked
// for consistency, and indexed by path and by map.
#include "io/deck_schema.hpp"

#include "core/error.hpp"
#include "io/deck_schema_rows.hpp"

#include <fmt/format.h>

#include <functional>
#include <map>

namespace iga::io {
namespace {

using schema_rows::Row;
using schema_rows::Type;

/// "> 0", ">= 1", "in (-1, 0.5)" in the typography of docs/deck.md.
std::string docs_range(const Range& range)
{
    std::string text;
    for (const char c : range.text()) {
        if (c == '-')
            text += "−";
        else
            text += c;
    }
    const auto at = text.find(">=");
    return at == std::string::npos ? text : text.replace(at, 2, "≥");
}

std::string docs_type(const Type& type)
{
    std::string range;  // " > 0", or nothing
    if (type.range.kind != Range::Kind::none)
        range.append(" ").append(docs_range(type.range));
    if (!type.text.empty())
        return std::string(type.text) + range;
    switch (type.value) {
    case ValueType::integer: return "integer" + range;
    case ValueType::number: return "number" + range;
    case ValueType::number_or_auto: return "number" + range + ", or `auto`";
    case ValueType::boolean: return "boolean";
    case ValueType::choice: {
        const std::vector<std::string> words = type.words();
        std::string text;
        for (std::size_t i = 0; i < words.size(); ++i) {
            text += i == 0 ? "" : words.size() == 2 ? " or " : ", ";
            text.append("`").append(words[i]).append("`");
        }
        return text;
    }
    default: return type.kind == KeyKind::map ? "map" : "list";
    }
}

std::string parent_of(const std::string& path)
{
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? std::string() : path.substr(0, dot);
}

struct Schema {
    std::vector<DeckKey> keys;
    std::map<std::string, std::size_t, std::less<>> index;
    std::map<std::string, std::vector<std::string>, std::less<>> children;  ///< map path -> its keys

    /// Adds `rows` under `base` ("" or "bodies.*.nurbs." ...), expanding the groups they include.
    void add(const Row* rows, std::size_t n, const std::string& base, std::map<const Row*, std::size_t>& row_ids);
};

void Schema::add(const Row* rows, std::size_t n, const std::string& base,
                 std::map<const Row*, std::size_t>& row_ids)
{
    for (std::size_t i = 0; i < n; ++i) {
        const Row& row = rows[i];
        DeckKey key;
        key.path = base + std::string(row.path);
        key.kind = row.type.kind;
        key.type = row.type.value;
        key.range = row.type.range;
        if (row.type.words)
            key.words = row.type.words();
        key.type_text = docs_type(row.type);
        key.presence = row.value.presence;
        key.default_text = row.value.presence == Presence::conditional ? "— (" + std::string(row.value.text) + ")"
                                                                       : std::string(row.value.text);
        key.meaning = row.meaning;
        key.group = row.type.group_name;
        key.row = row_ids.emplace(&row, row_ids.size()).first->second;

        // The table's own consistency: a key is declared once, under a map (or the items of a list).
        IGA_CHECK(!index.count(key.path), "deck schema: '" + key.path + "' is declared twice");
        std::string parent = parent_of(key.path);
        const bool item = parent.size() >= 2 && parent.compare(parent.size() - 2, 2, ".*") == 0;
        const auto owner = index.find(item ? parent.substr(0, parent.size() - 2) : parent);
        IGA_CHECK(parent.empty() || (owner != index.end() && keys[owner->second].kind ==
                                                                 (item ? KeyKind::list : KeyKind::map)),
                  "deck schema: '" + key.path + "' is not under a map or the items of a list");
        IGA_CHECK((key.type == ValueType::none) == (key.kind != KeyKind::value),
                  "deck schema: '" + key.path + "' needs a value type exactly when it holds a value");
        IGA_CHECK(key.type != ValueType::choice || !key.words.empty(), "deck schema: '" + key.path + "' has no words");

        index.emplace(key.path, keys.size());
        children[parent].push_back(key.path.substr(parent.empty() ? 0 : parent.size() + 1));
        keys.push_back(key);
        if (row.type.group)
            add(row.type.group, row.type.group_size, key.path + (key.kind == KeyKind::list ? ".*." : "."), row_ids);
    }
}

const Schema& schema()
{
    static const Schema built = [] {
        Schema s;
        std::map<const Row*, std::size_t> row_ids;
        const std::span<const Row> rows = schema_rows::deck_table();
        s.add(rows.data(), rows.size(), "", row_ids);
        return s;
    }();
    return built;
}

}  // namespace

bool Range::admits(double x) const
{
    switch (kind) {
    case Kind::above: return x > low;
    case Kind::at_least: return x >= low;
    case Kind::open_interval: return x > low && x < high;
    case Kind::none: break;
    }
    return true;
}

std::string Range::text() const
{
    switch (kind) {
    case Kind::above: return fmt::format("> {}", low);
    case Kind::at_least: return fmt::format(">= {}", low);
    case Kind::open_interval: return fmt::format("in ({}, {})", low, high);
    case Kind::none: break;
    }
    return {};
}

std::string Range::failure() const
{
    const std::string reason = why.empty() ? std::string() : " (" + std::string(why) + ")";
    return (kind == Kind::open_interval ? "must lie " : "must be ") + text() + reason;
}

const std::vector<DeckKey>& deck_keys()
{
    return schema().keys;
}

const DeckKey* find_deck_key(std::string_view path)
{
    const Schema& s = schema();
    const auto at = s.index.find(path);
    return at == s.index.end() ? nullptr : &s.keys[at->second];
}

const std::vector<std::string>& map_keys(std::string_view path)
{
    static const std::vector<std::string> none;
    const Schema& s = schema();
    const auto at = s.children.find(path);
    return at == s.children.end() ? none : at->second;
}

std::vector<std::string> deck_key_paths()
{
    std::vector<std::string> paths;
    for (const DeckKey& key : deck_keys())
        paths.push_back(key.path);
    return paths;
}

}  // namespace iga::io
