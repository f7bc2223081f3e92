// Cauchy stress recovery at parameter points: homogeneous small strain, the
// Eulerian neo-Hookean closed form under rotated stretches, zero stress under rotation.

#include "mechanics/stress_recovery.hpp"
#include "support/tolerance.hpp"
#include "test_patches.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace iga::mechanics {
namespace {

/// Displacements u_A = (F - I) X_A: the rational basis reproduces x = F X exactly.
RowMatrix homogeneous(const nurbs::Patch& patch, const MatN& F)
{
    const int d = patch.dim();
    return patch.control_points() * (F - MatN::Identity(d, d)).transpose();
}

/// A few parameter points inside and on the boundary of [0, 1]^d.
std::vector<VecN> sample_points(int d)
{
    std::vector<VecN> out;
    for (const double s : {0.0, 0.3, 0.77, 1.0}) {
        VecN xi(d);
        for (int i = 0; i < d; ++i)
            xi(i) = std::fmod(s + 0.21 * i, 1.0 + 1e-12);
        out.push_back(xi);
    }
    return out;
}

TEST(StressRecovery, HomogeneousSmallStrainGivesHookeStress)
{
    // sigma = lambda tr(eps) I + 2 mu eps (plane strain / 3D), or with lambda* in plane
    // stress; exact reproduction, round-off of O(E |eps|).
    constexpr double round_off = 1e-12;
    std::mt19937 rng(6);
    for (const PlaneMode plane : {PlaneMode::strain, PlaneMode::stress, PlaneMode::none}) {
        const int d = spatial_dim(plane);
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 2);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        const Material m{MaterialModel::neo_hookean, 10.0, 0.3, plane};
        const MatN G = test::random_matrix(d, d, rng, 1e-3);
        const MatN eps = 0.5 * (G + G.transpose());
        const Lame l = lame_parameters(m);
        const double lambda = plane == PlaneMode::stress ? 2 * l.lambda * l.mu / (l.lambda + 2 * l.mu) : l.lambda;
        const MatN expected = lambda * eps.trace() * MatN::Identity(d, d) + 2 * l.mu * eps;
        const RowMatrix u = homogeneous(patch, MatN(MatN::Identity(d, d) + G));
        for (const VecN& xi : sample_points(d)) {
            const PointStress s = cauchy_stress(patch, m, Kinematics::small, u, xi);
            ASSERT_EQ(s.status, ResponseStatus::ok);
            EXPECT_TRUE(test::at_most((s.cauchy - expected).norm(), round_off * m.E));
        }
    }
}

/// sigma = mu / J (b - I) + lambda ln J / J I with b = F F^T (the Eulerian form of
/// the compressible neo-Hookean law); in plane stress J includes lambda3 from
/// mu (lambda3^2 - 1) + lambda ln J = 0, solved here by scalar Newton in lambda3.
MatN neo_hookean_cauchy(const Material& m, const MatN& F)
{
    const Lame l = lame_parameters(m);
    const int d = static_cast<int>(F.rows());
    double J = F.determinant();
    if (m.plane == PlaneMode::stress) {
        double lambda3 = 1.0;
        for (int it = 0; it < 50; ++it) {
            const double g = l.mu * (lambda3 * lambda3 - 1.0) + l.lambda * std::log(J * lambda3);
            lambda3 -= g / (2.0 * l.mu * lambda3 + l.lambda / lambda3);
        }
        J *= lambda3;
    }
    const MatN b = F * F.transpose();
    return l.mu / J * (b - MatN::Identity(d, d)) + l.lambda * std::log(J) / J * MatN::Identity(d, d);
}

TEST(StressRecovery, NeoHookeanCauchyStressMatchesEulerianClosedForm)
{
    // Homogeneous F = Q U with a stretch of ~20%: exact reproduction, the local plane-stress
    // solve converges to round-off; differences are rounding of O(E).
    constexpr double round_off = 1e-11;
    // Positions x = F X are sums of O(1) terms: rounding only.
    constexpr double position_round_off = 1e-13;
    std::mt19937 rng(21);
    for (const PlaneMode plane : {PlaneMode::strain, PlaneMode::stress, PlaneMode::none}) {
        const int d = spatial_dim(plane);
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 1);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.1, 0.3);
        const Material m{MaterialModel::neo_hookean, 10.0, 0.3, plane};
        const MatN G = test::random_matrix(d, d, rng, 0.2);
        const MatN F = test::rotation(d, 0.7) * MatN(MatN::Identity(d, d) + 0.5 * (G + G.transpose()));
        const MatN expected = neo_hookean_cauchy(m, F);
        const RowMatrix u = homogeneous(patch, F);
        for (const VecN& xi : sample_points(d)) {
            const PointStress s = cauchy_stress(patch, m, Kinematics::finite, u, xi);
            ASSERT_EQ(s.status, ResponseStatus::ok);
            EXPECT_TRUE(test::at_most((s.cauchy - expected).norm(), round_off * m.E)) << "d = " << d;
            EXPECT_TRUE(test::at_most((s.x - F * s.X).norm(), position_round_off * (1.0 + s.X.norm())));
        }
    }
}

TEST(StressRecovery, RigidRotationIsStressFree)
{
    // F = Q: E = 0 to round-off, so sigma ~ eps E.
    constexpr double round_off = 1e-12;
    const nurbs::Patch patch = test::quarter_annulus(1.0, 2.0);
    for (const MaterialModel model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hookean}) {
        const Material m{model, 10.0, 0.3, PlaneMode::stress};
        const RowMatrix u = homogeneous(patch, test::rotation(2, 2.0));
        for (const VecN& xi : sample_points(2)) {
            const PointStress s = cauchy_stress(patch, m, Kinematics::finite, u, xi);
            EXPECT_TRUE(test::at_most(s.cauchy.norm(), round_off * m.E));
        }
    }
}

}  // namespace
}  // namespace iga::mechanics
