// Tests of side extraction: the side patch is the parent restricted to the side.

#include "core/error.hpp"
#include "nurbs/side_patch.hpp"
#include "random_patch.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <random>

namespace iga::nurbs {
namespace {

// Side and parent evaluate the same rational function with the same control
// points; the parent's extra direction contributes factors that are exactly 0
// or 1 at an open end, so only summation order differs (a few ulp).
constexpr double same_point_tolerance = 1e-13;

TEST(SidePatch, SideMatchesParentOnEverySide)
{
    std::mt19937 rng(31);
    SCOPED_TRACE("seed 31");
    const std::vector<Patch> parents{test::random_patch(rng, {2, 3}, 3, 2), test::random_patch(rng, {3, 1}, 2, 3),
                                     test::random_patch(rng, {2, 1, 3}, 2, 3)};
    for (const Patch& parent : parents) {
        const int n = parent.n_par();
        for (int s = 0; s < 2 * n; ++s) {
            const Side side = static_cast<Side>(s);
            const int fixed = side_direction(side);
            const SidePatch sp = extract_side(parent, side);
            ASSERT_EQ(sp.side, side);
            ASSERT_EQ(sp.patch.n_par(), n - 1);
            ASSERT_EQ(sp.patch.dim(), parent.dim());
            ASSERT_EQ(static_cast<int>(sp.parent_index.size()), sp.patch.n_control_points());
            for (int a = 0; a < sp.patch.n_control_points(); ++a) {
                const int A = sp.parent_index[a];
                EXPECT_EQ(parent.control_point_ijk(A)[fixed], side_at_end(side) ? parent.n_basis(fixed) - 1 : 0);
                EXPECT_EQ(sp.patch.control_points().row(a), parent.control_points().row(A));
                EXPECT_EQ(sp.patch.weights()(a), parent.weights()(A));
            }
            for (int sample = 0; sample < 20; ++sample) {
                const VecN eta = test::random_point(rng, sp.patch);
                VecN xi(n);
                for (int d = 0, m = 0; d < n; ++d)
                    xi(d) = d == fixed ? (side_at_end(side) ? parent.knots(d).back() : parent.knots(d).front())
                                       : eta(m++);
                const PointDerivatives on_side = evaluate(sp.patch, eta, 1);
                const PointDerivatives on_parent = evaluate(parent, xi, 1);
                EXPECT_TRUE(test::at_most((on_side.x - on_parent.x).norm(), same_point_tolerance));
                for (int d = 0, m = 0; d < n; ++d)
                    if (d != fixed) {
                        const double scale = std::max(1.0, on_parent.dx.col(d).norm());
                        EXPECT_TRUE(test::at_most((on_side.dx.col(m++) - on_parent.dx.col(d)).norm(),
                                                  same_point_tolerance * scale));
                    }
            }
        }
    }
}

TEST(SidePatch, CollapsedSides)
{
    const KnotVector k(1, {0, 0, 1, 1});
    RowMatrix P(4, 2);
    P << 0, 0, 1, 0, 0, 0, 1, 1;  // u0 collapsed to the origin; u1 from (1,0) to (1,1)
    const Patch patch({k, k}, P, Vector::Ones(4));
    // A collapsed side has all control points within the tolerance, a real side does not.
    constexpr double collapse_tolerance = 1e-12;
    EXPECT_TRUE(is_collapsed(extract_side(patch, Side::u0), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::u1), collapse_tolerance));
    EXPECT_FALSE(is_collapsed(extract_side(patch, Side::v0), collapse_tolerance));
    RowMatrix Q = P;
    Q(2, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(is_collapsed(extract_side(patch.with_control_points(Q), Side::u0), collapse_tolerance));
}

TEST(SidePatch, PreconditionsAreChecked)
{
    std::mt19937 rng(1);
    EXPECT_THROW(extract_side(test::random_patch(rng, {2}, 2, 2), Side::u0), Error);
    EXPECT_THROW(extract_side(test::random_patch(rng, {2, 2}, 2, 2), Side::w1), Error);
}

}  // namespace
}  // namespace iga::nurbs
