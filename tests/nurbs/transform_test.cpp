// Tests of placing patches (nurbs/transform.hpp): every step maps the patch's
// points exactly (the patch after the map, evaluated at a grid of parameters,
// equals the map of the patch before), rational patches included; a mirror
// keeps the Jacobian positive by reversing u; steps compose in list order.

#include "core/error.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"
#include "nurbs/transform.hpp"
#include "support/tolerance.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace iga::nurbs {
namespace {

// Mapping a point costs a few operations on O(size) numbers: round-off of a few
// eps relative to the coordinates' magnitude, far below 1e-13.
constexpr double mapping_tolerance = 1e-13;

VecN vec(std::initializer_list<double> values)
{
    VecN v(static_cast<Index>(values.size()));
    Index i = 0;
    for (double x : values)
        v(i++) = x;
    return v;
}

/// Parameter grid points of an n_par-variate patch on [0, 1]^n_par, 7 per direction.
std::vector<VecN> parameter_grid(int n_par)
{
    std::vector<VecN> out;
    constexpr int n = 7;
    for (int k = 0; k < (n_par == 3 ? n : 1); ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                VecN xi(n_par);
                xi(0) = i / (n - 1.0);
                xi(1) = j / (n - 1.0);
                if (n_par == 3)
                    xi(2) = k / (n - 1.0);
                out.push_back(xi);
            }
    return out;
}

/// max |x_after(xi') - map(x_before(xi))| / (1 + max |x|), xi' = xi with u reversed
/// when the map reverses orientations.
double mapping_error(const Patch& before, const Affine& map)
{
    const Patch after = transformed(before, map);
    const double size = 1.0 + before.control_points().cwiseAbs().maxCoeff() +
                        after.control_points().cwiseAbs().maxCoeff();
    double worst = 0.0;
    for (const VecN& xi : parameter_grid(before.n_par())) {
        VecN xi_after = xi;
        if (map.reverses_orientation())
            xi_after(0) = 1.0 - xi(0);
        const VecN expected = map.apply(evaluate(before, xi, 0).x);
        const VecN actual = evaluate(after, xi_after, 0).x;
        worst = std::max(worst, (actual - expected).norm() / size);
    }
    return worst;
}

double jacobian_det(const Patch& patch, const VecN& xi)
{
    const PointDerivatives x = evaluate(patch, xi, 1);
    return MatN(x.dx).determinant();
}

/// Smallest det J over interior grid points (the shapes' corners may be collapsed).
double min_interior_jacobian(const Patch& patch)
{
    double smallest = std::numeric_limits<double>::infinity();
    for (VecN xi : parameter_grid(patch.n_par())) {
        xi = 0.05 + 0.9 * xi.array();
        smallest = std::min(smallest, jacobian_det(patch, xi));
    }
    return smallest;
}

/// A few rational and polynomial test patches in 2D and 3D (a refined, graded one among them).
std::vector<std::pair<std::string, Patch>> patches_2d()
{
    return {{"quarter_disc", quarter_disc(vec({0.5, 1.0}), 2.0)},
            {"half_disc", half_disc(vec({-1.0, 0.25}), 0.75)},
            {"graded rectangle", insert_knots(rectangle(vec({1.0, 2.0}), vec({3.0, 0.5})), 0, {0.1, 0.15, 0.6})}};
}

std::vector<std::pair<std::string, Patch>> patches_3d()
{
    return {{"sphere_octant", sphere_octant(vec({0.5, -1.0, 2.0}), 1.5)},
            {"extruded half_disc", extrude(half_disc(vec({0.0, 1.0}), 1.0), 0.4)},
            {"box", box(vec({0.0, 0.0, 0.0}), vec({1.0, 2.0, 3.0}))}};
}

std::vector<std::pair<std::string, Affine>> maps_2d()
{
    return {{"translate", translation(vec({0.3, -7.25}))},
            {"rotate 37 about (1, -2)", rotation_2d(37.0, vec({1.0, -2.0}))},
            {"rotate -450", rotation_2d(-450.0, vec({0.0, 0.0}))},
            {"mirror x = 1", mirror(vec({1.0, 0.0}), vec({1.0, 0.0}))},
            {"mirror oblique", mirror(vec({1.0, 2.0}), vec({0.5, -0.5}))},
            {"scale 2.5", scaling(2.5, 2)}};
}

std::vector<std::pair<std::string, Affine>> maps_3d()
{
    return {{"translate", translation(vec({0.3, -7.25, 1e3}))},
            {"rotate 90 about z", rotation(vec({0.0, 0.0, 1.0}), 90.0, vec({0.0, 0.0, 0.0}))},
            {"rotate 123 about (1, 1, 1) through (1, 2, 3)",
             rotation(vec({1.0, 1.0, 1.0}), 123.0, vec({1.0, 2.0, 3.0}))},
            {"mirror y = -1", mirror(vec({0.0, 2.0, 0.0}), vec({0.0, -1.0, 0.0}))},
            {"mirror oblique", mirror(vec({1.0, -1.0, 0.5}), vec({0.2, 0.0, 1.0}))},
            {"scale 0.1", scaling(0.1, 3)}};
}

TEST(Transform, EveryStepMapsThePatchExactly)
{
    for (const auto& [patch_name, patch] : patches_2d())
        for (const auto& [map_name, map] : maps_2d())
            EXPECT_TRUE(test::at_most(mapping_error(patch, map), mapping_tolerance)) << patch_name << ", " << map_name;
    for (const auto& [patch_name, patch] : patches_3d())
        for (const auto& [map_name, map] : maps_3d())
            EXPECT_TRUE(test::at_most(mapping_error(patch, map), mapping_tolerance)) << patch_name << ", " << map_name;
}

TEST(Transform, WeightsAreKeptAndTheRotatedArcStaysOnTheRotatedCircle)
{
    const VecN center = vec({0.5, 1.0});
    constexpr double radius = 2.0;
    const Patch patch = quarter_disc(center, radius);
    const Affine map = rotation_2d(37.0, vec({-3.0, 4.0})).then(translation(vec({10.0, 0.5})));
    const Patch moved = transformed(patch, map);
    EXPECT_EQ(moved.weights(), patch.weights());
    const VecN moved_center = map.apply(center);
    for (int i = 0; i <= 100; ++i) {
        const VecN x = evaluate(moved, vec({i / 100.0, 0.0}), 0).x;  // side v0: the arc
        EXPECT_TRUE(test::near_rel((x - moved_center).norm(), radius, mapping_tolerance)) << "u = " << i / 100.0;
    }
}

TEST(Transform, AMirrorReversesUAndKeepsTheJacobianPositive)
{
    const Patch patch = quarter_disc(vec({0.0, 0.0}), 1.0);
    const Affine flip = mirror(vec({1.0, 0.0}), vec({0.0, 0.0}));
    ASSERT_TRUE(flip.reverses_orientation());
    ASSERT_TRUE(test::at_least(min_interior_jacobian(patch), 0.0));
    const Patch mirrored = transformed(patch, flip);
    EXPECT_TRUE(test::at_least(min_interior_jacobian(mirrored), 0.0));
    // The patch's u0 was the symmetry line x = 0 and u1 the collapsed point (1, 0):
    // after the mirror u0 is the collapsed point (-1, 0), u1 the line x = 0.
    EXPECT_TRUE(test::near((evaluate(mirrored, vec({0.0, 0.0}), 0).x - vec({-1.0, 0.0})).norm(), 0.0, 1e-15));
    EXPECT_TRUE(test::near((evaluate(mirrored, vec({0.0, 1.0}), 0).x - vec({-1.0, 0.0})).norm(), 0.0, 1e-15));
    EXPECT_TRUE(test::near((evaluate(mirrored, vec({1.0, 0.0}), 0).x - vec({0.0, -1.0})).norm(), 0.0, 1e-15));

    // Two mirrors make a rotation: nothing is reversed.
    const Affine twice = flip.then(mirror(vec({0.0, 1.0}), vec({0.0, 0.0})));
    EXPECT_FALSE(twice.reverses_orientation());
    EXPECT_EQ(transformed(patch, twice).control_points(), -patch.control_points());

    for (const auto& [name, solid] : patches_3d()) {
        const Affine map = mirror(vec({1.0, -1.0, 0.5}), vec({0.2, 0.0, 1.0}));
        EXPECT_TRUE(test::at_least(min_interior_jacobian(transformed(solid, map)), 0.0)) << name;
    }
}

TEST(Transform, ReversingADirectionTwiceGivesThePatchBack)
{
    const Patch patch = insert_knots(quarter_disc(vec({0.0, 0.0}), 1.0), 0, {0.25, 0.25, 0.75});
    const Patch reversed = reverse_direction(patch, 0);
    // Knots 1 - u of the values above: exact for these binary fractions.
    EXPECT_EQ(reversed.knots(0).knot_values(), (std::vector<double>{0, 0, 0, 0.25, 0.75, 0.75, 1, 1, 1}));
    const Patch back = reverse_direction(reversed, 0);
    EXPECT_EQ(back.control_points(), patch.control_points());
    EXPECT_EQ(back.weights(), patch.weights());
    EXPECT_EQ(back.knots(0).knot_values(), patch.knots(0).knot_values());
    EXPECT_THROW(reverse_direction(patch, 2), Error);
}

TEST(Transform, StepsComposeInListOrder)
{
    const Affine shift = translation(vec({1.0, 0.0}));
    const Affine turn = rotation_2d(90.0, vec({0.0, 0.0}));
    const VecN x = vec({1.0, 0.0});
    // Translate, then rotate: (1, 0) -> (2, 0) -> (0, 2). The other order: (0, 1) -> (1, 1).
    EXPECT_EQ(shift.then(turn).apply(x), vec({0.0, 2.0}));
    EXPECT_EQ(turn.then(shift).apply(x), vec({1.0, 1.0}));
    const Patch patch = quarter_disc(vec({0.0, 0.0}), 1.0);
    EXPECT_NE(transformed(patch, shift.then(turn)).control_points(),
              transformed(patch, turn.then(shift)).control_points());
    EXPECT_EQ(transformed(transformed(patch, shift), turn).control_points(),
              transformed(patch, shift.then(turn)).control_points());
}

TEST(Transform, QuarterTurnsAreExact)
{
    for (const auto& [angle, c, s] : std::vector<std::tuple<double, double, double>>{
             {0, 1, 0}, {90, 0, 1}, {180, -1, 0}, {270, 0, -1}, {360, 1, 0}, {-90, 0, -1}, {450, 0, 1},
             {-540, -1, 0}}) {
        const auto [cos, sin] = cos_sin_deg(angle);
        EXPECT_EQ(cos, c) << angle;
        EXPECT_EQ(sin, s) << angle;
    }
    // Rotating the box by 90 degrees about x through its corner: exact coordinates.
    const Patch brick = box(vec({0.0, 0.0, 0.0}), vec({1.0, 2.0, 3.0}));
    const Patch turned = transformed(brick, rotation(vec({2.0, 0.0, 0.0}), 90.0, vec({0.0, 0.0, 0.0})));
    for (int a = 0; a < brick.n_control_points(); ++a) {
        const auto p = brick.control_points().row(a);
        EXPECT_EQ(turned.control_points().row(a), (Eigen::RowVector3d() << p(0), -p(2), p(1)).finished());
    }
    // Away from quarter turns: cos^2 + sin^2 = 1 and the value of the library's cos.
    constexpr double trig_tolerance = 4e-16;  // a few ulps of numbers of size 1
    const auto [c, s] = cos_sin_deg(1e6 + 30.0);  // 1e6 = 2777 turns and 280 degrees
    EXPECT_TRUE(test::near(c, std::cos(310.0 * std::numbers::pi / 180.0), trig_tolerance));
    EXPECT_TRUE(test::near(s, std::sin(310.0 * std::numbers::pi / 180.0), trig_tolerance));
}

TEST(Transform, ScalingAndPreconditions)
{
    const Patch patch = rectangle(vec({1.0, 2.0}), vec({3.0, 4.0}));
    EXPECT_EQ(transformed(patch, scaling(2.0, 2)).control_points(), 2.0 * patch.control_points());
    EXPECT_THROW(scaling(0.0, 2), Error);
    EXPECT_THROW(scaling(-1.0, 2), Error);
    EXPECT_THROW(mirror(vec({0.0, 0.0}), vec({0.0, 0.0})), Error);
    EXPECT_THROW(rotation(vec({0.0, 0.0, 0.0}), 10.0, vec({0.0, 0.0, 0.0})), Error);
    EXPECT_THROW(cos_sin_deg(std::nan("")), Error);
    EXPECT_THROW(transformed(patch, translation(vec({1.0, 2.0, 3.0}))), Error);
}

// Issue 32: |axis| of [0, 0, 1e300] overflowed and of [0, 0, 5e-324] underflowed, and
// the rotation ended in an internal error. Any finite non-zero axis or normal has a
// direction; its length must not matter.
TEST(Transform, AxisAndNormalOfAnyFiniteLengthGiveTheSameMap)
{
    // Normalizing a scaled copy of the axis rounds differently by an ulp or two.
    constexpr double map_tolerance = 1e-15;
    auto same = [&](const Affine& a, const Affine& b) {
        return (a.A - b.A).cwiseAbs().maxCoeff() <= map_tolerance && (a.b - b.b).cwiseAbs().maxCoeff() <= map_tolerance;
    };
    const Affine about_z = rotation(vec({0.0, 0.0, 1.0}), 30.0, vec({1.0, 2.0, 0.0}));
    const Affine oblique = rotation(vec({1.0, -2.0, 2.0}), 30.0, vec({1.0, 2.0, 0.0}));
    const Affine mirror_y = mirror(vec({0.0, 1.0}), vec({0.0, 1.0}));
    for (double length : {1e300, 1.7e308, 5e-324, 1e-310}) {
        EXPECT_TRUE(same(rotation(vec({0.0, 0.0, length}), 30.0, vec({1.0, 2.0, 0.0})), about_z)) << length;
        if (std::isfinite(2.0 * length)) {
            EXPECT_TRUE(same(rotation(vec({length, -2.0 * length, 2.0 * length}), 30.0, vec({1.0, 2.0, 0.0})), oblique))
                << length;
        }
        EXPECT_TRUE(same(mirror(vec({0.0, length}), vec({0.0, 1.0})), mirror_y)) << length;
    }
    EXPECT_THROW(rotation(vec({0.0, 0.0, std::numeric_limits<double>::infinity()}), 10.0, vec({0.0, 0.0, 0.0})),
                 Error);
}

}  // namespace
}  // namespace iga::nurbs
