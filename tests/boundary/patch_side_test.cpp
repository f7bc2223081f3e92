// Side geometry: outward normals on every side of 2D and 3D patches (also rotated,
// curved, left-handed and degenerate ones), metric and jacobian, curvature against
// finite differences of the normal, collapsed sides and degenerate points (poles),
// folded sides.

#include "boundary/patch_side.hpp"
#include "mechanics/test_patches.hpp"
#include "nurbs/shapes.hpp"
#include "solids.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace iga::boundary {
namespace {

/// Exact shapes (circles, planes) evaluated in double precision: a few ulps.
constexpr double round_off = 1e-13;

VecN vec(std::initializer_list<double> values)
{
    VecN v(static_cast<Index>(values.size()));
    Index i = 0;
    for (const double x : values)
        v(i++) = x;
    return v;
}

/// Interior sample parameters of element e of a side: n per direction, (k + 1) / (n + 1).
std::vector<VecN> samples(const PatchSide& side, int e, int n)
{
    const nurbs::Element& el = side.elements()[static_cast<std::size_t>(e)];
    const int n_side = side.dim() - 1;
    std::vector<VecN> out;
    const int total = n_side == 1 ? n : n * n;
    for (int q = 0; q < total; ++q) {
        VecN xi(n_side);
        for (int k = 0, rest = q; k < n_side; ++k, rest /= n)
            xi(k) = el.lower[k] + (rest % n + 1.0) / (n + 1.0) * (el.upper[k] - el.lower[k]);
        out.push_back(xi);
    }
    return out;
}

/// Checks normal(x) == expected(x) at interior samples of every element of `side`.
void expect_normals(const PatchSide& side, const std::function<VecN(const VecN&)>& expected, double tolerance)
{
    const RowMatrix& X = side.patch().control_points();
    for (int e = 0; e < side.n_elements(); ++e)
        for (const VecN& xi : samples(side, e, 3)) {
            const SurfacePoint p = side.evaluate(X, e, xi, 1);
            EXPECT_FALSE(p.degenerate) << side_name(side.which());
            EXPECT_TRUE(test::at_most((p.normal - expected(p.x)).norm(), tolerance))
                << "side " << side_name(side.which()) << " at x = " << p.x.transpose();
        }
}

std::function<VecN(const VecN&)> constant(const VecN& n)
{
    return [n](const VecN&) { return n; };
}

TEST(PatchSide, OutwardNormalsOfRectangle)
{
    const nurbs::Patch patch = nurbs::rectangle(vec({1.0, -2.0}), vec({3.0, 0.5}));
    const std::pair<Side, VecN> cases[] = {{Side::u0, vec({-1, 0})},
                                           {Side::u1, vec({1, 0})},
                                           {Side::v0, vec({0, -1})},
                                           {Side::v1, vec({0, 1})}};
    for (const auto& [which, n] : cases) {
        const PatchSide side(patch, which);
        EXPECT_FALSE(side.collapsed());
        EXPECT_NE(side.outward_sign(), 0);
        expect_normals(side, constant(n), round_off);
    }
}

TEST(PatchSide, OutwardNormalsOfQuarterDiscAndItsCollapsedSide)
{
    const VecN c = vec({0.5, 1.0});
    const double R = 2.0;
    const nurbs::Patch patch = nurbs::quarter_disc(c, R);
    expect_normals(PatchSide(patch, Side::v0), [&](const VecN& x) { return VecN((x - c) / R); }, round_off);
    expect_normals(PatchSide(patch, Side::v1), constant(vec({0, 1})), round_off);
    expect_normals(PatchSide(patch, Side::u0), constant(vec({-1, 0})), round_off);

    // u1 is the point (c_x + R, c_y): no measure, no normal, nothing NaN.
    const PatchSide collapsed(patch, Side::u1);
    EXPECT_TRUE(collapsed.collapsed());
    EXPECT_EQ(collapsed.outward_sign(), 0);
    for (const double s : {0.0, 0.5, 1.0}) {
        const SurfacePoint p = collapsed.evaluate(collapsed.patch().control_points(), 0, vec({s}), 2);
        EXPECT_TRUE(p.degenerate);
        EXPECT_EQ(p.jacobian, 0.0);
        EXPECT_EQ(p.normal.norm(), 0.0);
        EXPECT_TRUE(p.curvature.allFinite());
    }
}

TEST(PatchSide, OutwardNormalsOfBlockAlsoLeftHanded)
{
    // The rule reads dX/dxi across the side, not the handedness: mirroring u (a
    // left-handed parametrization) swaps which face is u0 but keeps normals outward.
    const VecN size = vec({3.0, 2.0, 1.5});
    const nurbs::Patch block = test::grid_patch({2, 1, 2}, {2, 1, 3}, size);
    RowMatrix mirrored = block.control_points();
    mirrored.col(0) = size(0) - mirrored.col(0).array();
    const nurbs::Patch left = block.with_control_points(mirrored);
    for (int s = 0; s < 6; ++s) {
        const Side which = static_cast<Side>(s);
        const int dir = side_direction(which);
        VecN n = VecN::Zero(3);
        n(dir) = side_at_end(which) ? 1.0 : -1.0;
        expect_normals(PatchSide(block, which), constant(n), round_off);
        if (dir == 0)
            n = -n;
        expect_normals(PatchSide(left, which), constant(n), round_off);
    }
}

TEST(PatchSide, OutwardNormalsOfRotatedCurvedSolid)
{
    const double r_in = 1.0, r_out = 1.7, H = 0.8;
    const MatN Q = test::rotation(3, 0.7);
    const VecN t = vec({0.3, -1.0, 2.0});
    const nurbs::Patch patch = test::transformed(test::quarter_cylinder_shell(r_in, r_out, H), Q, t);
    // Local frame of the unrotated shell: e_r is the direction from the z axis.
    const auto local = [&](const VecN& x) { return VecN(Q.transpose() * (x - t)); };
    const auto radial = [&](double sign) {
        return [&, sign](const VecN& x) {
            VecN e = local(x);
            e(2) = 0.0;
            return VecN(Q * (sign * e.normalized()));
        };
    };
    expect_normals(PatchSide(patch, Side::u0), constant(Q * vec({0, -1, 0})), round_off);
    expect_normals(PatchSide(patch, Side::u1), constant(Q * vec({-1, 0, 0})), round_off);
    expect_normals(PatchSide(patch, Side::v0), radial(-1.0), round_off);
    expect_normals(PatchSide(patch, Side::v1), radial(1.0), round_off);
    expect_normals(PatchSide(patch, Side::w0), constant(Q * vec({0, 0, -1})), round_off);
    expect_normals(PatchSide(patch, Side::w1), constant(Q * vec({0, 0, 1})), round_off);
}

TEST(PatchSide, CurrentPointsTurnTheNormalWithTheBody)
{
    // The sign is fixed in the reference configuration; evaluate on rotated control
    // points returns the rotated normal and tangents (contact's current configuration).
    const nurbs::Patch patch = test::quarter_cylinder_shell(1.0, 1.7, 0.8);
    const MatN Q = test::rotation(3, 1.1);
    const PatchSide side(patch, Side::v1);
    const RowMatrix X = side.patch().control_points();
    const RowMatrix x = X * Q.transpose();
    for (const VecN& xi : samples(side, 0, 3)) {
        const SurfacePoint p0 = side.evaluate(X, 0, xi, 2);
        const SurfacePoint p1 = side.evaluate(x, 0, xi, 2);
        EXPECT_TRUE(test::at_most((p1.normal - Q * p0.normal).norm(), round_off));
        EXPECT_TRUE(test::at_most((p1.tangents - Q * p0.tangents).norm(), round_off * p0.tangents.norm()));
        EXPECT_TRUE(test::at_most((p1.curvature - p0.curvature).norm(), round_off * p0.metric.norm()));
    }
}

TEST(PatchSide, MetricAndJacobianOfDistortedSides)
{
    // m = a^T a by definition, and |n_raw|^2 = det m (Lagrange's identity in 3D).
    constexpr double identity_tolerance = 1e-13;
    std::mt19937 rng(7);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        for (int s = 0; s < 2 * d; ++s) {
            const PatchSide side(patch, static_cast<Side>(s));
            for (int e = 0; e < side.n_elements(); ++e)
                for (const VecN& xi : samples(side, e, 2)) {
                    const SurfacePoint p = side.evaluate(side.patch().control_points(), e, xi, 1);
                    const MatN m = p.tangents.transpose() * p.tangents;
                    EXPECT_TRUE(test::at_most((p.metric - m).norm(), identity_tolerance * m.norm()));
                    EXPECT_TRUE(test::near_rel(p.jacobian * p.jacobian, m.determinant(), identity_tolerance));
                    EXPECT_TRUE(test::near(p.normal.norm(), 1.0, identity_tolerance));
                    // Heap copies: GCC 12 warns falsely on products of capped VecN/MatN.
                    const Vector n = p.normal;
                    EXPECT_TRUE(test::at_most((Matrix(p.tangents).transpose() * n).norm(),
                                              identity_tolerance * p.tangents.norm()));
                    // Outward: these are small distortions of the unit cube.
                    EXPECT_GT(p.normal(side_direction(side.which())) * (side_at_end(side.which()) ? 1 : -1), 0.5);
                }
        }
    }
}

/// b_ab = -n_,a . a_b (Weingarten), with n_,a by central differences of evaluate.
MatN curvature_by_differences(const PatchSide& side, int e, const VecN& xi, double h)
{
    const RowMatrix& X = side.patch().control_points();
    const int n_side = side.dim() - 1;
    const SurfacePoint p = side.evaluate(X, e, xi, 1);
    MatN b(n_side, n_side);
    for (int a = 0; a < n_side; ++a) {
        VecN plus = xi, minus = xi;
        plus(a) += h;
        minus(a) -= h;
        const VecN dn = (side.evaluate(X, e, plus, 1).normal - side.evaluate(X, e, minus, 1).normal) / (2.0 * h);
        for (int c = 0; c < n_side; ++c)
            b(a, c) = -dn.dot(p.tangents.col(c));
    }
    return b;
}

// Central differences with h = 1e-5 on unit-size geometry: truncation O(h^2) ~ 1e-10,
// round-off eps / h ~ 1e-11, relative to |m| ~ 1.
constexpr double fd_step = 1e-5;
constexpr double fd_tolerance = 1e-8;

TEST(PatchSide, CurvatureOfCircleArcsAndItsSign)
{
    // Quarter annulus: the outer arc bounds the body from outside (b = -m / R), the
    // inner arc bounds a hole (b = +m / r).
    const double r_in = 0.6, r_out = 1.3;
    const nurbs::Patch patch = test::quarter_annulus(r_in, r_out);
    for (const auto& [which, expected] : {std::pair{Side::u1, -1.0 / r_out}, std::pair{Side::u0, 1.0 / r_in}}) {
        const PatchSide side(patch, which);
        for (const VecN& xi : samples(side, 0, 5)) {
            const SurfacePoint p = side.evaluate(side.patch().control_points(), 0, xi, 2);
            EXPECT_TRUE(test::near_rel(p.curvature(0, 0), expected * p.metric(0, 0), round_off));
            EXPECT_TRUE(test::at_most((p.curvature - curvature_by_differences(side, 0, xi, fd_step)).norm(),
                                      fd_tolerance * p.metric.norm()));
        }
    }
}

TEST(PatchSide, CurvatureOfSphereCylinderAndDistortedFaces)
{
    const double R = 1.4;
    const PatchSide sphere(test::octant_ball(R), Side::w1);
    for (const VecN& xi : samples(sphere, 0, 3)) {
        const SurfacePoint p = sphere.evaluate(sphere.patch().control_points(), 0, xi, 2);
        EXPECT_TRUE(test::at_most((p.curvature + p.metric / R).norm(), round_off * p.metric.norm()));
        EXPECT_TRUE(test::at_most((p.curvature - curvature_by_differences(sphere, 0, xi, fd_step)).norm(),
                                  fd_tolerance * p.metric.norm()));
    }
    // Outer face of the cylinder (u around, w along the axis): b_uu = -m_uu / R, 0 else.
    const PatchSide cylinder(test::quarter_cylinder_shell(1.0, R, 0.8), Side::v1);
    for (const VecN& xi : samples(cylinder, 0, 3)) {
        const SurfacePoint p = cylinder.evaluate(cylinder.patch().control_points(), 0, xi, 2);
        MatN expected = MatN::Zero(2, 2);
        expected(0, 0) = -p.metric(0, 0) / R;
        EXPECT_TRUE(test::at_most((p.curvature - expected).norm(), round_off * p.metric.norm()));
    }
    // A rational, distorted face: only the finite-difference identity.
    std::mt19937 rng(11);
    const nurbs::Patch patch = test::distorted(test::grid_patch({2, 2, 2}, {2, 1, 2}, VecN::Ones(3)), rng, 0.1, 0.3);
    for (const Side which : {Side::u0, Side::v1, Side::w1}) {
        const PatchSide side(patch, which);
        for (int e = 0; e < side.n_elements(); ++e)
            for (const VecN& xi : samples(side, e, 2)) {
                const SurfacePoint p = side.evaluate(side.patch().control_points(), e, xi, 2);
                EXPECT_TRUE(test::at_most((p.curvature - curvature_by_differences(side, e, xi, fd_step)).norm(),
                                          fd_tolerance * p.metric.norm()))
                    << side_name(which);
            }
    }
}

TEST(PatchSide, DegenerateHexahedronFacesAreFiniteWithLimitNormals)
{
    // The octant ball: faces with an edge collapsed to a point, a face collapsed to a
    // point and a face of zero area (boundary/solids.hpp).
    // The limit normal comes from second derivatives at the pole: a few ulps of them.
    constexpr double limit_tolerance = 1e-12;
    const double R = 1.4;
    const nurbs::Patch ball = test::octant_ball(R);

    const PatchSide centre(ball, Side::w0);
    EXPECT_TRUE(centre.collapsed());
    EXPECT_EQ(centre.outward_sign(), 0);

    const PatchSide pole_segment(ball, Side::v1);  // the segment centre-pole: no area, no normal
    EXPECT_FALSE(pole_segment.collapsed());
    EXPECT_EQ(pole_segment.outward_sign(), 0);

    // Sphere face: at the pole (v = 1) the tangent a_u vanishes.
    const PatchSide sphere(ball, Side::w1);
    EXPECT_EQ(sphere.outward_sign() * sphere.outward_sign(), 1);
    for (const double u : {0.0, 0.3, 0.5, 1.0}) {
        const SurfacePoint p = sphere.evaluate(sphere.patch().control_points(), 0, vec({u, 1.0}), 2);
        EXPECT_TRUE(p.degenerate);
        EXPECT_TRUE(test::at_most(p.jacobian, round_off));
        EXPECT_TRUE(test::at_most((p.normal - vec({0, 0, 1})).norm(), limit_tolerance)) << p.normal.transpose();
        EXPECT_TRUE(p.curvature.allFinite() && p.metric.allFinite());
    }
    // Plane faces with an edge at the centre (w = 0): their constant normal there too.
    const std::pair<Side, VecN> planes[] = {
        {Side::u0, vec({0, -1, 0})}, {Side::u1, vec({-1, 0, 0})}, {Side::v0, vec({0, 0, -1})}};
    for (const auto& [which, n] : planes) {
        const PatchSide side(ball, which);
        expect_normals(side, constant(n), round_off);
        for (const double s : {0.0, 0.4, 1.0}) {
            const SurfacePoint p = side.evaluate(side.patch().control_points(), 0, vec({s, 0.0}), 1);
            EXPECT_TRUE(p.degenerate) << side_name(which);
            EXPECT_TRUE(test::at_most((p.normal - n).norm(), limit_tolerance)) << side_name(which);
        }
    }
    // Every side, every sample, the ends included: nothing is NaN.
    for (int s = 0; s < 6; ++s) {
        const PatchSide side(ball, static_cast<Side>(s));
        for (const double u : {0.0, 0.5, 1.0})
            for (const double v : {0.0, 0.5, 1.0}) {
                const SurfacePoint p = side.evaluate(side.patch().control_points(), 0, vec({u, v}), 2);
                EXPECT_TRUE(p.x.allFinite() && p.tangents.allFinite() && p.normal.allFinite() &&
                            p.curvature.allFinite() && std::isfinite(p.jacobian))
                    << side_name(side.which()) << " at " << u << ", " << v;
            }
    }
}

TEST(PatchSide, FoldedSideIsRejected)
{
    // Side v0 of this patch is straight, but dX/dv at v = 0 has y-component
    // 1 - 8u + 10u^2 (u = 1/4: -3/8, u = 3/4: +5/8): the parametrization folds over.
    const nurbs::Patch patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1})},
                             (RowMatrix(6, 2) << 0, 0, 1, 0, 2, 0, 0, 1, 1, -3, 2, 3).finished(), Vector::Ones(6));
    EXPECT_THROW(PatchSide(patch, Side::v0), FoldedSide);
    EXPECT_THROW((void)outward_sign(patch, Side::v0), FoldedSide);
    EXPECT_NO_THROW(PatchSide(patch, Side::u0));
}

TEST(PatchSide, FreeOutwardSignAgreesWithTheObject)
{
    std::mt19937 rng(3);
    const nurbs::Patch patch = test::distorted(test::grid_patch({2, 2, 1}, {1, 2, 1}, VecN::Ones(3)), rng, 0.1, 0.3);
    for (int s = 0; s < 6; ++s)
        EXPECT_EQ(outward_sign(patch, static_cast<Side>(s)), PatchSide(patch, static_cast<Side>(s)).outward_sign());
    const nurbs::Patch disc = nurbs::half_disc(vec({0.0, 0.0}), 1.0);
    EXPECT_EQ(outward_sign(disc, Side::u0), 0);
}

}  // namespace
}  // namespace iga::boundary
