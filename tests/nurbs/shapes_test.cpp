// Tests of the built-in exact shapes: exact arcs and spheres, straight tops and
// planar faces, documented sides, collapsed corners, a positive Jacobian inside,
// exact volumes, and geometry kept by refinement.

#include "core/error.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"
#include "nurbs/side_patch.hpp"
#include "quadrature/gauss.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <limits>
#include <set>

namespace iga::nurbs {
namespace {

// Exact rational arcs: the only error is round-off in O(R) quantities.
constexpr double exact_tolerance = 1e-14;
// A side is collapsed when its control points coincide to round-off.
constexpr double collapse_tolerance = 1e-12;

const VecN center = (VecN(2) << 0.5, 1.0).finished();
constexpr double radius = 2.0;

VecN at(double u, double v) { return (VecN(2) << u, v).finished(); }

double jacobian_det(const Patch& patch, double u, double v)
{
    const PointDerivatives x = evaluate(patch, at(u, v), 1);
    return x.dx(0, 0) * x.dx(1, 1) - x.dx(0, 1) * x.dx(1, 0);
}

void expect_positive_jacobian_inside(const Patch& patch)
{
    for (int i = 1; i < 20; ++i)
        for (int j = 1; j < 20; ++j)
            EXPECT_TRUE(test::at_least(jacobian_det(patch, i / 20.0, j / 20.0), 1e-3)) << i << ", " << j;
}

TEST(Shapes, HalfDisc)
{
    const Patch patch = half_disc(center, radius);
    ASSERT_EQ(patch.n_par(), 2);
    EXPECT_EQ(patch.degree(0), 3);
    EXPECT_EQ(patch.degree(1), 1);
    EXPECT_EQ(patch.knots(0).n_spans(), 1);
    for (int i = 0; i <= 200; ++i) {
        const double u = i / 200.0;
        const VecN arc = evaluate(patch, at(u, 0.0), 0).x;
        EXPECT_TRUE(test::near((arc - center).norm(), radius, exact_tolerance * radius)) << "u " << u;
        EXPECT_TRUE(test::at_most(arc(1) - center(1), exact_tolerance * radius));  // lower half
        const VecN top = evaluate(patch, at(u, 1.0), 0).x;
        EXPECT_TRUE(test::near(top(1), center(1), exact_tolerance * radius));  // flat top
        EXPECT_TRUE(test::near(top(0), arc(0), exact_tolerance * radius));     // straight above the arc point
        const VecN mid = evaluate(patch, at(u, 0.37), 0).x;
        EXPECT_TRUE(test::near(mid(0), arc(0), exact_tolerance * radius));
    }
    EXPECT_TRUE(test::at_most((evaluate(patch, at(0, 0), 0).x - center - at(-radius, 0)).norm(), exact_tolerance));
    EXPECT_TRUE(test::at_most((evaluate(patch, at(0.5, 0), 0).x - center - at(0, -radius)).norm(), exact_tolerance));
    EXPECT_TRUE(test::at_most((evaluate(patch, at(1, 0), 0).x - center - at(radius, 0)).norm(), exact_tolerance));
    expect_positive_jacobian_inside(patch);

    EXPECT_TRUE(is_collapsed(extract_side(patch, Side::u0), collapse_tolerance));
    EXPECT_TRUE(is_collapsed(extract_side(patch, Side::u1), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::v0), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::v1), collapse_tolerance));
    const SidePatch arc = extract_side(patch, Side::v0);
    for (int i = 0; i <= 50; ++i)
        EXPECT_TRUE(test::near((evaluate(arc.patch, VecN::Constant(1, i / 50.0), 0).x - center).norm(), radius,
                               exact_tolerance * radius));
}

TEST(Shapes, QuarterDisc)
{
    const Patch patch = quarter_disc(center, radius);
    EXPECT_EQ(patch.degree(0), 2);
    EXPECT_EQ(patch.degree(1), 1);
    for (int i = 0; i <= 200; ++i) {
        const double u = i / 200.0;
        const VecN arc = evaluate(patch, at(u, 0.0), 0).x;
        EXPECT_TRUE(test::near((arc - center).norm(), radius, exact_tolerance * radius));
        EXPECT_TRUE(test::at_least(arc(0) - center(0), -exact_tolerance * radius));  // right half
        EXPECT_TRUE(test::at_most(arc(1) - center(1), exact_tolerance * radius));    // lower half
        const VecN top = evaluate(patch, at(u, 1.0), 0).x;
        EXPECT_TRUE(test::near(top(1), center(1), exact_tolerance * radius));
        EXPECT_TRUE(test::near(top(0), arc(0), exact_tolerance * radius));
        const VecN symmetry = evaluate(patch, at(0.0, u), 0).x;  // side u0 is the line x = c_x
        EXPECT_TRUE(test::near(symmetry(0), center(0), exact_tolerance * radius));
    }
    EXPECT_TRUE(test::at_most((evaluate(patch, at(0, 0), 0).x - center - at(0, -radius)).norm(), exact_tolerance));
    EXPECT_TRUE(test::at_most((evaluate(patch, at(1, 0), 0).x - center - at(radius, 0)).norm(), exact_tolerance));
    expect_positive_jacobian_inside(patch);
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::u0), collapse_tolerance));
    EXPECT_TRUE(is_collapsed(extract_side(patch, Side::u1), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::v0), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::v1), collapse_tolerance));
}

TEST(Shapes, Rectangle)
{
    const VecN corner = at(-1.0, 0.5);
    const VecN size = at(4.0, 1.0);
    const Patch patch = rectangle(corner, size);
    EXPECT_EQ(patch.degree(0), 1);
    EXPECT_EQ(patch.degree(1), 1);
    EXPECT_EQ(patch.elements().size(), 1u);
    const VecN x = evaluate(patch, at(0.25, 0.5), 0).x;
    EXPECT_TRUE(test::near(x(0), 0.0, exact_tolerance));
    EXPECT_TRUE(test::near(x(1), 1.0, exact_tolerance));
    EXPECT_TRUE(test::near(jacobian_det(patch, 0.3, 0.7), 4.0, exact_tolerance));
    const SidePatch right = extract_side(patch, Side::u1);
    for (int a = 0; a < 2; ++a)
        EXPECT_EQ(right.patch.control_points()(a, 0), 3.0);
    const SidePatch bottom = extract_side(patch, Side::v0);
    for (int a = 0; a < 2; ++a)
        EXPECT_EQ(bottom.patch.control_points()(a, 1), 0.5);
    EXPECT_THROW(rectangle(corner, at(-1.0, 1.0)), Error);
}

TEST(Shapes, SideNamesAndInvalidInput)
{
    for (const char* shape : {"half_disc", "quarter_disc", "rectangle"}) {
        const auto names = shape_side_names(shape);
        ASSERT_EQ(names.size(), 4u) << shape;
        for (const auto& [side, description] : names) {
            EXPECT_TRUE(parse_side(side).has_value()) << side;
            EXPECT_FALSE(description.empty());
        }
    }
    EXPECT_EQ(shape_side_names("half_disc")[0].first, "v0");
    EXPECT_NE(shape_side_names("half_disc")[0].second.find("contact"), std::string::npos);
    EXPECT_THROW(shape_side_names("triangle"), Error);
    EXPECT_THROW(half_disc(center, -1.0), Error);
    EXPECT_THROW(half_disc(center, std::nan("")), Error);
    EXPECT_THROW(quarter_disc(VecN::Zero(3), 1.0), Error);
}

// ---------------------------------------------------------------------------
// 3D shapes

// Volume by Gauss quadrature of det J: the integrand is a smooth rational
// function on each span (its poles, from the weights, lie off the real span);
// 10 points per direction on cells of at most 1/4 of the parameter interval
// converge to round-off.
constexpr double volume_tolerance = 1e-12;
// det J at the Gauss points of the mechanics (degree + 1 per direction),
// relative to the mean det J (volume / parametric volume): positive, above
// round-off (1e-16). It falls like a power of the distance to a collapsed side
// (the sphere's axis and pole), to ~1e-8 of the mean at the closest points.
constexpr double min_relative_jacobian = 1e-12;
// Refinement is exact in exact arithmetic; this is round-off of O(1) coordinates.
constexpr double refine_tolerance = 1e-13;

VecN at3(double u, double v, double w) { return (VecN(3) << u, v, w).finished(); }

const VecN center3 = (VecN(3) << 0.5, -1.0, 2.0).finished();

double det3(const Patch& patch, const std::array<int, 3>& span, const VecN& xi)
{
    const PointDerivatives x = combine(rational_basis(patch, span, xi, 1), patch.control_points());
    return Eigen::Matrix3d(x.dx).determinant();
}

struct VolumeReport {
    double volume = 0;
    double min_det = std::numeric_limits<double>::infinity();
};

/// Volume by 10-point Gauss rules on cells of at most 1/4 of each parameter
/// interval, and the smallest det J at the Gauss points of the mechanics.
VolumeReport integrate_volume(const Patch& patch)
{
    const quadrature::Rule1D rule = quadrature::gauss_legendre(10);
    const auto n_q = static_cast<int>(rule.points.size());
    int n_mechanics = 1;
    std::array<int, 3> n_sub{};
    for (int dir = 0; dir < 3; ++dir) {
        n_mechanics = std::max(n_mechanics, patch.degree(dir) + 1);
        n_sub[dir] = std::max(1, 4 / patch.knots(dir).n_spans());
    }
    VolumeReport report;
    for (const Element& e : patch.elements()) {
        const quadrature::TensorRule mechanics = quadrature::element_rule(patch, e, n_mechanics);
        for (Index q = 0; q < mechanics.points.rows(); ++q) {
            const double det = det3(patch, e.span, mechanics.points.row(q).transpose());
            report.min_det = std::isnan(det) ? det : std::min(report.min_det, det);
        }
        std::array<double, 3> h{};
        for (int dir = 0; dir < 3; ++dir)
            h[dir] = (e.upper[dir] - e.lower[dir]) / n_sub[dir];
        for (int cell = 0; cell < n_sub[0] * n_sub[1] * n_sub[2]; ++cell)
            for (int q = 0; q < n_q * n_q * n_q; ++q) {
                const std::array<int, 3> c{cell % n_sub[0], (cell / n_sub[0]) % n_sub[1], cell / (n_sub[0] * n_sub[1])};
                const std::array<int, 3> g{q % n_q, (q / n_q) % n_q, q / (n_q * n_q)};
                VecN xi(3);
                double weight = 1.0;
                for (int dir = 0; dir < 3; ++dir) {
                    xi(dir) = e.lower[dir] + h[dir] * (c[dir] + rule.points[g[dir]]);
                    weight *= h[dir] * rule.weights[g[dir]];
                }
                report.volume += weight * det3(patch, e.span, xi);
            }
    }
    return report;
}

void expect_valid_volume(const Patch& patch, double expected_volume)
{
    const VolumeReport r = integrate_volume(patch);
    EXPECT_TRUE(test::near_rel(r.volume, expected_volume, volume_tolerance));
    double parametric_volume = 1.0;
    for (int dir = 0; dir < 3; ++dir)
        parametric_volume *= patch.knots(dir).knots().back() - patch.knots(dir).knots().front();
    EXPECT_TRUE(test::at_least(r.min_det, min_relative_jacobian * expected_volume / parametric_volume));
}

Patch refined(Patch patch, const std::array<int, 3>& elevate, const std::array<int, 3>& spans)
{
    for (int dir = 0; dir < 3; ++dir) {
        if (elevate[dir] > 0)
            patch = elevate_degree(patch, dir, elevate[dir]);
        patch = refine_uniform(patch, dir, spans[dir]);
    }
    return patch;
}

TEST(Shapes, SphereOctantIsTheExactOctant)
{
    constexpr double R = 1.5;
    const Patch patch = sphere_octant(center3, R);
    ASSERT_EQ(patch.n_par(), 3);
    ASSERT_EQ(patch.dim(), 3);
    EXPECT_EQ(patch.degree(0), 2);
    EXPECT_EQ(patch.degree(1), 1);
    EXPECT_EQ(patch.degree(2), 2);
    const double tol = exact_tolerance * R;
    for (int i = 0; i <= 40; ++i)
        for (int k = 0; k <= 40; ++k) {
            const double u = i / 40.0, w = k / 40.0;
            const VecN sphere = evaluate(patch, at3(u, 0, w), 0).x - center3;  // v0: spherical face
            EXPECT_TRUE(test::near(sphere.norm(), R, tol)) << u << ", " << w;
            EXPECT_TRUE(test::near(evaluate(patch, at3(0, u, w), 0).x(0), center3(0), tol));  // u0: x = c_x
            EXPECT_TRUE(test::near(evaluate(patch, at3(u, w, 1), 0).x(1), center3(1), tol));  // w1: y = c_y
            EXPECT_TRUE(test::near(evaluate(patch, at3(u, w, 0), 0).x(2), center3(2), tol));  // w0: z = c_z
            const VecN axis = evaluate(patch, at3(u, 1, w), 0).x - center3;                   // v1: on the axis
            EXPECT_TRUE(test::at_most(axis.tail(2).norm(), tol));
            // Every point lies in the octant: x >= c_x, y >= c_y, z <= c_z, |x - c| <= R.
            const VecN inside = evaluate(patch, at3(u, 0.37, w), 0).x - center3;
            EXPECT_TRUE(test::at_least(inside(0), -tol));
            EXPECT_TRUE(test::at_least(inside(1), -tol));
            EXPECT_TRUE(test::at_most(inside(2), tol));
            EXPECT_TRUE(test::at_most(inside.norm(), R + tol));
        }
    // The lowest point is the corner (u, v, w) = (0, 0, 1) of the spherical face,
    // a regular one: its two tangents are horizontal and independent.
    const PointDerivatives lowest = evaluate(patch, at3(0, 0, 1), 1);
    EXPECT_TRUE(test::at_most((lowest.x - center3 - at3(0, 0, -R)).norm(), tol));
    const Eigen::Vector3d t_u = lowest.dx.col(0), t_w = lowest.dx.col(2);
    EXPECT_TRUE(test::at_most(std::abs(t_u(2)) + std::abs(t_w(2)), tol));
    EXPECT_TRUE(test::at_least(t_u.cross(t_w).norm(), 0.1 * t_u.norm() * t_w.norm()));
    EXPECT_TRUE(test::at_least(-t_u.cross(t_w)(2), 0.0));  // outward (-z) normal of v0 is -(t_u x t_w)
    // The pole of the revolution (u1, a point) and the axis (v1, a line) are the degenerate sides.
    EXPECT_TRUE(is_collapsed(extract_side(patch, Side::u1), collapse_tolerance));
    for (Side s : {Side::u0, Side::v0, Side::v1, Side::w0, Side::w1})
        EXPECT_FALSE(is_collapsed(extract_side(patch, s), collapse_tolerance)) << side_name(s);
    EXPECT_TRUE(test::at_most((evaluate(patch, at3(1, 0.3, 0.6), 0).x - center3 - at3(R, 0, 0)).norm(), tol));
    expect_valid_volume(patch, std::numbers::pi * R * R * R / 6.0);
}

TEST(Shapes, SphereOctantRefinedKeepsGeometryVolumeAndPositiveJacobian)
{
    constexpr double R = 1.0;
    const Patch coarse = sphere_octant(center3, R);
    const double volume = std::numbers::pi * R * R * R / 6.0;
    for (const auto& elevate : {std::array<int, 3>{0, 0, 0}, std::array<int, 3>{0, 1, 0}, std::array<int, 3>{1, 2, 1}}) {
        const Patch fine = refined(coarse, elevate, {4, 4, 4});
        EXPECT_EQ(fine.degree(1), 1 + elevate[1]);
        EXPECT_EQ(fine.elements().size(), 64u);
        expect_valid_volume(fine, volume);
        for (int i = 0; i <= 6; ++i)
            for (int j = 0; j <= 6; ++j)
                for (int k = 0; k <= 6; ++k) {
                    const VecN xi = at3(i / 6.0, j / 6.0, k / 6.0);
                    EXPECT_TRUE(test::at_most((evaluate(fine, xi, 0).x - evaluate(coarse, xi, 0).x).norm(),
                                              refine_tolerance));
                }
    }
    // Graded knots near the contact corner (u = 0, w = 1), as the 3D Hertz deck inserts them.
    Patch graded = elevate_degree(coarse, 1, 1);
    graded = insert_knots(graded, 0, {0.01, 0.02, 0.04, 0.08, 0.3});
    graded = insert_knots(graded, 2, {0.5, 0.9, 0.97, 0.99});
    graded = insert_knots(graded, 1, {0.05, 0.3});
    expect_valid_volume(graded, volume);
    for (double u : {0.0, 0.015, 0.5, 1.0})
        for (double w : {0.0, 0.95, 0.995, 1.0}) {
            const VecN xi = at3(u, 0.0, w);
            EXPECT_TRUE(test::at_most((evaluate(graded, xi, 0).x - evaluate(coarse, xi, 0).x).norm(),
                                      refine_tolerance));
        }
}

TEST(Shapes, BoxIsTrilinear)
{
    const VecN corner = at3(-1.0, 0.5, 2.0);
    const VecN size = at3(4.0, 1.0, 0.5);
    const Patch patch = box(corner, size);
    for (int dir = 0; dir < 3; ++dir)
        EXPECT_EQ(patch.degree(dir), 1);
    EXPECT_EQ(patch.elements().size(), 1u);
    for (double u : {0.0, 0.3, 1.0})
        for (double v : {0.0, 0.6, 1.0})
            for (double w : {0.0, 0.25, 1.0}) {
                const VecN expected = corner + size.cwiseProduct(at3(u, v, w));
                EXPECT_TRUE(test::at_most((evaluate(patch, at3(u, v, w), 0).x - expected).norm(), exact_tolerance));
            }
    // Sides: u0/u1 = x min/max, v0/v1 = y, w0/w1 = z.
    for (int k = 0; k < 6; ++k) {
        const Side side = static_cast<Side>(k);
        const int dir = side_direction(side);
        const double value = corner(dir) + (side_at_end(side) ? size(dir) : 0.0);
        const SidePatch sp = extract_side(patch, side);
        for (Index a = 0; a < sp.patch.n_control_points(); ++a)
            EXPECT_EQ(sp.patch.control_points()(a, dir), value) << side_name(side);
    }
    expect_valid_volume(patch, size.prod());
    expect_valid_volume(refined(patch, {1, 0, 2}, {3, 2, 4}), size.prod());
    EXPECT_THROW(box(corner, at3(1.0, 0.0, 1.0)), Error);
    EXPECT_THROW(box(corner, at(1.0, 1.0)), Error);
}

TEST(Shapes, ExtrudedShapesKeepTheirSectionAlongZ)
{
    constexpr double L = 0.2;
    const double R = radius;
    struct Case {
        const char* name;
        Patch planar;
        double area;
    };
    const std::vector<Case> cases = {{"quarter_disc", quarter_disc(center, R), std::numbers::pi * R * R / 4.0},
                                     {"half_disc", half_disc(center, R), std::numbers::pi * R * R / 2.0},
                                     {"rectangle", rectangle(center, at(3.0, 0.5)), 1.5}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Patch patch = extrude(c.planar, L);
        ASSERT_EQ(patch.n_par(), 3);
        ASSERT_EQ(patch.dim(), 3);
        EXPECT_EQ(patch.degree(2), 1);
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j)
                for (double w : {0.0, 0.4, 1.0}) {
                    const VecN section = evaluate(c.planar, at(i / 10.0, j / 10.0), 0).x;
                    const VecN x = evaluate(patch, at3(i / 10.0, j / 10.0, w), 0).x;
                    EXPECT_TRUE(test::at_most((x.head(2) - section).norm(), exact_tolerance));
                    EXPECT_TRUE(test::near(x(2), w * L, exact_tolerance));
                }
        const SidePatch bottom = extract_side(patch, Side::w0);
        const SidePatch top = extract_side(patch, Side::w1);
        EXPECT_TRUE(bottom.patch.control_points().col(2).isZero(0.0));
        EXPECT_TRUE((top.patch.control_points().col(2).array() == L).all());
        expect_valid_volume(patch, c.area * L);
        expect_valid_volume(refined(patch, {0, 1, 1}, {4, 4, 3}), c.area * L);
    }
    EXPECT_THROW(extrude(quarter_disc(center, R), 0.0), Error);
    EXPECT_THROW(extrude(quarter_disc(center, R), std::nan("")), Error);
    EXPECT_THROW(extrude(box(at3(0, 0, 0), at3(1, 1, 1)), 1.0), Error);
}

TEST(Shapes, SideNamesOf3dShapes)
{
    const auto expect_all_six = [](const std::vector<std::pair<std::string, std::string>>& names) {
        ASSERT_EQ(names.size(), 6u);
        std::set<std::string> sides;
        for (const auto& [side, description] : names) {
            EXPECT_TRUE(parse_side(side).has_value()) << side;
            EXPECT_FALSE(description.empty());
            sides.insert(side);
        }
        EXPECT_EQ(sides.size(), 6u);
    };
    expect_all_six(shape_side_names("sphere_octant"));
    expect_all_six(shape_side_names("box"));
    for (const char* shape : {"half_disc", "quarter_disc", "rectangle"})
        expect_all_six(shape_side_names(shape, true));
    EXPECT_EQ(shape_side_names("sphere_octant")[0].first, "v0");
    EXPECT_NE(shape_side_names("sphere_octant")[0].second.find("contact"), std::string::npos);
    EXPECT_EQ(shape_side_names("quarter_disc", true)[3].second, "collapsed to a line along z: right end of the top line");
    EXPECT_THROW(shape_side_names("box", true), Error);
    EXPECT_THROW(sphere_octant(center, 1.0), Error);  // needs 3 coordinates
    EXPECT_THROW(sphere_octant(center3, 0.0), Error);
}

}  // namespace
}  // namespace iga::nurbs
