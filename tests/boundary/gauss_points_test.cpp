// Side quadrature: weights integrate the exact length / area of curved sides
// (quarter circle, quarter cylinder, sphere octant with its pole), each Gauss point
// carries a consistent basis, collapsed and degenerate sides give finite weights.

#include "boundary/gauss_points.hpp"
#include "mechanics/test_patches.hpp"
#include "nurbs/shapes.hpp"
#include "solids.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace iga::boundary {
namespace {

/// Smooth rational integrands with 12 (16) Gauss points per span: round-off level.
constexpr double fine_rule_error = 1e-12;
/// Sums of a few dozen products of O(1) numbers.
constexpr double round_off = 1e-13;

TEST(GaussPoints, QuarterCircleArcLength)
{
    const double R = 2.5;
    const nurbs::Patch patch = nurbs::quarter_disc((VecN(2) << 1.0, -1.0).finished(), R);
    const PatchSide arc(patch, Side::v0);
    EXPECT_TRUE(test::near_rel(reference_measure(arc, 12), std::numbers::pi * R / 2, fine_rule_error));
    // Straight sides: u0 is linear (exact with the default rule), v1 a rational segment.
    EXPECT_TRUE(test::near_rel(reference_measure(PatchSide(patch, Side::u0), 0), R, round_off));
    EXPECT_TRUE(test::near_rel(reference_measure(PatchSide(patch, Side::v1), 12), R, fine_rule_error));
    EXPECT_EQ(reference_measure(PatchSide(patch, Side::u1), 0), 0.0);  // collapsed
}

TEST(GaussPoints, CylinderAndSphereOctantAreas)
{
    const double R = 1.3, H = 0.7;
    const MatN Q = test::rotation(3, 0.4);
    const VecN t = (VecN(3) << 1.0, 2.0, -0.5).finished();
    const nurbs::Patch shell = test::transformed(test::quarter_cylinder_shell(0.9, R, H), Q, t);
    EXPECT_TRUE(test::near_rel(reference_measure(PatchSide(shell, Side::v1), 12), std::numbers::pi / 2 * R * H,
                               fine_rule_error));
    EXPECT_TRUE(test::near_rel(reference_measure(PatchSide(shell, Side::w1), 12),
                               std::numbers::pi / 4 * (R * R - 0.9 * 0.9), fine_rule_error));

    const nurbs::Patch ball = test::transformed(test::octant_ball(R), Q, t);
    const PatchSide sphere(ball, Side::w1);
    EXPECT_TRUE(test::near_rel(reference_measure(sphere, 16), std::numbers::pi * R * R / 2, fine_rule_error));
    // The flat quarter discs with an edge at the centre.
    for (const Side s : {Side::u0, Side::u1, Side::v0})
        EXPECT_TRUE(test::near_rel(reference_measure(PatchSide(ball, s), 16), std::numbers::pi * R * R / 4,
                                   fine_rule_error))
            << side_name(s);
    EXPECT_EQ(reference_measure(PatchSide(ball, Side::w0), 0), 0.0);  // collapsed to the centre
    // The segment centre-pole: round-off only (its tangents are parallel).
    EXPECT_TRUE(test::at_most(reference_measure(PatchSide(ball, Side::v1), 0), round_off * R * R));
}

TEST(GaussPoints, PointsCarryTheirBasisAndWeights)
{
    // Partition of unity, x = sum N_a X_a, weight = parametric weight * jacobian,
    // parametric weights sum to the side's parameter box, points in element order.
    std::mt19937 rng(5);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        for (int s = 0; s < 2 * d; ++s) {
            const PatchSide side(patch, static_cast<Side>(s));
            const std::vector<GaussPoint> points = gauss_points(side, 3);
            const int per_element = d == 2 ? 3 : 9;
            ASSERT_EQ(static_cast<int>(points.size()), per_element * side.n_elements());
            const RowMatrix& X = side.patch().control_points();
            double parametric = 0.0;
            for (std::size_t g = 0; g < points.size(); ++g) {
                const GaussPoint& gp = points[g];
                EXPECT_EQ(gp.element, static_cast<int>(g) / per_element);
                EXPECT_TRUE(test::near(gp.N.sum(), 1.0, round_off));
                EXPECT_TRUE(test::at_most(std::abs(gp.dN.colwise().sum().sum()), round_off * gp.dN.norm()));
                VecN x = VecN::Zero(d);
                for (std::size_t a = 0; a < gp.indices.size(); ++a)
                    x += gp.N(static_cast<Index>(a)) * X.row(gp.indices[a]).transpose();
                EXPECT_TRUE(test::at_most((x - gp.reference.x).norm(), round_off));
                EXPECT_EQ(gp.weight, gp.parametric_weight * gp.reference.jacobian);
                EXPECT_GT(gp.weight, 0.0);
                parametric += gp.parametric_weight;
            }
            EXPECT_TRUE(test::near(parametric, 1.0, round_off));
            EXPECT_EQ(reference_measure(points), reference_measure(side, 3));
        }
    }
}

TEST(GaussPoints, DegenerateFacesGiveFiniteWeightsAndNormals)
{
    const nurbs::Patch ball = test::octant_ball(1.0);
    for (int s = 0; s < 6; ++s) {
        const PatchSide side(ball, static_cast<Side>(s));
        for (const GaussPoint& gp : gauss_points(side, 4)) {
            EXPECT_TRUE(std::isfinite(gp.weight) && gp.weight >= 0.0) << side_name(side.which());
            EXPECT_TRUE(gp.reference.normal.allFinite() && gp.N.allFinite() && gp.dN.allFinite());
            // A unit normal where the side has one, zero where it has none.
            const double expected = side.outward_sign() == 0 ? 0.0 : 1.0;
            EXPECT_TRUE(test::near(gp.reference.normal.norm(), expected, round_off)) << side_name(side.which());
        }
    }
}

}  // namespace
}  // namespace iga::boundary
