// Load paths through the whole solver (docs/deck.md, "Load paths"): amplitudes
// on loads, prescribed displacements and obstacle motions, read back from the
// results file only.
//  - small kinematics is linear in the loads: press and release returns to zero,
//    equal loads on the way up and down give equal states, and press-then-shear
//    is the superposition of the two loads' responses (the contract's example);
//  - a prescribed displacement follows its amplitude;
//  - a rigid plane pressed in and pulled back (constant stiffness + Woodbury,
//    penalty and augmented Lagrangian) leaves no contact force at the end;
//  - the stored step times land on every kink of the amplitudes;
//  - a cutback in the middle of a path (finite strain) reaches the same states as
//    the closed form, which a run without cutbacks reaches too;
//  - a follower pressure (finite strain) released along its path returns to zero;
//  - press, then shear on a floor with friction: the press is held while the
//    friction takes the shear (inputs/press_then_shear_friction_2d.yaml).

#include "block_closed_form.hpp"
#include "core/amplitude.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace iga::test {
namespace {

const std::string paths_deck = "tests/analysis/decks/block_load_paths_2d.yaml";
const std::string obstacle_deck = "tests/analysis/decks/block_obstacle_press_release_2d.yaml";

// A linear solve with the constant stiffness (4 x 4 spans of degree 2, E = 1000:
// condition ~1e4) reproduces a state to ~1e-12 relative; two linear states that
// differ by more than 1e-10 of the displacement scale are different states.
constexpr double linear_tolerance = 1e-10;

/// The steps of a results file with their pseudo-times (load_factor) and displacements.
struct Step {
    double t = 0.0;
    RowMatrix u;
    std::string group;
};

std::vector<Step> read_steps(const Results& results, const std::string& body = "block")
{
    std::vector<Step> out;
    for (const std::string& name : results.steps()) {
        const std::string group = "/steps/" + name;
        out.push_back({results.number(group, "load_factor"), results.matrix(group + "/displacement/" + body), group});
    }
    return out;
}

std::vector<double> times_of(const std::vector<Step>& steps)
{
    std::vector<double> t;
    for (const Step& s : steps)
        t.push_back(s.t);
    return t;
}

/// The displacement of the last step of a run of `deck` with the overrides.
RowMatrix final_displacement(const std::string& deck, const std::vector<std::string>& overrides,
                             const std::string& name)
{
    const auto file = scratch_dir(name) / "run.h5";
    const analysis::RunOutcome outcome = run_deck(source_path(deck), overrides, file);
    EXPECT_EQ(outcome.status, "completed") << outcome.message;
    const std::vector<Step> steps = read_steps(Results(file));
    return steps.empty() ? RowMatrix() : steps.back().u;
}

double max_abs(const RowMatrix& m)
{
    return m.size() == 0 ? 0.0 : m.cwiseAbs().maxCoeff();
}

TEST(LoadPath, PressAndReleaseReturnsToZeroAndPassesTheSameStatesBothWays)
{
    const auto file = scratch_dir("load_path_press_release") / "run.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path(paths_deck),
                 {"loads.0.amplitude=[[0, 0], [1, 1], [2, 0]]", "loads.1.force=[0, 0]", "steps.count=4"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const std::vector<Step> steps = read_steps(Results(file));
    ASSERT_EQ(times_of(steps), (std::vector<double>{0.5, 1.0, 1.5, 2.0}));
    const double scale = max_abs(steps[1].u);
    ASSERT_GT(scale, 0.0);
    EXPECT_TRUE(at_most(max_abs(steps[0].u - steps[2].u), linear_tolerance * scale)) << "t = 0.5 and t = 1.5";
    EXPECT_TRUE(at_most(max_abs(steps[3].u), linear_tolerance * scale)) << "t = 2: the force is gone";
}

TEST(LoadPath, PressThenShearIsTheSuperpositionOfTheTwoLoads)
{
    // The responses to each load alone and to both together, without amplitudes.
    const RowMatrix u_press =
        final_displacement(paths_deck, {"loads.0.amplitude=", "loads.1.force=[0, 0]", "steps.count=1"},
                           "load_path_press_alone");
    const RowMatrix u_shear =
        final_displacement(paths_deck, {"loads.1.amplitude=", "loads.0.force=[0, 0]", "steps.count=1"},
                           "load_path_shear_alone");
    const RowMatrix u_both =
        final_displacement(paths_deck, {"loads.0.amplitude=", "loads.1.amplitude=", "steps.count=1"},
                           "load_path_both_at_once");
    ASSERT_EQ(u_press.rows(), u_both.rows());
    ASSERT_EQ(u_shear.rows(), u_both.rows());
    const double scale = max_abs(u_both);

    // The deck as written: press over [0, 1], then shear over [1, 2] with the press held.
    const auto file = scratch_dir("load_path_press_then_shear") / "run.h5";
    const analysis::RunOutcome outcome = run_deck(source_path(paths_deck), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<Step> steps = read_steps(results);
    ASSERT_EQ(steps.size(), 20u) << "count 20 over [0, 2]";
    EXPECT_EQ(steps[9].t, 1.0) << "the kink of both amplitudes is a step";
    EXPECT_EQ(steps.back().t, 2.0);

    const Amplitude press({{0.0, 0.0}, {1.0, 1.0}, {2.0, 1.0}});
    const Amplitude shear({{0.0, 0.0}, {1.0, 0.0}, {2.0, 1.0}});
    const RowMatrix points = results.matrix("bodies/block/control_points");
    for (const Step& s : steps) {
        const RowMatrix expected = press(s.t) * u_press + shear(s.t) * u_shear;
        EXPECT_TRUE(at_most(max_abs(s.u - expected), linear_tolerance * scale)) << "t = " << s.t;
        // The press alone shears nothing: its x-displacements are antisymmetric
        // about x = 1/2, so the top's mean x-displacement is zero while t <= 1.
        double top_shift = 0.0;
        int n_top = 0;
        for (Index a = 0; a < points.rows(); ++a)
            if (points(a, 1) == 1.0) {
                top_shift += s.u(a, 0);
                ++n_top;
            }
        top_shift /= n_top;
        if (s.t <= 1.0)
            EXPECT_TRUE(at_most(std::abs(top_shift), linear_tolerance * scale)) << "t = " << s.t;
        else
            EXPECT_GT(top_shift, 0.0) << "t = " << s.t << ": the shear force pushes the top along +x";
    }
    // The end of the path is the combined load applied at once.
    EXPECT_TRUE(at_most(max_abs(steps.back().u - u_both), linear_tolerance * scale));
    EXPECT_TRUE(at_most(max_abs(u_both - u_press - u_shear), linear_tolerance * scale)) << "linearity";
}

TEST(LoadPath, APrescribedDisplacementFollowsItsAmplitude)
{
    // Pushed down by 0.01 over [0, 1], then drawn back to half of that at t = 3.
    const auto file = scratch_dir("load_path_displacement") / "run.h5";
    const analysis::RunOutcome outcome = run_deck(
        source_path(paths_deck),
        {"loads=[]", "steps.count=6",
         "constraints=[{body: block, side: v0, fix: [x, y]}, {body: block, side: v1, displacement: [~, -0.01], "
         "amplitude: [[0, 0], [1, 1], [3, 0.5]]}]"},
        file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<Step> steps = read_steps(results);
    ASSERT_EQ(times_of(steps), (std::vector<double>{0.5, 1.0, 1.5, 2.0, 2.5, 3.0}));
    const Amplitude a({{0.0, 0.0}, {1.0, 1.0}, {3.0, 0.5}});
    const RowMatrix points = results.matrix("bodies/block/control_points");
    for (const Step& s : steps)
        for (Index k = 0; k < points.rows(); ++k) {
            if (points(k, 1) == 1.0) {  // a prescribed dof holds a(t) * value: the same product, exactly
                EXPECT_EQ(s.u(k, 1), a(s.t) * -0.01) << "t = " << s.t << ", point " << k;
            }
        }
    // The whole field scales with the amplitude (linear elasticity).
    const double scale = max_abs(steps[1].u);
    EXPECT_TRUE(at_most(max_abs(steps[5].u - 0.5 * steps[1].u), linear_tolerance * scale));
}

// Penalty contact converged to Newton's 1e-10 relative residual: the state is
// known to ~1e-10 of its scale; two solves of the same obstacle position agree
// to that, and a released contact keeps at most that much force.
constexpr double contact_tolerance = 1e-8;
// The augmented Lagrangian settles the penetration only to within gap_tolerance
// (auto: 1e-3 h p_max / E' = 2.5e-6 here, 5e-4 of the plane's travel 0.005 at
// t = 0.5), so its force at one plane position is known to ~1e-3 relative.
constexpr double augmented_state_tolerance = 1e-3;

TEST(LoadPath, AnObstaclePressedInAndPulledBackLeavesNoForce)
{
    for (const char* enforcement : {"penalty", "augmented_lagrangian"}) {
        SCOPED_TRACE(enforcement);
        const auto file = scratch_dir(std::string("load_path_obstacle_") + enforcement) / "run.h5";
        const analysis::RunOutcome outcome =
            run_deck(source_path(obstacle_deck), {std::string("contact.press.enforcement=") + enforcement}, file);
        ASSERT_EQ(outcome.status, "completed") << outcome.message;
        const Results results(file);
        const std::vector<Step> steps = read_steps(results);
        // Adaptive steps (the first increment, closing the contact, takes many
        // iterations and shrinks the next one); these times are stored exactly: the
        // first increment T/count, the kink, the kink plus T/count, the end.
        std::vector<double> force;
        std::vector<RowMatrix> u;
        for (double t : {0.5, 1.0, 1.5, 2.0}) {
            const auto at = std::find_if(steps.begin(), steps.end(), [t](const Step& s) { return s.t == t; });
            ASSERT_TRUE(at != steps.end()) << "no step at t = " << t << ": " << ::testing::PrintToString(times_of(steps));
            force.push_back(results.number(at->group + "/contact/press/block.v1", "normal_force"));
            u.push_back(at->u);
        }
        ASSERT_GT(force[1], 0.0) << "the plane presses the block at t = 1";
        EXPECT_GT(force[1], force[0]);
        const double same_state =
            std::string(enforcement) == "penalty" ? contact_tolerance : augmented_state_tolerance;
        EXPECT_TRUE(near(force[2], force[0], same_state * force[1])) << "the same position at t = 0.5 and 1.5";
        EXPECT_TRUE(at_most(std::abs(force[3]), contact_tolerance * force[1])) << "released at t = 2";
        EXPECT_TRUE(at_most(max_abs(u[3]), contact_tolerance * max_abs(u[1])));
    }
}

TEST(LoadPath, IncrementsLandOnTheKinks)
{
    // count 3 over [0, 2]: increments of 2/3 would step over the kink at t = 1.
    const auto file = scratch_dir("load_path_kinks") / "run.h5";
    const analysis::RunOutcome outcome = run_deck(source_path(obstacle_deck), {"steps.count=3"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<double> t = times_of(read_steps(results));
    EXPECT_TRUE(std::find(t.begin(), t.end(), 1.0) != t.end()) << ::testing::PrintToString(t);
    EXPECT_EQ(t.back(), 2.0);
    for (std::size_t k = 1; k < t.size(); ++k) {
        EXPECT_GT(t[k], t[k - 1]);
        EXPECT_TRUE(at_most(t[k] - t[k - 1], 2.0 / 3.0 + 1e-15)) << "no increment beyond T/count";
    }
    // /history has one row per step, with the same times.
    EXPECT_EQ(results.reals("history/load_factor"), t);
}

// As in cutback_test.cpp: Newton's 1e-10 relative residual on the 4 x 4 net of the
// finite-strain block leaves its displacements exact to ~1e-11 relative.
constexpr double stretch_tolerance = 1e-8;
constexpr double E = 1000.0, nu = 0.3;

/// u = ((l1 - 1) X, (l2 - 1) Y) at every control point of the block.
void expect_homogeneous_stretch(const Results& results, const Step& step, const Stretch& exact)
{
    const RowMatrix points = results.matrix("bodies/block/control_points");
    ASSERT_EQ(step.u.rows(), points.rows());
    const double scale = std::max(std::abs(exact.l1 - 1.0), 1e-3);
    for (Index a = 0; a < points.rows(); ++a) {
        EXPECT_TRUE(near(step.u(a, 0), (exact.l1 - 1.0) * points(a, 0), stretch_tolerance * scale))
            << "t = " << step.t << ", point " << a;
        EXPECT_TRUE(near(step.u(a, 1), (exact.l2 - 1.0) * points(a, 1), stretch_tolerance * scale))
            << "t = " << step.t << ", point " << a;
    }
}

TEST(LoadPath, ACutbackInTheMiddleOfAPathReachesTheSameStates)
{
    // Traction 3000 (a 7.8x stretch) reached in two increments of the path: 20 %
    // of it over [0, 1], which Newton takes at once, then the rest over [1, 2] in
    // one increment, which a full Newton step (no line search) cannot take: it is
    // cut back from t = 1, the last converged state.
    constexpr double traction = 3000.0;
    const Amplitude a({{0.0, 0.0}, {1.0, 0.2}, {2.0, 1.0}});
    const std::vector<std::string> path = {"loads.0.traction=[3000, 0]", "loads.0.amplitude=[[0, 0], [1, 0.2], [2, 1]]",
                                           "newton.line_search=false"};
    for (const char* count : {"steps.count=2", "steps.count=40"}) {
        SCOPED_TRACE(count);
        std::vector<std::string> overrides = path;
        overrides.push_back(count);
        const auto file = scratch_dir(std::string("load_path_cutback_") + (count + 12)) / "run.h5";
        const analysis::RunOutcome outcome =
            run_deck(source_path("inputs/block_stretch_finite_2d.yaml"), overrides, file);
        ASSERT_EQ(outcome.status, "completed") << outcome.message;
        const Results results(file);
        const std::vector<Step> steps = read_steps(results);
        ASSERT_FALSE(steps.empty());
        double cut_from = -1.0;  // the time the first cut-back increment started at
        for (std::size_t k = 0; k < steps.size(); ++k) {
            expect_homogeneous_stretch(results, steps[k], neo_hookean_stretch(E, nu, a(steps[k].t) * traction));
            if (cut_from < 0.0 && results.number(steps[k].group, "cutbacks") > 0.0)
                cut_from = k == 0 ? 0.0 : steps[k - 1].t;
        }
        EXPECT_EQ(steps.back().t, 2.0);
        if (std::string(count) == "steps.count=2") {
            EXPECT_GE(outcome.cutbacks, 1) << "no cutback: the test no longer exercises one";
            EXPECT_EQ(cut_from, 1.0) << "the cut increment resumes from the state at t = 1";
        } else {
            EXPECT_EQ(outcome.cutbacks, 0) << "the reference run takes small increments without cutbacks";
        }
    }
}

TEST(LoadPath, PressThenShearOnARoughFloorHoldsThePressWhileFrictionTakesTheShear)
{
    // inputs/press_then_shear_friction_2d.yaml: no constraint, only the floor and its
    // friction hold the block, so by equilibrium the floor's normal force is the
    // press and its friction force the shear, at every converged step.
    const auto file = scratch_dir("load_path_press_then_shear_friction") / "run.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/press_then_shear_friction_2d.yaml"), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<double> t = results.reals("history/load_factor");
    const std::vector<double> normal = results.reals("history/contact/block_floor/block.v0/normal_force");
    const RowMatrix friction = results.matrix("history/contact/block_floor/block.v0/friction_force");
    ASSERT_EQ(t.size(), 20u);
    EXPECT_EQ(t[9], 1.0);
    const Amplitude press({{0.0, 0.0}, {1.0, 1.0}, {2.0, 1.0}});
    const Amplitude shear({{0.0, 0.0}, {1.0, 0.0}, {2.0, 1.0}});
    constexpr double press_force = 5.0, shear_force = 1.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        EXPECT_TRUE(near(normal[k], press(t[k]) * press_force, contact_tolerance * press_force)) << "t = " << t[k];
        EXPECT_TRUE(near(friction(static_cast<Index>(k), 0), -shear(t[k]) * shear_force,
                         contact_tolerance * press_force))
            << "t = " << t[k];
    }
}

TEST(LoadPath, AFollowerPressureReleasedAlongItsPathReturnsToZero)
{
    // Finite strain, a follower pressure on the right side, applied and removed:
    // elastic, so t = 0.5 and t = 1.5 (the same pressure) give the same state.
    const auto file = scratch_dir("load_path_follower") / "run.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/block_stretch_finite_2d.yaml"),
                 {"loads.0={body: block, side: u1, pressure: 100, amplitude: [[0, 0], [1, 1], [2, 0]]}",
                  "steps.count=4"},
                 file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const std::vector<Step> steps = read_steps(Results(file));
    ASSERT_EQ(times_of(steps), (std::vector<double>{0.5, 1.0, 1.5, 2.0}));
    const double scale = max_abs(steps[1].u);
    ASSERT_GT(scale, 0.0);
    EXPECT_TRUE(at_most(max_abs(steps[0].u - steps[2].u), stretch_tolerance * scale));
    EXPECT_TRUE(at_most(max_abs(steps[3].u), stretch_tolerance * scale));
}

}  // namespace
}  // namespace iga::test
