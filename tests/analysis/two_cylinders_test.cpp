// Two identical deformable cylinders in two-half-pass contact
// (inputs/hertz_two_cylinders_2d.yaml): the core "no master, no slave" checks of
// docs/theory.md "Verification problems".
//
// The deck: two quarter discs of radius 1 meeting at the origin, the lower one
// the exact mirror image of the upper one about y = 0 (same knots in u, mirrored
// knots 1 - v in v), E = 1000, nu = 0.3, plane strain, eps = 1e6. Hertz for two
// cylinders: E* = E/(2(1 - nu^2)), R* = 1/2, F = 10 (5 on the quarter), so
// a = 0.10764 and p0 = 59.143 as for the cylinder on a plane.
//  (a) Mirror-symmetric set-up (both flat faces displacement-driven by d towards
//      each other): the two sides' Gauss-point pressures are mirror images.
//  (b) Force-driven (bottom held, top loaded with 5): both sides match Hertz.
//  (c) Listing the bodies and the pair's surfaces in the other order changes
//      nothing but round-off.
//  (d) Newton converges quadratically: here the gap depends nonlinearly on u
//      (projection onto a moving curved surface), the b-terms of docs/theory.md "GPTS tangent in tensor form" matter.

#include "run_support.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace iga::test {
namespace {

const std::string pair_group = "results/contact/mate/";
const std::string upper_side = "upper.v0";  // arc of the upper body (first in the deck)
const std::string lower_side = "lower.v1";  // arc of the lower body
const std::string reference_group = "reference/mate";
constexpr double applied_force = 5.0;
constexpr double hertz_p0 = 59.143;  // p0 = sqrt(F E* / (pi R*)), F = 10 (deck header)
constexpr double newton_tolerance = 1e-10;  // newton.tolerance of the deck (default)

std::string deck_path()
{
    return source_path("inputs/hertz_two_cylinders_2d.yaml");
}

analysis::RunOutcome run_parsed(io::Deck deck, const std::filesystem::path& file)
{
    deck.output.file = file.string();
    RunContext context(nullptr, Verbosity::quiet);
    return analysis::run(deck, analysis::RunOptions{}, context);
}

/// The same scene with the two bodies, and the two surfaces of the pair, listed
/// in the other order.
io::Deck swapped(io::Deck deck)
{
    EXPECT_EQ(deck.bodies.size(), 2u);
    EXPECT_EQ(deck.contact.size(), 1u);
    std::swap(deck.bodies[0], deck.bodies[1]);
    std::swap(deck.contact[0].first, deck.contact[0].second);
    return deck;
}

/// Overrides for (a): no load; both flat faces driven by d towards each other
/// (x held as well on those faces, the same on both bodies).
std::vector<std::string> displacement_driven(double d)
{
    std::ostringstream s;
    s.precision(17);
    s << "constraints=[{body: upper, side: u0, fix: [x]}, {body: lower, side: u0, fix: [x]}, "
      << "{body: upper, side: v1, displacement: [0, " << -d << "]}, "
      << "{body: lower, side: v0, displacement: [0, " << d << "]}]";
    return {"loads=[]", s.str()};
}

double max_abs(const std::vector<double>& v)
{
    double m = 0.0;
    for (double x : v)
        m = std::isfinite(x) ? std::max(m, std::abs(x)) : std::nan("");
    return m;
}

/// max_i |a_i - b_i| (NaN if the sizes differ or anything is not finite).
double max_difference(const std::vector<double>& a, const std::vector<double>& b)
{
    if (a.size() != b.size() || a.empty())
        return std::nan("");
    double m = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = std::abs(a[i] - b[i]);
        m = std::isfinite(d) ? std::max(m, d) : std::nan("");
        if (std::isnan(m))
            return m;
    }
    return m;
}

TEST(TwoCylinders, MirrorSymmetricSetUpGivesMirrorPressures)
{
    // d = 0.0171 loads the quarter with about 5, the Hertz force of the deck.
    constexpr double d = 0.0171;
    const auto file = scratch_dir("two_cylinders_mirror") / "mirror.h5";
    const analysis::RunOutcome outcome = run_deck(deck_path(), displacement_driven(d), file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);

    const std::string up = pair_group + upper_side + "/gauss_points/";
    const std::string low = pair_group + lower_side + "/gauss_points/";
    const RowMatrix X_up = results.matrix(up + "reference_coordinates");
    const RowMatrix X_low = results.matrix(low + "reference_coordinates");
    ASSERT_EQ(X_up.rows(), X_low.rows());
    ASSERT_EQ(X_up.cols(), 2);
    // The meshes are mirror images: the same parameters, Gauss point by Gauss point,
    // give mirrored points. Tolerance: the deck's knots 1 - v and sqrt(2)/2 agree
    // with the mirror to round-off (1e-16), 1e-13 leaves room for the refinement's
    // arithmetic; a different mesh is off by 1e-3 and more.
    constexpr double mirror_geometry_tolerance = 1e-13;
    for (Index g = 0; g < X_up.rows(); ++g) {
        EXPECT_TRUE(near(X_low(g, 0), X_up(g, 0), mirror_geometry_tolerance)) << "x of Gauss point " << g;
        EXPECT_TRUE(near(X_low(g, 1), -X_up(g, 1), mirror_geometry_tolerance)) << "y of Gauss point " << g;
    }

    const std::vector<double> p_up = results.reals(up + "pressure");
    const std::vector<double> p_low = results.reals(low + "pressure");
    const double p_max = max_abs(p_up);
    // d was picked so that the set-up reaches the Hertz load; this only guards
    // against comparing two unloaded (or barely touching) sides.
    constexpr double load_level_tolerance = 0.05;
    EXPECT_TRUE(near_rel(p_max, hertz_p0, load_level_tolerance)) << "the set-up is loaded to the Hertz level";
    // Exact symmetry: the scene, the two-half-pass assembly and every Newton iterate
    // are mirror-equivariant, so only round-off separates the sides: 1e-16 in the
    // data, amplified by the penalty system (eps/E = 1e3 times a mesh condition
    // ~1e4) to ~1e-12 at worst (measured 4e-14). 1e-8 (tighter than the ~1e-6 the
    // brief allows) is still far above that, and far below the asymmetry of a biased
    // formulation: single pass breaks the mirror of the displacements by 1.4e-4.
    constexpr double mirror_pressure_tolerance = 1e-8;
    EXPECT_TRUE(at_most(max_difference(p_up, p_low) / p_max, mirror_pressure_tolerance))
        << "Gauss-point pressures, same parameter order";

    const std::vector<double> post_up = results.reals(pair_group + upper_side + "/postprocessed/pressure");
    const std::vector<double> post_low = results.reals(pair_group + lower_side + "/postprocessed/pressure");
    EXPECT_TRUE(at_most(max_difference(post_up, post_low) / p_max, mirror_pressure_tolerance))
        << "post-processed pressures, same parameter order";
    EXPECT_TRUE(near_rel(results.number(pair_group + lower_side, "normal_force"),
                         results.number(pair_group + upper_side, "normal_force"), mirror_pressure_tolerance))
        << "equal and opposite resultants";
}

TEST(TwoCylinders, ForceDrivenMatchesTwoCylinderHertzOnBothSides)
{
    const auto file = scratch_dir("two_cylinders_force") / "force.h5";
    const analysis::RunOutcome outcome = run_deck(deck_path(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);

    // Same sources of error as the cylinder on a plane (hertz_test.cpp): finite
    // bodies (~0.3 % peak, ~0.6 % L2), the penalty (kappa = eps a/E* = 196 here:
    // -0.2 % peak), the graded mesh. Measured on both sides: peak -0.29 %, L2 0.99 %
    // and 0.92 %. The bounds leave room for mesh changes; using E* of a rigid plane
    // (twice that of two cylinders) would raise the peak by 41 %.
    constexpr double peak_tolerance = 0.015;
    constexpr double l2_tolerance = 0.025;
    for (const std::string& prefix : {std::string(), lower_side + "."}) {
        SCOPED_TRACE(prefix.empty() ? upper_side : lower_side);
        const double peak = results.number(reference_group, prefix + "peak");
        const double l2 = results.number(reference_group, prefix + "l2");
        RecordProperty(prefix + "peak", std::to_string(peak));
        RecordProperty(prefix + "l2", std::to_string(l2));
        EXPECT_TRUE(near(peak, 0.0, peak_tolerance)) << "peak";
        EXPECT_TRUE(at_most(l2, l2_tolerance)) << "L2";
    }

    // The upper body is held vertically by its own half pass alone: its contact
    // resultant balances the load to the Newton tolerance (1e-10 relative).
    constexpr double force_tolerance = 1e-6;
    EXPECT_TRUE(near_rel(results.number(pair_group + upper_side, "normal_force"), applied_force, force_tolerance));
    // The lower body's half pass is balanced by its support, not by the load: the
    // two-half-pass forces are equal and opposite only approximately (docs/theory.md
    // "Contact formulation"), up to the quadrature of each side: both passes integrate over the current
    // surface (docs/theory.md "Two-half-pass balance"); measured +0.003 % (it was
    // -0.35 % with reference lengths). 0.2 % bounds this; a lost pass or point set is O(1).
    constexpr double momentum_balance_tolerance = 0.002;
    EXPECT_TRUE(near_rel(results.number(pair_group + lower_side, "normal_force"), applied_force,
                         momentum_balance_tolerance));
}

TEST(TwoCylinders, ListingOrderDoesNotChangeTheAnswer)
{
    const auto dir = scratch_dir("two_cylinders_order");
    const io::Deck deck = io::read_deck(deck_path());
    const analysis::RunOutcome first = run_parsed(deck, dir / "as_listed.h5");
    ASSERT_EQ(first.status, "completed") << first.message;
    const analysis::RunOutcome second = run_parsed(swapped(deck), dir / "swapped.h5");
    ASSERT_EQ(second.status, "completed") << second.message;
    const Results a(dir / "as_listed.h5"), b(dir / "swapped.h5");
    ASSERT_EQ(b.reals("bodies/lower/degrees").size(), 2u) << "the swapped run has the same bodies";

    // The swapped run solves the same equations with permuted dofs and carriers:
    // the same Newton path in exact arithmetic. Differences are the LU's round-off
    // on a different ordering, at the level of the converged residual (1e-10 of
    // the force) times the penalty amplification; measured 2e-11 (post-processed)
    // and 5e-11 (Gauss points) relative to the peak. 1e-8 leaves a factor 200; a
    // master/slave bias (single pass) moves the solution by ~1e-4 and more.
    constexpr double order_tolerance = 1e-8;
    for (const std::string& side : {upper_side, lower_side}) {
        SCOPED_TRACE(side);
        const std::string group = pair_group + side + "/postprocessed/pressure";
        const std::vector<double> p_a = a.reals(group), p_b = b.reals(group);
        const double p_max = max_abs(p_a);
        constexpr double loaded_fraction = 0.9;  // the peak is within 1.5 % of p0 (ForceDriven... test)
        EXPECT_TRUE(at_least(p_max, loaded_fraction * hertz_p0)) << "the side is loaded";
        EXPECT_TRUE(at_most(max_difference(p_a, p_b) / p_max, order_tolerance)) << "post-processed pressure";
        const std::string gauss = pair_group + side + "/gauss_points/pressure";
        EXPECT_TRUE(at_most(max_difference(a.reals(gauss), b.reals(gauss)) / p_max, order_tolerance))
            << "Gauss-point pressure";
    }
    // The errors against Hertz are the same numbers, stored under the other side's names.
    constexpr double error_tolerance = 1e-8;  // relative changes of the pressure, as above
    EXPECT_TRUE(near(b.number(reference_group, upper_side + ".l2"), a.number(reference_group, "l2"), error_tolerance));
    EXPECT_TRUE(near(b.number(reference_group, "l2"), a.number(reference_group, lower_side + ".l2"), error_tolerance));
}

// Dissimilar bodies (docs/theory.md "Two-half-pass balance"): upper E = 1000, nu = 0.3,
// lower E = 3000, nu = 0 (the set-up). Their surfaces stretch differently under
// the pressure (plane strain: eps_t = -(1 - 2 nu)(1 + nu) p / E, 0.52 p/1000 against
// p/3000), so half passes that integrated over their own reference surfaces differed by
// that strain difference: the lower pass carried 4.952 of 5 (-1.0 %), at every h. Both
// passes now integrate over the current surface. Frictionless Hertz holds for dissimilar
// materials with 1/E* = sum (1 - nu^2)/E: E* = 804.29, a = 0.08897, p0 = 71.556.
std::vector<std::string> dissimilar(std::vector<std::string> more = {})
{
    more.insert(more.begin(), {"materials=[{name: rubber, model: linear_elastic, E: 1000.0, nu: 0.3}, "
                               "{name: stiff, model: linear_elastic, E: 3000.0, nu: 0.0}]",
                               "bodies.lower.material=stiff"});
    return more;
}

/// The lower body's support reaction (y) and both sides' resultants of a dissimilar run.
struct Balance {
    double support, upper, lower;
};

Balance balance_of(const Results& results)
{
    return {results.reals("results/reactions/lower.v0").at(1),
            results.number(pair_group + upper_side, "normal_force"),
            results.number(pair_group + lower_side, "normal_force")};
}

TEST(TwoCylinders, DissimilarBodiesBalanceAndMatchHertz)
{
    const auto file = scratch_dir("two_cylinders_dissimilar") / "graded.h5";
    const analysis::RunOutcome outcome = run_deck(deck_path(), dissimilar(), file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    // The graded mesh resolves the zone with du = 0.001 at its edge: what is left of the
    // imbalance is the quadrature of the pressure's kink there (measured +0.011 %). The
    // issue's bound 0.2 % is far below the 1.0 % of a mismatched measure.
    constexpr double balance_tolerance = 0.002;
    const Balance b = balance_of(results);
    RecordProperty("support", std::to_string(b.support));
    EXPECT_TRUE(near_rel(b.support, applied_force, balance_tolerance)) << "support reaction " << b.support;
    EXPECT_TRUE(near_rel(b.upper, applied_force, balance_tolerance)) << "upper resultant " << b.upper;
    EXPECT_TRUE(near_rel(b.lower, applied_force, balance_tolerance)) << "lower resultant " << b.lower;
    // Pressure against Hertz with E* of the two materials, both sides. The bounds are
    // those of the identical bodies (ForceDriven...); measured peak -0.75 % / +0.19 %,
    // L2 2.2 % / 1.0 % (upper / lower).
    EXPECT_TRUE(near(results.number(reference_group, "E_star"), 804.2895442, 1e-6)) << "E* of two materials";
    constexpr double peak_tolerance = 0.015;
    constexpr double l2_tolerance = 0.025;
    for (const std::string& prefix : {std::string(), lower_side + "."}) {
        SCOPED_TRACE(prefix.empty() ? upper_side : lower_side);
        EXPECT_TRUE(near(results.number(reference_group, prefix + "peak"), 0.0, peak_tolerance)) << "peak";
        EXPECT_TRUE(at_most(results.number(reference_group, prefix + "l2"), l2_tolerance)) << "L2";
    }
}

// The imbalance is discretization error: on uniform meshes (n spans along the quarter
// arc, 8 radially) it falls with h like the pressure's L2 error. Measured support
// reaction errors -2.27 % (n = 16) and +0.13 % (n = 64), L2 31 % and 9.4 %; with
// reference measures it stayed near -1 % at every n.
TEST(TwoCylinders, DissimilarImbalanceFallsWithH)
{
    const auto dir = scratch_dir("two_cylinders_dissimilar_h");
    std::vector<double> error;
    for (const int n : {16, 64}) {
        const std::string refine = "{elevate: [0, 1], spans: [" + std::to_string(n) + ", 8]}";
        const auto file = dir / ("n" + std::to_string(n) + ".h5");
        const analysis::RunOutcome outcome =
            run_deck(deck_path(), dissimilar({"bodies.upper.refine=" + refine, "bodies.lower.refine=" + refine}), file);
        ASSERT_EQ(outcome.status, "completed") << outcome.message;
        error.push_back(std::abs(balance_of(Results(file)).support / applied_force - 1.0));
    }
    // h / 4 must cut the error at least fourfold (first order; measured 17x), and the
    // fine mesh lands within 0.5 % (measured 0.13 %).
    EXPECT_TRUE(at_most(error[1], error[0] / 4.0)) << error[0] << " -> " << error[1];
    EXPECT_TRUE(at_most(error[1], 0.005)) << error[1];
}

// Newton's relative residuals e_0, e_1, ... of the force-driven run. The last step
// (to the deck tolerance) is read: measured 1.6e-6 -> 6.8e-11, C = e_{k+1}/e_k^2 = 25.
// The step before, 1.2e-4 -> 1.6e-6 (C = 118), still changes the active set at the
// contact edge, where each half pass now integrates over its current length.
TEST(TwoCylinders, NewtonConvergesQuadratically)
{
    const auto file = scratch_dir("two_cylinders_newton") / "newton.h5";
    const analysis::RunOutcome outcome = run_deck(deck_path(), {}, file);
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const Results results(file);
    const std::vector<double> e = newton_residuals(results);
    std::ostringstream history;
    for (double v : e)
        history << v << " ";
    SCOPED_TRACE("relative residuals: " + history.str());
    RecordProperty("residuals", history.str());

    ASSERT_GE(e.size(), 3u);
    const double e_k = e[e.size() - 2], e_next = e.back();
    // Relative residuals: C ~ ||K^-1|| ||d2r/du2|| / force scale (measured 25). A tangent
    // with a relative error delta converges linearly at a rate ~delta (the b-terms of
    // docs/theory.md "GPTS tangent" dropped: 13 %, rate ~0.1), so C ~ delta / e_k: 100 at e_k = 1.6e-6
    // admits no tangent error above ~2e-4.
    constexpr double quadratic_constant_bound = 100.0;
    EXPECT_TRUE(at_least(e_k, 1e-7)) << "the last step starts well above the tolerance";
    EXPECT_TRUE(at_most(e_next, quadratic_constant_bound * e_k * e_k)) << "e_k = " << e_k;
    EXPECT_TRUE(at_most(e.back(), newton_tolerance)) << "converged to the deck tolerance";
}

}  // namespace
}  // namespace iga::test
