// Tests of --set PATH=VALUE (docs/deck.md "General rules"): setting
// existing and new keys, addressing list items by name and by index, refusing
// paths the format does not have, and locating bad values at <command line>.

#include "deck_test_support.hpp"

#include "io/deck_writer.hpp"
#include "io/overrides.hpp"

#include <gtest/gtest.h>

namespace iga::io {
namespace {

using test::issue_of;
using test::issues_of;
using test::minimal_deck;
using test::read;
using test::replaced;

TEST(Overrides, SetExistingKeysByItemName)
{
    const Deck d = read(minimal_deck, {"materials.steel.E=2.1e5", "contact.block_floor.penalty=1e6",
                                       "contact.block_floor.formulation=single_pass"});
    EXPECT_EQ(d.materials[0].E, 2.1e5);
    EXPECT_EQ(d.contact[0].penalty, 1e6);
    EXPECT_EQ(d.contact[0].formulation, Formulation::single_pass);
    // The resolved deck is the deck after overrides.
    EXPECT_NE(d.resolved_yaml.find("E: 210000.0"), std::string::npos) << d.resolved_yaml;
}

TEST(Overrides, SetKeysTheDeckLeavesOut)
{
    const Deck d = read(minimal_deck, {"output.paraview=true", "contact.block_floor.quadrature=6",
                                       "bodies.block.refine.spans=[64,16]", "steps.count=20", "title=My run"});
    EXPECT_TRUE(d.output.paraview);
    EXPECT_EQ(d.contact[0].quadrature, 6);
    EXPECT_EQ(d.bodies[0].refine.spans, (std::vector<int>{64, 16}));
    EXPECT_EQ(d.steps.count, 20);
    EXPECT_EQ(d.title, "My run");
}

TEST(Overrides, SetListItemsByIndex)
{
    const Deck d = read(minimal_deck, {"loads.0.traction=[0,-20]", "constraints.0.fix=[x, y]",
                                       "bodies.block.shape.size.0=4", "bodies.0.material=steel"});
    EXPECT_EQ(d.loads[0].vector, (std::vector<double>{0.0, -20.0}));
    EXPECT_EQ(d.constraints[0].fixed, (std::vector<bool>{true, true}));
    EXPECT_EQ(d.bodies[0].shape->size, (std::vector<double>{4.0, 1.0}));
}

TEST(Overrides, ReplaceWholeItemsAndListsAndApplyInOrder)
{
    const Deck d = read(minimal_deck, {"loads.0={body: block, side: v1, pressure: 3}",
                                       "constraints=[{body: block, side: v0, fix: [y]}, {body: b, side: u0, fix: [x]}]",
                                       "constraints.1.body=block", "steps.count=2", "steps.count=5"});
    EXPECT_EQ(d.loads[0].kind, LoadKind::pressure);
    EXPECT_EQ(d.loads[0].pressure, 3.0);
    ASSERT_EQ(d.constraints.size(), 2u);
    EXPECT_EQ(d.constraints[0].side, Side::v0);
    EXPECT_EQ(d.steps.count, 5);  // the later override wins
}

TEST(Overrides, AnOverrideMayRepairTheDeck)
{
    const std::string bad = replaced(minimal_deck, "nu: 0.3", "nu: 0.6");
    EXPECT_EQ(read(bad, {"materials.steel.nu=0.3"}).materials[0].nu, 0.3);
}

TEST(Overrides, AnEmptyValueMeansNotGiven)
{
    EXPECT_EQ(read(minimal_deck + "steps: {count: 4}\n", {"steps.count="}).steps.count, 1);
}

TEST(OverridesErrors, PathsTheFormatDoesNotHave)
{
    EXPECT_EQ(issue_of(minimal_deck, {"contact.block_floor.penalti=1e6"}),
              "<command line>: error: contact.block_floor.penalti = 1e6: 'penalti' is not a key of "
              "'contact.block_floor' (did you mean 'penalty'?)");
    EXPECT_EQ(issue_of(minimal_deck, {"contact.blok_floor.penalty=1e6"}),
              "<command line>: error: contact.blok_floor.penalty = 1e6: no item named 'blok_floor' in 'contact' (did "
              "you mean 'block_floor'?)");
    EXPECT_EQ(issue_of(minimal_deck, {"materials.rubber.E=1"}),
              "<command line>: error: materials.rubber.E = 1: no item named 'rubber' in 'materials' (items: steel)");
    EXPECT_EQ(issue_of(minimal_deck, {"loads.3.force=[0,1]"}),
              "<command line>: error: loads.3.force = [0,1]: no item 3 in 'loads', which has 1 (indices start at 0)");
    EXPECT_EQ(issue_of(minimal_deck, {"loads.first.force=[0,1]"}),
              "<command line>: error: loads.first.force = [0,1]: no item named 'first' in 'loads' (its items have no "
              "names: use an index)");
    EXPECT_EQ(issue_of(minimal_deck, {"precision.tolerance=1"}),
              "<command line>: error: precision.tolerance = 1: 'precision' is not a key of the deck (keys: format, "
              "title, analysis, materials, bodies, constraints, loads, contact, steps, newton, solver, output, "
              "accuracy)");
    EXPECT_EQ(issue_of(minimal_deck, {"solvers.tolerance=1"}),
              "<command line>: error: solvers.tolerance = 1: 'solvers' is not a key of the deck (did you mean "
              "'solver'?)");
    EXPECT_EQ(issue_of(minimal_deck, {"solver.tolerance=1"}),
              "<command line>: error: solver.tolerance = 1: 'tolerance' is not a key of 'solver' (keys: backend, type, "
              "options)");
    EXPECT_EQ(issue_of(minimal_deck, {"format.x=1"}),
              "<command line>: error: format.x = 1: 'format' is a single value: nothing can follow it");
    EXPECT_EQ(issue_of(minimal_deck, {"steps..count=1"}),
              "<command line>: error: steps..count = 1: empty name in the path (two dots, or a dot at an end)");
    // Items are never created: a deck without contact pairs has no pair to set.
    const std::string no_contact = minimal_deck.substr(0, minimal_deck.find("contact:"));
    EXPECT_EQ(issue_of(no_contact, {"contact.cyl_floor.penalty=1e6"}),
              "<command line>: error: contact.cyl_floor.penalty = 1e6: the deck has no 'contact', so it has no "
              "'cyl_floor'");
}

TEST(OverridesErrors, MalformedArguments)
{
    EXPECT_EQ(issue_of(minimal_deck, {"penalty"}),
              "<command line>: error: --set 'penalty': expected PATH=VALUE, e.g. contact.cyl_floor.penalty=1e6");
    EXPECT_EQ(issue_of(minimal_deck, {"=3"}),
              "<command line>: error: --set '=3': expected PATH=VALUE, e.g. contact.cyl_floor.penalty=1e6");
    EXPECT_EQ(issue_of(minimal_deck, {"bodies.block.refine.spans=[64,16"}),
              "<command line>: error: bodies.block.refine.spans = [64,16: not valid YAML (end of sequence flow not "
              "found)");
}

TEST(OverridesErrors, BadValuesAreReportedAtTheCommandLine)
{
    EXPECT_EQ(issue_of(minimal_deck, {"materials.steel.nu=0.6"}),
              "<command line>: error: materials.steel.nu = 0.6: must lie in (-1, 0.5)");
    EXPECT_EQ(issue_of(minimal_deck, {"contact.block_floor.penalty=abc"}),
              "<command line>: error: contact.block_floor.penalty = abc: expected a number > 0 or auto");
    // Inside a value or a map that --set created.
    EXPECT_EQ(issue_of(minimal_deck, {"bodies.block.refine.spans=[0,16]"}),
              "<command line>: error: bodies.block.refine.spans.0 = 0: must be >= 1");
    EXPECT_EQ(issues_of(minimal_deck, {"output.reference.radius=1"}),
              (std::vector<std::string>{"<command line>: error: output.reference: missing required key 'pair'",
                                        "<command line>: error: output.reference: missing required key 'type'"}));
}

TEST(OverridesErrors, CommandLineAndDeckIssuesTogether)
{
    const auto issues = issues_of(replaced(minimal_deck, "E: 1000", "E: -1"),
                                  {"newton.max_iterations=0", "nonsense", "steps.count=2"});
    ASSERT_EQ(issues.size(), 3u);
    EXPECT_EQ(issues[0], "<command line>: error: --set 'nonsense': expected PATH=VALUE, e.g. "
                         "contact.cyl_floor.penalty=1e6");
    EXPECT_EQ(issues[1], "hertz.yaml:6:8: error: materials.steel.E = -1: must be > 0");
    EXPECT_EQ(issues[2], "<command line>: error: newton.max_iterations = 0: must be >= 1");
}

/// Every leaf path of `node` in --set syntax, with its value as YAML flow text.
void collect_leaves(const YAML::Node& node, const std::string& path, std::vector<std::string>& out)
{
    const auto join = [&](const std::string& segment) { return path.empty() ? segment : path + "." + segment; };
    if (node.IsMap()) {
        for (const auto& entry : node)
            collect_leaves(entry.second, join(entry.first.Scalar()), out);
    } else if (node.IsSequence() && node.size() > 0 && node[0].IsMap()) {
        for (std::size_t i = 0; i < node.size(); ++i)
            collect_leaves(node[i], join(node[i]["name"] ? node[i]["name"].Scalar() : std::to_string(i)), out);
    } else {
        YAML::Emitter text;
        text << YAML::Flow << node;
        out.push_back(path + "=" + text.c_str());
    }
}

TEST(Overrides, EveryKeyOfTheResolvedDeckCanBeSet)
{
    // Setting each key to the value it already has must be accepted and change
    // nothing: --set walks the deck schema (io/deck_schema.hpp), so this holds the
    // keys the writer emits to the schema, and their values to the reader.
    // The second deck adds the keys only some items have (amplitudes, a motion).
    const std::string with_paths =
        replaced(replaced(replaced(minimal_deck, "{body: block, side: u0, fix: [x]}",
                                   "{body: block, side: u0, displacement: [0.1, ~], amplitude: [[0, 0], [1, 1], [2, 0]]}"),
                          "traction: [0, -1]}", "traction: [0, -1], amplitude: [[0, 0], [2, 1]]}"),
                 "normal: [0, 1]}}", "normal: [0, 1]}, motion: [0, 0.1], amplitude: [[0, 0], [1, 1]]}");
    for (const std::string& deck : {minimal_deck, with_paths}) {
        const Deck d = read(deck + "output: {reference: {pair: block_floor, type: hertz_cylinder_plane, radius: "
                                   "1, force: 2}}\n");
        std::vector<std::string> sets;
        collect_leaves(YAML::Load(d.resolved_yaml), "", sets);
        EXPECT_GT(sets.size(), 30u);
        for (const std::string& set : sets) {
            Deck e;
            ASSERT_NO_THROW(e = read(d.resolved_yaml, {set})) << set;
            EXPECT_TRUE(e == read(d.resolved_yaml)) << set;
        }
    }
}

}  // namespace
}  // namespace iga::io
