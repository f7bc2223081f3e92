// Tests of the built-in exact shapes: exact arcs, straight tops, documented
// sides, collapsed corners and a positive Jacobian inside.

#include "core/error.hpp"
#include "nurbs/shapes.hpp"
#include "nurbs/side_patch.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace iga::nurbs
