// Adaptive load stepping through the whole solver, on the finite-strain block
// (inputs/block_stretch_finite_2d.yaml, closed forms in block_closed_form.hpp):
//  - an increment too large for Newton is cut back and the run still completes;
//  - a load beyond the limit load of the material cannot converge: the CLI exits
//    with 1, and the results file is readable, has status "failed", a message
//    naming the increment, and every increment that did converge.

#include "app/cli_support.hpp"
#include "block_closed_form.hpp"
#include "io/results_writer.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>

namespace iga::test {
namespace {

constexpr double E = 1000.0, nu = 0.3;

// As in finite_block_test.cpp: Newton's 1e-10 relative residual on a 4 x 4 net
// (condition ~1e2) leaves the control-point displacements exact to ~1e-11
// relative; a wrong converged state is off by far more.
constexpr double stretch_tolerance = 1e-8;

/// u = ((l1 - 1) X, (l2 - 1) Y) at every control point of the block.
void expect_homogeneous_stretch(const Results& results, const std::string& group, const Stretch& exact)
{
    const RowMatrix points = results.matrix("bodies/block/control_points");
    const RowMatrix u = results.matrix(group + "/displacement/block");
    ASSERT_EQ(u.rows(), points.rows());
    const double scale = std::abs(exact.l1 - 1.0);
    for (Index a = 0; a < points.rows(); ++a) {
        EXPECT_TRUE(near(u(a, 0), (exact.l1 - 1.0) * points(a, 0), stretch_tolerance * scale)) << group << ", " << a;
        EXPECT_TRUE(near(u(a, 1), (exact.l2 - 1.0) * points(a, 1), stretch_tolerance * scale)) << group << ", " << a;
    }
}

// Traction 3000 in one increment, without line search: a 7.8x stretch of the
// neo-Hookean block. The first full Newton step from the reference state
// inverts the elements (det F <= 0), the evaluation fails, and the stepper must
// halve the increment (with the line search on, Newton alone copes with this
// block: the deck default takes 10 iterations and no cutback).
TEST(Cutback, DivergingIncrementSucceedsAfterCuttingBack)
{
    constexpr double traction = 3000.0;
    const auto dir = scratch_dir("cutback_success");
    const auto file = dir / "block.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/block_stretch_finite_2d.yaml"),
                 {"loads.0.traction=[3000, 0]", "steps.count=1", "newton.line_search=false"}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;

    const Results results(file);
    EXPECT_EQ(results.text("/", "status"), "completed");
    const std::vector<std::string> steps = results.steps();
    ASSERT_FALSE(steps.empty());
    double cutbacks = 0.0;
    double previous_lambda = 0.0;
    for (const std::string& step : steps) {
        const std::string group = "/steps/" + step;
        cutbacks += results.number(group, "cutbacks");
        const double lambda = results.number(group, "load_factor");
        EXPECT_GT(lambda, previous_lambda) << group << ": load factors increase";
        previous_lambda = lambda;
        expect_homogeneous_stretch(results, group, neo_hookean_stretch(E, nu, lambda * traction));
    }
    EXPECT_TRUE(at_least(cutbacks, 1.0)) << "no increment was cut back: the test no longer exercises cutbacks";
    EXPECT_EQ(cutbacks, double(outcome.cutbacks));
    EXPECT_GT(steps.size(), 1u) << "a cut-back increment leaves more than one converged increment";
    EXPECT_EQ(previous_lambda, 1.0) << "the run must end at exactly lambda = 1";
}

// Saint Venant-Kirchhoff in compression has a limit load: P11 = k l1 (l1^2 - 1)/2
// with k = E/(1 - nu^2) reaches its minimum -k/(3 sqrt 3) = -211.5 at l1 = 1/sqrt 3,
// so a nominal stress of -300 has no solution beyond the load factor
// 211.5/300 = 0.705. The run must stop with a clear failure there.
TEST(Cutback, LoadBeyondLimitFailsCleanly)
{
    constexpr double traction = -300.0;
    const double k = E / (1.0 - nu * nu);
    const double limit_factor = k / (3.0 * std::sqrt(3.0)) / -traction;

    const auto dir = scratch_dir("cutback_failure");
    const auto file = dir / "block.h5";
    const CliResult cli = run_cli(shell_quote(source_path("inputs/block_stretch_finite_2d.yaml")) + " -q -o " +
                                      shell_quote(file.string()) +
                                      " --set materials.soft.model=saint_venant_kirchhoff"
                                      " --set 'loads.0.traction=[-300, 0]'",
                                  dir);
    EXPECT_EQ(cli.exit_code, 1) << cli.err;
    ASSERT_TRUE(std::filesystem::exists(file)) << "a failed run still leaves its results file";

    const Results results(file);
    EXPECT_EQ(results.text("/", "status"), "failed");
    const std::string message = results.text("/", "message");
    const std::vector<std::string> steps = results.steps();
    ASSERT_FALSE(steps.empty()) << "the increments below the limit load converge";

    // The message names the increment that failed: the one after the last stored.
    std::smatch match;
    ASSERT_TRUE(std::regex_search(message, match, std::regex("increment ([0-9]+)"))) << message;
    EXPECT_EQ(std::stoul(match[1].str()), steps.size() + 1) << message;

    // Every converged increment is stored, in order, below the limit load, and is
    // the exact homogeneous state at its load factor.
    double previous_lambda = 0.0;
    for (std::size_t k_step = 0; k_step < steps.size(); ++k_step) {
        const std::string group = "/steps/" + steps[k_step];
        EXPECT_EQ(steps[k_step], io::step_group_name(int(k_step) + 1));
        const double lambda = results.number(group, "load_factor");
        EXPECT_GT(lambda, previous_lambda) << group;
        EXPECT_TRUE(at_most(lambda, limit_factor)) << group;
        previous_lambda = lambda;
        expect_homogeneous_stretch(results, group, svk_stretch(E, nu, lambda * traction));
    }
    // /results is the last converged increment.
    const RowMatrix last = results.matrix("/steps/" + steps.back() + "/displacement/block");
    const RowMatrix linked = results.matrix("results/displacement/block");
    EXPECT_EQ((last - linked).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Cutback, AShearBeyondFrictionNamesTheFrictionLimit)
{
    // The block pressed by 5 at mu = 0.3 holds a shear up to mu N = 1.5; sheared by 2 it
    // slides off at t = 1.75. The message says friction gave out (issue 32), not that a
    // body may be unconstrained.
    const auto dir = scratch_dir("cutback_friction_limit");
    const auto file = dir / "block.h5";
    const CliResult cli = run_cli(shell_quote(source_path("inputs/press_then_shear_friction_2d.yaml")) + " -q -o " +
                                      shell_quote(file.string()) + " --set 'loads.1.force=[2, 0]'",
                                  dir);
    EXPECT_EQ(cli.exit_code, 1) << cli.err;
    EXPECT_NE(cli.err.find("the friction on block.v0 in contact pair 'block_floor' had reached its limit"),
              std::string::npos)
        << cli.err;
    EXPECT_NE(cli.err.find("beyond what friction can hold (mu N)"), std::string::npos) << cli.err;
    EXPECT_EQ(cli.err.find("Constrain every rigid-body motion"), std::string::npos) << cli.err;
}

TEST(Cutback, AShearBeyondFrictionOnADeformableBaseNamesTheFrictionLimitToo)
{
    // A steel cube set on an aluminium plate, pressed by 1000, then pushed along by up to
    // 400 > mu N = 300. On a deformable base the tangent is not singular and Newton
    // stagnates instead; the message still says that friction gave out and what that means.
    const auto dir = scratch_dir("cutback_friction_limit_deformable");
    const auto deck = dir / "cube.yaml";
    std::ofstream(deck) << R"(format: 1
analysis: {dimension: 2, plane: strain, kinematics: small}
materials:
  - {name: steel, model: linear_elastic, E: 210000.0, nu: 0.3}
  - {name: alu, model: linear_elastic, E: 70000.0, nu: 0.33}
bodies:
  - name: plate
    material: alu
    shape: {type: rectangle, corner: [0.0, 0.0], size: [40.0, 5.0]}
    refine: {elevate: [1, 1], spans: [8, 2]}
  - name: cube
    material: steel
    shape: {type: rectangle, corner: [15.0, 5.0], size: [10.0, 10.0]}
    refine: {elevate: [1, 1], spans: [4, 4]}
constraints:
  - {body: plate, side: v0, fix: [x, y]}
loads:
  - {body: cube, side: v1, force: [0.0, -1000.0], amplitude: [[0, 0], [1, 1], [2, 1]]}
  - {body: cube, side: u0, force: [400.0, 0.0], amplitude: [[0, 0], [1, 0], [2, 1]]}
contact:
  - name: seat
    between: [cube.v0, plate.v1]
    penalty: auto
    friction: {coefficient: 0.3}
steps: {count: 4}
)";
    const CliResult cli = run_cli(shell_quote(deck.string()) + " -q -o " + shell_quote((dir / "cube.h5").string()), dir);
    EXPECT_EQ(cli.exit_code, 1) << cli.err;
    EXPECT_NE(cli.err.find("the friction on cube.v0 in contact pair 'seat' had reached its limit"), std::string::npos)
        << cli.err;
    EXPECT_NE(cli.err.find("no equilibrium exists beyond this load"), std::string::npos) << cli.err;
    // Nothing else holds the cube: the message says so outright, not "if a force ...".
    EXPECT_NE(cli.err.find("Body cube has no prescribed displacement along the contact and no other contact"),
              std::string::npos)
        << cli.err;
}

}  // namespace
}  // namespace iga::test
