// Element geometry: reference gradients reproduce linear fields, weights sum to the
// reference area, non-positive Jacobians are rejected with their location.

#include "mechanics/element_geometry.hpp"
#include "nurbs/shapes.hpp"
#include "support/tolerance.hpp"
#include "test_patches.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <string>

namespace iga::mechanics {
namespace {

TEST(ElementGeometry, GradientsReproduceLinearFieldsAndSumToZero)
{
    // sum_a X_a (dR_a/dX)^T = I and sum_a dR_a/dX = 0 hold pointwise for any
    // rational basis (linear precision, partition of unity): round-off only.
    constexpr double round_off = 1e-12;
    std::mt19937 rng(12);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.15, 0.3);
        for (const ElementGeometry& g : patch_geometry(patch)) {
            ASSERT_EQ(static_cast<int>(g.points.size()), d == 2 ? 9 : 27);  // default (p + 1)^d
            Matrix X(g.n_local(), d);
            for (int a = 0; a < g.n_local(); ++a)
                X.row(a) = patch.control_points().row(g.indices[static_cast<std::size_t>(a)]);
            for (const QuadraturePoint& q : g.points) {
                EXPECT_TRUE(test::at_most((X.transpose() * q.dR_dX - Matrix::Identity(d, d)).norm(), round_off));
                EXPECT_TRUE(test::at_most(q.dR_dX.colwise().sum().norm(), round_off * q.dR_dX.norm()));
                EXPECT_TRUE(test::near(q.R.sum(), 1.0, round_off));
                EXPECT_TRUE(test::at_most((X.transpose() * q.R - q.X).norm(), round_off));
            }
        }
    }
}

TEST(ElementGeometry, WeightsSumToReferenceArea)
{
    // Quarter annulus 1 <= r <= 2: area 3 pi / 4. det J is smooth but not polynomial,
    // so the default 3-point rule errs by ~1e-4 and a 12-point rule by round-off.
    constexpr double default_rule_error = 1e-3;
    constexpr double fine_rule_error = 1e-12;
    const nurbs::Patch patch = test::quarter_annulus(1.0, 2.0);
    const double exact = 0.75 * std::numbers::pi;
    for (const auto& [n, tolerance] : {std::pair{0, default_rule_error}, std::pair{12, fine_rule_error}}) {
        double area = 0.0;
        for (const ElementGeometry& g : patch_geometry(patch, n))
            for (const QuadraturePoint& q : g.points)
                area += q.weight;
        EXPECT_TRUE(test::near_rel(area, exact, tolerance)) << n << " points";
    }
}

TEST(ElementGeometry, BuiltInDiscShapesArePositivelyOriented)
{
    // The built-in shapes are right-handed (det J > 0 at every interior Gauss point,
    // else element_geometry throws) and their areas are pi R^2 / 2 and pi R^2 / 4,
    // integrated to round-off by 32 points per direction (smooth rational integrands; the
    // cubic arc with weights 1/3 needs more than 16 points for 1e-12).
    constexpr double fine_rule_error = 1e-12;
    const double R = 1.5;
    const VecN center = (VecN(2) << 0.5, 1.0).finished();
    for (const auto& [patch, exact] : {std::pair{nurbs::half_disc(center, R), 0.5 * std::numbers::pi * R * R},
                                       std::pair{nurbs::quarter_disc(center, R), 0.25 * std::numbers::pi * R * R}}) {
        double area = 0.0;
        for (const ElementGeometry& g : patch_geometry(patch, 32))
            for (const QuadraturePoint& q : g.points)
                area += q.weight;
        EXPECT_TRUE(test::near_rel(area, exact, fine_rule_error));
        EXPECT_NO_THROW(patch_geometry(patch));
    }
}

TEST(ElementGeometry, LeftHandedPatchIsRejectedWithLocation)
{
    // Mirroring x makes det(dX/dxi) < 0 everywhere: bad input, reported with the point.
    const nurbs::Patch patch = test::grid_patch({1, 1}, {1, 1}, VecN::Ones(2));
    RowMatrix mirrored = patch.control_points();
    mirrored.col(0) *= -1.0;
    const nurbs::Patch left = patch.with_control_points(mirrored);
    try {
        element_geometry(left, left.elements().front());
        FAIL() << "expected NonPositiveJacobian";
    } catch (const NonPositiveJacobian& e) {
        EXPECT_LT(e.det_J(), 0.0);
        EXPECT_EQ(e.xi().size(), 2);
        EXPECT_NE(std::string(e.what()).find("non-positive Jacobian"), std::string::npos);
    }
}

TEST(ElementGeometry, CollapsedElementIsRejected)
{
    // All control points moved onto the x axis: zero area, det J = 0 at every Gauss point.
    const nurbs::Patch patch = test::grid_patch({1, 1}, {1, 1}, VecN::Ones(2));
    RowMatrix flat = patch.control_points();
    flat.col(1).setZero();
    const nurbs::Patch collapsed = patch.with_control_points(flat);
    EXPECT_THROW(element_geometry(collapsed, collapsed.elements().front()), NonPositiveJacobian);
}

}  // namespace
}  // namespace iga::mechanics
