#include "io/deck_key_tables.hpp"

#include "io/deck_schema.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

namespace iga::io {
namespace {

constexpr std::string_view open_marker = "<!-- keys: ";
constexpr std::string_view marker_end = " -->";
constexpr std::string_view close_marker = "<!-- /keys -->";
constexpr std::string_view top_level = "top-level";

/// What a table documents: a group once for all its places, any other map by its path.
std::string identity(const DeckKey& key)
{
    return key.group.empty() ? key.path : "group " + key.group;
}

/// The schema path of the map a marker names ("" for the top level), and its identity;
/// nothing when it names no map.
std::optional<std::pair<std::string, std::string>> marked_map(const std::string& name)
{
    if (name == top_level)
        return std::pair<std::string, std::string>{"", ""};
    const bool items = name.size() > 2 && name.compare(name.size() - 2, 2, ".*") == 0;
    const DeckKey* key = find_deck_key(items ? name.substr(0, name.size() - 2) : name);
    if (!key || key->kind != (items ? KeyKind::list : KeyKind::map))
        return std::nullopt;
    return std::pair<std::string, std::string>{name, identity(*key)};
}

/// A cell of a markdown table: `|` would end it.
std::string cell(const std::string& text)
{
    std::string out;
    for (const char c : text)
        out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

/// The rows of the keys of map `map`, keys written from `prefix` on; descends into the
/// maps and lists whose identity has no table in `tabled`.
void add_rows(const std::string& map, const std::string& prefix, const std::set<std::string>& tabled,
              std::string& out, std::set<std::size_t>& shown)
{
    for (const std::string& name : map_keys(map)) {
        const DeckKey& key = *find_deck_key(map.empty() ? name : map + "." + name);
        out += "| `" + prefix + name + "` | " + cell(key.type_text) + " | " + cell(key.default_text) + " | " +
               cell(key.meaning) + " |\n";
        shown.insert(key.row);
        if (key.kind == KeyKind::value || tabled.count(identity(key)))
            continue;
        const bool items = key.kind == KeyKind::list;
        add_rows(key.path + (items ? ".*" : ""), prefix + name + (items ? ".*." : "."), tabled, out, shown);
    }
}

struct Marker {
    std::size_t line = 0;  ///< 1-based
    std::string map;
};

}  // namespace

KeyTables generate_key_tables(std::string_view markdown)
{
    // The document as lines, and its markers.
    std::vector<std::string> lines;
    for (std::size_t start = 0; start < markdown.size();) {
        const auto end = std::min(markdown.find('\n', start), markdown.size());
        lines.emplace_back(markdown.substr(start, end - start));
        start = end + 1;
    }
    std::vector<Marker> markers;
    std::vector<std::size_t> closes;
    std::set<std::string> tabled;  // identities of the maps that have a table
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& line = lines[i];
        if (line == close_marker) {
            if (markers.size() != closes.size() + 1)
                throw std::invalid_argument("line " + std::to_string(i + 1) + ": '" + std::string(close_marker) +
                                            "' without a '" + std::string(open_marker) + "MAP -->' before it");
            closes.push_back(i);
            continue;
        }
        if (line.rfind(open_marker, 0) != 0)
            continue;
        const std::string where = "line " + std::to_string(i + 1) + ": ";
        if (line.size() < open_marker.size() + marker_end.size() ||
            line.compare(line.size() - marker_end.size(), marker_end.size(), marker_end) != 0)
            throw std::invalid_argument(where + "expected '" + std::string(open_marker) + "MAP -->'");
        if (closes.size() != markers.size())
            throw std::invalid_argument(where + "a table opens inside the table opened at line " +
                                        std::to_string(markers.back().line));
        const std::string name =
            line.substr(open_marker.size(), line.size() - open_marker.size() - marker_end.size());
        const auto map = marked_map(name);
        if (!map)
            throw std::invalid_argument(where + "'" + name + "' names no map of the deck schema (io/deck_schema.hpp)");
        markers.push_back({i + 1, map->first});
        tabled.insert(map->second);
    }
    if (closes.size() != markers.size())
        throw std::invalid_argument("line " + std::to_string(markers.back().line) + ": no '" +
                                    std::string(close_marker) + "' after the table");

    // Every line outside the tables as it is; each table generated.
    KeyTables result;
    std::set<std::size_t> shown;
    std::size_t next = 0;
    for (std::size_t t = 0; t < markers.size(); ++t) {
        const std::size_t open = markers[t].line - 1;
        for (; next <= open; ++next)
            result.markdown += lines[next] + "\n";
        result.markdown += "\n| key | type | default | meaning |\n|---|---|---|---|\n";
        add_rows(markers[t].map, "", tabled, result.markdown, shown);
        result.markdown += "\n";
        next = closes[t];
        result.tables.push_back(markers[t].map.empty() ? std::string(top_level) : markers[t].map);
    }
    for (; next < lines.size(); ++next)
        result.markdown += lines[next] + (next + 1 < lines.size() || markdown.back() == '\n' ? "\n" : "");

    std::set<std::size_t> reported;
    for (const DeckKey& key : deck_keys())
        if (!shown.count(key.row) && reported.insert(key.row).second)
            result.undocumented.push_back(key.path);
    return result;
}

}  // namespace iga::io
