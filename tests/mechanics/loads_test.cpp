// Loads: total force on a curved side, consistent nodal forces of a traction,
// outward normal sign on every side, follower pressure tangent = FD, rotation of
// the follower pressure with the body, gravity, pressure on a sphere octant with its
// pole, a folded side rejected.

#include "mechanics/loads.hpp"
#include "boundary/solids.hpp"
#include "nurbs/shapes.hpp"
#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"
#include "test_patches.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace iga::mechanics {
namespace {

constexpr Side sides_2d[] = {Side::u0, Side::u1, Side::v0, Side::v1};
constexpr Side sides_3d[] = {Side::u0, Side::u1, Side::v0, Side::v1, Side::w0, Side::w1};

/// Sum over a side of the nodal force vectors: the resultant (d). Heap vectors here:
/// GCC 12 reports a false -Warray-bounds on vectorized differences of capped VecN.
Vector resultant(const std::vector<Vector>& forces, int d)
{
    Vector total = Vector::Zero(d);
    for (const Vector& f : forces)
        for (Index a = 0; a < f.size() / d; ++a)
            total += f.segment(a * d, d);
    return total;
}

Matrix local_displacement(const RowMatrix& u, const std::vector<int>& indices)
{
    Matrix out(static_cast<Index>(indices.size()), u.cols());
    for (std::size_t a = 0; a < indices.size(); ++a)
        out.row(static_cast<Index>(a)) = u.row(indices[a]);
    return out;
}

TEST(Loads, TotalForceOnCurvedSideIsExact)
{
    // t = F / A_0 with A_0 from the same quadrature, and the rational basis sums to one:
    // the nodal forces add up to F to round-off, however coarse the quadrature.
    constexpr double round_off = 1e-14;
    const nurbs::Patch patch = test::quarter_annulus(1.0, 2.0);
    const SideQuadrature side = side_quadrature(patch, Side::u1);  // outer arc
    VecN F(2);
    F << 3.0, -7.0;
    const VecN t = F / reference_measure(side);
    std::vector<Vector> forces;
    for (const SideElement& e : side.elements)
        forces.push_back(dead_traction(e, 2, t).f_ext);
    EXPECT_TRUE(test::at_most((resultant(forces, 2) - F).norm(), round_off * F.norm()));
}

TEST(Loads, ReferenceLengthOfArcConvergesToQuarterCircle)
{
    // The rational quadratic is an exact circle; |dX/ds| is smooth (not polynomial),
    // so the default 3-point rule is accurate to ~1e-4 and 12 points to round-off.
    constexpr double default_rule_error = 1e-3;
    constexpr double fine_rule_error = 1e-12;
    const nurbs::Patch patch = test::quarter_annulus(1.0, 2.0);
    const double exact = std::numbers::pi;  // (pi / 2) * 2
    EXPECT_TRUE(test::near_rel(reference_measure(side_quadrature(patch, Side::u1)), exact, default_rule_error));
    EXPECT_TRUE(test::near_rel(reference_measure(side_quadrature(patch, Side::u1, 12)), exact, fine_rule_error));
    EXPECT_TRUE(test::near_rel(reference_measure(side_quadrature(patch, Side::u0, 12)), exact / 2, fine_rule_error));
}

TEST(Loads, TractionOnStraightSideGivesConsistentNodalForces)
{
    // Quadratic B-splines on knots {0,0,0,1/2,1,1,1} integrate to 1/6, 1/3, 1/3, 1/6 of
    // the length (Greville spacing); p + 1 Gauss points are exact for them.
    constexpr double round_off = 1e-14;
    const nurbs::Patch patch = test::grid_patch({2, 1}, {2, 1}, (VecN(2) << 4.0, 1.0).finished());
    const SideQuadrature side = side_quadrature(patch, Side::v1);  // top, y = 1, length 4
    VecN t(2);
    t << 0.5, -2.0;
    Vector nodal = Vector::Zero(patch.n_control_points() * 2);
    for (const SideElement& e : side.elements) {
        const LocalForce f = dead_traction(e, 2, t);
        for (std::size_t a = 0; a < f.indices.size(); ++a)
            nodal.segment(f.indices[a] * 2, 2) += f.f_ext.segment(static_cast<Index>(a) * 2, 2);
    }
    const double share[] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    for (int i = 0; i < 4; ++i) {
        const int top = i + 4 * 1;  // control point (i, 1)
        const int bottom = i;
        EXPECT_TRUE(test::at_most((nodal.segment(top * 2, 2) - share[i] * 4.0 * t).norm(), round_off * 4.0 * t.norm()));
        EXPECT_TRUE(test::at_most(nodal.segment(bottom * 2, 2).norm(), 0.0));
    }
}

TEST(Loads, PressurePushesAlongInwardNormalOnEverySide)
{
    // On an axis-aligned box the resultant of a pressure p on a side is -p n_out |side|,
    // integrated exactly (constant normal, polynomial basis): round-off only.
    constexpr double round_off = 1e-13;
    const double p = 2.5;
    for (const int d : {2, 3}) {
        VecN size(d);
        size(0) = 3.0;
        size(1) = 2.0;
        if (d == 3)
            size(2) = 1.5;
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::grid_patch(degrees, spans, size);
        const int n_sides = 2 * d;
        for (int s = 0; s < n_sides; ++s) {
            const Side which = d == 2 ? sides_2d[s] : sides_3d[s];
            const SideQuadrature side = side_quadrature(patch, which);
            const int dir = side_direction(which);
            const double area = size.prod() / size(dir);
            Vector expected = Vector::Zero(d);
            expected(dir) = -p * area * (side_at_end(which) ? 1.0 : -1.0);
            for (const Kinematics kin : {Kinematics::small, Kinematics::finite}) {
                std::vector<Vector> forces;
                for (const SideElement& e : side.elements) {
                    const Matrix zero = Matrix::Zero(e.n_local(), d);
                    const LocalForceTangent f = follower_pressure(e, d, p, kin, zero);
                    forces.push_back(f.f_ext);
                    if (kin == Kinematics::small) {
                        EXPECT_EQ(f.df_ext_du.size(), 0);
                    }
                }
                EXPECT_TRUE(test::at_most((resultant(forces, d) - expected).norm(), round_off * p * area))
                    << "d = " << d << ", side " << side_name(which);
            }
            EXPECT_TRUE(test::near_rel(reference_measure(side), area, round_off));
        }
    }
}

TEST(Loads, PressureOnCurvedSideMatchesArcIntegral)
{
    // Outer arc of radius R: int n ds over the quarter = R (1, 1); 12 Gauss points
    // integrate the smooth rational integrand to round-off.
    constexpr double fine_rule_error = 1e-12;
    const double R = 2.0, p = 3.0;
    const nurbs::Patch patch = test::quarter_annulus(1.0, R);
    const SideQuadrature side = side_quadrature(patch, Side::u1, 12);
    std::vector<Vector> forces;
    for (const SideElement& e : side.elements)
        forces.push_back(follower_pressure(e, 2, p, Kinematics::small, Matrix()).f_ext);
    const Vector total = resultant(forces, 2);
    EXPECT_TRUE(test::near_rel(total(0), -p * R, fine_rule_error));
    EXPECT_TRUE(test::near_rel(total(1), -p * R, fine_rule_error));
}

TEST(Loads, FollowerPressureTangentIsDerivative)
{
    // The pressure force is linear (2D) or quadratic (3D) in u: central differences are
    // exact up to round-off eps |f| / h ~ 1e-10 relative for h = 1e-6.
    constexpr double fd_step = 1e-6;
    constexpr double fd_tolerance = 1e-8;
    std::mt19937 rng(31);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        const RowMatrix u = test::random_matrix(patch.n_control_points(), d, rng, 0.05);
        for (const Side s : {Side::u0, Side::v1, d == 3 ? Side::w1 : Side::u1}) {
            const SideQuadrature side = side_quadrature(patch, s);
            for (const SideElement& e : side.elements) {
                const Matrix u_local = local_displacement(u, e.indices);
                const LocalForceTangent f = follower_pressure(e, d, 1.7, Kinematics::finite, u_local);
                const Matrix fd = test::central_difference_jacobian(
                    [&](const Vector& v) {
                        return follower_pressure(e, d, 1.7, Kinematics::finite, test::unflatten(v, d)).f_ext;
                    },
                    test::flatten(u_local), fd_step);
                EXPECT_TRUE(test::at_most((f.df_ext_du - fd).norm() / fd.norm(), fd_tolerance))
                    << "d = " << d << ", side " << side_name(s);
                // Not symmetric element by element: R_a dR_b != -R_b dR_a. A symmetrized
                // tangent would be off by O(1); 1e-3 only rules out accidental symmetry.
                constexpr double asymmetry = 1e-3;
                EXPECT_TRUE(test::at_least((f.df_ext_du - f.df_ext_du.transpose()).norm(), asymmetry * fd.norm()));
            }
        }
    }
}

TEST(Loads, FollowerPressureRotatesWithTheBody)
{
    // Under a rigid rotation x = Q X the pressure force on each node turns by Q:
    // exact rotation of exact (polynomial in u) expressions, round-off only.
    constexpr double round_off = 1e-13;
    std::mt19937 rng(4);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 1);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        const MatN Q = test::rotation(d, 0.9);
        const RowMatrix X = patch.control_points();
        const RowMatrix u = X * (Q - MatN::Identity(d, d)).transpose();
        const SideQuadrature side = side_quadrature(patch, Side::v0);
        for (const SideElement& e : side.elements) {
            const Matrix zero = Matrix::Zero(e.n_local(), d);
            const Vector f0 = follower_pressure(e, d, 1.0, Kinematics::finite, zero).f_ext;
            const Vector f1 = follower_pressure(e, d, 1.0, Kinematics::finite, local_displacement(u, e.indices)).f_ext;
            for (int a = 0; a < e.n_local(); ++a)
                EXPECT_TRUE(test::at_most((f1.segment(a * d, d) - Q * f0.segment(a * d, d)).norm(),
                                          round_off * f0.norm()));
        }
    }
}

TEST(Loads, GravitySumsToWeight)
{
    // Partition of unity and an affine element: sum = rho g |body| to round-off.
    constexpr double round_off = 1e-14;
    const nurbs::Patch patch = test::grid_patch({2, 3}, {3, 2}, (VecN(2) << 2.0, 0.5).finished());
    VecN g(2);
    g << 0.0, -9.81;
    std::vector<Vector> forces;
    for (const nurbs::Element& el : patch.elements())
        forces.push_back(gravity(element_geometry(patch, el), 7.8, g).f_ext);
    const VecN expected = 7.8 * 1.0 * g;  // area 2 x 0.5 = 1
    EXPECT_TRUE(test::at_most((resultant(forces, 2) - expected).norm(), round_off * expected.norm()));
}

TEST(Loads, PressureOnBuiltInHalfDiscArcPushesUp)
{
    // half_disc (nurbs/shapes.hpp): v0 is the lower half circle, whose outward normal
    // integrates to (0, -2R); a pressure p therefore pushes with (0, 2 p R). The
    // collapsed sides u0, u1 carry nothing. 32 points: the rational cubic integrand
    // is smooth, integrated to round-off.
    constexpr double fine_rule_error = 1e-12;
    const double R = 1.5, p = 2.0;
    const nurbs::Patch patch = nurbs::half_disc((VecN(2) << 0.5, 1.0).finished(), R);
    const SideQuadrature arc = side_quadrature(patch, Side::v0, 32);
    std::vector<Vector> forces;
    for (const SideElement& e : arc.elements)
        forces.push_back(follower_pressure(e, 2, p, Kinematics::small, Matrix()).f_ext);
    const Vector total = resultant(forces, 2);
    EXPECT_TRUE(test::near(total(0), 0.0, fine_rule_error * p * R));
    EXPECT_TRUE(test::near_rel(total(1), 2.0 * p * R, fine_rule_error));
    EXPECT_TRUE(test::near_rel(reference_measure(arc), std::numbers::pi * R, fine_rule_error));
    for (const Side collapsed : {Side::u0, Side::u1}) {
        const SideQuadrature side = side_quadrature(patch, collapsed);
        EXPECT_EQ(reference_measure(side), 0.0);
        for (const SideElement& e : side.elements) {
            const Matrix u = Matrix::Constant(e.n_local(), 2, 0.1);
            EXPECT_EQ(follower_pressure(e, 2, p, Kinematics::finite, u).f_ext.norm(), 0.0);
        }
    }
}

TEST(Loads, PressureAndForceOnSphereOctantWithItsPole)
{
    // int n dA over the octant x, y, z >= 0 of a sphere = (pi R^2 / 4) (1, 1, 1) (its
    // projections on the coordinate planes). The face has its edge v = 1 collapsed to the
    // pole, where the area element vanishes; 16 points integrate the smooth rational
    // integrand to round-off. A force spread over it sums to F exactly.
    constexpr double fine_rule_error = 1e-12;
    constexpr double round_off = 1e-14;
    const double R = 1.3, p = 0.8;
    const nurbs::Patch ball = test::octant_ball(R);
    const SideQuadrature sphere = side_quadrature(ball, Side::w1, 16);
    for (const Kinematics kin : {Kinematics::small, Kinematics::finite}) {
        std::vector<Vector> forces;
        for (const SideElement& e : sphere.elements)
            forces.push_back(follower_pressure(e, 3, p, kin, Matrix::Zero(e.n_local(), 3)).f_ext);
        const Vector total = resultant(forces, 3);
        for (int i = 0; i < 3; ++i)
            EXPECT_TRUE(test::near_rel(total(i), -p * std::numbers::pi * R * R / 4, fine_rule_error));
    }
    const VecN F = (VecN(3) << 1.0, -2.0, 0.5).finished();
    const VecN t = F / reference_measure(sphere);
    std::vector<Vector> forces;
    for (const SideElement& e : sphere.elements)
        forces.push_back(dead_traction(e, 3, t).f_ext);
    EXPECT_TRUE(test::at_most((resultant(forces, 3) - F).norm(), round_off * F.norm()));
    // The centre face (collapsed) and the pole segment (zero area) carry nothing.
    for (const Side s : {Side::w0, Side::v1}) {
        const SideQuadrature side = side_quadrature(ball, s);
        EXPECT_TRUE(test::at_most(reference_measure(side), round_off * R * R));
        for (const SideElement& e : side.elements)
            EXPECT_EQ(follower_pressure(e, 3, p, Kinematics::finite, Matrix::Zero(e.n_local(), 3)).f_ext.norm(), 0.0);
    }
}

TEST(Loads, FoldedSideIsRejected)
{
    // dX/dv at v = 0 has y-component 1 - 8u + 10u^2: it changes sign along side v0.
    const nurbs::Patch patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1})},
                             (RowMatrix(6, 2) << 0, 0, 1, 0, 2, 0, 0, 1, 1, -3, 2, 3).finished(), Vector::Ones(6));
    EXPECT_THROW(side_quadrature(patch, Side::v0), boundary::FoldedSide);
}

}  // namespace
}  // namespace iga::mechanics
