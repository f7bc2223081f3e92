// Reactions, obstacle forces and flexible constraints (issue 9): global balance
// of every increment, a displaced top against a moving obstacle, free components
// of a prescribed displacement, and conflicting constraints named in the error.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include "core/error.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace iga::test {

namespace {

// Equilibrium of the converged state: the free rows of the residual are below
// 1e-10 relative (Newton tolerance), so the constrained rows balance the contact
// force to that order; 1e-6 relative is the bound, far above round-off.
constexpr double balance_tolerance = 1e-6;
// Two small-kinematics runs that differ only in which side moves solve the same
// linear problem up to Newton's tolerance (1e-10): 1e-6 relative is the bound.
constexpr double same_force_tolerance = 1e-6;

std::vector<double> attribute_vector(const Results& r, const std::string& object, const std::string& name)
{
    const io::h5::Handle o = io::h5::open_object(r.id(), object);
    return io::h5::read_attribute(o.id(), name).reals;
}

}  // namespace

TEST(Reactions, DisplacedTopBalancesTheContactForceEveryIncrement)
{
    const auto dir = scratch_dir("reactions_balance");
    const auto out = dir / "hertz_displacement.h5";
    const auto outcome = run_deck(source_path("inputs/hertz_displacement_2d.yaml"), {}, out);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(out);
    const std::vector<std::string> steps = r.steps();
    ASSERT_GE(steps.size(), 2u);
    for (const std::string& step : steps) {
        const std::string group = "steps/" + step;
        const RowMatrix top = r.matrix(group + "/reactions/cylinder.v1");
        const RowMatrix symmetry = r.matrix(group + "/reactions/cylinder.u0");
        const std::vector<double> floor = attribute_vector(r, group + "/contact/cyl_floor", "obstacle_force");
        ASSERT_EQ(floor.size(), 2u);
        ASSERT_EQ(top.size(), 2);
        // The body is held by the top, the symmetry line and the floor only:
        // reactions = force on the floor (both are forces the body passes on).
        const double scale = std::abs(floor[1]);
        ASSERT_TRUE(at_least(scale, 1e-3)) << "no contact force in " << step;
        EXPECT_TRUE(near(top(0) + symmetry(0), floor[0], balance_tolerance * scale)) << step;
        EXPECT_TRUE(near(top(1) + symmetry(1), floor[1], balance_tolerance * scale)) << step;
        // The constraint pushes the body down onto the floor.
        EXPECT_LT(top(1), 0.0) << step;
    }
    // /history holds the same numbers, one row per increment.
    const RowMatrix history = r.matrix("history/reactions/cylinder.v1");
    ASSERT_EQ(history.rows(), static_cast<Index>(steps.size()));
    const RowMatrix last = r.matrix("steps/" + steps.back() + "/reactions/cylinder.v1");
    EXPECT_EQ(history(history.rows() - 1, 1), last(1));
    EXPECT_EQ(r.matrix("history/load_factor").rows(), static_cast<Index>(steps.size()));
    EXPECT_EQ(r.matrix("history/contact/cyl_floor/cylinder.v0/normal_force").rows(),
              static_cast<Index>(steps.size()));
}

TEST(Reactions, ForceDrivenHertzContactBalancesTheLoad)
{
    // Force control: the floor takes the applied half load F/2 = 5 (docs/theory.md "The Hertz benchmark").
    const auto dir = scratch_dir("reactions_force");
    const auto out = dir / "hertz.h5";
    const auto outcome = run_deck(source_path("inputs/hertz.yaml"), {}, out);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(out);
    const std::vector<double> floor = attribute_vector(r, "results/contact/cyl_floor", "obstacle_force");
    ASSERT_EQ(floor.size(), 2u);
    EXPECT_TRUE(near(floor[1], -5.0, balance_tolerance * 5.0));
    // Frictionless floor, vertical load: nothing pushes the quarter sideways.
    EXPECT_TRUE(near(r.matrix("results/reactions/cylinder.u0")(0), 0.0, balance_tolerance * 5.0));
}

TEST(Reactions, DisplacedTopAndMovingFloorGiveTheSameContactForce)
{
    const auto dir = scratch_dir("reactions_moving_floor");
    const std::string deck = source_path("inputs/hertz_displacement_2d.yaml");
    // Fixed increments, so that both runs stop at the same load factors.
    const auto a = run_deck(deck, {"steps.adaptive=false"}, dir / "top.h5");
    // The same relative motion, made by the floor: the top is held in y, the floor rises.
    const auto b = run_deck(
        deck, {"steps.adaptive=false", "constraints.1.displacement=[~, 0]", "bodies.floor.rigid.motion=[0, 0.01]"},
        dir / "floor.h5");
    ASSERT_EQ(a.status, "completed") << a.message;
    ASSERT_EQ(b.status, "completed") << b.message;
    const Results ra(dir / "top.h5"), rb(dir / "floor.h5");
    const std::vector<std::string> steps = ra.steps();
    ASSERT_EQ(steps, rb.steps());
    for (const std::string& step : steps) {
        const std::string side = "steps/" + step + "/contact/cyl_floor/cylinder.v0";
        const double fa = ra.number(side, "normal_force"), fb = rb.number(side, "normal_force");
        ASSERT_TRUE(at_least(fa, 1e-3)) << step;
        EXPECT_TRUE(near(fa, fb, same_force_tolerance * fa)) << step << ": " << fa << " vs " << fb;
        const auto floor_a = attribute_vector(ra, "steps/" + step + "/contact/cyl_floor", "obstacle_force");
        const auto floor_b = attribute_vector(rb, "steps/" + step + "/contact/cyl_floor", "obstacle_force");
        EXPECT_TRUE(near(floor_a[1], floor_b[1], same_force_tolerance * fa)) << step;
    }
}

TEST(Reactions, FreeComponentOfAPrescribedDisplacementMoves)
{
    // displacement: [~, -0.01] on the top: y is prescribed on every top control point,
    // x is free (a frictionless platen), so the top spreads sideways (nu = 0.3).
    const auto dir = scratch_dir("free_component");
    const auto out = dir / "free.h5";
    const auto outcome = run_deck(source_path("inputs/hertz_displacement_2d.yaml"), {}, out);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results r(out);
    const RowMatrix u = r.matrix("results/displacement/cylinder");
    const RowMatrix cp = r.matrix("bodies/cylinder/control_points");
    // The top v1 is the last row of control points (u runs fastest): n_u of them.
    // (The collapsed corner u1 repeats the point (1, 1) in every row: not all points
    // at y = 1 are on the top.)
    const std::vector<double> degrees = r.reals("bodies/cylinder/degrees");
    const Index n_u = static_cast<Index>(r.reals("bodies/cylinder/knots/u").size()) -
                      static_cast<Index>(degrees[0]) - 1;
    int top_points = 0;
    double max_ux = 0.0;
    for (Index a = cp.rows() - n_u; a < cp.rows(); ++a) {
        EXPECT_TRUE(near(cp(a, 1), 1.0, 1e-14)) << "control point " << a << " is not on the top";
        ++top_points;
        EXPECT_TRUE(near(u(a, 1), -0.01, 1e-14)) << "control point " << a;  // prescribed exactly
        max_ux = std::max(max_ux, std::abs(u(a, 0)));
    }
    EXPECT_GE(top_points, 2);
    // The free component really moved: far above round-off (the spread is ~1e-3).
    EXPECT_TRUE(at_least(max_ux, 1e-5)) << max_ux;
    // Only y carries a reaction on the top; the x reaction is zero because x is free.
    EXPECT_EQ(r.matrix("results/reactions/cylinder.v1")(0), 0.0);
}

TEST(Reactions, ConflictingConstraintsNameBothItemsAndThePoint)
{
    // The symmetry line clamped in y meets the displaced top at the corner (0, 1).
    io::Deck deck = io::read_deck(source_path("inputs/hertz_displacement_2d.yaml"),
                                  {"constraints.0.fix=[x, y]"});
    deck.output.file = (scratch_dir("conflict") / "never.h5").string();
    RunContext context(nullptr, Verbosity::quiet);
    try {
        analysis::run(deck, analysis::RunOptions{}, context);
        FAIL() << "conflicting constraints were accepted";
    } catch (const DeckError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("hertz_displacement_2d.yaml:"), std::string::npos) << message;
        EXPECT_NE(message.find("constraints.1"), std::string::npos) << message;
        EXPECT_NE(message.find("constraints.0 (cylinder.u0)"), std::string::npos) << message;
        EXPECT_NE(message.find("y-displacement"), std::string::npos) << message;
        EXPECT_NE(message.find("(0, 1)"), std::string::npos) << message;
        EXPECT_NE(message.find("the sides cylinder.u0 and cylinder.v1 meet there"), std::string::npos) << message;
        EXPECT_EQ(message.find(".cpp"), std::string::npos) << "internal source path in: " << message;
    }
    EXPECT_FALSE(std::filesystem::exists(deck.output.file));
}

// Two items on one side that prescribe different values (a press written twice) name
// that side once, not as two sides that meet.
TEST(Reactions, ConflictingConstraintsOnOneSideSayItIsOneSide)
{
    io::Deck deck = io::read_deck(source_path("inputs/hertz_displacement_2d.yaml"),
                                  {"constraints=[{body: cylinder, side: u0, fix: [x]}, "
                                   "{body: cylinder, side: v1, displacement: [~, -0.01]}, "
                                   "{body: cylinder, side: v1, displacement: [~, -0.02]}]"});
    deck.output.file = (scratch_dir("conflict_one_side") / "never.h5").string();
    RunContext context(nullptr, Verbosity::quiet);
    try {
        analysis::run(deck, analysis::RunOptions{}, context);
        FAIL() << "conflicting constraints were accepted";
    } catch (const DeckError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("constraints.2"), std::string::npos) << message;
        EXPECT_NE(message.find("both items are on the side cylinder.v1"), std::string::npos) << message;
        EXPECT_EQ(message.find("meet there"), std::string::npos) << message;
    }
    EXPECT_FALSE(std::filesystem::exists(deck.output.file));
}

}  // namespace iga::test
