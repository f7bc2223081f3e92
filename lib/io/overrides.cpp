#include "io/overrides.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace iga::io {
namespace {

/// The shape of a deck: which keys each map may hold and what lists contain.
/// Mirrors the key lists of deck_reader.cpp (tests/io/overrides_test.cpp checks
/// that every key the resolved-deck writer emits can be set).
struct Schema {
    enum class Kind { value, map, list };
    Kind kind = Kind::value;
    std::vector<std::string> keys;  ///< map: its keys
    std::vector<Schema> children;   ///< map: one per key; list: the item schema
};

Schema value()
{
    return {};
}

Schema map(std::vector<std::pair<std::string, Schema>> entries)
{
    Schema s{Schema::Kind::map, {}, {}};
    for (auto& [key, child] : entries) {
        s.keys.push_back(key);
        s.children.push_back(std::move(child));
    }
    return s;
}

Schema list(Schema item)
{
    return Schema{Schema::Kind::list, {}, {std::move(item)}};
}

Schema make_deck_schema()
{
    const auto v = value();
    // `transform:` steps: each item is a map with one of these keys (io/transform_reader.hpp).
    const Schema transform = list(map({{"translate", v},
                                       {"rotate", map({{"axis", v}, {"angle_deg", v}, {"about", v}})},
                                       {"mirror", map({{"normal", v}, {"point", v}})},
                                       {"scale", v}}));
    const Schema nurbs = map({{"degrees", v}, {"knots", v}, {"control_points", v}, {"transform", transform}});
    return map({
        {"format", v},
        {"title", v},
        {"analysis", map({{"dimension", v}, {"plane", v}, {"kinematics", v}})},
        {"materials", list(map({{"name", v}, {"model", v}, {"E", v}, {"nu", v}}))},
        {"bodies", list(map({{"name", v},
                             {"material", v},
                             {"nurbs", nurbs},
                             {"shape", map({{"type", v},
                                            {"center", v},
                                            {"radius", v},
                                            {"corner", v},
                                            {"size", v},
                                            {"extrude", v},
                                            {"transform", transform}})},
                             {"patches", list(map({{"name", v},
                                                   {"nurbs", nurbs},
                                                   {"refine", map({{"elevate", v}, {"spans", v}, {"insert", v}})}}))},
                             {"geometry", map({{"file", v}, {"transform", transform}})},
                             {"refine", map({{"elevate", v}, {"spans", v}, {"insert", v}})},
                             {"quadrature", map({{"element", v}, {"side", v}})},
                             {"surfaces", v},  // a map of user-chosen names: set as a whole
                             {"rigid", map({{"plane", map({{"point", v}, {"normal", v}})},
                                            {"circle", map({{"center", v}, {"radius", v}})},
                                            {"sphere", map({{"center", v}, {"radius", v}})},
                                            {"motion", v},
                                            {"amplitude", v}})}}))},
        {"constraints", list(map({{"body", v}, {"side", v}, {"fix", v}, {"displacement", v}, {"amplitude", v}}))},
        {"loads", list(map({{"body", v},
                            {"side", v},
                            {"traction", v},
                            {"force", v},
                            {"pressure", v},
                            {"gravity", v},
                            {"density", v},
                            {"amplitude", v}}))},
        {"contact", list(map({{"name", v},
                              {"between", v},
                              {"formulation", v},
                              {"enforcement", v},
                              {"penalty", v},
                              {"augmented_lagrangian", map({{"gap_tolerance", v}, {"max_updates", v}})},
                              {"friction", map({{"coefficient", v}, {"tangential_penalty", v}})},
                              {"quadrature", v}}))},
        {"steps", map({{"count", v}, {"adaptive", v}, {"max_cutbacks", v}})},
        {"newton", map({{"tolerance", v}, {"max_iterations", v}, {"line_search", v}})},
        {"solver", map({{"backend", v}, {"type", v}, {"options", v}})},
        {"output", map({{"file", v},
                        {"every_step", v},
                        {"samples_per_span", v},
                        {"reference", map({{"pair", v}, {"type", v}, {"radius", v}, {"radii", v}, {"force", v}})},
                        {"paraview", v},
                        {"fields", v}})},
    });
}

const Schema& deck_schema()
{
    static const Schema schema = make_deck_schema();  // immutable table, built once
    return schema;
}

void collect_paths(const Schema& schema, const std::string& prefix, std::vector<std::string>& out)
{
    if (schema.kind == Schema::Kind::list) {
        collect_paths(schema.children.front(), prefix + ".*", out);
        return;
    }
    for (std::size_t k = 0; k < schema.keys.size(); ++k) {
        const std::string path = prefix.empty() ? schema.keys[k] : prefix + "." + schema.keys[k];
        out.push_back(path);
        collect_paths(schema.children[k], path, out);
    }
}

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

/// Walks `path` down the tree and the schema together and stores `value` at its end.
/// Returns the reason for refusing, or nullopt on success.
std::optional<std::string> set_path(YAML::Node& root, const std::vector<std::string>& segments, const YAML::Node& value,
                                    DeckSource& source)
{
    YAML::Node node;
    node.reset(root);  // reset() rebinds; operator= would overwrite the tree
    const Schema* schema = &deck_schema();
    std::string walked;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const std::string& segment = segments[i];
        const bool last = i + 1 == segments.size();
        if (segment.empty())
            return std::string("empty name in the path (two dots, or a dot at an end)");
        const std::string here = walked.empty() ? segment : walked + "." + segment;
        YAML::Node next;

        if (schema->kind == Schema::Kind::map) {
            const auto key = std::find(schema->keys.begin(), schema->keys.end(), segment);
            if (key == schema->keys.end()) {
                const std::string hint = did_you_mean(segment, schema->keys);
                return "'" + segment + "' is not a key of " + quoted(walked) +
                       (hint.empty() ? " (keys: " + join_names(schema->keys) + ")" : hint);
            }
            const Schema* child_schema = &schema->children[static_cast<std::size_t>(key - schema->keys.begin())];
            if (last) {
                node[segment] = value;
                source.add_command_line_node(value);
                return std::nullopt;
            }
            const YAML::Node& const_node = node;  // const lookup: does not insert the key
            const YAML::Node existing = const_node[segment];
            if (!existing.IsDefined() || existing.IsNull()) {
                if (child_schema->kind != Schema::Kind::map)
                    return "the deck has no '" + here + "', so it has no '" + segments[i + 1] + "'";
                const YAML::Node created(YAML::NodeType::Map);
                node[segment] = created;
                source.add_command_line_node(created);
            }
            next.reset(node[segment]);
            if (child_schema->kind == Schema::Kind::map && !next.IsMap())
                return "'" + here + "' is not a map in the deck";
            if (child_schema->kind == Schema::Kind::list && !next.IsSequence())
                return "'" + here + "' is not a list in the deck";
            schema = child_schema;
        } else {
            // A list of items, or a list value such as knots or a force vector.
            if (!node.IsSequence())
                return "'" + walked + "' is a single value: nothing can follow it";
            const std::optional<std::size_t> index = schema->kind == Schema::Kind::list
                                                         ? find_item(node, segment)
                                                         : (is_index(segment) && std::stoul(segment) < node.size()
                                                                ? std::optional(std::stoul(segment))
                                                                : std::nullopt);
            if (!index) {
                const std::vector<std::string> names = item_names(node);
                if (schema->kind == Schema::Kind::list && !is_index(segment))
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
            if (schema->kind == Schema::Kind::list) {
                schema = &schema->children.front();
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

std::vector<std::string> deck_key_paths()
{
    std::vector<std::string> out;
    collect_paths(deck_schema(), "", out);
    return out;
}

}  // namespace iga::io
