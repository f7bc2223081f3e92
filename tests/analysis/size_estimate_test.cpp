// Tests of analysis::estimate_size / check_size (analysis/size_estimate.hpp): the
// estimate agrees with the model build_scene actually builds, realistic decks pass,
// and each absurd key (spans, elevate, quadrature, samples_per_span) is refused in
// no time, with a DeckError that names its key path and located in the deck.

#include "analysis/scene.hpp"
#include "analysis/size_estimate.hpp"
#include "assembly/dof_map.hpp"
#include "assembly/sparse_pattern.hpp"
#include "io/deck_reader.hpp"
#include "run_support.hpp"

#include "core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace iga::analysis {
namespace {

using test::source_path;

// A memory limit that no realistic test deck comes near (the bad-input base deck needs
// well under a megabyte) and every absurd one exceeds by orders of magnitude.
constexpr double test_memory_bytes = 4e9;

SizeLimits test_limits()
{
    SizeLimits limits;
    limits.memory_bytes = test_memory_bytes;
    return limits;
}

io::Deck base_deck(const std::vector<std::string>& overrides = {})
{
    return io::read_deck(source_path("verification/bad_input/base.yaml"), overrides);
}

/// The message of the DeckError check_size throws ("" if none).
std::string refusal(const io::Deck& deck)
{
    try {
        check_size(deck, test_limits());
    } catch (const DeckError& e) {
        return e.what();
    }
    return "";
}

TEST(SizeEstimate, DofsAgreeWithTheBuiltScene)
{
    // Uniform spans on a single-span patch: the estimate is exact; knot insertion
    // (hertz: insert lists) is counted as an upper bound.
    for (const char* deck_file : {"verification/bad_input/base.yaml", "inputs/lame_cylinder_2d.yaml",
                                  "inputs/block_stretch_finite_2d.yaml", "inputs/hertz.yaml"}) {
        SCOPED_TRACE(deck_file);
        const io::Deck deck = io::read_deck(source_path(deck_file));
        const SizeEstimate e = estimate_size(deck);
        const Scene scene = build_scene(deck);
        const auto actual = static_cast<double>(scene.dofs->n_full());
        EXPECT_GE(e.dofs, actual);
        // An upper bound only where knots are inserted or spans do not line up: within 2x here.
        constexpr double max_overestimate = 2.0;
        EXPECT_LE(e.dofs, max_overestimate * actual);
        EXPECT_TRUE(std::isfinite(e.bytes) && e.bytes > 0);
    }
    const SizeEstimate base = estimate_size(base_deck());
    ASSERT_EQ(base.bodies.size(), 1u);
    EXPECT_EQ(base.dofs, 2.0 * 4 * 4) << "elevate [1, 1] + spans [2, 2] on a bilinear square: 4 x 4 control points";
    EXPECT_EQ(base.bodies[0].degrees, (std::vector<double>{2, 2}));
    EXPECT_EQ(base.bodies[0].spans, (std::vector<double>{2, 2}));
}

// Decks with and without contact: single-patch bodies, a rigid plane, two
// deformable cylinders, two blocks pressed together, three bodies.
const char* const sized_decks[] = {"verification/bad_input/base.yaml", "inputs/lame_cylinder_2d.yaml",
                                   "inputs/block_stretch_finite_2d.yaml", "inputs/hertz.yaml",
                                   "inputs/hertz_two_cylinders_2d.yaml", "inputs/contact_patch_test_2d.yaml",
                                   "inputs/squeeze_three_bodies_2d.yaml"};

TEST(SizeEstimate, NonzerosAgreeWithTheBuiltPattern)
{
    // The estimate counts the tangent entries over all dofs (constrained ones too):
    // compared with the scene's blocks (elements and the contact couplings the search
    // registers) scattered into a pattern with no dof constrained. The bodies' share is
    // exact for single-patch bodies with simple knots (all decks here); the contact
    // couplings' share is a model of facing sides (see the header), a few per cent of
    // the entries on these decks: within 15 %.
    constexpr double nonzero_tolerance = 0.15;
    for (const char* deck_file : sized_decks) {
        SCOPED_TRACE(deck_file);
        const io::Deck deck = io::read_deck(source_path(deck_file));
        const SizeEstimate e = estimate_size(deck);
        const Scene scene = build_scene(deck);
        std::vector<int> nodes_per_body;
        for (const BodyModel& body : scene.bodies)
            nodes_per_body.push_back(body.n_nodes);
        const assembly::DofMap unconstrained(scene.dim, nodes_per_body, {});
        std::vector<std::vector<int>> blocks;
        for (int b = 0; b < scene.pattern->n_blocks(); ++b)
            blocks.push_back(scene.pattern->block_dofs(b));
        const auto actual = static_cast<double>(assembly::SparsePattern(unconstrained, std::move(blocks)).n_nonzeros());
        EXPECT_NEAR(e.nonzeros, actual, nonzero_tolerance * actual);
    }
}

TEST(SizeEstimate, ContactCouplingsAreSparse)
{
    // The coupling blocks the scene registers up front (one per slave element and
    // master element within the search margin) against the estimate (facing sides,
    // uniform spans): the same order, never the dense (side dofs)^2 block. A graded
    // side puts more elements inside the margin (hertz_two_cylinders_2d: 3.4x more),
    // sides that face only in part meet fewer (squeeze_three_bodies_2d: 1.7x fewer):
    // within a factor 4 either way.
    constexpr double coupling_factor = 4.0;
    for (const char* deck_file : sized_decks) {
        SCOPED_TRACE(deck_file);
        const io::Deck deck = io::read_deck(source_path(deck_file));
        const SizeEstimate e = estimate_size(deck);
        const Scene scene = build_scene(deck);
        double actual = 0;
        for (const PairModel& pair : scene.pairs)
            actual += static_cast<double>(pair.blocks.size());
        if (scene.pairs.empty()) {
            EXPECT_EQ(e.contact_couplings, 0.0);
            continue;
        }
        EXPECT_GE(e.contact_couplings, actual / coupling_factor);
        EXPECT_LE(e.contact_couplings, actual * coupling_factor);
    }
}

TEST(SizeEstimate, RealisticDecksAreAccepted)
{
    for (const char* deck_file : {"verification/bad_input/base.yaml", "inputs/hertz.yaml",
                                  "inputs/hertz_two_cylinders_2d.yaml", "inputs/contact_patch_test_2d.yaml"}) {
        SCOPED_TRACE(deck_file);
        EXPECT_EQ(refusal(io::read_deck(source_path(deck_file))), "");
    }
    // Legal extremes just inside the hard limits.
    EXPECT_EQ(refusal(base_deck({"contact.touch.quadrature=64", "output.samples_per_span=1000",
                                 "bodies.block.refine.elevate=[19, 19]"})),
              "");
    // A huge steps.count is legal: nothing is allocated per planned increment.
    EXPECT_EQ(refusal(base_deck({"steps.count=1000000000"})), "");
}

TEST(SizeEstimate, EachAbsurdKeyIsRefusedByName)
{
    struct Case {
        std::string set, key, reason;
    };
    const std::vector<Case> cases = {
        {"bodies.block.refine.spans=[1e8, 1e8]", "bodies.block.refine.spans = [100000000, 100000000]: ",
         "of memory"},
        {"bodies.block.refine.elevate=[40, 40]", "bodies.block.refine.elevate = [40, 40]: ", "above the limit of 20"},
        {"contact.touch.quadrature=100000", "contact.touch.quadrature = 100000: ", "more than 64 Gauss points"},
        {"output.samples_per_span=1e9", "output.samples_per_span = 1000000000: ", "more than 1000 sample points"},
        // Too big for memory without any single hard limit: spans in one direction only.
        {"bodies.block.refine.spans=[2, 100000000]", "bodies.block.refine.spans = [2, 100000000]: ", "of memory"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.set);
        const std::string message = refusal(base_deck({c.set}));
        EXPECT_NE(message.find("base.yaml:"), std::string::npos) << message;
        EXPECT_NE(message.find(c.key), std::string::npos) << message;
        EXPECT_NE(message.find(c.reason), std::string::npos) << message;
    }
}

TEST(SizeEstimate, CulpritIsTheKeyThatMakesTheModelBig)
{
    // Moderate elevation and an absurd span count: the spans are named, not the elevation.
    const std::string message = refusal(base_deck({"bodies.block.refine.elevate=[3, 3]",
                                                   "bodies.block.refine.spans=[100000, 100000]"}));
    EXPECT_NE(message.find("bodies.block.refine.spans"), std::string::npos) << message;
    // The memory figures are in the message.
    EXPECT_NE(message.find("GB of memory"), std::string::npos) << message;
    EXPECT_NE(message.find("4 GB"), std::string::npos) << "the limit it was compared with: " << message;
}

TEST(SizeEstimate, BuildSceneRefusesBeforeAllocating)
{
    // Without the check this would try to build 1e16 control points (minutes, then bad_alloc).
    EXPECT_THROW(build_scene(base_deck({"bodies.block.refine.spans=[1e8, 1e8]"})), DeckError);
}

// Issue 32: one element of degree 20 in 3D (21^3 control points) holds a dense element
// matrix of (3 * 21^3)^2 doubles, 6.2 GB, while it is assembled. The estimate left it
// out and let the deck through to a bad_alloc on a 25 GB machine.
TEST(SizeEstimate, AHighDegreeElementCountsItsDenseElementMatrix)
{
    const auto dir = test::scratch_dir("size_estimate_degree20");
    {
        std::ofstream out(dir / "deck.yaml");
        out << R"(format: 1
analysis: {dimension: 3, kinematics: small}
materials: [{name: m, E: 100.0, nu: 0.3}]
bodies:
  - name: cube
    material: m
    shape: {type: box, corner: [0, 0, 0], size: [1, 1, 1]}
    refine: {elevate: [19, 19, 19]}
constraints:
  - {body: cube, side: w0, fix: [x, y, z]}
)";
    }
    const io::Deck deck = io::read_deck((dir / "deck.yaml").string());
    const double element_dofs = 3 * std::pow(21.0, 3);
    const double element_matrix_bytes = 8 * element_dofs * element_dofs;
    const double tangent_bytes = 2 * 12 * estimate_size(deck).nonzeros;
    EXPECT_GE(estimate_size(deck).bytes, tangent_bytes + element_matrix_bytes);
}

TEST(SizeEstimate, MachineMemoryIsKnown)
{
    // Any machine that runs the tests has more than 64 MB and less than 1 PB.
    constexpr double plausible_min = 64e6, plausible_max = 1e15;
    const double bytes = machine_memory_bytes();
    EXPECT_GT(bytes, plausible_min);
    EXPECT_LT(bytes, plausible_max);
}


// Two bilinear unit squares side by side, glued along x = 1, refined differently
// per patch (no knot crosses the interface: the v spans agree), with a contact
// surface of both bottoms on a rigid floor.
std::string two_patch_deck()
{
    return R"(format: 1
analysis: {dimension: 2, plane: strain}
materials: [{name: m, E: 100.0, nu: 0.3}]
bodies:
  - name: block
    material: m
    patches:
      - name: left
        nurbs: {degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]],
                control_points: [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]}
        refine: {spans: [6, 2]}
      - name: right
        nurbs: {degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]],
                control_points: [[1, 0, 1], [2, 0, 1], [1, 1, 1], [2, 1, 1]]}
        refine: {spans: [2, 2]}
    refine: {elevate: [1, 1]}
    surfaces: {bottom: [left.v0, right.v0], top: [left.v1, right.v1]}
  - name: floor
    rigid: {plane: {point: [0.0, 0.0], normal: [0.0, 1.0]}}
constraints:
  - {body: block, side: top, displacement: [0.0, -0.01]}
contact:
  - {name: touch, between: [block.bottom, floor], penalty: 1.0e4}
)";
}

TEST(SizeEstimate, MultiPatchBodiesAreEstimatedPatchByPatch)
{
    const auto dir = test::scratch_dir("size_estimate_multipatch");
    {
        std::ofstream out(dir / "deck.yaml");
        out << two_patch_deck();
    }
    const io::Deck deck = io::read_deck((dir / "deck.yaml").string());
    const SizeEstimate e = estimate_size(deck);
    ASSERT_EQ(e.bodies.size(), 1u);
    const BodySize& body = e.bodies.front();
    ASSERT_EQ(body.patches.size(), 2u);
    // Each patch after the body's elevate [1, 1] and its own spans: exact here.
    EXPECT_EQ(body.patches[0].name, "left");
    EXPECT_EQ(body.patches[0].degrees, (std::vector<double>{2, 2}));
    EXPECT_EQ(body.patches[0].spans, (std::vector<double>{6, 2}));
    EXPECT_EQ(body.patches[0].control_points, (std::vector<double>{8, 4}));
    EXPECT_EQ(body.patches[1].spans, (std::vector<double>{2, 2}));
    EXPECT_EQ(body.patches[1].control_points, (std::vector<double>{4, 4}));

    // Against the built body: the patches' control points, and the dofs with the
    // interface column (4 control points) counted once per patch.
    const Scene scene = build_scene(deck);
    ASSERT_EQ(scene.bodies.size(), 1u);
    double patch_dofs = 0;
    for (const PatchModel& patch : scene.bodies.front().patches)
        patch_dofs += 2.0 * patch.patch.n_control_points();
    EXPECT_EQ(body.dofs, patch_dofs);
    EXPECT_EQ(body.dofs, static_cast<double>(scene.dofs->n_full()) + 2 * 4);
    EXPECT_EQ(body.elements, 6 * 2 + 2 * 2);
    // The contact surface spans both bottoms: (degree + 2) Gauss points on each of 6 + 2 spans.
    ASSERT_EQ(scene.pairs.size(), 1u);
    EXPECT_EQ(e.contact_gauss_points, static_cast<double>(scene.pairs.front().pair.n_gauss_points(0)));
    EXPECT_EQ(e.contact_gauss_points, 4.0 * (6 + 2));
}

TEST(SizeEstimate, AbsurdPatchRefinementIsRefusedByItsPatchKey)
{
    const auto dir = test::scratch_dir("size_estimate_multipatch_refusal");
    {
        std::ofstream out(dir / "deck.yaml");
        out << two_patch_deck();
    }
    const std::string deck_file = (dir / "deck.yaml").string();
    struct Case {
        std::string set, key;
    };
    const std::vector<Case> cases = {
        // Only the second patch is refined absurdly: an estimate from the first patch would miss it.
        {"bodies.block.patches.right.refine.spans=[1e5, 1e5]", "bodies.block.patches.right.refine.spans = [100000, 100000]: "},
        {"bodies.block.patches.right.refine.elevate=[30, 0]", "bodies.block.patches.right.refine.elevate = [30, 0]: "},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.set);
        const std::string message = refusal(io::read_deck(deck_file, {c.set}));
        EXPECT_NE(message.find("deck.yaml:"), std::string::npos) << message;
        EXPECT_NE(message.find(c.key), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace iga::analysis
