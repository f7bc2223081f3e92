// The `amplitude` key of loads, constraints and rigid motions (docs/deck.md,
// "Load paths"): read into the deck, written back by the resolved-deck writer,
// settable with --set, and every rule of valid points reported located, one
// table row per rule.

#include "deck_test_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace iga::io {
namespace {

using test::issue_of;
using test::minimal_deck;
using test::read;
using test::replaced;

const std::string load_line = "{body: block, side: v1, traction: [0, -1]}";
const std::string constraint_line = "{body: block, side: u0, fix: [x]}";
const std::string floor_line = "rigid: {plane: {point: [0, 0], normal: [0, 1]}}";

const Amplitude press_release({{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}});

TEST(AmplitudeReader, EveryScaledItemTakesOne)
{
    std::string text = replaced(minimal_deck, load_line,
                                "{body: block, side: v1, traction: [0, -1], amplitude: [[0, 0], [1, 1], [2, 0]]}");
    text = replaced(text, constraint_line,
                    "{body: block, side: u0, fix: [x], displacement: [~, 0.1], amplitude: [[0, 0], [1, 1], [2, 0]]}");
    text = replaced(text, floor_line,
                    "rigid: {plane: {point: [0, 0], normal: [0, 1]}, motion: [0, 1], amplitude: [[0, 0], [1, 1], "
                    "[2, 0]]}");
    const Deck d = read(text);
    EXPECT_EQ(d.loads[0].amplitude, press_release);
    EXPECT_EQ(d.constraints[0].amplitude, press_release);
    EXPECT_EQ(d.bodies[1].amplitude, press_release);
    EXPECT_FALSE(d.bodies[0].amplitude.has_value());

    // The resolved deck writes them back, and reads back to the same deck.
    EXPECT_NE(d.resolved_yaml.find("amplitude: [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]"), std::string::npos)
        << d.resolved_yaml;
    const Deck again = read(d.resolved_yaml);
    EXPECT_TRUE(again.loads == d.loads && again.constraints == d.constraints && again.bodies == d.bodies);
}

TEST(AmplitudeReader, WithoutOneAnItemRampsAndTheResolvedDeckSaysNothing)
{
    const Deck d = read(minimal_deck);
    EXPECT_FALSE(d.loads[0].amplitude.has_value());
    EXPECT_FALSE(d.constraints[0].amplitude.has_value());
    EXPECT_EQ(d.resolved_yaml.find("amplitude"), std::string::npos) << d.resolved_yaml;
}

TEST(AmplitudeReader, AZeroDisplacementWithAnAmplitudeRoundTrips)
{
    // The writer turns zero values into `fix`, which takes no amplitude: with an
    // amplitude they stay under `displacement`.
    const Deck d = read(replaced(minimal_deck, constraint_line,
                                 "{body: block, side: u0, displacement: [0, ~], amplitude: [[0, 0], [1, 1]]}"));
    EXPECT_NE(d.resolved_yaml.find("displacement: [0.0, ~]"), std::string::npos) << d.resolved_yaml;
    EXPECT_TRUE(read(d.resolved_yaml).constraints == d.constraints);
}

TEST(AmplitudeReader, SetWithTheCommandLine)
{
    const Deck d = read(minimal_deck, {"loads.0.amplitude=[[0,0],[1,1],[2,0]]"});
    EXPECT_EQ(d.loads[0].amplitude, press_release);
    const Deck point = read(minimal_deck, {"loads.0.amplitude=[[0,0],[1,1],[2,1]]", "loads.0.amplitude.2.1=0"});
    EXPECT_EQ(point.loads[0].amplitude, press_release);
    const Deck motion = read(minimal_deck, {"bodies.floor.rigid.motion=[0, 1]",
                                            "bodies.floor.rigid.amplitude=[[0,0],[1,1],[2,0]]"});
    EXPECT_EQ(motion.bodies[1].amplitude, press_release);
    EXPECT_EQ(issue_of(minimal_deck, {"loads.0.amplitude=[[0,0]]"}),
              "<command line>: error: loads.0.amplitude = [[0, 0]]: expected a list of at least 2 points [time, "
              "value], e.g. [[0, 0], [1, 1]]");
}

struct BadAmplitude {
    const char* name;
    std::string from, to;  ///< the change to minimal_deck
    std::string message;
};

TEST(AmplitudeReaderErrors, EachRuleIsReportedAtItsKey)
{
    const auto load = [](const std::string& amplitude) {
        return "{body: block, side: v1, traction: [0, -1], amplitude: " + amplitude + "}";
    };
    const std::vector<BadAmplitude> table = {
        {"fewer than two points", load_line, load("[[0, 0]]"),
         "hertz.yaml:17:59: error: loads.0.amplitude = [[0, 0]]: expected a list of at least 2 points [time, value], "
         "e.g. [[0, 0], [1, 1]]"},
        {"not a list", load_line, load("1"),
         "hertz.yaml:17:59: error: loads.0.amplitude = 1: expected a list of at least 2 points [time, value], e.g. "
         "[[0, 0], [1, 1]]"},
        {"a point that is not a pair", load_line, load("[[0, 0], [1]]"),
         "hertz.yaml:17:68: error: loads.0.amplitude.1 = [1]: expected a list of 2 numbers"},
        {"a value that is not finite", load_line, load("[[0, 0], [1, .nan]]"),
         "hertz.yaml:17:72: error: loads.0.amplitude.1.1 = .nan: must be a finite number"},
        {"a time that is not a number", load_line, load("[[0, 0], [end, 1]]"),
         "hertz.yaml:17:69: error: loads.0.amplitude.1.0 = end: expected a number"},
        {"a first time other than 0", load_line, load("[[0.5, 0], [1, 1]]"),
         "hertz.yaml:17:61: error: loads.0.amplitude.0.0 = 0.5: the first time must be 0 (the load path starts at "
         "t = 0)"},
        {"times that repeat", load_line, load("[[0, 0], [1, 1], [1, 2]]"),
         "hertz.yaml:17:77: error: loads.0.amplitude.2.0 = 1: times must increase strictly (the point before is at "
         "t = 1.0)"},
        {"times that decrease", load_line, load("[[0, 0], [2, 1], [1, 2]]"),
         "hertz.yaml:17:77: error: loads.0.amplitude.2.0 = 1: times must increase strictly (the point before is at "
         "t = 2.0)"},
        {"a constraint with only fix", constraint_line, "{body: block, side: u0, fix: [x], amplitude: [[0, 0], [1, 1]]}",
         "hertz.yaml:15:50: error: constraints.0.amplitude: scales a 'displacement'; this constraint has only 'fix' "
         "(held at zero), so there is nothing to scale"},
        {"a fixed obstacle", floor_line,
         "rigid: {plane: {point: [0, 0], normal: [0, 1]}, amplitude: [[0, 0], [1, 1]]}",
         "hertz.yaml:13:64: error: bodies.floor.rigid.amplitude: scales the obstacle's 'motion'; this obstacle has "
         "none (it is fixed), so there is nothing to scale"},
        {"a misspelt key", load_line, "{body: block, side: v1, traction: [0, -1], amplitud: [[0, 0], [1, 1]]}",
         "hertz.yaml:17:48: error: loads.0: unknown key 'amplitud' (did you mean 'amplitude'?)"},
    };
    for (const BadAmplitude& row : table) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(issue_of(replaced(minimal_deck, row.from, row.to)), row.message);
    }
}

}  // namespace
}  // namespace iga::io
