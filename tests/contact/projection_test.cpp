// Closest-point projection onto 2D NURBS curves: exact circles give the analytic
// foot point, gap and curvature; patch ends and C0 knots give the documented
// statuses; bad input gives a status, never NaN.

#include "contact/projection.hpp"

#include "fixtures.hpp"
#include "support/tolerance.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>

namespace iga::contact {
namespace {

using test::vec2;

VecN xi1(double xi) { return VecN::Constant(1, xi); }

// Newton takes its last step once that step is below 1e-12 (curve size +
// distance), so the foot point is at round-off level; 1e-12 R is the brief's bar.
constexpr double foot_tolerance = 1e-12;
// The distance depends on the tangential offset only to second order: round-off.
constexpr double distance_tolerance = 1e-12;
// Normal and curvature come from derivatives at the foot point: a few ulps times
// the condition of the rational evaluation.
constexpr double derivative_tolerance = 1e-11;
// A parameter from a converged projection: foot point accuracy / |x_xi| (~1).
constexpr double parameter_tolerance = 1e-11;
// One combination sum R_b P_b: round-off.
constexpr double combination_tolerance = 1e-14;

TEST(Projection, QuarterCircleMatchesAnalyticFootPoint)
{
    const double R = 2.0;
    const nurbs::Patch arc = test::quarter_arc(R);
    for (const double theta : {0.05, 0.3, std::numbers::pi / 4, 1.2, 1.5})
        for (const double r : {0.5 * R, 0.97 * R, R, 1.01 * R, 3.0 * R, 10.0 * R}) {
            const VecN x = vec2(r * std::cos(theta), r * std::sin(theta));
            const Projection p = project_to_surface(arc, +1, x);
            ASSERT_EQ(p.status, Projection::Status::ok) << "theta " << theta << " r " << r;
            const VecN foot = vec2(R * std::cos(theta), R * std::sin(theta));
            EXPECT_TRUE(test::at_most((p.point - foot).norm(), foot_tolerance * R)) << "theta " << theta << " r " << r;
            EXPECT_TRUE(test::near(p.distance, std::abs(r - R), distance_tolerance * (R + r)));
            // Outward (away from the centre) normal: inside the circle is a penetration.
            EXPECT_TRUE(test::near(p.gap, R - r, distance_tolerance * (R + r)));
            EXPECT_TRUE(test::at_most((p.normal - foot / R).norm(), derivative_tolerance));
            // A circle of radius R: b = n . x_xixi = -m / R (curving away from the normal).
            EXPECT_TRUE(test::near_rel(p.curvature(0, 0), -p.metric(0, 0) / R, derivative_tolerance));
            EXPECT_TRUE(test::near(p.metric(0, 0), p.tangents.col(0).squaredNorm(), 0.0));
            // The basis returned is that of the foot point: sum R_b P_b = point.
            VecN from_basis = VecN::Zero(2);
            for (std::size_t b = 0; b < p.basis.indices.size(); ++b)
                from_basis += p.basis.R(static_cast<Index>(b)) * arc.control_points().row(p.basis.indices[b]).transpose();
            EXPECT_TRUE(test::at_most((from_basis - p.point).norm(), combination_tolerance * R));
        }
}

TEST(Projection, FarAndWrongStartsConverge)
{
    const double R = 1.0;
    const nurbs::Patch arc = test::quarter_arc(R);
    const double theta = 1.4;
    const VecN x = vec2(0.9 * std::cos(theta), 0.9 * std::sin(theta));
    for (const double start : {0.0, 0.2, 1.0, -5.0, 7.0}) {
        ProjectionOptions options;
        options.start = xi1(start);
        const Projection p = project_to_surface(arc, +1, x, options);
        ASSERT_EQ(p.status, Projection::Status::ok) << "start " << start;
        EXPECT_TRUE(test::at_most((p.point - vec2(std::cos(theta), std::sin(theta))).norm(), foot_tolerance));
    }
}

TEST(Projection, WarmStartNeedsFewerIterations)
{
    const nurbs::Patch arc = test::quarter_arc(1.0);
    const VecN x = vec2(0.95 * std::cos(0.7), 0.95 * std::sin(0.7));
    const Projection cold = project_to_surface(arc, +1, x);
    ASSERT_EQ(cold.status, Projection::Status::ok);
    EXPECT_GE(cold.iterations, 2);  // sampling start is not on the foot point

    ProjectionOptions options;
    options.start = cold.xi;
    const Projection warm = project_to_surface(arc, +1, x, options);
    ASSERT_EQ(warm.status, Projection::Status::ok);
    EXPECT_LE(warm.iterations, 1);  // already converged at the start
    EXPECT_TRUE(test::near(warm.xi(0), cold.xi(0), parameter_tolerance));

    // A slightly moved point from the old foot point: quadratic convergence.
    const VecN moved = x + vec2(1e-3, -2e-3);
    const Projection moved_warm = project_to_surface(arc, +1, moved, options);
    ASSERT_EQ(moved_warm.status, Projection::Status::ok);
    EXPECT_LE(moved_warm.iterations, 3);
}

TEST(Projection, BeyondPatchEndIsOffEnd)
{
    const double R = 1.0;
    const nurbs::Patch arc = test::quarter_arc(R);  // ends at (0, R) with tangent along -x
    for (const VecN& x : {vec2(-0.3, 1.1), vec2(-0.2, 0.8), vec2(0.5, -0.4)}) {
        const Projection p = project_to_surface(arc, +1, x);
        EXPECT_EQ(p.status, Projection::Status::off_end) << x.transpose();
        EXPECT_TRUE(p.xi(0) == 0.0 || p.xi(0) == 1.0);
        EXPECT_TRUE(std::isfinite(p.gap));
    }
    // Just inside the domain the projection is an ordinary one.
    const Projection inside = project_to_surface(arc, +1, vec2(0.01, 1.2));
    EXPECT_EQ(inside.status, Projection::Status::ok);
}

TEST(Projection, SmoothDoubleKnotIsNotAKink)
{
    // The undeformed two-quarter half circle is C1 at its double knot: a point
    // straight below the knot projects onto it orthogonally from both spans.
    const double R = 1.0;
    const nurbs::Patch half = test::two_quarter_half_circle(R);
    const Projection p = project_to_surface(half, +1, vec2(0.0, 0.9));
    ASSERT_EQ(p.status, Projection::Status::ok);
    EXPECT_TRUE(test::near(p.xi(0), 0.5, parameter_tolerance));
    EXPECT_TRUE(test::near(p.gap, 0.1, distance_tolerance));
}

/// The half circle with its knot control point raised: a convex corner at xi = 1/2.
nurbs::Patch kinked_half_circle(double raise)
{
    nurbs::Patch half = test::two_quarter_half_circle(1.0);
    RowMatrix P = half.control_points();
    P(2, 1) += raise;
    return half.with_control_points(P);
}

TEST(Projection, C0KinkPicksTheNearerSpanWithoutChattering)
{
    const double raise = 0.2;
    const nurbs::Patch kinked = kinked_half_circle(raise);
    const double top = 1.0 + raise;  // the corner (0, 1.2)

    // Penetrating points just below the corner, swept across it: each lands
    // orthogonally on both spans; the nearer one wins, so the chosen span
    // switches once, at x = 0, and the gap is continuous across the switch.
    std::optional<double> previous_gap;
    int switches = 0;
    std::optional<bool> previous_left;
    std::optional<VecN> warm;
    constexpr int n_sweep = 41;
    for (int k = 0; k < n_sweep; ++k) {
        const double xs = -0.02 + 0.04 * k / (n_sweep - 1.0) + 1e-4;  // never exactly on the bisector
        const VecN x = vec2(xs, top - 0.05);
        ProjectionOptions options;
        options.start = warm;
        const Projection p = project_to_surface(kinked, +1, x, options);
        ASSERT_EQ(p.status, Projection::Status::ok) << "x " << xs;
        const bool on_first_span = p.xi(0) < 0.5;  // xi < 1/2 is the x > 0 quarter
        EXPECT_EQ(on_first_span, xs > 0.0) << "x " << xs;
        // Same answer with the warm start taken from the other span's foot point.
        ProjectionOptions other;
        other.start = xi1(on_first_span ? 0.75 : 0.25);
        const Projection q = project_to_surface(kinked, +1, x, other);
        EXPECT_TRUE(test::near(q.xi(0), p.xi(0), parameter_tolerance)) << "x " << xs;
        if (previous_left && *previous_left != on_first_span)
            ++switches;
        if (previous_gap) {
            // Gap is the smaller of two smooth distances: Lipschitz with
            // constant 1 in the point position (step 1e-3 here).
            EXPECT_TRUE(test::at_most(std::abs(p.gap - *previous_gap), 1.01 * 0.04 / (n_sweep - 1.0)));
        }
        EXPECT_TRUE(test::at_least(p.gap, 0.0));
        previous_gap = p.gap;
        previous_left = on_first_span;
        warm = p.xi;
    }
    EXPECT_EQ(switches, 1);

    // A point outside, right above the corner: between the one-sided normals
    // (in the normal fan) both spans clamp to the corner: at_kink, open gap.
    const Projection above = project_to_surface(kinked, +1, vec2(0.001, top + 0.3));
    EXPECT_EQ(above.status, Projection::Status::at_kink);
    EXPECT_TRUE(test::near(above.xi(0), 0.5, 0.0));
    EXPECT_TRUE(test::at_most(above.gap, 0.0));
}

TEST(Projection, CandidateSpansRestrictTheSearch)
{
    // With only the second quarter as candidate, the foot point is found there
    // (clamped at the knot for a point whose true foot is on the first quarter).
    const nurbs::Patch half = test::two_quarter_half_circle(1.0);
    const VecN x = vec2(0.6, 0.6);
    const std::vector<int> second_only{1};
    ProjectionOptions options;
    options.candidate_elements = second_only;
    const Projection p = project_to_surface(half, +1, x, options);
    EXPECT_GE(p.xi(0), 0.5);
    const Projection all = project_to_surface(half, +1, x);
    EXPECT_LT(all.xi(0), 0.5);
    EXPECT_LT(all.distance, p.distance);
}

TEST(Projection, NonFiniteInputFailsWithFiniteFields)
{
    const nurbs::Patch arc = test::quarter_arc(1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Projection p = project_to_surface(arc, +1, vec2(nan, 0.5));
    EXPECT_EQ(p.status, Projection::Status::failed);
    EXPECT_TRUE(std::isfinite(p.gap) && p.xi.allFinite() && p.point.allFinite() && p.normal.allFinite());

    RowMatrix P = arc.control_points();
    P(1, 0) = nan;
    const Projection q = project_to_surface(arc.with_control_points(P), +1, vec2(0.5, 0.5));
    EXPECT_EQ(q.status, Projection::Status::failed);
    EXPECT_TRUE(std::isfinite(q.gap));

    // A NaN warm start is ignored, not propagated.
    ProjectionOptions options;
    options.start = xi1(nan);
    const Projection r = project_to_surface(arc, +1, vec2(0.5, 0.5), options);
    EXPECT_EQ(r.status, Projection::Status::ok);
}

TEST(Projection, SurfaceSidesAreNotSupported)
{
    const nurbs::Patch surface = nurbs::rectangle(vec2(0, 0), vec2(1, 1));
    EXPECT_THROW(project_to_surface(surface, +1, vec2(0.5, 2.0)), Error);
}

}  // namespace
}  // namespace iga::contact
