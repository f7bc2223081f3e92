// Two deformable sphere octants in 3D (inputs/hertz_two_spheres_3d.yaml on a
// coarse mesh): two-half-pass GPTS between two curved deformable faces, where
// each face is the other's master, so the consistent tangent must carry the
// variation of the foot point and of the curved master's normal (docs/theory.md):
// Newton converges quadratically once the active set settles.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace iga::test {
namespace {

constexpr double newton_tolerance = 1e-10;  // the deck's default (newton.tolerance)

/// The canonical deck with a coarse mesh: the same exact geometry and grading
/// toward the contact point, about 2.5k dofs (the canonical 25k take minutes).
std::vector<std::string> coarse_mesh()
{
    return {"bodies.0.refine.insert=[[0.03, 0.06, 0.1, 0.2, 0.4], [0.05, 0.2], [0.03, 0.06, 0.1, 0.2, 0.4]]",
            "bodies.1.refine.insert=[[0.015, 0.03, 0.05, 0.1, 0.2, 0.4], [0.03, 0.15], "
            "[0.6, 0.8, 0.9, 0.95, 0.97, 0.985]]"};
}

// Relative residuals e_0, e_1, ... The last step that ends clearly above the
// round-off floor of the penalty system (~1e-11 here) must be quadratic:
// measured 1.19e-3 -> 3.94e-8 (C = 0.03, order 2.5). A tangent without the
// variation of the master normal converges linearly (e_{k+1} ~ 0.1 e_k, C ~ 1e2
// at e_k ~ 1e-3), which the bound below rejects.
TEST(TwoSpheres3d, NewtonConvergesQuadraticallyOnACurvedDeformableMaster)
{
    const auto file = scratch_dir("two_spheres_3d_newton") / "two_spheres.h5";
    const analysis::RunOutcome outcome = run_deck(source_path("inputs/hertz_two_spheres_3d.yaml"), coarse_mesh(), file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<double> e = newton_residuals(results);
    std::ostringstream history;
    for (double v : e)
        history << v << " ";
    SCOPED_TRACE("relative residuals: " + history.str());

    constexpr double roundoff_floor = 1e-9;  // a hundred times the floor seen here
    const std::size_t k = last_step_above(e, roundoff_floor);
    ASSERT_LT(k + 1, e.size()) << "no step ends above the round-off floor";
    const double e_k = e[k], e_next = e[k + 1];
    constexpr double quadratic_constant_bound = 10.0;  // C = O(1) for relative residuals (measured 0.03)
    constexpr double min_order = 1.8;                  // 2 in exact arithmetic; a linear step gives ~1
    EXPECT_TRUE(at_most(e_next, quadratic_constant_bound * e_k * e_k)) << "e_k = " << e_k;
    EXPECT_TRUE(at_least(std::log(e_next) / std::log(e_k), min_order)) << "order, e_k = " << e_k;
    EXPECT_TRUE(at_most(e.back(), newton_tolerance)) << "converged to the deck tolerance";
}

}  // namespace
}  // namespace iga::test
