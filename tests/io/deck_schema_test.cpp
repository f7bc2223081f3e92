// The deck schema (io/deck_schema.hpp) against the reader and the resolved-deck
// writer. Two decks that together give every key of the schema are read, written
// back and read again:
//  - a key of the schema that the decks do not give fails EveryKeyIsGivenByTheDecks
//    (so a key added to the schema is added to the decks below; a key of a group at
//    one of its places);
//  - a key the decks give that the resolved deck leaves out fails
//    EveryKeyGivenIsReadAndWrittenBack: the reader ignores it, or the writer forgets it;
//  - a key the writer emits that the schema does not have fails
//    TheWriterEmitsOnlyKeysOfTheSchema;
//  - a key the reader reads or accepts that the schema does not have cannot be: the
//    reader's key checks and typed reads take the keys from the schema (a read of an
//    unknown key is an internal error, which every test reading a deck would meet).
// The documented defaults are held to the reader's (DefaultsOfTheTableAreTheReaders).

#include "deck_test_support.hpp"

#include "io/deck_names.hpp"
#include "io/deck_schema.hpp"
#include "io/yaml_cursor.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace iga::io {
namespace {

const std::string deck_dir = std::string(IGA_SOURCE_DIR) + "/inputs";  // four_squares.xml

/// A 2D deck with every key the schema has but those of 3D decks.
const std::string every_key_2d = R"(format: 1
title: every key of the deck format, 2D
analysis: {dimension: 2, plane: stress, kinematics: finite}
materials:
  - {name: steel, model: neo_hookean, E: 1000, nu: 0.3}
bodies:
  - name: block
    material: steel
    nurbs:
      degrees: [1, 1]
      knots: [[0, 0, 1, 1], [0, 0, 1, 1]]
      control_points: [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]
      transform:
        - {translate: [0, 1]}
        - {rotate: {angle_deg: 90, about: [0, 1]}}
        - {mirror: {normal: [1, 0], point: [0, 0]}}
        - {scale: 2}
    refine: {elevate: [1, 1], spans: [2, 2], insert: [[0.25], []]}
    quadrature: {element: 3, side: 4}
  - name: disc
    material: steel
    shape: {type: quarter_disc, center: [5, 1], radius: 1, transform: [{translate: [1, 0]}]}
  - {name: plate, material: steel, shape: {type: rectangle, corner: [10, 0], size: [2, 1]}}
  - name: pair
    material: steel
    patches:
      - name: left
        nurbs:
          degrees: [1, 1]
          knots: [[0, 0, 1, 1], [0, 0, 1, 1]]
          control_points: [[20, 0, 1], [21, 0, 1], [20, 1, 1], [21, 1, 1]]
        refine: {spans: [2, 1]}
      - name: right
        nurbs:
          degrees: [1, 1]
          knots: [[0, 0, 1, 1], [0, 0, 1, 1]]
          control_points: [[21, 0, 1], [22, 0, 1], [21, 1, 1], [22, 1, 1]]
    surfaces: {bottom: [left.v0, right.v0]}
  - {name: squares, material: steel, geometry: {file: four_squares.xml, transform: [{translate: [30, 0]}]}}
  - name: floor
    rigid: {plane: {point: [0, -1], normal: [0, 1]}, motion: [0, 0.1], amplitude: [[0, 0], [1, 1]]}
  - {name: ball, rigid: {circle: {center: [5, -3], radius: 1}}}
constraints:
  - {body: block, side: u0, fix: [x]}
  - {body: plate, side: v0, displacement: [~, -0.01], amplitude: [[0, 0], [2, 1]]}
loads:
  - {body: block, side: v1, traction: [0, -1], amplitude: [[0, 0], [1, 1], [2, 0]]}
  - {body: plate, side: v1, force: [0, -1]}
  - {body: pair, side: bottom, pressure: 2}
  - {body: disc, gravity: [0, -9.81], density: 7800}
contact:
  - name: block_floor
    between: [block.v0, floor]
    formulation: single_pass
    enforcement: augmented_lagrangian
    penalty: 1.0e4
    augmented_lagrangian: {gap_tolerance: 1.0e-6, max_updates: 10}
    quadrature: 5
  - name: disc_ball
    between: [disc.v0, ball]
    penalty: auto
    friction: {coefficient: 0.3, tangential_penalty: 1.0e3}
  - name: plate_floor
    between: [plate.v0, floor]
    law: {type: exponential, clearance: 0.01, pressure: 5.0}
steps: {count: 4, adaptive: false, max_cutbacks: 2}
newton: {tolerance: 1.0e-8, max_iterations: 12, line_search: false}
solver: {backend: petsc, type: iterative, options: "-ksp_monitor"}
output:
  file: every_key.h5
  every_step: false
  samples_per_span: 4
  reference: {pair: block_floor, type: hertz_cylinder_plane, radius: 1, force: 2}
  paraview: true
  fields: false
accuracy:
  target: {pair: block_floor, quantity: force, error: 0.02}
  budget: {levels: 3, dofs: 1.0e5, seconds: 60}
)";

/// The keys only a 3D deck has: an extrusion, a rotation axis, a rigid sphere, a point-contact reference.
const std::string every_key_3d = R"(format: 1
analysis: {dimension: 3}
materials:
  - {name: m, E: 1000, nu: 0.3}
bodies:
  - {name: ball, material: m, shape: {type: sphere_octant, center: [0, 0, 1], radius: 1}}
  - name: slab
    material: m
    shape:
      type: quarter_disc
      center: [3, 1]
      radius: 1
      extrude: 0.2
      transform: [{rotate: {axis: [0, 0, 1], angle_deg: 90}}]
  - {name: block, material: m, shape: {type: box, corner: [0, 0, -1], size: [2, 2, 1]}}
  - {name: moon, rigid: {sphere: {center: [0, 0, 5], radius: 1}}}
contact:
  - {name: touch, between: [ball.v0, block.w1], penalty: 1.0e5}
output:
  reference: {pair: touch, type: hertz_two_spheres, radii: [1, 2], force: 1.5}
)";

Deck read_here(const std::string& text)
{
    return read_deck_text(text, "every_key.yaml", deck_dir, {});
}

/// The key paths of `node` with list items written `*`: what the schema calls them.
/// Paths the schema does not have go to `unknown` (and are not walked further).
void schema_paths(const YAML::Node& node, const std::string& map, std::set<std::string>& out,
                  std::set<std::string>& unknown)
{
    for (const auto& entry : node) {
        const std::string path = (map.empty() ? "" : map + ".") + entry.first.Scalar();
        const DeckKey* key = find_deck_key(path);
        if (!key) {
            unknown.insert(path);
            continue;
        }
        out.insert(path);
        if (key->kind == KeyKind::map)
            schema_paths(entry.second, path, out, unknown);
        else if (key->kind == KeyKind::list)
            for (const YAML::Node& item : entry.second)
                schema_paths(item, path + ".*", out, unknown);
    }
}

struct Paths {
    std::set<std::string> known, unknown;
};

Paths paths_of(const std::string& yaml)
{
    Paths p;
    schema_paths(YAML::Load(yaml), "", p.known, p.unknown);
    return p;
}

std::string listed(const std::set<std::string>& paths)
{
    std::string out;
    for (const std::string& path : paths)
        out += "\n  " + path;
    return out;
}

TEST(DeckSchema, EveryKeyIsGivenByTheDecks)
{
    std::set<std::string> given;
    for (const std::string& deck : {every_key_2d, every_key_3d}) {
        const Paths p = paths_of(deck);
        EXPECT_TRUE(p.unknown.empty()) << "keys of the test decks the schema does not have:" << listed(p.unknown);
        given.insert(p.known.begin(), p.known.end());
    }
    // A key of a group (nurbs, refine, transform) is read by the same code at each of
    // its places: one place will do.
    std::set<std::size_t> rows;
    for (const std::string& path : given)
        rows.insert(find_deck_key(path)->row);
    std::set<std::string> missing;
    for (const DeckKey& key : deck_keys())
        if (rows.insert(key.row).second)
            missing.insert(key.path);
    EXPECT_TRUE(missing.empty()) << "keys of the schema (lib/io/deck_schema.cpp) that the decks of this test do not "
                                    "give; add them to every_key_2d or every_key_3d:"
                                 << listed(missing);
}

TEST(DeckSchema, EveryKeyGivenIsReadAndWrittenBack)
{
    for (const std::string& deck : {every_key_2d, every_key_3d}) {
        Deck d;
        ASSERT_NO_THROW(d = read_here(deck)) << deck;
        EXPECT_TRUE(read_here(d.resolved_yaml) == d) << d.resolved_yaml;
        const Paths given = paths_of(deck);
        const Paths written = paths_of(d.resolved_yaml);
        std::set<std::string> lost;
        for (const std::string& path : given.known)
            if (!written.known.count(path))
                lost.insert(path);
        EXPECT_TRUE(lost.empty()) << "keys the deck gives that the resolved deck leaves out (the reader does not read "
                                     "them into io::Deck, or io::write_resolved_yaml does not write them):"
                                  << listed(lost) << "\n"
                                  << d.resolved_yaml;
    }
}

TEST(DeckSchema, TheWriterEmitsOnlyKeysOfTheSchema)
{
    for (const std::string& deck : {every_key_2d, every_key_3d, test::minimal_deck, test::hertz_deck,
                                     test::cube_deck_3d, test::two_cylinders_deck, test::shapes_deck_3d}) {
        const std::string resolved = read_here(deck).resolved_yaml;
        const Paths written = paths_of(resolved);
        EXPECT_TRUE(written.unknown.empty()) << "io::write_resolved_yaml writes keys that the schema "
                                                "(lib/io/deck_schema.cpp) does not have:"
                                             << listed(written.unknown) << "\n"
                                             << resolved;
    }
}

/// The scalar values of `node` at their concrete paths (items by index), and the
/// schema path of each.
void scalars(const YAML::Node& node, const std::string& at, const std::string& map,
             std::map<std::string, std::pair<std::string, std::string>>& out)
{
    for (const auto& entry : node) {
        const std::string path = (map.empty() ? "" : map + ".") + entry.first.Scalar();
        const std::string here = (at.empty() ? "" : at + ".") + entry.first.Scalar();
        const DeckKey* key = find_deck_key(path);
        if (!key)
            continue;
        if (key->kind == KeyKind::map)
            scalars(entry.second, here, path, out);
        else if (key->kind == KeyKind::list)
            for (std::size_t i = 0; i < entry.second.size(); ++i)
                scalars(entry.second[i], here + "." + std::to_string(i), path + ".*", out);
        else if (entry.second.IsScalar())
            out[here] = {path, entry.second.Scalar()};
    }
}

TEST(DeckSchema, DefaultsOfTheTableAreTheReaders)
{
    // A deck that leaves out every key with a default; the resolved deck shows the
    // reader's defaults. The second pair enables the keys that only some pairs have.
    const std::string deck = R"(format: 1
analysis: {dimension: 2}
materials:
  - {name: steel, E: 1000, nu: 0.3}
bodies:
  - {name: block, material: steel, shape: {type: rectangle, corner: [0, 0], size: [2, 1]}}
  - {name: floor, rigid: {plane: {point: [0, 0], normal: [0, 1]}}}
contact:
  - {name: plain, between: [block.v0, floor], penalty: 1.0e4}
  - {name: more, between: [block.u1, floor], penalty: 1.0e4, enforcement: augmented_lagrangian,
     friction: {coefficient: 0.3}}
accuracy: {target: {pair: plain, error: 0.01}}
)";
    std::map<std::string, std::pair<std::string, std::string>> given, written;
    scalars(YAML::Load(deck), "", "", given);
    scalars(YAML::Load(test::read(deck).resolved_yaml), "", "", written);

    std::set<std::string> checked;
    for (const auto& [at, entry] : written) {
        const auto& [path, value] = entry;
        const DeckKey& key = *find_deck_key(path);
        const std::string& text = key.default_text;
        // Defaults written as one code span, `25`, are values the reader fills in.
        if (given.count(at) || text.size() < 2 || text.front() != '`' || text.back() != '`' ||
            text.find('`', 1) != text.size() - 1)
            continue;
        std::string documented = text.substr(1, text.size() - 2);
        if (documented == "\"\"")
            documented.clear();
        const auto a = parse_number(documented), b = parse_number(value);
        EXPECT_TRUE(a && b ? *a == *b : documented == value)
            << at << ": the schema's default is " << text << ", the reader's " << value;
        checked.insert(path);
    }
    std::set<std::string> unchecked;
    for (const DeckKey& key : deck_keys())
        if (key.kind == KeyKind::value && key.default_text.size() > 2 && key.default_text.front() == '`' &&
            key.default_text.find('`', 1) == key.default_text.size() - 1 && key.type != ValueType::other &&
            !checked.count(key.path))
            unchecked.insert(key.path);
    EXPECT_TRUE(unchecked.empty()) << "defaults this test does not see in the resolved deck:" << listed(unchecked);
}

TEST(DeckSchema, TheTableSpellsWhatTheReaderAndWriterSpell)
{
    // The keys a transform step and a load are told apart by: spelled in io/deck_names.hpp
    // for the reader and the writer, and keys of the schema.
    const std::vector<std::string>& steps = map_keys("bodies.*.nurbs.transform.*");
    EXPECT_EQ(steps, std::vector<std::string>(transform_step_keys.begin(), transform_step_keys.end()));
    const std::vector<std::string>& load_keys = map_keys("loads.*");
    for (const auto& entry : DeckNames<LoadKind>::all)
        EXPECT_NE(std::find(load_keys.begin(), load_keys.end(), std::string(entry.name)), load_keys.end())
            << entry.name;
    // Groups: one declaration, every place.
    EXPECT_EQ(map_keys("bodies.*.nurbs"), map_keys("bodies.*.patches.*.nurbs"));
    EXPECT_EQ(map_keys("bodies.*.shape.transform.*"), steps);
    EXPECT_EQ(find_deck_key("bodies.*.nurbs.degrees")->row, find_deck_key("bodies.*.patches.*.nurbs.degrees")->row);
}

TEST(DeckSchema, PathsKindsAndRanges)
{
    const DeckKey* mu = find_deck_key("contact.*.friction.coefficient");
    ASSERT_NE(mu, nullptr);
    EXPECT_EQ(mu->kind, KeyKind::value);
    EXPECT_EQ(mu->type, ValueType::number);
    EXPECT_EQ(mu->presence, Presence::required);
    EXPECT_EQ(mu->range.failure(), "must be >= 0 (0: frictionless)");
    EXPECT_EQ(find_deck_key("materials.*.nu")->type_text, "number in (−1, 0.5)");
    EXPECT_EQ(find_deck_key("materials.*.nu")->range.failure(), "must lie in (-1, 0.5)");
    EXPECT_EQ(find_deck_key("steps.count")->type_text, "integer ≥ 1");
    EXPECT_EQ(find_deck_key("analysis.kinematics")->type_text, "`small` or `finite`");
    EXPECT_EQ(find_deck_key("contact.*.penalty")->type_text, "number > 0, or `auto`");
    EXPECT_EQ(find_deck_key("loads.*.density")->default_text, "— (gravity)");
    EXPECT_EQ(find_deck_key("contact")->kind, KeyKind::list);
    EXPECT_EQ(find_deck_key("contact.*"), nullptr);  // items have no entry of their own
    EXPECT_EQ(map_keys("solver"), (std::vector<std::string>{"backend", "type", "options"}));
    EXPECT_TRUE(map_keys("no.such.map").empty());
    const auto paths = deck_key_paths();
    EXPECT_EQ(std::set<std::string>(paths.begin(), paths.end()).size(), paths.size());
    EXPECT_GT(paths.size(), 100u);
}

}  // namespace
}  // namespace iga::io
