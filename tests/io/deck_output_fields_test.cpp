// output.fields: stress fields at the tessellation points. Its default follows
// output.paraview, an explicit value wins, and the resolved deck states it.

#include "deck_test_support.hpp"

#include "io/deck_writer.hpp"

#include <gtest/gtest.h>

namespace iga::io {
namespace {

using test::issue_of;
using test::minimal_deck;
using test::read;

TEST(OutputFields, DefaultFollowsParaview)
{
    EXPECT_FALSE(read(minimal_deck).output.fields);
    EXPECT_TRUE(read(minimal_deck + "output: {paraview: true}\n").output.fields);
    EXPECT_FALSE(read(minimal_deck + "output: {paraview: false}\n").output.fields);
    EXPECT_TRUE(read(minimal_deck, {"output.paraview=true"}).output.fields);  // --set counts as the deck
}

TEST(OutputFields, ExplicitValueWins)
{
    EXPECT_TRUE(read(minimal_deck + "output: {fields: true}\n").output.fields);
    EXPECT_FALSE(read(minimal_deck + "output: {paraview: true, fields: false}\n").output.fields);
}

TEST(OutputFields, ResolvedDeckStatesItAndRoundTrips)
{
    for (const std::string& text : {minimal_deck, minimal_deck + "output: {paraview: true}\n",
                                    minimal_deck + "output: {paraview: true, fields: false}\n"}) {
        const Deck first = read(text);
        const std::string yaml = write_resolved_yaml(first);
        EXPECT_NE(yaml.find(std::string("\n  fields: ") + (first.output.fields ? "true" : "false") + "\n"),
                  std::string::npos)
            << yaml;
        const Deck second = read_deck_text(yaml, "resolved.yaml", "");
        EXPECT_EQ(second.output, first.output) << yaml;
    }
}

TEST(OutputFields, NotABooleanIsALocatedError)
{
    EXPECT_EQ(issue_of(minimal_deck + "output: {fields: 3}\n"),
              "hertz.yaml:22:18: error: output.fields = 3: expected true or false");
}

}  // namespace
}  // namespace iga::io
