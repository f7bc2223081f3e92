// Closest-point projection onto NURBS sides: 2D curves and 3D surfaces. Exact
// circles, cylinders and spheres give the analytic foot point, gap and curvature;
// patch ends, C0 knots and creases give the documented statuses; a collapsed edge
// (a sphere's pole) and bad input give finite fields, never NaN.

#include "contact/contact_pair.hpp"
#include "contact/projection.hpp"

#include "fixtures.hpp"
#include "surface_fixtures.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Geometry>
#include <array>
#include <vector>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <random>

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

TEST(Projection, SafeguardedNewtonDoesNotCycle)
{
    // Far below the rational arch, plain Newton (full Hessian, trust region of
    // half a span) jumps between two points for ever; taking back the steps that
    // move away converges to the orthogonal foot, nearer than either end.
    const nurbs::Patch arch = test::rational_arch();
    {
        const VecN x = vec2(0.785831, -1.26881);
        const Projection p = project_to_surface(arch, test::rational_arch_sign, x);
        ASSERT_EQ(p.status, Projection::Status::ok) << x.transpose();
        EXPECT_TRUE(test::at_most(std::abs((x - p.point).dot(p.tangents.col(0))), distance_tolerance * p.distance));
        EXPECT_LT(p.distance, (x - arch.control_points().row(0).transpose()).norm());
        EXPECT_LT(p.distance, (x - arch.control_points().row(2).transpose()).norm());
        EXPECT_LE(p.iterations, 25);  // converges after the safeguard starts (iteration 10), well before 30
    }
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

TEST(Projection, SidesOfTheWrongShapeAreClearErrors)
{
    // A surface in 2D (n_par = 2, d = 2) is not a side.
    const nurbs::Patch surface = nurbs::rectangle(vec2(0, 0), vec2(1, 1));
    EXPECT_THROW(project_to_surface(surface, +1, vec2(0.5, 2.0)), Error);
}

}  // namespace
}  // namespace iga::contact

// ---------------------------------------------------------------------------
// Surfaces in 3D
// ---------------------------------------------------------------------------
namespace iga::contact {
namespace {

using test::vec3;

// Foot points of exact surfaces: Newton stops one step below 1e-12 (size +
// distance), so round-off of the rational evaluation is all that is left; the
// brief's bar for the analytic comparison is 1e-10.
constexpr double surface_foot_tolerance = 1e-10;
// Normals and curvature tensors from derivatives at the foot point: a few ulps
// times the condition of the rational evaluation, with room for the pole region.
constexpr double surface_derivative_tolerance = 1e-9;

VecN direction(double polar, double azimuth)
{
    return vec3(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
}

/// Every field finite (a failed projection too): NaN must never leak.
::testing::AssertionResult all_fields_finite(const Projection& p)
{
    const bool ok = p.xi.allFinite() && p.point.allFinite() && p.tangents.allFinite() && p.second.allFinite() &&
                    p.normal.allFinite() && p.metric.allFinite() && p.curvature.allFinite() &&
                    std::isfinite(p.gap) && std::isfinite(p.distance);
    return ok ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << "a field is not finite";
}

nurbs::Patch refined_cylinder()
{
    nurbs::Patch cyl = test::quarter_cylinder(2.0, 3.0);
    cyl = nurbs::insert_knots(cyl, 0, {0.25, 0.5, 0.75});
    return nurbs::insert_knots(cyl, 1, {0.5});
}

TEST(SurfaceProjection, QuarterCylinderMatchesAnalyticFootPoint)
{
    const double R = 2.0, L = 3.0;  // refined_cylinder()
    const nurbs::Patch cyl = refined_cylinder();
    for (const double theta : {0.05, 0.4, std::numbers::pi / 4, 1.3, 1.52})
        for (const double z : {0.03 * L, 0.5 * L, 0.73 * L, 0.98 * L})
            for (const double r : {0.6 * R, 0.98 * R, R, 1.02 * R, 4.0 * R}) {
                const VecN x = vec3(r * std::cos(theta), r * std::sin(theta), z);
                const Projection p = project_to_surface(cyl, +1, x);
                ASSERT_EQ(p.status, Projection::Status::ok) << x.transpose();
                const VecN foot = vec3(R * std::cos(theta), R * std::sin(theta), z);
                const VecN radial = vec3(std::cos(theta), std::sin(theta), 0.0);
                EXPECT_TRUE(test::at_most((p.point - foot).norm(), surface_foot_tolerance * R)) << x.transpose();
                EXPECT_TRUE(test::near(p.gap, R - r, surface_foot_tolerance * (R + r)));
                EXPECT_TRUE(test::near(p.distance, std::abs(R - r), surface_foot_tolerance * (R + r)));
                EXPECT_TRUE(test::at_most((p.normal - radial).norm(), surface_derivative_tolerance));
                // Cylinder: b_uu = -m_uu / R around the arc, no curvature along z.
                const double m_uu = p.metric(0, 0);
                EXPECT_TRUE(test::near_rel(p.curvature(0, 0), -m_uu / R, surface_derivative_tolerance));
                EXPECT_TRUE(test::at_most(std::abs(p.curvature(0, 1)) + std::abs(p.curvature(1, 1)),
                                          surface_derivative_tolerance * m_uu));
                EXPECT_TRUE(test::at_most((p.metric - p.tangents.transpose() * p.tangents).norm(), 0.0));
                // The basis is that of the foot point, on the element reported.
                VecN from_basis = VecN::Zero(3);
                for (std::size_t b = 0; b < p.basis.indices.size(); ++b)
                    from_basis += p.basis.R(static_cast<Index>(b)) *
                                  cyl.control_points().row(p.basis.indices[b]).transpose();
                EXPECT_TRUE(test::at_most((from_basis - p.point).norm(), surface_foot_tolerance * R));
                const nurbs::Element e = cyl.elements()[static_cast<std::size_t>(p.element)];
                for (int k = 0; k < 2; ++k)
                    EXPECT_TRUE(p.xi(k) >= e.lower[k] && p.xi(k) <= e.upper[k]) << "element " << p.element;
            }
}

TEST(SurfaceProjection, SphereOctantMatchesAnalyticFootPoint)
{
    const double R = 1.5;
    nurbs::Patch sphere = test::sphere_octant(R);
    sphere = nurbs::insert_knots(sphere, 0, {1.0 / 3.0, 2.0 / 3.0});
    sphere = nurbs::insert_knots(sphere, 1, {0.3, 0.7});
    for (const double polar : {0.02, 0.3, 0.8, 1.2, 1.55})
        for (const double azimuth : {0.03, 0.6, 1.1, 1.54})
            for (const double r : {0.5 * R, 0.99 * R, 1.03 * R, 3.0 * R}) {
                const VecN dir = direction(polar, azimuth);
                const VecN x = r * dir;
                const Projection p = project_to_surface(sphere, +1, x);
                ASSERT_EQ(p.status, Projection::Status::ok) << x.transpose();
                EXPECT_TRUE(test::at_most((p.point - R * dir).norm(), surface_foot_tolerance * R)) << x.transpose();
                EXPECT_TRUE(test::near(p.gap, R - r, surface_foot_tolerance * (R + r)));
                EXPECT_TRUE(test::at_most((p.normal - dir).norm(), surface_derivative_tolerance)) << x.transpose();
                // Sphere: b_ab = -m_ab / R in any parametrization.
                EXPECT_TRUE(test::at_most((p.curvature + p.metric / R).norm(),
                                          surface_derivative_tolerance * p.metric.norm()));
                EXPECT_EQ(p.candidates, 9);
            }
}

TEST(SurfaceProjection, PointAboveTheCollapsedPole)
{
    // v = 1 of the octant is collapsed to the pole: a_u = 0 there. Points on the
    // axis project onto the pole with the right normal; points next to the axis
    // project next to it; nothing divides by zero.
    const double R = 1.0;
    const nurbs::Patch sphere = test::sphere_octant(R);
    for (const double z : {1.4, 1.0, 0.8, 0.05}) {
        const Projection p = project_to_surface(sphere, +1, vec3(0.0, 0.0, z));
        ASSERT_EQ(p.status, Projection::Status::ok) << "z " << z;
        EXPECT_TRUE(all_fields_finite(p));
        EXPECT_TRUE(test::at_most((p.point - vec3(0, 0, R)).norm(), surface_foot_tolerance));
        EXPECT_TRUE(test::at_most((p.normal - vec3(0, 0, 1)).norm(), surface_derivative_tolerance));
        EXPECT_TRUE(test::near(p.gap, R - z, surface_foot_tolerance));
        EXPECT_TRUE(test::near(p.xi(1), 1.0, 0.0));
    }
    for (const double polar : {1e-9, 1e-6, 1e-3}) {
        const VecN dir = direction(polar, 0.7);
        const Projection p = project_to_surface(sphere, +1, 1.2 * dir);
        ASSERT_EQ(p.status, Projection::Status::ok) << "polar " << polar;
        EXPECT_TRUE(all_fields_finite(p));
        EXPECT_TRUE(test::at_most((p.point - R * dir).norm(), surface_foot_tolerance)) << "polar " << polar;
        EXPECT_TRUE(test::at_most((p.normal - dir).norm(), surface_derivative_tolerance)) << "polar " << polar;
    }
    // Next to the axis at the azimuth of the patch edge u = 1 (90 degrees): a
    // start on the pole with the azimuth of u = 0 would see no gradient along its
    // meridian (perpendicular to the offset) and stop at the pole.
    for (const double rho : {1e-2, 1e-4, 1e-7}) {
        const VecN x = vec3(0.0, rho, 1.2);
        const Projection p = project_to_surface(sphere, +1, x);
        ASSERT_EQ(p.status, Projection::Status::ok) << "rho " << rho;
        EXPECT_TRUE(test::at_most((p.point - R * x.normalized()).norm(), surface_foot_tolerance)) << "rho " << rho;
        EXPECT_TRUE(test::at_most((p.normal - x.normalized()).norm(), surface_derivative_tolerance));
    }
    // A warm start at the pole with another azimuth converges too.
    ProjectionOptions options;
    options.start = test::vec2(0.9, 1.0);
    const Projection warm = project_to_surface(sphere, +1, 1.1 * direction(0.2, 0.3), options);
    ASSERT_EQ(warm.status, Projection::Status::ok);
    EXPECT_TRUE(test::at_most((warm.point - R * direction(0.2, 0.3)).norm(), surface_foot_tolerance));
}

TEST(SurfaceProjection, PolesOnOtherEdgesGiveTheLimitNormal)
{
    // The octant re-parametrized so that the pole is the edge v = 0, or u = 1:
    // the limit normal takes its sign from the side of the edge the foot is on.
    const nurbs::Patch sphere = test::sphere_octant(1.0);
    const RowMatrix& P = sphere.control_points();
    const Vector& w = sphere.weights();
    RowMatrix reversed(9, 3), transposed(9, 3);
    Vector w_reversed(9), w_transposed(9);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            reversed.row(i + 3 * j) = P.row(i + 3 * (2 - j));  // v reversed: pole at v = 0
            w_reversed(i + 3 * j) = w(i + 3 * (2 - j));
            transposed.row(i + 3 * j) = P.row(j + 3 * i);  // u and v swapped: pole at u = 1
            w_transposed(i + 3 * j) = w(j + 3 * i);
        }
    // Both flip a_1 x a_2, so the outward sign is -1.
    for (const nurbs::Patch& surface : {nurbs::Patch(sphere.all_knots(), reversed, w_reversed),
                                        nurbs::Patch(sphere.all_knots(), transposed, w_transposed)})
        for (const double polar : {0.0, 1e-9, 1e-4, 0.3}) {
            const VecN dir = direction(polar, 0.7);
            const Projection p = project_to_surface(surface, -1, 1.2 * dir);
            ASSERT_EQ(p.status, Projection::Status::ok) << "polar " << polar;
            EXPECT_TRUE(all_fields_finite(p));
            EXPECT_TRUE(test::at_most((p.point - dir).norm(), surface_foot_tolerance)) << "polar " << polar;
            EXPECT_TRUE(test::at_most((p.normal - dir).norm(), surface_derivative_tolerance)) << "polar " << polar;
            EXPECT_TRUE(test::near(p.gap, -0.2, surface_foot_tolerance));
        }
}

// The inner sphere of the hollow-sphere scene's shell (verification/scenes/, coarse
// copy) as a run met it, deformed, and a point of the ball just above the shell's rim,
// 0.17 away, next to the collapsed pole of the shell's octant (u = 1). Near the pole the
// parametrization is singular: Newton's steps swing between two azimuths and do not
// settle in 30 iterations, from any start (the true nearest point is on the edge v = 0,
// 0.01 from the pole). The projection reports the nearest point it found (`unsettled`),
// not a failure, so a point this far open does not fail the step: contact_pair.cpp
// takes it as open where the law stays inactive with the gap unsettled_margin x size
// nearer, and the point found is within that of the surface's nearest (measured
// 2.2e-4 against a margin of 1.4e-3; the nearest from a 400 x 400 sample grid).
TEST(SurfaceProjection, NearACollapsedPoleAnUnsettledNewtonReportsTheNearestPointFound)
{
    const std::vector<std::array<double, 4>> points = {
        {0, 0.68956134583229967, -0.018192437541498064, 1},
        {0.13179797427362297, 0.68941783275557855, -0.018369309831440101, 0.92677669529663709},
        {0.38644479399522175, 0.58814917229362518, -0.01862988734600252, 0.85355339059327406},
        {0.58831673270631479, 0.38644195831001449, -0.018697534686642397, 0.85355339059327395},
        {0.68919029667138698, 0.13153113380571685, -0.018566554333316412, 0.92677669529663698},
        {0.68943501943700836, -9.1554696185978032e-05, -0.018652176684050524, 1},
        {0, 0.69215916488873452, -0.15175353556701163, 0.92677669529663709},
        {0.1315430616601716, 0.69227088990870767, -0.15151610846206162, 0.85891504294495558},
        {0.38977035958402323, 0.59240526174675212, -0.13329261588044575, 0.79105339059327406},
        {0.59075158651801563, 0.38765305473599188, -0.093460577100249881, 0.79105339059327395},
        {0.6903283142225044, 0.13169981287722862, -0.044159529109991547, 0.85891504294495546},
        {0.68941015757068991, -0.00013474380680595678, -0.018620704950739059, 0.92677669529663709},
        {0, 0.59811183643784038, -0.41952160326360155, 0.85355339059327406},
        {0.13399326083095828, 0.59815011073399948, -0.41963952677501626, 0.79105339059327395},
        {0.38795874664192365, 0.50529265744274787, -0.35705537543799587, 0.72855339059327395},
        {0.59329480302910087, 0.33251954131620026, -0.24124976243095653, 0.72855339059327395},
        {0.69190539736217804, 0.11248002627204559, -0.09321753010361343, 0.79105339059327395},
        {0.68951519768711544, -0.00011780980405550052, -0.018726491759731925, 0.85355339059327406},
        {0, 0.41304613461679673, -0.65921506433219723, 0.85355339059327395},
        {0.140445010702514, 0.41322385618429952, -0.65924017214065977, 0.79105339059327395},
        {0.40531368776567223, 0.34438394473758993, -0.55549518199071901, 0.72855339059327395},
        {0.59292522219373134, 0.21711762326723613, -0.35771224565473869, 0.72855339059327395},
        {0.69356908926239602, 0.074802940994807762, -0.13316419538701635, 0.79105339059327395},
        {0.68946626581277215, -0.00028942451851629786, -0.018504380041019373, 0.85355339059327395},
        {0, 0.14383649606942081, -0.78745022194721004, 0.92677669529663698},
        {0.1435797307458006, 0.14355496723397379, -0.78737948775273769, 0.85891504294495558},
        {0.41385994677607285, 0.11974849599998488, -0.65987215522488751, 0.79105339059327406},
        {0.59822502401829891, 0.074376104262132328, -0.41962449220605585, 0.79105339059327395},
        {0.691507446238674, 0.025156478033281717, -0.15155902407633443, 0.85891504294495546},
        {0.69025024433957938, 1.170266364299851e-05, -0.018865223860086756, 0.92677669529663698},
        {0, 0, -0.78749399746127813, 1},
        {0.14379338154751867, 0, -0.78737171113285054, 0.92677669529663709},
        {0.4138748724428995, 0, -0.6600319531979042, 0.85355339059327406},
        {0.59837837246949788, 0, -0.41985338413762663, 0.85355339059327395},
        {0.69142002701412664, 0, -0.15145660571714548, 0.92677669529663698},
        {0.69027538501008601, 0, -0.018895514826071491, 1}};
    RowMatrix P(36, 3);
    Vector w(36);
    for (Index a = 0; a < 36; ++a) {
        P.row(a) << points[a][0], points[a][1], points[a][2];
        w(a) = points[a][3];
    }
    const nurbs::KnotVector knots(2, {0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1});
    const nurbs::Patch shell = test::make_surface(knots, knots, P, w);
    const VecN x = vec3(0.5295803628684399, 0.007297980702319842, 0.035189076134723662);
    const Projection p = project_to_surface(shell, -1, x);
    ASSERT_EQ(p.status, Projection::Status::unsettled);
    EXPECT_TRUE(all_fields_finite(p));
    double nearest = std::numeric_limits<double>::infinity();
    constexpr int samples = 400;
    for (int i = 0; i <= samples; ++i)
        for (int j = 0; j <= samples; ++j) {
            const nurbs::PointDerivatives at =
                nurbs::combine(nurbs::rational_basis(shell, test::vec2(double(i) / samples, double(j) / samples), 0),
                               shell.control_points());
            nearest = std::min(nearest, (at.x - x).norm());
        }
    // Never nearer than the surface is (the grid's best is within 1e-6 of its minimum),
    // and within the margin contact_pair.cpp allows an unsettled gap.
    const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
    EXPECT_GE(p.distance, nearest - 1e-6);
    EXPECT_LE(p.distance, nearest + unsettled_margin * size);
    EXPECT_LT(p.gap, -0.1);  // clearly open
}

TEST(SurfaceProjection, WarmStartNeedsFewerIterations)
{
    const nurbs::Patch sphere = nurbs::insert_knots(test::sphere_octant(1.0), 0, {0.5});
    const VecN x = 0.97 * direction(0.9, 0.5);
    const Projection cold = project_to_surface(sphere, +1, x);
    ASSERT_EQ(cold.status, Projection::Status::ok);
    EXPECT_GE(cold.iterations, 2);  // the sampling start is not the foot point

    ProjectionOptions options;
    options.start = cold.xi;
    options.start_element = cold.element;
    const Projection warm = project_to_surface(sphere, +1, x, options);
    ASSERT_EQ(warm.status, Projection::Status::ok);
    EXPECT_LE(warm.iterations, 1);  // already converged at the start
    EXPECT_TRUE(test::at_most((warm.point - cold.point).norm(), surface_foot_tolerance));

    // A slightly moved point from the old foot point: quadratic convergence.
    const Projection moved = project_to_surface(sphere, +1, x + vec3(1e-3, -2e-3, 1e-3), options);
    ASSERT_EQ(moved.status, Projection::Status::ok);
    EXPECT_LE(moved.iterations, 3);

    // A wrong warm start (far corner of the domain) still finds the foot point.
    options.start = test::vec2(1.0, 0.0);
    options.start_element = -1;
    const Projection wrong = project_to_surface(sphere, +1, x, options);
    ASSERT_EQ(wrong.status, Projection::Status::ok);
    EXPECT_TRUE(test::at_most((wrong.point - cold.point).norm(), surface_foot_tolerance));
}

TEST(SurfaceProjection, BeyondThePatchBoundaryIsOffEnd)
{
    const double R = 2.0, L = 3.0;  // refined_cylinder()
    const nurbs::Patch cyl = refined_cylinder();
    // Above the top edge z = L: Newton stops on the bound v = 1 and continues
    // along the edge to the nearest point of the top circle.
    const double theta = 0.6;
    const Projection top = project_to_surface(cyl, +1, vec3(2.3 * std::cos(theta), 2.3 * std::sin(theta), L + 0.4));
    EXPECT_EQ(top.status, Projection::Status::off_end);
    EXPECT_TRUE(test::near(top.xi(1), 1.0, 0.0));
    EXPECT_TRUE(test::at_most((top.point - vec3(R * std::cos(theta), R * std::sin(theta), L)).norm(),
                              surface_foot_tolerance * R));
    EXPECT_TRUE(all_fields_finite(top));
    // Past the side edge theta = pi/2 (the line x = 0): off_end on u = 1.
    const Projection side = project_to_surface(cyl, +1, vec3(-0.5, 2.2, 1.0));
    EXPECT_EQ(side.status, Projection::Status::off_end);
    EXPECT_TRUE(test::near(side.xi(0), 1.0, 0.0));
    EXPECT_TRUE(test::at_most((side.point - vec3(0.0, R, 1.0)).norm(), surface_foot_tolerance * R));
    // Past both: the corner.
    const Projection corner = project_to_surface(cyl, +1, vec3(-0.5, 2.2, -0.3));
    EXPECT_EQ(corner.status, Projection::Status::off_end);
    EXPECT_TRUE(test::at_most((corner.point - vec3(0.0, R, 0.0)).norm(), surface_foot_tolerance * R));
    // Just inside the domain the projection is an ordinary one.
    EXPECT_EQ(project_to_surface(cyl, +1, vec3(0.3, 2.1, 2.9)).status, Projection::Status::ok);
}

/// Quarter cylinder (R = 1, L = 2) with a double knot at u = 1/2 (multiplicity =
/// degree: C0) whose row of control points is pushed out by `raise`: a ridge
/// along z at 45 degrees.
nurbs::Patch creased_cylinder(double raise)
{
    nurbs::Patch cyl = nurbs::insert_knots(test::quarter_cylinder(1.0, 2.0), 0, {0.5, 0.5});
    RowMatrix P = cyl.control_points();
    const int n_u = cyl.n_basis(0);
    for (int j = 0; j < cyl.n_basis(1); ++j) {
        const Index a = 2 + n_u * j;  // the interpolated control point at u = 1/2
        const double r = std::hypot(P(a, 0), P(a, 1));
        P(a, 0) *= (r + raise) / r;
        P(a, 1) *= (r + raise) / r;
    }
    return cyl.with_control_points(P);
}

TEST(SurfaceProjection, C0CreaseIsAtKinkInsideTheFanAndOkOnEachSide)
{
    const double raise = 0.2;
    const nurbs::Patch creased = creased_cylinder(raise);
    const double s = std::sqrt(0.5);
    const VecN ridge_dir = vec3(s, s, 0.0), along = vec3(-s, s, 0.0);  // along: towards larger u
    const VecN ridge = (1.0 + raise) * ridge_dir + vec3(0, 0, 0.8);
    // Outside, right above the ridge: both faces clamp to the crease.
    for (const double offset : {-0.01, 0.0005, 0.02}) {
        const Projection p = project_to_surface(creased, +1, ridge + 0.3 * ridge_dir + offset * along);
        EXPECT_EQ(p.status, Projection::Status::at_kink) << "offset " << offset;
        EXPECT_TRUE(test::near(p.xi(0), 0.5, 0.0));
        EXPECT_TRUE(test::near(p.point(2), 0.8, surface_foot_tolerance));
        EXPECT_TRUE(test::at_most(p.gap, 0.0));
        EXPECT_TRUE(all_fields_finite(p));
    }
    // Just below the ridge (penetrating): orthogonal on the nearer face, ok.
    for (const double offset : {-0.01, -0.001, 0.001, 0.01}) {
        const Projection p = project_to_surface(creased, +1, ridge - 0.05 * ridge_dir + offset * along);
        ASSERT_EQ(p.status, Projection::Status::ok) << "offset " << offset;
        EXPECT_EQ(p.xi(0) > 0.5, offset > 0.0) << "offset " << offset;
        EXPECT_TRUE(test::at_least(p.gap, 0.0));
    }
}

TEST(SurfaceProjection, FarPointWithAllElementsAsCandidates)
{
    const double R = 1.0;
    nurbs::Patch sphere = test::sphere_octant(R);
    sphere = nurbs::refine_uniform(nurbs::refine_uniform(sphere, 0, 4), 1, 4);
    const VecN dir = direction(0.7, 0.9);
    const Projection p = project_to_surface(sphere, +1, 50.0 * dir);
    ASSERT_EQ(p.status, Projection::Status::ok);
    EXPECT_EQ(p.candidates, 16);
    EXPECT_TRUE(test::at_most((p.point - R * dir).norm(), surface_foot_tolerance));
    EXPECT_TRUE(test::near(p.gap, R - 50.0, surface_foot_tolerance * 50.0));
}

TEST(SurfaceProjection, DerivativesMatchFiniteDifferencesOfTheSurface)
{
    // A general rational surface: a refined sphere octant with perturbed control
    // points and weights (no symmetry to hide a transposed index).
    nurbs::Patch base = nurbs::insert_knots(test::sphere_octant(1.0), 0, {0.4});
    base = nurbs::insert_knots(base, 1, {0.6});
    RowMatrix P = base.control_points();
    Vector w = base.weights();
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (Index a = 0; a < P.rows(); ++a) {
        P.row(a) += 0.05 * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
        w(a) *= 1.0 + 0.2 * unit(rng);
    }
    const nurbs::Patch surface(base.all_knots(), P, w);
    // Central differences with h = 1e-5 on a unit-size surface: truncation
    // h^2 |x'''| ~ 1e-9, round-off eps / h ~ 1e-11; 1e-7 leaves a margin, yet a
    // wrong column or a missing term is O(1).
    constexpr double h = 1e-5;
    constexpr double fd_tolerance = 1e-7;
    for (const VecN& x : {vec3(0.9, 0.3, 0.5), vec3(0.3, 0.5, 0.7), vec3(0.6, 0.6, 0.2)}) {
        const Projection p = project_to_surface(surface, +1, x);
        ASSERT_EQ(p.status, Projection::Status::ok) << "seed 17, x " << x.transpose();
        const nurbs::Element e = surface.elements()[static_cast<std::size_t>(p.element)];
        Matrix fd_tangents(3, 2), fd_second(3, 3);
        Matrix fd_d2(3, 4);  // d(a_alpha)/dxi^beta, column alpha + 2 beta
        for (int k = 0; k < 2; ++k) {
            ASSERT_TRUE(p.xi(k) - h > e.lower[k] && p.xi(k) + h < e.upper[k]) << "foot too close to a knot line";
            VecN plus = p.xi, minus = p.xi;
            plus(k) += h;
            minus(k) -= h;
            const nurbs::PointDerivatives xp = nurbs::evaluate(surface, plus, 1), xm = nurbs::evaluate(surface, minus, 1);
            fd_tangents.col(k) = (xp.x - xm.x) / (2 * h);
            for (int a = 0; a < 2; ++a)
                fd_d2.col(a + 2 * k) = (xp.dx.col(a) - xm.dx.col(a)) / (2 * h);
        }
        fd_second.col(0) = fd_d2.col(0);                            // uu
        fd_second.col(1) = 0.5 * (fd_d2.col(1) + fd_d2.col(2));     // uv (= vu)
        fd_second.col(2) = fd_d2.col(3);                            // vv
        EXPECT_TRUE(test::at_most((p.tangents - fd_tangents).norm() / fd_tangents.norm(), fd_tolerance));
        EXPECT_TRUE(test::at_most((p.second - fd_second).norm() / fd_second.norm(), fd_tolerance));
        Matrix fd_curvature(2, 2);
        fd_curvature << p.normal.dot(fd_second.col(0)), p.normal.dot(fd_second.col(1)),
            p.normal.dot(fd_second.col(1)), p.normal.dot(fd_second.col(2));
        EXPECT_TRUE(test::at_most((p.curvature - fd_curvature).norm() / fd_second.norm(), fd_tolerance));
        // Orthogonality and the outward convention n = (a_1 x a_2) / |a_1 x a_2|.
        const Eigen::Vector3d a1 = p.tangents.col(0), a2 = p.tangents.col(1);
        EXPECT_TRUE(test::at_most((Eigen::Vector3d(p.normal) - a1.cross(a2).normalized()).norm(),
                                  surface_derivative_tolerance));
        EXPECT_TRUE(test::at_most(((x - p.point).transpose() * p.tangents).norm(), surface_foot_tolerance));
    }
}

TEST(SurfaceProjection, DegenerateAndNonFiniteDataFailWithFiniteFields)
{
    const nurbs::Patch sphere = test::sphere_octant(1.0);
    // All control points equal: no tangent anywhere.
    const RowMatrix same = RowMatrix::Constant(sphere.n_control_points(), 3, 0.25);
    const Projection p = project_to_surface(sphere.with_control_points(same), +1, vec3(1, 1, 1));
    EXPECT_EQ(p.status, Projection::Status::failed);
    EXPECT_TRUE(all_fields_finite(p));

    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Projection q = project_to_surface(sphere, +1, vec3(nan, 0.5, 0.5));
    EXPECT_EQ(q.status, Projection::Status::failed);
    EXPECT_TRUE(all_fields_finite(q));
    RowMatrix P = sphere.control_points();
    P(4, 2) = nan;
    const Projection r = project_to_surface(sphere.with_control_points(P), +1, vec3(0.5, 0.5, 0.5));
    EXPECT_EQ(r.status, Projection::Status::failed);
    EXPECT_TRUE(all_fields_finite(r));

    // A NaN warm start is ignored, not propagated.
    ProjectionOptions options;
    options.start = test::vec2(nan, 0.5);
    const Projection s = project_to_surface(sphere, +1, vec3(0.5, 0.5, 0.5), options);
    EXPECT_EQ(s.status, Projection::Status::ok);
}

TEST(SurfaceProjection, CandidateElementsRestrictTheSearch)
{
    nurbs::Patch sphere = nurbs::refine_uniform(nurbs::refine_uniform(test::sphere_octant(1.0), 0, 2), 1, 2);
    const VecN x = 1.1 * direction(1.2, 0.3);  // foot on element 0 (low azimuth, near the equator)
    const Projection all = project_to_surface(sphere, +1, x);
    ASSERT_EQ(all.status, Projection::Status::ok);
    EXPECT_EQ(all.element, 0);
    const std::vector<int> far_one{3};
    ProjectionOptions options;
    options.candidate_elements = far_one;
    // The region is the whole C1 surface: Newton from element 3's samples still
    // reaches the true foot point across element boundaries.
    const Projection restricted = project_to_surface(sphere, +1, x, options);
    EXPECT_EQ(restricted.status, Projection::Status::ok);
    EXPECT_EQ(restricted.candidates, 1);
    EXPECT_TRUE(test::at_most((restricted.point - all.point).norm(), surface_foot_tolerance));
    const std::vector<int> bad{4};
    options.candidate_elements = bad;
    EXPECT_THROW(project_to_surface(sphere, +1, x, options), Error);
}

}  // namespace
}  // namespace iga::contact
