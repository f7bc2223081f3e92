// Orientation signs of contact sides (boundary::outward_sign) and the global element search.

#include "contact/contact_pair.hpp"
#include "contact/gap.hpp"
#include "boundary/patch_side.hpp"
#include "contact/projection.hpp"
#include "contact/search.hpp"

#include "fixtures.hpp"
#include "support/tolerance.hpp"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace iga::contact {
namespace {

using boundary::outward_sign;
using test::vec2;

/// Outward normal of side `side` of `parent` at the middle of the side.
VecN outward_normal_at_middle(const nurbs::Patch& parent, Side side)
{
    const nurbs::SidePatch s = nurbs::extract_side(parent, side);
    const nurbs::KnotVector& k = s.patch.knots(0);
    VecN xi(1);
    xi(0) = 0.5 * (k.front() + k.back());
    const nurbs::PointDerivatives p = nurbs::evaluate(s.patch, xi, 1);
    return curve_normal_2d(p.dx.col(0), outward_sign(parent, side));
}

// Normals of axis-aligned sides are exact up to round-off.
constexpr double normal_tolerance = 1e-14;
// The half disc's rational cubic arc: a few more operations, still round-off.
constexpr double arc_normal_tolerance = 1e-13;

TEST(Orientation, RectangleSidesPointOutward)
{
    const nurbs::Patch block = nurbs::rectangle(vec2(1, 2), vec2(3, 1));
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(block, Side::u0) - vec2(-1, 0)).norm(), normal_tolerance));
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(block, Side::u1) - vec2(1, 0)).norm(), normal_tolerance));
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(block, Side::v0) - vec2(0, -1)).norm(), normal_tolerance));
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(block, Side::v1) - vec2(0, 1)).norm(), normal_tolerance));
}

TEST(Orientation, MirroredParametrizationFlipsTheSign)
{
    const nurbs::Patch block = nurbs::rectangle(vec2(0, 0), vec2(2, 1));
    RowMatrix P = block.control_points();
    P.col(0) = -P.col(0);  // u now runs along -x: same sides, opposite orientation
    const nurbs::Patch mirrored = block.with_control_points(P);
    for (const Side s : {Side::u0, Side::u1, Side::v0, Side::v1})
        EXPECT_EQ(outward_sign(mirrored, s), -outward_sign(block, s)) << side_name(s);
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(mirrored, Side::v1) - vec2(0, 1)).norm(), normal_tolerance));
}

TEST(Orientation, HalfDiscArcPointsAwayFromTheCentre)
{
    // The arc's end points are degenerate corners (dX/dv = 0 there); the sign
    // must still be found, and the lowest point's normal is straight down.
    const nurbs::Patch disc = nurbs::half_disc(vec2(0, 1), 1.0);
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(disc, Side::v0) - vec2(0, -1)).norm(), arc_normal_tolerance));
    EXPECT_TRUE(test::at_most((outward_normal_at_middle(disc, Side::v1) - vec2(0, 1)).norm(), arc_normal_tolerance));
}

TEST(Orientation, CurvedBlockTopPointsUp)
{
    const nurbs::Patch block = test::curved_block();
    EXPECT_TRUE(test::at_least(outward_normal_at_middle(block, Side::v1)(1), 0.9));
}

TEST(Orientation, CurvesAreClearErrorsAndCubeFacesPointOutward)
{
    const nurbs::Patch curve = test::quarter_arc(1.0);
    EXPECT_THROW(DeformableSide::make(curve, Side::u0), Error);  // a curve has no contact side
    // A trilinear unit cube: every face is a contact surface whose normal points out.
    RowMatrix P(8, 3);
    for (int a = 0; a < 8; ++a)
        P.row(a) << a % 2, (a / 2) % 2, a / 4;
    const nurbs::KnotVector linear(1, {0, 0, 1, 1});
    const nurbs::Patch cube({linear, linear, linear}, P, Vector::Ones(8));
    for (int k = 0; k < 6; ++k) {
        const Side s = static_cast<Side>(k);
        const DeformableSide face = DeformableSide::make(cube, s);
        VecN mid(2);
        mid << 0.5, 0.5;
        const nurbs::PointDerivatives p = nurbs::evaluate(face.pieces[0].side.patch, mid, 1);
        const VecN n = face.pieces[0].outward_sign * boundary::raw_normal(p.dx).normalized();
        VecN expected = VecN::Zero(3);
        expected(side_direction(s)) = side_at_end(s) ? 1.0 : -1.0;
        EXPECT_TRUE(test::near((n - expected).norm(), 0.0, normal_tolerance)) << side_name(s);
    }
}

TEST(Search, CandidatesContainTheFootPointSpan)
{
    nurbs::Patch half = test::two_quarter_half_circle(1.0);
    half = nurbs::insert_knots(half, 0, {0.125, 0.25, 0.375, 0.625, 0.75, 0.875});
    const ElementSearch search(half, SearchOptions{.distance = 0.05});
    EXPECT_EQ(search.n_elements(), 8);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(0.0, 3.14159), radius(0.96, 1.04);
    for (int k = 0; k < 200; ++k) {
        const double t = angle(rng), r = radius(rng);
        const VecN x = vec2(r * std::cos(t), r * std::sin(t));
        const std::vector<int> c = search.candidates(x);
        const Projection p = project_to_surface(half, +1, x);
        ASSERT_EQ(p.status, Projection::Status::ok);
        const int foot_span = p.element;
        EXPECT_TRUE(std::find(c.begin(), c.end(), foot_span) != c.end()) << "seed 11, sample " << k;
        EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
    }
}

TEST(Search, FarPointsHaveNoCandidates)
{
    const nurbs::Patch arc = test::quarter_arc(1.0);
    const ElementSearch search(arc, SearchOptions{.distance = 0.1});
    EXPECT_TRUE(search.candidates(vec2(5, 5)).empty());
    EXPECT_TRUE(search.candidates(vec2(-2, 0.5)).empty());
    EXPECT_FALSE(search.candidates(vec2(0.7, 0.7)).empty());
    // The union box covers the arc, inflated.
    EXPECT_TRUE(search.bounds().contains(vec2(1.05, 0.0)));
    EXPECT_FALSE(search.bounds().overlaps(Box{vec2(3, 3), vec2(4, 4)}));
}

}  // namespace
}  // namespace iga::contact
