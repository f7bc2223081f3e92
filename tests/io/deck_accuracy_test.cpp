// The `accuracy:` block (docs/deck.md "Accuracy on demand"): its values and defaults,
// the resolved deck's round trip, and each mistake named at its key.

#include "deck_test_support.hpp"

#include "io/deck_writer.hpp"

#include <gtest/gtest.h>

namespace iga::io {
namespace {

using test::hertz_deck;
using test::issue_of;
using test::read;

const std::string target = "accuracy:\n  target: {pair: cyl_floor, quantity: force, error: 0.02}\n";

TEST(DeckAccuracy, ReadsTheTargetAndTheBudgetWithTheirDefaults)
{
    EXPECT_FALSE(read(hertz_deck).accuracy.has_value());
    const Deck d = read(hertz_deck + target);
    ASSERT_TRUE(d.accuracy.has_value());
    EXPECT_EQ(d.accuracy->pair, "cyl_floor");
    EXPECT_EQ(d.accuracy->quantity, AccuracyQuantity::force);
    EXPECT_DOUBLE_EQ(d.accuracy->error, 0.02);
    EXPECT_EQ(d.accuracy->levels, 6);
    EXPECT_EQ(d.accuracy->dofs, 0.0);
    EXPECT_EQ(d.accuracy->seconds, 0.0);

    const Deck b = read(hertz_deck + "accuracy:\n  target: {pair: cyl_floor, error: 0.01}\n"
                                     "  budget: {levels: 4, dofs: 2.0e6, seconds: 3600}\n");
    EXPECT_EQ(b.accuracy->quantity, AccuracyQuantity::pressure_l2);
    EXPECT_EQ(b.accuracy->levels, 4);
    EXPECT_DOUBLE_EQ(b.accuracy->dofs, 2.0e6);
    EXPECT_DOUBLE_EQ(b.accuracy->seconds, 3600.0);
    // --set reaches it like any key (a penalty sweep's script, a tighter target).
    EXPECT_DOUBLE_EQ(read(hertz_deck + target, {"accuracy.target.error=0.005"}).accuracy->error, 0.005);
}

TEST(DeckAccuracy, TheResolvedDeckKeepsIt)
{
    const Deck first = read(hertz_deck + "accuracy:\n  target: {pair: cyl_floor, quantity: contact_radius, "
                                         "error: 0.03}\n  budget: {levels: 3, seconds: 60}\n");
    const std::string yaml = write_resolved_yaml(first);
    Deck second = read_deck_text(yaml, "resolved.yaml", "");
    second.source_file = first.source_file;
    EXPECT_TRUE(second == first) << yaml;
}

TEST(DeckAccuracy, MistakesAreNamedAtTheirKey)
{
    EXPECT_NE(issue_of(hertz_deck + "accuracy:\n  target: {pair: floor_touch, error: 0.01}\n")
                  .find("accuracy.target.pair = floor_touch: unknown contact pair 'floor_touch'"),
              std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + "accuracy:\n  target: {pair: cyl_floor, error: 0}\n")
                  .find("accuracy.target.error = 0: must be > 0"),
              std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + "accuracy:\n  target: {pair: cyl_floor}\n").find("missing required key 'error'"),
              std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + "accuracy:\n  budget: {levels: 3}\n").find("needs a target"), std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + target, {"accuracy.budget.levels=1"}).find("must be >= 2"), std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + target, {"accuracy.target.quantity=stick_zone"})
                  .find("accuracy.target.quantity = stick_zone: stick_zone needs friction on pair 'cyl_floor'"),
              std::string::npos);
    EXPECT_EQ(read(hertz_deck + target, {"accuracy.target.quantity=stick_zone",
                                         "contact.cyl_floor.friction.coefficient=0.3"})
                  .accuracy->quantity,
              AccuracyQuantity::stick_zone)
        << "with friction the stick zone is read";
    EXPECT_NE(issue_of(hertz_deck + target, {"accuracy.target.quantity=peak"}).find("accuracy.target.quantity"),
              std::string::npos);
    EXPECT_NE(issue_of(hertz_deck + "accuracy:\n  target: {pair: cyl_floor, error: 0.01}\n  budjet: {levels: 3}\n")
                  .find("budjet"),
              std::string::npos);
}

// A multi-patch body's zone is refined on a patch side (`patch.side`) or on a named surface.
TEST(DeckAccuracy, APatchSideOrANamedSurfaceOfAMultiPatchBodyIsATarget)
{
    const std::string two_patches = R"(format: 1
analysis: {dimension: 2, plane: strain}
materials:
  - {name: rubber, model: linear_elastic, E: 1000.0, nu: 0.3}
bodies:
  - name: block
    material: rubber
    patches:
      - {name: low, nurbs: {degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]],
                           control_points: [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]}}
      - {name: high, nurbs: {degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]],
                            control_points: [[0, 1, 1], [1, 1, 1], [0, 2, 1], [1, 2, 1]]}}
    surfaces:
      bottom: [low.v0]
  - name: floor
    rigid: {plane: {point: [0.0, 0.0], normal: [0.0, 1.0]}}
constraints:
  - {body: block, side: high.v1, displacement: [0.0, -0.01]}
contact:
  - {name: press, between: [block.low.v0, floor], penalty: 1.0e4}
accuracy:
  target: {pair: press, error: 0.05}
)";
    const Deck d = read(two_patches);
    ASSERT_TRUE(d.accuracy.has_value());
    EXPECT_EQ(d.accuracy->pair, "press");
    EXPECT_EQ(read(two_patches, {"contact.press.between=[block.bottom, floor]"}).accuracy->pair, "press");
}

}  // namespace
}  // namespace iga::io
