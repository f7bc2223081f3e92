#include "io/overrides.hpp"

#include "io/deck_schema.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace iga::io {
namespace {

std::string trim(std::string_view s)
{
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos)
        return {};
    const auto last = s.find_last_not_of(" \t");
    return std::string(s.substr(first, last - first + 1));
}

std::vector<std::string> split_path(const std::string& path)
{
    std::vector<std::string> segments;
    std::size_t start = 0;
    while (true) {
        const auto dot = path.find('.', start);
        segments.push_back(path.substr(start, dot - start));
        if (dot == std::string::npos)
            return segments;
        start = dot + 1;
    }
}

bool is_index(const std::string& s)
{
    const auto digit = [](unsigned char c) { return std::isdigit(c) != 0; };
    return !s.empty() && s.size() < 9 && std::all_of(s.begin(), s.end(), digit);
}

std::string quoted(const std::string& walked)
{
    return walked.empty() ? std::string("the deck") : "'" + walked + "'";
}

/// Position of the item of `list` called `segment`: by `name` first, then by index.
std::optional<std::size_t> find_item(const YAML::Node& list, const std::string& segment)
{
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node item = list[i];
        if (item.IsMap() && item["name"] && item["name"].IsScalar() && item["name"].Scalar() == segment)
            return i;
    }
    if (is_index(segment) && std::stoul(segment) < list.size())
        return std::stoul(segment);
    return std::nullopt;
}

std::vector<std::string> item_names(const YAML::Node& list)
{
    std::vector<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node item = list[i];
        if (item.IsMap() && item["name"] && item["name"].IsScalar())
            names.push_back(item["name"].Scalar());
    }
    return names;
}

/// `key` below the schema path `path`.
std::string below(const std::string& path, const std::string& key)
{
    return path.empty() ? key : path + "." + key;
}

/// Walks `path` down the tree and the deck schema (io/deck_schema.hpp) together and
/// stores `value` at its end. Returns the reason for refusing, or nullopt on success.
std::optional<std::string> set_path(YAML::Node& root, const std::vector<std::string>& segments, const YAML::Node& value,
                                    DeckSource& source)
{
    YAML::Node node;
    node.reset(root);  // reset() rebinds; operator= would overwrite the tree
    // Where the walk is in the schema: a map (the top level "", a map key or a list
    // item "contact.*"), a list of items, or a value (a list value such as knots).
    std::string schema_path;
    KeyKind kind = KeyKind::map;
    std::string walked;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const std::string& segment = segments[i];
        const bool last = i + 1 == segments.size();
        if (segment.empty())
            return std::string("empty name in the path (two dots, or a dot at an end)");
        const std::string here = walked.empty() ? segment : walked + "." + segment;
        YAML::Node next;

        if (kind == KeyKind::map) {
            const std::vector<std::string>& keys = map_keys(schema_path);
            if (std::find(keys.begin(), keys.end(), segment) == keys.end()) {
                const std::string hint = did_you_mean(segment, keys);
                return "'" + segment + "' is not a key of " + quoted(walked) +
                       (hint.empty() ? " (keys: " + join_names(keys) + ")" : hint);
            }
            const DeckKey& key = *find_deck_key(below(schema_path, segment));
            if (last) {
                node[segment] = value;
                source.add_command_line_node(value);
                return std::nullopt;
            }
            const YAML::Node& const_node = node;  // const lookup: does not insert the key
            const YAML::Node existing = const_node[segment];
            if (!existing.IsDefined() || existing.IsNull()) {
                if (key.kind != KeyKind::map)
                    return "the deck has no '" + here + "', so it has no '" + segments[i + 1] + "'";
                const YAML::Node created(YAML::NodeType::Map);
                node[segment] = created;
                source.add_command_line_node(created);
            }
            next.reset(node[segment]);
            if (key.kind == KeyKind::map && !next.IsMap())
                return "'" + here + "' is not a map in the deck";
            if (key.kind == KeyKind::list && !next.IsSequence())
                return "'" + here + "' is not a list in the deck";
            schema_path = key.path;
            kind = key.kind;
        } else {
            // A list of items, or a list value such as knots or a force vector.
            if (!node.IsSequence())
                return "'" + walked + "' is a single value: nothing can follow it";
            const bool items = kind == KeyKind::list;
            const std::optional<std::size_t> index =
                items ? find_item(node, segment)
                      : (is_index(segment) && std::stoul(segment) < node.size() ? std::optional(std::stoul(segment))
                                                                                : std::nullopt);
            if (!index) {
                const std::vector<std::string> names = item_names(node);
                if (items && !is_index(segment))
                    return "no item named '" + segment + "' in '" + walked + "'" +
                           (names.empty() ? std::string(" (its items have no names: use an index)")
                                          : hint_or_list(segment, names, "items"));
                return "no item " + segment + " in '" + walked + "', which has " + std::to_string(node.size()) +
                       " (indices start at 0)";
            }
            if (last) {
                node[*index] = value;
                source.add_command_line_node(value);
                return std::nullopt;
            }
            next.reset(node[*index]);
            if (items) {
                schema_path += ".*";
                kind = KeyKind::map;
                if (!next.IsMap())
                    return "'" + here + "' is not a map in the deck";
            }
        }
        node.reset(next);
        walked = here;
    }
    return std::nullopt;
}

}  // namespace

void apply_overrides(YAML::Node& root, const std::vector<std::string>& set_overrides, DeckSource& source,
                     IssueList& issues)
{
    const SourceLocation command_line{std::string(command_line_file), 0, 0};
    for (const std::string& argument : set_overrides) {
        const auto equals = argument.find('=');
        const std::string path = equals == std::string::npos ? std::string() : trim(argument.substr(0, equals));
        if (path.empty()) {
            issues.add(DeckIssue{command_line, "", "",
                                 "--set '" + argument + "': expected PATH=VALUE, e.g. contact.cyl_floor.penalty=1e6"});
            continue;
        }
        const std::string text = argument.substr(equals + 1);
        std::vector<YAML::Node> documents;
        try {
            documents = YAML::LoadAll(text);
        } catch (const YAML::Exception& e) {
            issues.add(DeckIssue{command_line, path, text, "not valid YAML (" + e.msg + ")"});
            continue;
        }
        if (documents.size() > 1) {
            issues.add(DeckIssue{command_line, path, text,
                                 "holds more than one YAML document ('---' or '...' on a line of its own): a value "
                                 "is one document"});
            continue;
        }
        const YAML::Node value = documents.empty() ? YAML::Node() : documents.front();
        if (!root.IsDefined() || root.IsNull())
            root = YAML::Node(YAML::NodeType::Map);
        if (!root.IsMap()) {
            issues.add(DeckIssue{command_line, path, text, "cannot be set: the deck is not a map of keys"});
            continue;
        }
        if (const auto refused = set_path(root, split_path(path), value, source))
            issues.add(DeckIssue{command_line, path, text, *refused});
    }
}

}  // namespace iga::io
