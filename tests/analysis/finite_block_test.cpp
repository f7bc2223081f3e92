// Finite-strain uniaxial stretch of a unit block (inputs/block_stretch_finite_2d.yaml)
// through the whole solver: the stretch against the closed form
// (block_closed_form.hpp) at every converged increment, for neo-Hookean and
// Saint Venant-Kirchhoff, and the quadratic convergence of Newton read from
// /convergence.
//
// Set-up: plane strain, held by symmetry conditions only (u_x = 0 on x = 0,
// u_y = 0 on y = 0), dead traction t = 100 lambda on x = 1 per unit reference
// length, so the nominal stress is P11 = t, P22 = 0 and the deformation is
// homogeneous: u = ((l1 - 1) X, (l2 - 1) Y) at every point, hence at every
// control point (the NURBS space contains linear fields).

#include "block_closed_form.hpp"
#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace iga::test {
namespace {

constexpr double E = 1000.0, nu = 0.3, traction = 100.0;
const LameParameters lame = lame_parameters_3d(E, nu);

std::string block_deck()
{
    return source_path("inputs/block_stretch_finite_2d.yaml");
}

class FiniteBlock : public ::testing::TestWithParam<std::string> {};

TEST_P(FiniteBlock, StretchMatchesClosedFormAtEveryIncrement)
{
    const std::string model = GetParam();
    const auto dir = scratch_dir("finite_block_" + model);
    const auto file = dir / "block.h5";
    const analysis::RunOutcome outcome = run_deck(block_deck(), {"materials.soft.model=" + model}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;

    // Guard on the oracle itself: the SVK stretch satisfies P11 written with the
    // plane-strain modulus E/(1 - nu^2) (= 4 mu (lambda + mu)/(lambda + 2 mu)), and
    // the neo-Hookean one the lateral condition. Terms are O(100): round-off ~1e-13.
    constexpr double oracle_tolerance = 1e-10;
    const Stretch final_svk = svk_stretch(E, nu, traction), final_nh = neo_hookean_stretch(E, nu, traction);
    ASSERT_TRUE(near(final_svk.l1 * (final_svk.l1 * final_svk.l1 - 1.0) / 2.0 * E / (1.0 - nu * nu), traction,
                     oracle_tolerance));
    ASSERT_TRUE(near(lame.mu * (final_nh.l2 * final_nh.l2 - 1.0) + lame.lambda * std::log(final_nh.l1 * final_nh.l2),
                     0.0, oracle_tolerance));

    const Results results(file);
    const RowMatrix points = results.matrix("bodies/block/control_points");
    const std::vector<std::string> steps = results.steps();
    ASSERT_EQ(steps.size(), std::size_t(outcome.increments));
    ASSERT_FALSE(steps.empty());

    // Newton stops at a relative residual of 1e-10 (deck default) and usually
    // overshoots to ~1e-14 (quadratic); the 4 x 4 control net has a stiffness
    // condition number ~1e2, so the control-point displacements are exact to
    // ~1e-11 relative. 1e-8 keeps margin, while a wrong stress measure or a
    // missing geometric term is off by 1e-3 and more at this 10 % stretch.
    constexpr double relative_tolerance = 1e-8;
    for (const std::string& step : steps) {
        const std::string group = "/steps/" + step;
        const double load_factor = results.number(group, "load_factor");
        const Stretch exact = model == "neo_hookean" ? neo_hookean_stretch(E, nu, load_factor * traction)
                                                     : svk_stretch(E, nu, load_factor * traction);
        const RowMatrix u = results.matrix(group + "/displacement/block");
        ASSERT_EQ(u.rows(), points.rows());
        const double scale = std::abs(exact.l1 - 1.0);
        std::map<double, std::vector<double>> ux_on_line;  // reference x -> u_x of its control points
        for (Index a = 0; a < points.rows(); ++a) {
            const double X = points(a, 0), Y = points(a, 1);
            EXPECT_TRUE(near(u(a, 0), (exact.l1 - 1.0) * X, relative_tolerance * scale))
                << group << ", u_x of control point " << a;
            EXPECT_TRUE(near(u(a, 1), (exact.l2 - 1.0) * Y, relative_tolerance * scale))
                << group << ", u_y of control point " << a;
            ux_on_line[X].push_back(u(a, 0));
        }
        // Homogeneity: every control point on a line x = const moves by the same u_x.
        for (const auto& [X, values] : ux_on_line) {
            const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
            EXPECT_TRUE(at_most(*hi - *lo, relative_tolerance * scale)) << group << ", line x = " << X;
        }
        if (step == steps.back()) {
            // load_stepping.hpp: the last increment is snapped to end at exactly 1.
            EXPECT_TRUE(near(load_factor, 1.0, 0.0)) << "the run must end at exactly lambda = 1";
            // lambda1 = 1 + u_x(right side) / 1, the headline number of the deck.
            const double lambda1 = 1.0 + u(points.rows() - 1, 0);
            EXPECT_TRUE(near_rel(lambda1, exact.l1, relative_tolerance)) << "final stretch";
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Models, FiniteBlock, ::testing::Values("neo_hookean", "saint_venant_kirchhoff"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// Quadratic convergence of Newton (the tangent is the exact derivative of the
// residual). Read from /convergence: per increment, the relative residuals
// e_0, e_1, ... of the converged attempt. Asserted:
//  (a) bounded quadratic constant: e_{k+1} / e_k^2 <= C wherever the iteration is
//      in its asymptotic range (e_k < 1e-2) and e_{k+1} is above round-off
//      (e_k^2 >= 1e-13, so that the ~1e-15 floor of the relative residual cannot
//      inflate the ratio). The residuals are relative (divided by the force
//      scale), so C does not depend on the load magnitude or units.
//  (b) the last such step shows an order log e_{k+1} / log e_k >= 1.8.
//  (c) every increment converges to the deck tolerance within 6 iterations
//      (the deck header promises 4-5).
TEST(FiniteBlockNewton, ConvergesQuadratically)
{
    const auto dir = scratch_dir("finite_block_newton");
    const auto file = dir / "block.h5";
    const analysis::RunOutcome outcome = run_deck(block_deck(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;

    const Results results(file);
    const RowMatrix table = results.matrix("convergence");
    ASSERT_EQ(table.cols(), 4);
    std::map<int, std::vector<double>> history;
    for (Index k = 0; k < table.rows(); ++k) {
        EXPECT_EQ(table(k, 1), double(history[int(table(k, 0))].size())) << "iterations listed in order";
        history[int(table(k, 0))].push_back(table(k, 2));
    }
    ASSERT_EQ(history.size(), std::size_t(outcome.increments));

    // Quadratic constant for a relative residual: C ~ ||K^-1|| ||d2r/du2|| scaled by
    // the force scale, O(1) for this 10 % strain; 10 leaves room, while a
    // tangent with an O(1e-2) error (linear convergence) gives ratios ~1e2 and growing.
    constexpr double quadratic_constant_bound = 10.0;
    constexpr double asymptotic_range = 1e-2;
    constexpr double roundoff_floor_squared = 1e-13;
    // Order of the last step: 2 in exact arithmetic; 1.8 allows e_{k+1} to sit a
    // decade above e_k^2 at e_k ~ 1e-5, while linear convergence gives ~1.
    constexpr double min_order = 1.8;
    constexpr double tolerance = 1e-10;  // newton.tolerance of the deck (default)
    constexpr std::size_t max_iterations = 6;

    std::ostringstream dump;
    for (const auto& [increment, e] : history) {
        dump << "increment " << increment << ":";
        for (double v : e)
            dump << " " << v;
        dump << "\n";
    }
    SCOPED_TRACE(dump.str());

    for (const auto& [increment, e] : history) {
        ASSERT_GE(e.size(), 2u) << "increment " << increment;
        EXPECT_TRUE(at_most(e.back(), tolerance)) << "increment " << increment;
        EXPECT_LE(e.size() - 1, max_iterations) << "increment " << increment;
        double last_order = std::nan("");
        for (std::size_t k = 0; k + 1 < e.size(); ++k) {
            if (!(e[k] < asymptotic_range) || e[k] * e[k] < roundoff_floor_squared)
                continue;
            EXPECT_TRUE(at_most(e[k + 1] / (e[k] * e[k]), quadratic_constant_bound))
                << "increment " << increment << ", iteration " << k;
            last_order = std::log(e[k + 1]) / std::log(e[k]);
        }
        // NaN (no step in the asymptotic range) fails too: then the test proves nothing.
        EXPECT_TRUE(at_least(last_order, min_order)) << "increment " << increment;
    }
}

}  // namespace
}  // namespace iga::test
