// Tests of `transform:` in the deck (io/transform_reader.cpp; docs/deck.md "Placing
// geometry"): the steps as read (defaults made explicit), on shapes, raw NURBS,
// patches of a multi-patch body; the resolved deck reads back equal; --set reaches
// the steps; every class of bad step is a located error (one table per dimension).

#include "deck_test_support.hpp"

#include <gtest/gtest.h>

#include <variant>

namespace iga::io {
namespace {

using test::issue_of;
using test::issues_of;
using test::minimal_deck;
using test::read;
using test::replaced;
using test::shapes_deck_3d;

const std::string block_shape = "{type: rectangle, corner: [0, 0], size: [2, 1]}";

/// minimal_deck with `transform: <steps>` on the block's shape (line 11 of the deck).
std::string with_2d_steps(const std::string& steps)
{
    return replaced(minimal_deck, block_shape,
                    "{type: rectangle, corner: [0, 0], size: [2, 1], transform: " + steps + "}");
}

/// shapes_deck_3d with `transform: <steps>` on the ball (line 8 of the deck).
std::string with_3d_steps(const std::string& steps)
{
    return replaced(shapes_deck_3d, "radius: 1}\n    refine", "radius: 1, transform: " + steps + "}\n    refine");
}

/// The resolved deck reads back to an equal deck and writes itself again unchanged
/// (as tests/io/deck_reader_test.cpp's round trip: read from the folder "").
void expect_round_trip(const std::string& text)
{
    const Deck first = read(text);
    Deck second;
    ASSERT_NO_THROW(second = read_deck_text(first.resolved_yaml, "resolved.yaml", "")) << first.resolved_yaml;
    EXPECT_EQ(second.resolved_yaml, first.resolved_yaml) << "writing is not idempotent";
    second.source_file = first.source_file;
    EXPECT_TRUE(second == first) << first.resolved_yaml;
}

TEST(TransformReader, ReadsEveryStepWithItsDefaults)
{
    const Deck d = read(with_2d_steps("[{translate: [1, 2]}, {rotate: {angle_deg: 30}}, "
                                      "{rotate: {axis: [0, 0, 2], angle_deg: -90, about: [1, 1]}}, "
                                      "{mirror: {normal: [0, 3]}}, {scale: 2.5}]"));
    const std::vector<TransformStep>& steps = d.bodies[0].shape->transform;
    ASSERT_EQ(steps.size(), 5u);
    EXPECT_EQ(std::get<Translate>(steps[0]).offset, (std::vector<double>{1, 2}));
    EXPECT_EQ(std::get<Rotate>(steps[1]), (Rotate{{}, 30.0, {0, 0}}));  // 2D: about z, about the origin
    EXPECT_EQ(std::get<Rotate>(steps[2]), (Rotate{{}, -90.0, {1, 1}}));  // [0, 0, a > 0] restates z
    EXPECT_EQ(std::get<Mirror>(steps[3]), (Mirror{{0, 3}, {0, 0}}));    // kept as written, not normalized
    EXPECT_EQ(std::get<Scale>(steps[4]).factor, 2.5);
    EXPECT_TRUE(reverses_u(steps));
    EXPECT_FALSE(reverses_u({Mirror{{1, 0}, {0, 0}}, Mirror{{0, 1}, {0, 0}}}));

    const Deck d3 = read(with_3d_steps("[{rotate: {axis: [1, 0, 0], angle_deg: 90}}]"));
    EXPECT_EQ(std::get<Rotate>(d3.bodies[0].shape->transform[0]), (Rotate{{1, 0, 0}, 90.0, {0, 0, 0}}));
}

TEST(TransformReader, RawNurbsPatchesAndGeometryFilesTakeSteps)
{
    const std::string mirrored = replaced(test::hertz_deck, "        - [1.0, 1.0, 1.0]\n    refine:",
                                          "        - [1.0, 1.0, 1.0]\n      transform: [{mirror: {normal: [1, 0]}}]\n"
                                          "    refine:");
    const Deck d = read(mirrored);
    ASSERT_EQ(d.bodies[0].nurbs->transform.size(), 1u);
    expect_round_trip(mirrored);

    const std::string patches = replaced(minimal_deck, "shape: " + block_shape,
                                         "patches:\n"
                                         "      - name: left\n"
                                         "        nurbs: {degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]], "
                                         "control_points: [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]], "
                                         "transform: [{translate: [1, 0]}, {scale: 2}]}\n");
    const std::string renamed = replaced(patches, "block.v0", "block.left.v0");
    const std::string one_patch = replaced(replaced(renamed, "side: u0", "side: left.u0"), "side: v1", "side: left.v1");
    const Deck m = read(one_patch);
    ASSERT_EQ(m.bodies[0].patches.size(), 1u);
    EXPECT_EQ(m.bodies[0].patches[0].nurbs.transform.size(), 2u);
    expect_round_trip(one_patch);

    // A geometry file: every imported patch takes the steps, the resolved deck keeps them under `geometry`.
    const std::string file = std::string(IGA_SOURCE_DIR) + "/inputs/four_squares.xml";
    const std::string imported = replaced(
        replaced(replaced(one_patch, "block.left.v0", "block.p2.v0"), "side: left.u0", "side: p0.u0"), "side: left.v1",
        "side: p0.v1");
    const std::string from_file = imported.substr(0, imported.find("    patches:")) + "    geometry: {file: " + file +
                                  ", transform: [{mirror: {normal: [1, 0], point: [0.5, 0]}}]}\n" +
                                  imported.substr(imported.find("  - name: floor"));
    const Deck g = read(from_file);
    ASSERT_EQ(g.bodies[0].patches.size(), 4u);
    EXPECT_EQ(g.bodies[0].geometry_transform.size(), 1u);
    for (const PatchData& patch : g.bodies[0].patches)
        EXPECT_EQ(patch.nurbs.transform, g.bodies[0].geometry_transform) << patch.name;
    expect_round_trip(from_file);
}

TEST(TransformReader, TheResolvedDeckReadsBackEqual)
{
    expect_round_trip(with_2d_steps("[{translate: [1, 2]}, {rotate: {angle_deg: 0.1, about: [1e-3, 2]}}, "
                                    "{mirror: {normal: [0.6, 0.8], point: [1, 1]}}, {scale: 0.3}]"));
    expect_round_trip(with_3d_steps("[{rotate: {axis: [1, 1, 1], angle_deg: 120, about: [0, 0, 1]}}, "
                                    "{mirror: {normal: [0, 0, 1]}}, {translate: [0, 0, 0.5]}]"));
    const std::string yaml = read(with_3d_steps("[{scale: 2}, {mirror: {normal: [0, 0, 1]}}]")).resolved_yaml;
    EXPECT_NE(yaml.find("transform: [{scale: 2.0}, {mirror: {normal: [0.0, 0.0, 1.0], point: [0.0, 0.0, 0.0]}}]"),
              std::string::npos)
        << yaml;
}

TEST(TransformReader, SetReachesTheSteps)
{
    const std::string deck = with_2d_steps("[{translate: [1, 2]}, {rotate: {angle_deg: 30}}]");
    const Deck d = read(deck, {"bodies.block.shape.transform.1.rotate.angle_deg=45",
                               "bodies.block.shape.transform.0.translate=[3, 4]"});
    EXPECT_EQ(std::get<Rotate>(d.bodies[0].shape->transform[1]).angle_deg, 45.0);
    EXPECT_EQ(std::get<Translate>(d.bodies[0].shape->transform[0]).offset, (std::vector<double>{3, 4}));
    // Onto a shape without one, and a whole list.
    const Deck e = read(minimal_deck, {"bodies.block.shape.transform=[{mirror: {normal: [1, 0]}}]"});
    EXPECT_TRUE(reverses_u(e.bodies[0].shape->transform));
    EXPECT_EQ(issue_of(minimal_deck, {"bodies.block.shape.transform=[{scale: -1}]"}),
              "<command line>: error: bodies.block.shape.transform.0.scale = -1: must be > 0 (a uniform scale factor; "
              "use mirror to turn the patch over)");
    EXPECT_EQ(issue_of(deck, {"bodies.block.shape.transform.0.shift=1"}),
              "<command line>: error: bodies.block.shape.transform.0.shift = 1: 'shift' is not a key of "
              "'bodies.block.shape.transform.0' (keys: translate, rotate, mirror, scale)");
}

struct Row {
    const char* name;
    const char* steps;
    std::string issue;
};

TEST(TransformReaderErrors, TwoDimensional)
{
    const std::string at = "hertz.yaml:11:";
    const std::string path = "error: bodies.block.shape.transform";
    const std::vector<Row> rows = {
        {"unknown step", "[{rotat: {angle_deg: 1}}]",
         at + "73: " + path + ".0: unknown key 'rotat' (did you mean 'rotate'?)"},
        {"unknown step far from any", "[{shear: 1}]",
         at + "73: " + path + ".0: unknown key 'shear' (known keys: translate, rotate, mirror, scale)"},
        {"two steps in one item", "[{translate: [1, 0], scale: 2}]",
         at + "72: " + path + ".0: takes exactly one of translate, rotate, mirror, scale (got translate, scale): "
                              "write each step as its own list item, in the order they apply"},
        {"empty item", "[{}]", at + "72: " + path + ".0: needs one of translate, rotate, mirror, scale"},
        {"not a list", "{translate: [1, 0]}",
         at + "71: " + path + ": expected a list of steps, e.g. [{translate: [1, 0]}, {rotate: {angle_deg: 90}}]"},
        {"item not a map", "[translate]",
         at + "72: " + path + ".0 = translate: expected a map with one of translate, rotate, mirror, scale, e.g. "
                              "{rotate: {angle_deg: 90}}"},
        {"translate length", "[{translate: [1, 0, 0]}]",
         at + "84: " + path + ".0.translate = [1, 0, 0]: expected a list of 2 numbers"},
        {"translate not finite", "[{translate: [1, .inf]}]",
         at + "88: " + path + ".0.translate.1 = .inf: must be a finite number"},
        {"2D axis", "[{rotate: {axis: [1, 0, 0], angle_deg: 90}}]",
         at + "88: " + path + ".0.rotate.axis = [1, 0, 0]: a 2D rotation turns about the z axis, counter-clockwise: "
                              "leave 'axis' out or write [0, 0, 1] (for a clockwise turn give a negative angle_deg)"},
        {"2D axis -z", "[{rotate: {axis: [0, 0, -1], angle_deg: 90}}]",
         at + "88: " + path + ".0.rotate.axis = [0, 0, -1]: a 2D rotation turns about the z axis, counter-clockwise: "
                              "leave 'axis' out or write [0, 0, 1] (for a clockwise turn give a negative angle_deg)"},
        {"missing angle", "[{rotate: {about: [0, 0]}}]",
         at + "81: " + path + ".0.rotate: missing required key 'angle_deg'"},
        {"angle not finite", "[{rotate: {angle_deg: .nan}}]",
         at + "93: " + path + ".0.rotate.angle_deg = .nan: must be a finite number"},
        {"about length", "[{rotate: {angle_deg: 1, about: [0]}}]",
         at + "103: " + path + ".0.rotate.about = [0]: expected a list of 2 numbers"},
        {"unknown rotate key", "[{rotate: {angle_deg: 1, abut: [0, 0]}}]",
         at + "96: " + path + ".0.rotate: unknown key 'abut' (did you mean 'about'?)"},
        {"zero normal", "[{mirror: {normal: [0, 0]}}]",
         at + "90: " + path + ".0.mirror.normal = [0, 0]: must have non-zero length"},
        {"missing normal", "[{mirror: {point: [0, 0]}}]",
         at + "81: " + path + ".0.mirror: missing required key 'normal'"},
        {"point length", "[{mirror: {normal: [1, 0], point: [1, 2, 3]}}]",
         at + "105: " + path + ".0.mirror.point = [1, 2, 3]: expected a list of 2 numbers"},
        {"scale zero", "[{scale: 0}]",
         at + "80: " + path + ".0.scale = 0: must be > 0 (a uniform scale factor; use mirror to turn the patch over)"},
        {"scale negative", "[{scale: -2}]",
         at + "80: " + path + ".0.scale = -2: must be > 0 (a uniform scale factor; use mirror to turn the patch over)"},
        {"scale not a number", "[{scale: [2, 2]}]", at + "80: " + path + ".0.scale = [2, 2]: expected a number"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(issues_of(with_2d_steps(row.steps)), std::vector<std::string>{row.issue});
    }
}

TEST(TransformReaderErrors, ThreeDimensional)
{
    const std::string at = "hertz.yaml:8:";
    const std::string path = "error: bodies.ball.shape.transform";
    const std::vector<Row> rows = {
        {"3D rotation needs an axis", "[{rotate: {angle_deg: 90}}]",
         at + "85: " + path + ".0.rotate: missing required key 'axis'"},
        {"zero axis", "[{rotate: {axis: [0, 0, 0], angle_deg: 90}}]",
         at + "92: " + path + ".0.rotate.axis = [0, 0, 0]: must have non-zero length"},
        {"axis length", "[{rotate: {axis: [0, 1], angle_deg: 90}}]",
         at + "92: " + path + ".0.rotate.axis = [0, 1]: expected a list of 3 numbers"},
        {"axis not finite", "[{rotate: {axis: [0, -.inf, 1], angle_deg: 90}}]",
         at + "96: " + path + ".0.rotate.axis.1 = -.inf: must be a finite number"},
        {"2D translation in 3D", "[{translate: [1, 0]}]",
         at + "88: " + path + ".0.translate = [1, 0]: expected a list of 3 numbers"},
        {"2D mirror normal in 3D", "[{mirror: {normal: [0, 1]}}]",
         at + "94: " + path + ".0.mirror.normal = [0, 1]: expected a list of 3 numbers"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(issues_of(with_3d_steps(row.steps)), std::vector<std::string>{row.issue});
    }
    // Independent problems in several steps are reported together.
    EXPECT_EQ(issues_of(with_3d_steps("[{scale: 0}, {translate: [1]}]")).size(), 2u);
}

}  // namespace
}  // namespace iga::io
