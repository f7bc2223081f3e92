// Pointwise material response: closed forms, tangent = FD of stress, stress = FD
// of energy, consistent linearization, plane-stress condition, failure status.

#include "mechanics/material.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace iga::mechanics {
namespace {

constexpr MaterialModel all_models[] = {MaterialModel::linear_elastic, MaterialModel::saint_venant_kirchhoff,
                                        MaterialModel::neo_hookean};
constexpr PlaneMode all_planes[] = {PlaneMode::strain, PlaneMode::stress, PlaneMode::none};
constexpr Kinematics all_kinematics[] = {Kinematics::small, Kinematics::finite};

std::string label(MaterialModel m, PlaneMode p, Kinematics k, double nu)
{
    const char* models[] = {"linear_elastic", "saint_venant_kirchhoff", "neo_hookean"};
    const char* planes[] = {"plane strain", "plane stress", "3D"};
    return std::string(models[static_cast<int>(m)]) + ", " + planes[static_cast<int>(p)] + ", " +
           (k == Kinematics::small ? "small" : "finite") + ", nu = " + std::to_string(nu);
}

/// Symmetric d x d strain with entries uniform in [-scale, scale].
MatN random_strain(int d, std::mt19937& rng, double scale)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    MatN e(d, d);
    for (int i = 0; i < d; ++i)
        for (int j = i; j < d; ++j)
            e(i, j) = e(j, i) = scale * unit(rng);
    return e;
}

TEST(Material, LameParametersMatchDefinition)
{
    // Two floating-point operations of rounding each.
    constexpr double round_off = 1e-14;
    const Lame l = lame_parameters({MaterialModel::linear_elastic, 210.0, 0.3, PlaneMode::none});
    EXPECT_TRUE(test::near_rel(l.lambda, 210.0 * 0.3 / (1.3 * 0.4), round_off));
    EXPECT_TRUE(test::near_rel(l.mu, 210.0 / 2.6, round_off));
}

TEST(Material, HookeTangentMatchesTextbookMatrices)
{
    // Closed-form matrices from E, nu: a few roundings of O(E).
    constexpr double round_off = 1e-13;
    const double E = 3.0, nu = 0.25;
    const MatN zero2 = MatN::Zero(2, 2);

    VoigtMatrix strain_d(3, 3), stress_d(3, 3);
    const double c = E / ((1 + nu) * (1 - 2 * nu));
    strain_d << c * (1 - nu), c * nu, 0, c * nu, c * (1 - nu), 0, 0, 0, c * (1 - 2 * nu) / 2;
    const double s = E / (1 - nu * nu);
    stress_d << s, s * nu, 0, s * nu, s, 0, 0, 0, s * (1 - nu) / 2;

    const auto plane_strain = small_strain_response({MaterialModel::linear_elastic, E, nu, PlaneMode::strain}, zero2);
    const auto plane_stress = small_strain_response({MaterialModel::linear_elastic, E, nu, PlaneMode::stress}, zero2);
    EXPECT_TRUE(test::at_most((plane_strain.tangent - strain_d).norm(), round_off * E));
    EXPECT_TRUE(test::at_most((plane_stress.tangent - stress_d).norm(), round_off * E));

    VoigtMatrix d3 = VoigtMatrix::Zero(6, 6);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            d3(i, j) = c * nu;
        d3(i, i) = c * (1 - nu);
        d3(i + 3, i + 3) = c * (1 - 2 * nu) / 2;
    }
    const auto solid = small_strain_response({MaterialModel::linear_elastic, E, nu, PlaneMode::none}, MatN::Zero(3, 3));
    EXPECT_TRUE(test::at_most((solid.tangent - d3).norm(), round_off * E));
}

TEST(Material, PlaneStressSaintVenantKirchhoffUsesReducedLambda)
{
    // S = lambda* tr(E) I + 2 mu E, lambda* = 2 lambda mu / (lambda + 2 mu): exact
    // reduction, so agreement to round-off of the local Newton (|S| ~ 0.1 E).
    constexpr double round_off = 1e-12;
    std::mt19937 rng(11);
    const Material m{MaterialModel::saint_venant_kirchhoff, 5.0, 0.35, PlaneMode::stress};
    const Lame l = lame_parameters(m);
    const double lambda_star = 2 * l.lambda * l.mu / (l.lambda + 2 * l.mu);
    const MatN E2 = random_strain(2, rng, 0.1);
    const auto r = finite_strain_response(m, E2);
    const MatN expected = lambda_star * E2.trace() * MatN::Identity(2, 2) + 2 * l.mu * E2;
    ASSERT_EQ(r.status, ResponseStatus::ok);
    EXPECT_TRUE(test::at_most((r.stress - expected).norm(), round_off * m.E));
    EXPECT_TRUE(test::near_rel(r.strain33, -l.lambda * E2.trace() / (l.lambda + 2 * l.mu), round_off));
}

TEST(Material, TangentIsCentralDifferenceOfStress)
{
    // Central differences with h = 1e-5 on strains ~0.1: truncation ~h^2 |S'''| ~ 1e-9 E,
    // round-off ~eps |S| / h ~ 1e-12 E; a wrong tangent term is O(0.1) relative.
    constexpr double fd_step = 1e-5;
    constexpr double fd_tolerance = 1e-7;
    // Tangents are symmetric in exact arithmetic; C^-1 is symmetric only to rounding.
    constexpr double symmetry_round_off = 1e-13;
    std::mt19937 rng(2024);
    for (const double nu : {0.3, 0.45})
        for (const MaterialModel model : all_models)
            for (const PlaneMode plane : all_planes)
                for (const Kinematics kin : all_kinematics) {
                    const Material m{model, 7.0, nu, plane};
                    const int d = spatial_dim(plane);
                    const int nv = n_voigt(d);
                    const MatN strain = random_strain(d, rng, 0.1);
                    const auto r = stress_response(m, kin, strain);
                    ASSERT_EQ(r.status, ResponseStatus::ok) << label(model, plane, kin, nu);
                    VoigtMatrix fd(nv, nv);
                    const VoigtVector v = strain_to_voigt(strain);
                    for (int J = 0; J < nv; ++J) {
                        VoigtVector vp = v, vm = v;
                        vp(J) += fd_step;
                        vm(J) -= fd_step;
                        const auto rp = stress_response(m, kin, strain_from_voigt(vp, d));
                        const auto rm = stress_response(m, kin, strain_from_voigt(vm, d));
                        fd.col(J) = (stress_to_voigt(rp.stress) - stress_to_voigt(rm.stress)) / (2 * fd_step);
                    }
                    const double err = (r.tangent - fd).norm() / fd.norm();
                    EXPECT_TRUE(test::at_most(err, fd_tolerance)) << label(model, plane, kin, nu);
                    // Hyperelastic tangents are symmetric; the condensation keeps that.
                    EXPECT_TRUE(test::at_most((r.tangent - r.tangent.transpose()).norm() / r.tangent.norm(), symmetry_round_off))
                        << label(model, plane, kin, nu);
                }
}

TEST(Material, StressIsCentralDifferenceOfEnergy)
{
    // Same step and error budget as above, one derivative lower (W ~ 1e-2 E).
    constexpr double fd_step = 1e-5;
    constexpr double fd_tolerance = 1e-7;
    std::mt19937 rng(99);
    for (const MaterialModel model : all_models)
        for (const PlaneMode plane : all_planes)
            for (const Kinematics kin : all_kinematics) {
                const Material m{model, 7.0, 0.3, plane};
                const int d = spatial_dim(plane);
                const MatN strain = random_strain(d, rng, 0.1);
                const auto r = stress_response(m, kin, strain);
                const VoigtVector v = strain_to_voigt(strain);
                VoigtVector fd(n_voigt(d));
                for (int J = 0; J < n_voigt(d); ++J) {
                    VoigtVector vp = v, vm = v;
                    vp(J) += fd_step;
                    vm(J) -= fd_step;
                    fd(J) = (stress_response(m, kin, strain_from_voigt(vp, d)).energy -
                             stress_response(m, kin, strain_from_voigt(vm, d)).energy) /
                            (2 * fd_step);
                }
                const double err = (stress_to_voigt(r.stress) - fd).norm() / fd.norm();
                EXPECT_TRUE(test::at_most(err, fd_tolerance)) << label(model, plane, kin, 0.3);
            }
}

TEST(Material, AllModelsLinearizeToHooke)
{
    // At E = 0 every finite law has S = 0, W = 0 and the Hooke tangent, to round-off of O(E).
    constexpr double round_off = 1e-13;
    for (const MaterialModel model : all_models)
        for (const PlaneMode plane : all_planes) {
            const Material m{model, 7.0, 0.3, plane};
            const int d = spatial_dim(plane);
            const auto finite = finite_strain_response(m, MatN::Zero(d, d));
            const auto small = small_strain_response(m, MatN::Zero(d, d));
            EXPECT_TRUE(test::at_most(finite.stress.norm(), round_off * m.E)) << label(model, plane, Kinematics::finite, 0.3);
            EXPECT_TRUE(test::at_most(std::abs(finite.energy), round_off * m.E));
            EXPECT_TRUE(test::at_most((finite.tangent - small.tangent).norm(), round_off * m.E))
                << label(model, plane, Kinematics::finite, 0.3);
        }
}

TEST(Material, PlaneStressMatchesThreeDimensionalLawWithZeroS33)
{
    // The 2D plane-stress state is the 3D state at (E2, E33): same in-plane S and
    // S33 = 0, to the local Newton's tolerance (1e-13 of the stress scale) plus round-off.
    constexpr double solve_tolerance = 1e-12;
    std::mt19937 rng(5);
    for (const MaterialModel model : all_models) {
        const Material m2{model, 7.0, 0.3, PlaneMode::stress};
        const Material m3{model, 7.0, 0.3, PlaneMode::none};
        const MatN E2 = random_strain(2, rng, 0.1);
        const auto r2 = finite_strain_response(m2, E2);
        MatN E3 = MatN::Zero(3, 3);
        E3.topLeftCorner(2, 2) = E2;
        E3(2, 2) = r2.strain33;
        const auto r3 = finite_strain_response(m3, E3);
        EXPECT_TRUE(test::at_most(std::abs(r3.stress(2, 2)), solve_tolerance * m2.E));
        EXPECT_TRUE(test::at_most((r3.stress.topLeftCorner(2, 2) - r2.stress).norm(), solve_tolerance * m2.E));
        EXPECT_TRUE(test::near(r3.energy, r2.energy, solve_tolerance * m2.E));
    }
}

TEST(Material, NeoHookeanReportsInadmissibleStrain)
{
    // C = I + 2E = 0 for E = -I/2: ln J is undefined, the response must say so and be NaN.
    for (const PlaneMode plane : all_planes) {
        const int d = spatial_dim(plane);
        const auto r = finite_strain_response({MaterialModel::neo_hookean, 1.0, 0.3, plane}, MatN(-0.5 * MatN::Identity(d, d)));
        EXPECT_NE(r.status, ResponseStatus::ok);
        EXPECT_FALSE(std::isfinite(r.stress(0, 0)));
    }
}

TEST(Material, NanStrainIsNotOk)
{
    // A NaN strain must never come back as a finite, ok response.
    const double nan = std::nan("");
    for (const MaterialModel model : all_models)
        for (const PlaneMode plane : all_planes) {
            const int d = spatial_dim(plane);
            const auto r = finite_strain_response({model, 1.0, 0.3, plane}, MatN::Constant(d, d, nan));
            EXPECT_FALSE(r.status == ResponseStatus::ok && r.stress.allFinite());
        }
}

}  // namespace
}  // namespace iga::mechanics
