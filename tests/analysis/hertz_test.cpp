// The canonical Hertz benchmark through the whole solver (inputs/hertz.yaml):
// a quarter cylinder (R = 1, E = 1000, nu = 0.3, plane strain) pressed on a rigid
// plane by F/2 = 5, two-half-pass GPTS penalty, Sauer's post-processing.
//
// Oracles (docs/theory.md "The Hertz benchmark", "Hertz formulas"): the Hertz curve
// a = 0.10764, p0 = 59.143, and the
// run's own errors against it, stored in /reference/cyl_floor (definitions in
// analytic/pressure_errors.hpp; reference coordinates, mirrored half model):
// peak, half_width, l2 for the post-processed pressure. The tolerances are the
// known non-discretization effects plus the measured discretization error of the
// deck's graded mesh (du ~ a/70 at the contact edge), with a margin:
//  - a finite cylinder is not Hertz's half-space: ~0.3 % low peak, ~0.6 % L2 (docs/theory.md
//    "The Hertz benchmark");
//  - a finite penalty lowers and widens the curve, by a function of
//    kappa = eps a / E* only (docs/theory.md "Effect of a finite penalty"): kappa = 98 (eps 1e6): peak -0.3 %, a +1 %;
//    kappa = 9800 (eps 1e8): negligible; kappa = 0.98 (eps 1e4): p_max/p0 = 0.80,
//    a/a_H = 1.39.
// Also: the contact force balances the load (the cylinder is held only by
// contact), and Newton converges quadratically once the active set settles.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace iga::test {
namespace {

const std::string side_group = "results/contact/cyl_floor/cylinder.v0";
const std::string reference_group = "reference/cyl_floor";
constexpr double applied_force = 5.0;  // the quarter model carries half of F = 10

/// Runs inputs/hertz.yaml with the given penalty into its own scratch folder.
std::filesystem::path run_hertz(const std::string& name, const std::string& penalty)
{
    const auto file = scratch_dir(name) / "hertz.h5";
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/hertz.yaml"), {"contact.cyl_floor.penalty=" + penalty}, file);
    EXPECT_EQ(outcome.status, "completed") << outcome.message;
    return file;
}

struct HertzErrors {
    double peak, half_width, l2;
};

HertzErrors post_processed_errors(const Results& results)
{
    return {results.number(reference_group, "peak"), results.number(reference_group, "half_width"),
            results.number(reference_group, "l2")};
}

TEST(Hertz, PenaltyOneMillionMatchesHertz)
{
    const auto file = run_hertz("hertz_1e6", "1.0e6");
    const Results results(file);
    ASSERT_EQ(results.text("/", "status"), "completed");
    const HertzErrors e = post_processed_errors(results);
    RecordProperty("peak", std::to_string(e.peak));
    RecordProperty("half_width", std::to_string(e.half_width));
    RecordProperty("l2", std::to_string(e.l2));

    // Peak: -0.3 % (finite cylinder) - 0.3 % (kappa = 98) expected, -0.62 % measured;
    // 1 % allows mesh and sampling changes; a penalty 10x softer (kappa 9.8) is -3 %.
    constexpr double peak_tolerance = 0.01;
    // Half-width: +1 % from the penalty, plus the 1 % crossing read on a du ~ a/70
    // mesh; measured +2.2 %. A penalty 10x softer widens the zone by 7 % (docs/theory.md
    // "Effect of a finite penalty").
    constexpr double half_width_tolerance = 0.03;
    // L2: 0.6 % floor of the finite cylinder, penalty and discretization on top;
    // measured 1.75 %. A pressure 3 % off in scale alone already gives 3.5 %.
    constexpr double l2_tolerance = 0.025;
    EXPECT_TRUE(near(e.peak, 0.0, peak_tolerance)) << "peak";
    EXPECT_TRUE(near(e.half_width, 0.0, half_width_tolerance)) << "half-width";
    EXPECT_TRUE(at_most(e.l2, l2_tolerance)) << "L2";
}

// The cylinder is held vertically by contact alone, so at equilibrium the contact
// resultant equals the applied force, whatever the discretization. Three views of
// it: the sum over the carrier's Gauss points of p W (computed here from the
// stored pressure and weight), the side's normal_force attribute, and the
// reference's normal_force (the post-processed resultant, which equals the Gauss
// sum by partition of unity, docs/theory.md "Sauer's pressure post-processing").
TEST(Hertz, ContactForceBalancesTheLoad)
{
    const auto file = run_hertz("hertz_force", "1.0e6");
    const Results results(file);
    ASSERT_EQ(results.text("/", "status"), "completed");
    const std::vector<double> p = results.reals(side_group + "/gauss_points/pressure");
    const std::vector<double> W = results.reals(side_group + "/gauss_points/weight");
    ASSERT_EQ(p.size(), W.size());
    ASSERT_FALSE(p.empty());
    double gauss_sum = 0.0;
    int active = 0;
    for (std::size_t g = 0; g < p.size(); ++g) {
        EXPECT_TRUE(at_least(p[g], 0.0)) << "penalty pressure eps <g> is never negative, point " << g;
        EXPECT_TRUE(at_least(W[g], 0.0)) << "Gauss weight w |dX/deta|, point " << g;
        gauss_sum += p[g] * W[g];
        active += p[g] > 0.0 ? 1 : 0;
    }
    EXPECT_GT(active, 20) << "the contact zone spans many Gauss points on this mesh";

    // Newton stops at a relative residual of 1e-10 of the force scale (5): the force
    // balance holds to ~1e-10 (measured 5e-11). 1e-6 is the brief's bound; a lost
    // Gauss point or a wrong weight is 1e-3 and more.
    constexpr double force_tolerance = 1e-6;
    EXPECT_TRUE(near_rel(gauss_sum, applied_force, force_tolerance)) << "sum of p W";
    EXPECT_TRUE(near_rel(results.number(side_group, "normal_force"), applied_force, force_tolerance))
        << "normal_force attribute of the side";
    EXPECT_TRUE(near_rel(results.number(reference_group, "normal_force"), applied_force, force_tolerance))
        << "normal_force stored with the reference";
}

TEST(Hertz, StifferPenaltyComesCloser)
{
    const auto file = run_hertz("hertz_1e8", "1.0e8");
    const Results results(file);
    ASSERT_EQ(results.text("/", "status"), "completed");
    const HertzErrors e = post_processed_errors(results);
    RecordProperty("peak", std::to_string(e.peak));
    RecordProperty("half_width", std::to_string(e.half_width));
    RecordProperty("l2", std::to_string(e.l2));

    // kappa = 9800 removes the penalty error: what remains is the finite cylinder
    // (0.3 % peak, 0.6 % L2) and the mesh. Measured: peak -0.30 %, half-width
    // +1.15 %, L2 0.82 %; the eps = 1e6 values (-0.62 %, +2.2 %, 1.75 %) fail all three.
    constexpr double peak_tolerance = 0.006;
    constexpr double half_width_tolerance = 0.02;
    constexpr double l2_tolerance = 0.01;
    EXPECT_TRUE(near(e.peak, 0.0, peak_tolerance)) << "peak";
    EXPECT_TRUE(near(e.half_width, 0.0, half_width_tolerance)) << "half-width";
    EXPECT_TRUE(at_most(e.l2, l2_tolerance)) << "L2";
}

// eps = 1e4 (kappa = 0.98): the penalty layer is as compliant as the cylinder
// over the contact width; the half-space model of docs/theory.md "Effect of a finite penalty" predicts at
// kappa = 1 a peak of 0.80 p0 (-20 %) and a half-width of 1.39 a (+39 %). The run
// must converge and show that softening (measured -20.2 % and +42.7 %).
TEST(Hertz, SoftPenaltyShowsExpectedSoftening)
{
    const auto file = run_hertz("hertz_1e4", "1.0e4");
    const Results results(file);
    ASSERT_EQ(results.text("/", "status"), "completed");
    const HertzErrors e = post_processed_errors(results);
    RecordProperty("peak", std::to_string(e.peak));
    RecordProperty("half_width", std::to_string(e.half_width));

    // Window around the predicted -20 %: +-5 % for the finite cylinder, kappa 0.98
    // instead of 1 and the mesh; eps = 1e6 (-0.6 %) or a missing penalty (-100 %) fall outside.
    constexpr double peak_low = -0.25, peak_high = -0.15;
    // Predicted +39 %; the post-processed curve's 1 % crossing sits a little further
    // out. 30 % separates clearly from the +2 % of a stiff penalty.
    constexpr double min_half_width = 0.30;
    EXPECT_TRUE(at_least(e.peak, peak_low)) << "peak";
    EXPECT_TRUE(at_most(e.peak, peak_high)) << "peak";
    EXPECT_TRUE(at_least(e.half_width, min_half_width)) << "half-width";

    constexpr double force_tolerance = 1e-6;  // as in ContactForceBalancesTheLoad
    EXPECT_TRUE(near_rel(results.number(side_group, "normal_force"), applied_force, force_tolerance));
}

// Newton on the Hertz deck: the relative residuals e_0, e_1, ... of the one
// increment, from /convergence. Against a rigid plane in small kinematics the
// gap is linear in u, so the contact residual is piecewise linear: once the active
// set is the final one, the Newton step is exact up to round-off (the last step,
// e.g. 2.2e-4 -> 3.4e-11 at eps = 1e6), while the steps before it are the search
// for the active set (1.6e-3 -> 2.2e-4 needs C = 87 at eps 1e6, 21 at 1e8: not
// quadratic, and not asserted). The last step is what a wrong tangent (a missing
// term, a wrong sign, a wrong scale) breaks: it then converges linearly, or not
// at all. The two-cylinder deck, whose gap is nonlinear in u, checks a true
// quadratic step (two_cylinders_test.cpp).
TEST(Hertz, NewtonConvergesQuadraticallyOnceTheActiveSetSettles)
{
    for (const std::string penalty : {"1.0e6", "1.0e8"}) {
        SCOPED_TRACE("penalty " + penalty);
        const auto file = run_hertz("hertz_newton_" + penalty, penalty);
        const Results results(file);
        ASSERT_EQ(results.text("/", "status"), "completed");
        const RowMatrix table = results.matrix("convergence");
        ASSERT_EQ(table.cols(), 4);
        std::vector<double> e;
        for (Index k = 0; k < table.rows(); ++k) {
            ASSERT_EQ(table(k, 0), 1.0) << "one increment";
            EXPECT_EQ(table(k, 1), double(e.size())) << "iterations listed in order";
            e.push_back(table(k, 2));
        }
        ASSERT_GE(e.size(), 3u);
        std::ostringstream history;
        for (double v : e)
            history << v << " ";
        SCOPED_TRACE("relative residuals: " + history.str());
        RecordProperty("residuals_" + penalty, history.str());

        const double e_k = e[e.size() - 2], e_next = e.back();
        // Relative residuals, so C is free of load scale and units. A quadratic step
        // with C ~ 1 is what an exact tangent gives (here even far less: 7e-4 at
        // eps 1e6, 1.6e-3 at 1e8); a tangent error of O(1e-2) leaves e_{k+1} ~ 1e-2 e_k,
        // i.e. C ~ 1e-2/e_k ~ 50 at e_k = 2e-4.
        constexpr double quadratic_constant_bound = 1.0;
        // Order log e_{k+1} / log e_k: 2 for a quadratic step from e_k < 1 (measured
        // 2.9 and 2.75: the step is exact); a linear step gives ~1.
        constexpr double min_order = 1.8;
        constexpr double tolerance = 1e-10;  // newton.tolerance (deck default)
        // Where a Newton step can be called quadratic at all (C e_k < 1 with C ~ 1e2).
        constexpr double asymptotic_range = 1e-2;
        EXPECT_TRUE(at_most(e_next, tolerance)) << "converged to the deck tolerance";
        EXPECT_TRUE(at_most(e_k, asymptotic_range)) << "the last step starts in the asymptotic range";
        EXPECT_TRUE(at_most(e_next, quadratic_constant_bound * e_k * e_k)) << "e_k = " << e_k;
        EXPECT_TRUE(at_least(std::log(e_next) / std::log(e_k), min_order)) << "order of the last step";
    }
}

}  // namespace
}  // namespace iga::test
