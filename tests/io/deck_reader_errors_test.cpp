// Tests of the located messages of io::read_deck / read_deck_text for every
// class of bad input that docs/deck.md names (file:line:col, key path in
// --set syntax, value as written, reason). Messages are compared as whole
// strings: their text is part of the contract. Columns point at the value (or,
// for an unknown key, at the key; for a missing key, at the enclosing map).

#include "deck_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace iga::io {
namespace {

using test::cube_deck_3d;
using test::hertz_deck;
using test::issue_of;
using test::issues_of;
using test::minimal_deck;
using test::read;
using test::replaced;

// ---------------------------------------------------------------------------
// Files and YAML

TEST(DeckReaderErrors, MissingFile)
{
    try {
        read_deck("no/such/deck.yaml", {});
        ADD_FAILURE() << "no error";
    } catch (const DeckError& e) {
        EXPECT_STREQ(e.what(), "no/such/deck.yaml: error: no such deck file");
    }
}

TEST(DeckReaderErrors, DirectoryInsteadOfFile)
{
    const std::string dir = ::testing::TempDir();
    try {
        read_deck(dir, {});
        ADD_FAILURE() << "no error";
    } catch (const DeckError& e) {
        EXPECT_EQ(std::string(e.what()), dir + ": error: is a directory, not a deck file");
    }
}

TEST(DeckReaderErrors, UnreadableFile)
{
    namespace fs = std::filesystem;
    const fs::path path = fs::path(::testing::TempDir()) / "igacontact_unreadable_deck.yaml";
    std::ofstream(path) << minimal_deck;
    fs::permissions(path, fs::perms::none);
    const bool readable_anyway = static_cast<bool>(std::ifstream(path));
    if (readable_anyway) {
        fs::remove(path);
        GTEST_SKIP() << "this user can read files without permission (root)";
    }
    try {
        read_deck(path.string(), {});
        ADD_FAILURE() << "no error";
    } catch (const DeckError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": error: cannot open the deck file (Permission denied)");
    }
    fs::remove(path);
}

TEST(DeckReaderErrors, MalformedYamlIsLocated)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "E: 1000", "E: [1000")),
              "hertz.yaml:7:7: error: invalid YAML: end of sequence flow not found");
    EXPECT_EQ(issue_of("format: 1\n  bad indent: 2\n"), "hertz.yaml:2:13: error: invalid YAML: illegal map value");
}

TEST(DeckReaderErrors, EmptyDeckAndNonMapDeck)
{
    EXPECT_EQ(issue_of(""),
              "hertz.yaml: error: the deck is empty: it needs at least format, analysis, materials and bodies");
    EXPECT_EQ(issue_of("- 1\n- 2\n"), "hertz.yaml:1:1: error: expected a map of keys");
}

// ---------------------------------------------------------------------------
// Types, keys, names

TEST(DeckReaderErrors, WrongTypes)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "E: 1000", "E: stiff")),
              "hertz.yaml:6:8: error: materials.steel.E = stiff: expected a number");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "format: 1", "format: 1.5")),
              "hertz.yaml:1:9: error: format = 1.5: expected an integer");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "corner: [0, 0]", "corner: [0]")),
              "hertz.yaml:11:38: error: bodies.block.shape.corner = [0]: expected a list of 2 numbers");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "corner: [0, 0]", "corner: 0")),
              "hertz.yaml:11:38: error: bodies.block.shape.corner = 0: expected a list of 2 numbers");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "material: steel", "material: [steel]")),
              "hertz.yaml:10:15: error: bodies.block.material = [steel]: expected a string");
    EXPECT_EQ(issue_of(minimal_deck + "output: {paraview: yes}\n"),
              "hertz.yaml:22:20: error: output.paraview = yes: expected true or false");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "model: linear_elastic", "model: neo_hokean")),
              "hertz.yaml:5:12: error: materials.steel.model = neo_hokean: expected one of linear_elastic, "
              "saint_venant_kirchhoff, neo_hookean (did you mean 'neo_hookean'?)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "analysis: {dimension: 2}", "analysis: 2")),
              "hertz.yaml:2:11: error: analysis = 2: expected a map of keys");
}

TEST(DeckReaderErrors, NotANumberAndInfinityAreRejectedWhereverNumbersAreRead)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "E: 1000", "E: .nan")),
              "hertz.yaml:6:8: error: materials.steel.E = .nan: must be a finite number");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "traction: [0, -1]", "traction: [0, -.inf]")),
              "hertz.yaml:17:43: error: loads.0.traction.1 = -.inf: must be a finite number");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", "penalty: .NaN")),
              "hertz.yaml:21:14: error: contact.block_floor.penalty = .NaN: must be a finite number");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "normal: [0, 1]", "normal: [.inf, 1]")),
              "hertz.yaml:13:45: error: bodies.floor.rigid.plane.normal.0 = .inf: must be a finite number");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "format: 1", "format: .nan")),
              "hertz.yaml:1:9: error: format = .nan: expected an integer");
    EXPECT_EQ(issue_of(minimal_deck + "newton: {tolerance: .inf}\n"),
              "hertz.yaml:22:21: error: newton.tolerance = .inf: must be a finite number");
}

TEST(DeckReaderErrors, MissingRequiredKeys)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    E: 1000\n", "")),
              "hertz.yaml:4:5: error: materials.steel: missing required key 'E'");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "format: 1\n", "")),
              "hertz.yaml:1:1: error: missing required key 'format'");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    penalty: 1.0e4\n", "")),
              "hertz.yaml:19:5: error: contact.block_floor: missing required key 'penalty'");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "analysis: {dimension: 2}", "analysis: {plane: strain}")),
              "hertz.yaml:2:11: error: analysis: missing required key 'dimension'");
}

TEST(DeckReaderErrors, UnknownKeysSuggestTheClosestKnownKey)
{
    const auto issues = issues_of(replaced(minimal_deck, "penalty: 1.0e4", "penalti: 1.0e4"));
    ASSERT_EQ(issues.size(), 2u);
    EXPECT_EQ(issues[0],
              "hertz.yaml:21:5: error: contact.block_floor: unknown key 'penalti' (did you mean 'penalty'?)");
    EXPECT_EQ(issues[1], "hertz.yaml:19:5: error: contact.block_floor: missing required key 'penalty'");

    EXPECT_EQ(issue_of(minimal_deck + "bodys: []\n"),
              "hertz.yaml:22:1: error: unknown key 'bodys' (did you mean 'bodies'?)");
    // Nothing close: list what is known instead.
    EXPECT_EQ(issue_of(minimal_deck + "steps: {frobnicate: 1}\n"),
              "hertz.yaml:22:9: error: steps: unknown key 'frobnicate' (known keys: count, adaptive, max_cutbacks)");
}

TEST(DeckReaderErrors, DuplicateKeysAndNames)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    nu: 0.3\n", "    nu: 0.3\n    nu: 0.2\n")),
              "hertz.yaml:8:5: error: materials.steel: duplicate key 'nu' (first given at line 7)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    nu: 0.3\n", "    nu: 0.3\n  - {name: steel, E: 1, nu: 0}\n")),
              "hertz.yaml:8:12: error: materials.steel.name = steel: duplicate material name (first defined at line "
              "4)");
    // The second 'block' is not registered, so the pair's reference to 'floor' fails too.
    EXPECT_EQ(issues_of(replaced(minimal_deck, "  - name: floor", "  - name: block")),
              (std::vector<std::string>{
                  "hertz.yaml:12:11: error: bodies.block.name = block: duplicate body name (first defined at line 9)",
                  "hertz.yaml:20:25: error: contact.block_floor.between.1 = floor: unknown body 'floor' (bodies: "
                  "block)"}));
    EXPECT_EQ(issue_of(minimal_deck + "  - {name: block_floor, between: [block.v1, floor], penalty: 1}\n"),
              "hertz.yaml:22:12: error: contact.block_floor.name = block_floor: duplicate contact pair name (first "
              "defined at line 19)");
    EXPECT_EQ(issues_of(replaced(minimal_deck, "name: steel", "name: st.eel")),
              (std::vector<std::string>{
                  "hertz.yaml:4:11: error: materials.st.eel.name = st.eel: must be a non-empty word without '.' (the "
                  "separator in key paths and body.side)",
                  "hertz.yaml:10:15: error: bodies.block.material = steel: unknown material 'steel' (there are no "
                  "materials)"}));
}

/// Duplicate keys anywhere (any map, flow or block, any depth, also in --set values),
/// and YAML documents after the first: a YAML reader keeps one value and drops the
/// rest without a word (a surface given twice acted on half of itself).
TEST(DeckReaderErrors, DuplicateKeysAnywhereAndSecondDocuments)
{
    const std::string shape = "    shape: {type: rectangle, corner: [0, 0], size: [2, 1]}\n";
    struct Row {
        const char* name;
        std::string deck;
        std::vector<std::string> sets;
        std::string expected;
    };
    const std::vector<Row> rows = {
        {"surface twice, flow map", replaced(minimal_deck, shape, shape + "    surfaces: {bottom: [v0], bottom: [u1]}\n"),
         {}, "hertz.yaml:12:30: error: bodies.block.surfaces: duplicate key 'bottom' (first given at line 12)"},
        {"surface twice, block map",
         replaced(minimal_deck, shape, shape + "    surfaces:\n      bottom: [v0]\n      bottom: [u1]\n"), {},
         "hertz.yaml:14:7: error: bodies.block.surfaces: duplicate key 'bottom' (first given at line 13)"},
        {"surface twice, --set value", minimal_deck, {"bodies.block.surfaces={bottom: [v0], bottom: [u1]}"},
         "<command line>: error: bodies.block.surfaces: duplicate key 'bottom'"},
        {"known key twice, deep in a flow map",
         replaced(minimal_deck, "normal: [0, 1]}", "normal: [0, 1], normal: [0, -1]}"), {},
         "hertz.yaml:13:52: error: bodies.floor.rigid.plane: duplicate key 'normal' (first given at line 13)"},
        {"known key twice, --set value", minimal_deck, {"steps={count: 2, count: 3}"},
         "<command line>: error: steps: duplicate key 'count'"},
        {"second document in the deck", minimal_deck + "---\nsteps: {count: 3}\n", {},
         "hertz.yaml:23:1: error: a second YAML document ('---'): a deck is one document"},
        {"second document in a --set value", minimal_deck, {"steps.count=3\n---\n4"},
         "<command line>: error: steps.count = 3\n---\n4: holds more than one YAML document ('---' or '...' on a "
         "line of its own): a value is one document"},
        {"integer out of range", minimal_deck, {"steps.count=3e9"},
         "<command line>: error: steps.count = 3e9: out of range: an integer here is at most 2147483647"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(issue_of(row.deck, row.sets), row.expected);
    }
}

// ---------------------------------------------------------------------------
// References between sections

TEST(DeckReaderErrors, UnknownReferences)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "material: steel", "material: stel")),
              "hertz.yaml:10:15: error: bodies.block.material = stel: unknown material 'stel' (did you mean 'steel'?)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "material: steel", "material: rubber")),
              "hertz.yaml:10:15: error: bodies.block.material = rubber: unknown material 'rubber' (materials: steel)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{body: block, side: u0", "{body: blok, side: u0")),
              "hertz.yaml:15:12: error: constraints.0.body = blok: unknown body 'blok' (did you mean 'block'?)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "side: u0", "side: w0")),
              "hertz.yaml:15:25: error: constraints.0.side = w0: 'w0' is not a side of a 2D patch (sides: u0, u1, v0, "
              "v1)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{body: block, side: u0", "{body: floor, side: u0")),
              "hertz.yaml:15:12: error: constraints.0.body = floor: rigid body 'floor' takes no constraints: rigid "
              "obstacles are fixed");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{body: block, side: v1", "{body: floor, side: v1")),
              "hertz.yaml:17:12: error: loads.0.body = floor: rigid body 'floor' takes no loads: rigid obstacles are "
              "fixed");
}

TEST(DeckReaderErrors, ContactSurfaces)
{
    const auto between = [](const std::string& list) {
        return issue_of(replaced(minimal_deck, "between: [block.v0, floor]", "between: " + list));
    };
    EXPECT_EQ(between("[block.v3, floor]"),
              "hertz.yaml:20:15: error: contact.block_floor.between.0 = block.v3: 'v3' is not a side of a 2D patch "
              "(sides: u0, u1, v0, v1)");
    EXPECT_EQ(between("[block.v0, floor.v1]"),
              "hertz.yaml:20:25: error: contact.block_floor.between.1 = floor.v1: 'floor' is a rigid body: it has no "
              "sides, write just 'floor'");
    EXPECT_EQ(between("[block, floor]"),
              "hertz.yaml:20:15: error: contact.block_floor.between.0 = block: a deformable body's surface needs a "
              "side, e.g. 'block.v0' (sides: u0, u1, v0, v1)");
    EXPECT_EQ(between("[blocks.v0, floor]"),
              "hertz.yaml:20:15: error: contact.block_floor.between.0 = blocks.v0: unknown body 'blocks' (did you "
              "mean 'block'?)");
    EXPECT_EQ(between("[block.v0]"),
              "hertz.yaml:20:14: error: contact.block_floor.between = [block.v0]: expected a list of two surfaces: "
              "[body.side, body.side or rigid body]");
    EXPECT_EQ(between("[block.v0, block.v0]"),
              "hertz.yaml:20:14: error: contact.block_floor.between = [block.v0, block.v0]: the two surfaces are the "
              "same side");
    const std::string wall = "  - {name: wall, rigid: {plane: {point: [0, 0], normal: [1, 0]}}}\n";
    EXPECT_EQ(issue_of(replaced(replaced(minimal_deck, "between: [block.v0, floor]", "between: [wall, floor]"),
                                "bodies:\n", "bodies:\n" + wall)),
              "hertz.yaml:21:14: error: contact.block_floor.between = [wall, floor]: at least one surface must be the "
              "side of a deformable body");
}

// ---------------------------------------------------------------------------
// Values

TEST(DeckReaderErrors, MaterialValues)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "nu: 0.3", "nu: 0.6")),
              "hertz.yaml:7:9: error: materials.steel.nu = 0.6: must lie in (-1, 0.5)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "nu: 0.3", "nu: 0.5")),
              "hertz.yaml:7:9: error: materials.steel.nu = 0.5: must lie in (-1, 0.5)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "nu: 0.3", "nu: -1")),
              "hertz.yaml:7:9: error: materials.steel.nu = -1: must lie in (-1, 0.5)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "E: 1000", "E: 0")),
              "hertz.yaml:6:8: error: materials.steel.E = 0: must be > 0");
}

TEST(DeckReaderErrors, FormatAndDimension)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "format: 1", "format: 2")),
              "hertz.yaml:1:9: error: format = 2: unsupported deck format: this program reads format 1");
    // Later sections depend on the dimension: reading stops after it.
    EXPECT_EQ(issue_of(replaced(minimal_deck, "dimension: 2", "dimension: 4")),
              "hertz.yaml:2:23: error: analysis.dimension = 4: must be 2 or 3");
    EXPECT_EQ(issue_of(replaced(cube_deck_3d, "dimension: 3,", "dimension: 3, plane: strain,")),
              "hertz.yaml:2:33: error: analysis.plane = strain: applies to 2D only (analysis.dimension is 3)");
}

TEST(DeckReaderErrors, NurbsPatches)
{
    const auto nurbs = [](const std::string& from, const std::string& to) {
        return issue_of(replaced(hertz_deck, from, to));
    };
    EXPECT_EQ(nurbs("degrees: [2, 1]", "degrees: [2, 0]"),
              "hertz.yaml:17:20: error: bodies.cylinder.nurbs.degrees.1 = 0: must be >= 1");
    EXPECT_EQ(nurbs("degrees: [2, 1]", "degrees: [2]"),
              "hertz.yaml:17:16: error: bodies.cylinder.nurbs.degrees = [2]: expected a list of 2 integers");
    EXPECT_EQ(nurbs("[0, 0, 1, 1]]", "[0, 0, 1, 0.5, 1]]"),
              "hertz.yaml:18:45: error: bodies.cylinder.nurbs.knots.1.3 = 0.5: knots must be non-decreasing (the knot "
              "before is 1)");
    EXPECT_EQ(nurbs("[0, 0, 1, 1]]", "[0, 1, 1]]"),
              "hertz.yaml:18:35: error: bodies.cylinder.nurbs.knots.1 = [0, 1, 1]: too few knots for degree 1: an open "
              "knot vector has at least 2(p+1) = 4");
    EXPECT_EQ(nurbs("[0, 0, 1, 1]]", "[0, 0, 0, 1, 1]]"),
              "hertz.yaml:18:35: error: bodies.cylinder.nurbs.knots.1 = [0, 0, 0, 1, 1]: not an open knot vector: the "
              "first and the last value must each appear exactly degree + 1 = 2 times, with a parameter interval of "
              "positive length");
    // The control-point count is not checked against knots that are themselves wrong.
    EXPECT_EQ(nurbs("[[0, 0, 0, 1, 1, 1],", "[[0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1],"),
              "hertz.yaml:18:25: error: bodies.cylinder.nurbs.knots.0.3 = 0.5: interior knot 0.5 appears 3 times, "
              "more than the degree 2");
    EXPECT_EQ(nurbs("[[0, 0, 0, 1, 1, 1],", "[[0, 0, 0, 0.5, 1, 1, 1],"),
              "hertz.yaml:20:9: error: bodies.cylinder.nurbs.control_points: expected 8 control points (4 x 2 from "
              "the knots and degrees), got 6");
    EXPECT_EQ(nurbs("[1.0, 1.0, 1.0]\n        - [0.0, 1.0, 1.0]", "[1.0, 1.0, 0]\n        - [0.0, 1.0, 1.0]"),
              "hertz.yaml:22:22: error: bodies.cylinder.nurbs.control_points.2.2 = 0: weight must be > 0");
    EXPECT_EQ(nurbs("[0.0, 0.0, 1.0]", "[0.0, 0.0]"),
              "hertz.yaml:20:11: error: bodies.cylinder.nurbs.control_points.0 = [0.0, 0.0]: expected a list of 3 "
              "numbers");
}

TEST(DeckReaderErrors, Refinement)
{
    const auto refine = [](const std::string& from, const std::string& to) {
        return issue_of(replaced(hertz_deck, from, to));
    };
    EXPECT_EQ(refine("elevate: [1, 1]", "elevate: [1, -1]"),
              "hertz.yaml:27:20: error: bodies.cylinder.refine.elevate.1 = -1: must be >= 0");
    EXPECT_EQ(refine("elevate: [1, 1]", "elevate: [1]"),
              "hertz.yaml:27:16: error: bodies.cylinder.refine.elevate = [1]: expected a list of 2 integers");
    EXPECT_EQ(refine("spans: [32, 16]", "spans: [0, 16]"),
              "hertz.yaml:28:15: error: bodies.cylinder.refine.spans.0 = 0: must be >= 1");
    EXPECT_EQ(refine("insert: [[0.05, 0.1], []]", "insert: [[0.05, 1.0], []]"),
              "hertz.yaml:29:23: error: bodies.cylinder.refine.insert.0.1 = 1.0: must lie strictly inside the "
              "parameter interval (0, 1)");
    EXPECT_EQ(refine("insert: [[0.05, 0.1], []]", "insert: [[0.05, 0.1]]"),
              "hertz.yaml:29:15: error: bodies.cylinder.refine.insert = [[0.05, 0.1]]: expected a list of 2 lists of "
              "knot values (one per parametric direction)");
    // Degree 2 elevated to 3 allows a knot three times, not four.
    EXPECT_EQ(refine("insert: [[0.05, 0.1], []]", "insert: [[0.3, 0.3, 0.3, 0.3], []]"),
              "hertz.yaml:29:17: error: bodies.cylinder.refine.insert.0.0 = 0.3: the knot would appear 4 times, more "
              "than the degree 3");
    EXPECT_NO_THROW(read(replaced(hertz_deck, "insert: [[0.05, 0.1], []]", "insert: [[0.3, 0.3, 0.3], []]")));
}

TEST(DeckReaderErrors, BodyQuadrature)
{
    const auto quadrature = [](const std::string& value) {
        return issue_of(replaced(minimal_deck, "size: [2, 1]}\n", "size: [2, 1]}\n    quadrature: " + value + "\n"));
    };
    EXPECT_EQ(quadrature("{element: 0}"), "hertz.yaml:12:27: error: bodies.block.quadrature.element = 0: must be >= 1");
    EXPECT_EQ(quadrature("{side: 2.5}"), "hertz.yaml:12:24: error: bodies.block.quadrature.side = 2.5: expected an integer");
    EXPECT_EQ(quadrature("{elements: 4}"),
              "hertz.yaml:12:18: error: bodies.block.quadrature: unknown key 'elements' (did you mean 'element'?)");
    EXPECT_EQ(quadrature("4"), "hertz.yaml:12:17: error: bodies.block.quadrature = 4: expected a map of keys");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "  - name: floor\n", "  - name: floor\n    quadrature: {element: 4}\n")),
              "hertz.yaml:13:17: error: bodies.floor.quadrature: a rigid body takes no 'quadrature'");
    const Deck d = read(replaced(minimal_deck, "size: [2, 1]}\n", "size: [2, 1]}\n    quadrature: {element: 6, side: 8}\n"));
    EXPECT_EQ(d.bodies.at(0).quadrature, (Quadrature{.element = 6, .side = 8}));
}

TEST(DeckReaderErrors, BuiltInShapes)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "size: [2, 1]", "size: [2, 0]")),
              "hertz.yaml:11:56: error: bodies.block.shape.size.1 = 0: must be > 0");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{type: rectangle, corner: [0, 0], size: [2, 1]}",
                                "{type: half_disc, center: [0, 1], radius: -1}")),
              "hertz.yaml:11:54: error: bodies.block.shape.radius = -1: must be > 0");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{type: rectangle, corner: [0, 0], size: [2, 1]}",
                                "{type: half_disc, center: [0, 1, 2], radius: 1}")),
              "hertz.yaml:11:38: error: bodies.block.shape.center = [0, 1, 2]: expected a list of 2 numbers");
    EXPECT_EQ(issues_of(replaced(minimal_deck, "{type: rectangle, corner: [0, 0], size: [2, 1]}",
                                 "{type: quarter_disc, corner: [0, 1], radius: 1}")),
              (std::vector<std::string>{"hertz.yaml:11:41: error: bodies.block.shape.corner: does not apply to a "
                                        "quarter_disc (it takes center and radius)",
                                        "hertz.yaml:11:12: error: bodies.block.shape: missing required key 'center'"}));
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    shape: {type: rectangle, corner: [0, 0], size: [2, 1]}\n", "")),
              "hertz.yaml:9:5: error: bodies.block: needs 'nurbs', 'shape', 'patches' or 'geometry' (or 'rigid' for an obstacle)");
    EXPECT_EQ(issue_of(replaced(cube_deck_3d, "refine: {spans: [2, 2, 2]}",
                                "shape: {type: rectangle, corner: [0, 0], size: [1, 1]}")),
              "hertz.yaml:6:5: error: bodies.cube: takes one of 'nurbs', 'shape', 'patches' or 'geometry', not several");
}

// Built-in shapes in 3D decks and shapes of the wrong dimension: one row per
// bad `shape:` of a body `ball` added to the 3D cube deck (line 6), the whole
// message compared.
TEST(DeckReaderErrors, BuiltInShapesIn3d)
{
    struct Row {
        const char* name;
        const char* shape;
        std::vector<std::string> issues;
    };
    const std::string at = "hertz.yaml:6:";
    const std::vector<Row> rows = {
        {"2D shape without extrusion", "{type: half_disc, center: [0, 0], radius: 1}",
         {at + "42: error: bodies.ball.shape: a 2D shape in a 3D deck needs 'extrude: L', its length along z (or "
               "use a 3D shape: sphere_octant, box)"}},
        {"extrusion not positive", "{type: quarter_disc, center: [0, 0], radius: 1, extrude: 0}",
         {at + "99: error: bodies.ball.shape.extrude = 0: must be > 0"}},
        {"extruded shape takes 2D coordinates", "{type: rectangle, corner: [0, 0, 0], size: [1, 1], extrude: 1}",
         {at + "68: error: bodies.ball.shape.corner = [0, 0, 0]: expected a list of 2 numbers"}},
        {"3D shape is not extruded", "{type: box, corner: [0, 0, 0], size: [1, 1, 1], extrude: 2}",
         {at + "99: error: bodies.ball.shape.extrude: does not apply to a box (a 3D shape; only 2D shapes are "
               "extruded)"}},
        {"sphere_octant takes 3 coordinates", "{type: sphere_octant, center: [0, 0], radius: 1}",
         {at + "72: error: bodies.ball.shape.center = [0, 0]: expected a list of 3 numbers"}},
        {"sphere_octant takes center and radius", "{type: sphere_octant, corner: [0, 0, 0], radius: 1}",
         {at + "72: error: bodies.ball.shape.corner: does not apply to a sphere_octant (it takes center and "
               "radius)",
          at + "42: error: bodies.ball.shape: missing required key 'center'"}},
        {"box size positive", "{type: box, corner: [0, 0, 0], size: [1, -1, 1]}",
         {at + "83: error: bodies.ball.shape.size.1 = -1: must be > 0"}},
        {"sphere_octant radius positive", "{type: sphere_octant, center: [0, 0, 0], radius: 0}",
         {at + "91: error: bodies.ball.shape.radius = 0: must be > 0"}},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(issues_of(replaced(cube_deck_3d, "bodies:\n",
                                     std::string("bodies:\n  - {name: ball, material: steel, shape: ") + row.shape +
                                         "}\n")),
                  row.issues);
    }
    // The other way round: 3D shapes and extrusion in a 2D deck.
    EXPECT_EQ(issue_of(replaced(minimal_deck, "{type: rectangle, corner: [0, 0], size: [2, 1]}",
                                "{type: sphere_octant, center: [0, 0, 1], radius: 1}")),
              "hertz.yaml:11:19: error: bodies.block.shape.type = sphere_octant: a 3D shape, but analysis.dimension "
              "is 2 (2D shapes: half_disc, quarter_disc, rectangle)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "size: [2, 1]}", "size: [2, 1], extrude: 1}")),
              "hertz.yaml:11:69: error: bodies.block.shape.extrude: applies to 3D decks only (it sweeps a 2D shape "
              "along z)");
}

TEST(DeckReaderErrors, RigidBodies)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "normal: [0, 1]", "normal: [0, 0]")),
              "hertz.yaml:13:44: error: bodies.floor.rigid.plane.normal = [0, 0]: must have non-zero length");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "normal: [0, 1]", "normal: [0, 1, 0]")),
              "hertz.yaml:13:44: error: bodies.floor.rigid.plane.normal = [0, 1, 0]: expected a list of 2 numbers");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "  - name: floor\n", "  - name: floor\n    material: steel\n")),
              "hertz.yaml:13:15: error: bodies.floor.material: a rigid body takes no 'material'");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "    rigid: {plane: {point: [0, 0], normal: [0, 1]}}\n",
                                "    rigid: {plane: {point: [0, 0]}}\n")),
              "hertz.yaml:13:20: error: bodies.floor.rigid.plane: missing required key 'normal'");
}

TEST(DeckReaderErrors, ConstraintsAndLoads)
{
    const auto constraint = [](const std::string& text) {
        return issue_of(replaced(minimal_deck, "{body: block, side: u0, fix: [x]}", text));
    };
    EXPECT_EQ(constraint("{body: block, side: u0}"),
              "hertz.yaml:15:5: error: constraints.0: needs 'fix' (components held at zero) and/or 'displacement' "
              "(prescribed values, ~ for a free component)");
    // fix and displacement combine; a component may not be both held at zero and moved.
    const Deck combined = read(replaced(minimal_deck, "{body: block, side: u0, fix: [x]}",
                                        "{body: block, side: u0, fix: [x], displacement: [~, 1]}"));
    EXPECT_EQ(combined.constraints[0].fixed, (std::vector<bool>{true, true}));
    EXPECT_EQ(combined.constraints[0].value, (std::vector<double>{0.0, 1.0}));
    EXPECT_EQ(constraint("{body: block, side: u0, fix: [x], displacement: [0.5, 1]}"),
              "hertz.yaml:15:54: error: constraints.0.displacement.0 = 0.5: component x is also in 'fix' (held at "
              "zero); write ~ here or drop it from 'fix'");
    EXPECT_EQ(constraint("{body: block, side: u0, displacement: [~, ~]}"),
              "hertz.yaml:15:43: error: constraints.0.displacement = [~, ~]: prescribes no component (every entry "
              "is ~)");
    EXPECT_EQ(constraint("{body: block, side: u0, displacement: [~]}"),
              "hertz.yaml:15:43: error: constraints.0.displacement = [~]: expected a list of 2 values (~ leaves a "
              "component free), e.g. [~, -0.01]");
    EXPECT_EQ(constraint("{body: block, side: u0, fix: [x, z]}"),
              "hertz.yaml:15:38: error: constraints.0.fix.1 = z: expected a component: x, y");
    EXPECT_EQ(constraint("{body: block, side: u0, fix: x}"),
              "hertz.yaml:15:34: error: constraints.0.fix = x: expected a list of components, e.g. [x, y]");

    const auto load = [](const std::string& text) {
        return issue_of(replaced(minimal_deck, "{body: block, side: v1, traction: [0, -1]}", text));
    };
    EXPECT_EQ(load("{body: block, side: v1}"),
              "hertz.yaml:17:5: error: loads.0: needs one of traction, force, pressure, gravity");
    EXPECT_EQ(load("{body: block, side: v1, traction: [0, -1], force: [0, 1]}"),
              "hertz.yaml:17:5: error: loads.0: takes exactly one of traction, force, pressure, gravity (got traction, "
              "force)");
    EXPECT_EQ(load("{body: block, gravity: [0, -9.81]}"),
              "hertz.yaml:17:5: error: loads.0: missing required key 'density'");
    EXPECT_EQ(load("{body: block, gravity: [0, -9.81], density: 0}"),
              "hertz.yaml:17:49: error: loads.0.density = 0: must be > 0");
    EXPECT_EQ(load("{body: block, side: v1, gravity: [0, -9.81], density: 1}"),
              "hertz.yaml:17:25: error: loads.0.side = v1: gravity acts on the whole body: no side");
    EXPECT_EQ(load("{body: block, pressure: 2}"), "hertz.yaml:17:5: error: loads.0: missing required key 'side'");
    EXPECT_EQ(load("{body: block, side: v1, pressure: 2, density: 1}"),
              "hertz.yaml:17:51: error: loads.0.density = 1: applies to gravity loads only");
}

TEST(DeckReaderErrors, ContactStepsNewtonOutput)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", "penalty: 0")),
              "hertz.yaml:21:14: error: contact.block_floor.penalty = 0: must be > 0");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", "penalty: 1.0e4\n    quadrature: 0")),
              "hertz.yaml:22:17: error: contact.block_floor.quadrature = 0: must be >= 1");
    EXPECT_EQ(issue_of(minimal_deck + "steps: {count: 0}\n"), "hertz.yaml:22:16: error: steps.count = 0: must be >= 1");
    EXPECT_EQ(issue_of(minimal_deck + "steps: {max_cutbacks: -1}\n"),
              "hertz.yaml:22:23: error: steps.max_cutbacks = -1: must be >= 0");
    EXPECT_EQ(issue_of(minimal_deck + "newton: {tolerance: 0}\n"),
              "hertz.yaml:22:21: error: newton.tolerance = 0: must be > 0");
    EXPECT_EQ(issue_of(minimal_deck + "newton: {max_iterations: 0}\n"),
              "hertz.yaml:22:26: error: newton.max_iterations = 0: must be >= 1");
    EXPECT_EQ(issue_of(minimal_deck + "output: {samples_per_span: 0}\n"),
              "hertz.yaml:22:28: error: output.samples_per_span = 0: must be >= 1");
    EXPECT_EQ(issue_of(minimal_deck + "output: {file: ''}\n"),
              "hertz.yaml:22:16: error: output.file: must not be empty");
}

TEST(DeckReaderErrors, EnforcementAndAutoPenalty)
{
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", "penalty: fast")),
              "hertz.yaml:21:14: error: contact.block_floor.penalty = fast: expected a number > 0 or auto");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", "penalty: 1.0e4\n    enforcement: lagrange")),
              "hertz.yaml:22:18: error: contact.block_floor.enforcement = lagrange: expected one of penalty, "
              "augmented_lagrangian");
    const std::string augmented = "penalty: 1.0e4\n    enforcement: augmented_lagrangian\n    augmented_lagrangian: ";
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", augmented + "{gap_tolerance: -1.0e-9}")),
              "hertz.yaml:23:43: error: contact.block_floor.augmented_lagrangian.gap_tolerance = -1.0e-9: must be > 0");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", augmented + "{max_updates: 0}")),
              "hertz.yaml:23:41: error: contact.block_floor.augmented_lagrangian.max_updates = 0: must be >= 1");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4", augmented + "{gap_tol: 1.0e-9}")),
              "hertz.yaml:23:28: error: contact.block_floor.augmented_lagrangian: unknown key 'gap_tol' (known "
              "keys: gap_tolerance, max_updates)");
    EXPECT_EQ(issue_of(replaced(minimal_deck, "penalty: 1.0e4",
                                "penalty: 1.0e4\n    augmented_lagrangian: {max_updates: 5}")),
              "hertz.yaml:22:27: error: contact.block_floor.augmented_lagrangian: applies with enforcement: "
              "augmented_lagrangian only (the pair's enforcement is penalty)");
}

// contact.<pair>.law: the exponential (softened) law takes clearance and pressure, both
// required, finite and > 0, and refuses a penalty and the augmented Lagrangian beside it.
TEST(DeckReaderErrors, ContactLaw)
{
    struct Row {
        const char* name;
        std::string replacement;  ///< for `penalty: 1.0e4` of the minimal deck
        std::string expected;
    };
    const std::string exponential = "law: {type: exponential, clearance: 0.01, pressure: 5.0}";
    const std::vector<Row> rows = {
        {"the spec's spelling reads", exponential, ""},
        {"a penalty beside it", "penalty: 1.0e4\n    " + exponential, "hertz.yaml:21:14: error: contact.block_floor.penalty: does not apply with law: exponential (its "
         "stiffness is set by the law's clearance and pressure)"},
        {"the augmented Lagrangian beside it", "enforcement: augmented_lagrangian\n    " + exponential, "hertz.yaml:21:18: error: contact.block_floor.enforcement = augmented_lagrangian: the exponential law has "
         "no multipliers; use enforcement: penalty or leave it out with law: exponential"},
        {"no clearance", "law: {type: exponential, pressure: 5.0}", "hertz.yaml:21:10: error: contact.block_floor.law: missing required key 'clearance'"},
        {"clearance zero", "law: {type: exponential, clearance: 0, pressure: 5.0}", "hertz.yaml:21:41: error: contact.block_floor.law.clearance = 0: must be > 0"},
        {"pressure negative", "law: {type: exponential, clearance: 0.01, pressure: -5}", "hertz.yaml:21:57: error: contact.block_floor.law.pressure = -5: must be > 0"},
        {"pressure NaN", "law: {type: exponential, clearance: 0.01, pressure: .nan}", "hertz.yaml:21:57: error: contact.block_floor.law.pressure = .nan: must be a finite number"},
        {"clearance infinite", "law: {type: exponential, clearance: .inf, pressure: 5.0}", "hertz.yaml:21:41: error: contact.block_floor.law.clearance = .inf: must be a finite number"},
        {"an unknown type", "law: {type: softened, clearance: 0.01, pressure: 5.0}", "hertz.yaml:21:17: error: contact.block_floor.law.type = softened: expected one of penalty, exponential"},
        {"no type", "law: {clearance: 0.01, pressure: 5.0}", "hertz.yaml:21:10: error: contact.block_floor.law: missing required key 'type'"},
        {"an unknown key", "law: {type: exponential, clearance: 0.01, pressure: 5.0, slope: 2}", "hertz.yaml:21:62: error: contact.block_floor.law: unknown key 'slope' (known keys: type, clearance, "
         "pressure)"},
        {"clearance with the penalty law", "penalty: 1.0e4\n    law: {type: penalty, clearance: 0.01}", "hertz.yaml:22:37: error: contact.block_floor.law.clearance: applies with type: exponential only"},
        {"a word instead of a map", "penalty: 1.0e4\n    law: exponential", "hertz.yaml:22:10: error: contact.block_floor.law = exponential: expected a map of keys"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        const std::string deck = replaced(minimal_deck, "penalty: 1.0e4", row.replacement);
        if (row.expected.empty())
            EXPECT_EQ(read(deck).contact.front().law.type, LawType::exponential);
        else
            EXPECT_EQ(issue_of(deck), row.expected);
    }
}

TEST(DeckReaderErrors, OutputReference)
{
    const auto reference = [](const std::string& text) {
        return issue_of(minimal_deck + "output:\n  reference: " + text + "\n");
    };
    EXPECT_EQ(reference("{pair: block_flor, type: hertz_cylinder_plane, radius: 1, force: 10}"),
              "hertz.yaml:23:21: error: output.reference.pair = block_flor: unknown contact pair 'block_flor' (did you "
              "mean 'block_floor'?)");
    EXPECT_EQ(reference("{pair: block_floor, type: hertz, radius: 1, force: 10}"),
              "hertz.yaml:23:40: error: output.reference.type = hertz: expected one of hertz_cylinder_plane, "
              "hertz_two_cylinders, hertz_sphere_plane, hertz_two_spheres");
    EXPECT_EQ(reference("{pair: block_floor, type: hertz_cylinder_plane, radius: 0, force: 10}"),
              "hertz.yaml:23:70: error: output.reference.radius = 0: must be > 0");
    EXPECT_EQ(reference("{pair: block_floor, type: hertz_cylinder_plane, radius: 1, force: -10}"),
              "hertz.yaml:23:80: error: output.reference.force = -10: must be > 0");
    EXPECT_EQ(reference("{pair: block_floor, type: hertz_two_cylinders, radii: [1, 0], force: 1}"),
              "hertz.yaml:23:72: error: output.reference.radii.1 = 0: must be > 0");
    EXPECT_EQ(issues_of(minimal_deck +
                        "output:\n  reference: {pair: block_floor, type: hertz_two_cylinders, radius: 1, force: 1}\n"),
              (std::vector<std::string>{"hertz.yaml:23:69: error: output.reference.radius: does not apply to "
                                        "hertz_two_cylinders (it takes 'radii')",
                                        "hertz.yaml:23:14: error: output.reference: missing required key 'radii'"}));
}

// References of the wrong dimension: line contact in 3D decks, point contact in 2D decks.
TEST(DeckReaderErrors, OutputReferenceDimension)
{
    EXPECT_EQ(issue_of(minimal_deck +
                       "output:\n  reference: {pair: block_floor, type: hertz_sphere_plane, radius: 1, force: 1}\n"),
              "hertz.yaml:23:40: error: output.reference.type = hertz_sphere_plane: a 3D point-contact reference; a "
              "2D deck takes hertz_cylinder_plane or hertz_two_cylinders");
    EXPECT_EQ(issue_of(cube_deck_3d +
                       "output:\n  reference: {pair: cube_table, type: hertz_two_cylinders, radii: [1, 2], force: "
                       "1}\n"),
              "hertz.yaml:32:39: error: output.reference.type = hertz_two_cylinders: a 2D line-contact reference; a "
              "3D deck takes hertz_sphere_plane or hertz_two_spheres");
    EXPECT_EQ(issues_of(cube_deck_3d +
                        "output:\n  reference: {pair: cube_table, type: hertz_two_spheres, radius: 1, force: 1}\n"),
              (std::vector<std::string>{"hertz.yaml:32:66: error: output.reference.radius: does not apply to "
                                        "hertz_two_spheres (it takes 'radii')",
                                        "hertz.yaml:32:14: error: output.reference: missing required key 'radii'"}));
    EXPECT_EQ(issue_of(cube_deck_3d +
                       "output:\n  reference: {pair: cube_table, type: hertz_sphere_plane, radius: 1, force: 0}\n"),
              "hertz.yaml:32:77: error: output.reference.force = 0: must be > 0");
}

TEST(DeckReaderErrors, IndependentIssuesAreReportedTogether)
{
    std::string deck = replaced(minimal_deck, "nu: 0.3", "nu: 0.6");
    deck = replaced(deck, "material: steel", "material: stel");
    deck = replaced(deck, "penalty: 1.0e4", "penalty: -1");
    deck += "newton: {tolerance: 0, max_iterations: 0}\n";
    try {
        read(deck);
        ADD_FAILURE() << "no error";
    } catch (const DeckError& e) {
        ASSERT_EQ(e.issues().size(), 5u) << e.what();
        EXPECT_EQ(std::string(e.what()),
                  "hertz.yaml:7:9: error: materials.steel.nu = 0.6: must lie in (-1, 0.5)\n"
                  "hertz.yaml:10:15: error: bodies.block.material = stel: unknown material 'stel' (did you mean "
                  "'steel'?)\n"
                  "hertz.yaml:21:14: error: contact.block_floor.penalty = -1: must be > 0\n"
                  "hertz.yaml:22:21: error: newton.tolerance = 0: must be > 0\n"
                  "hertz.yaml:22:40: error: newton.max_iterations = 0: must be >= 1");
    }
}

}  // namespace
}  // namespace iga::io
