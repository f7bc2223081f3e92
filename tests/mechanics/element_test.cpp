// Element kernel: tangent = FD of the internal force, force = FD of the energy,
// rigid modes of the small-strain stiffness, objectivity, uniaxial stretch closed forms.

#include "mechanics/element.hpp"
#include "mechanics/element_geometry.hpp"
#include "support/finite_difference.hpp"
#include "support/tolerance.hpp"
#include "test_patches.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace iga::mechanics {
namespace {

constexpr MaterialModel all_models[] = {MaterialModel::linear_elastic, MaterialModel::saint_venant_kirchhoff,
                                        MaterialModel::neo_hookean};
constexpr Kinematics all_kinematics[] = {Kinematics::small, Kinematics::finite};

std::string label(MaterialModel m, PlaneMode p, Kinematics k)
{
    const char* models[] = {"linear_elastic", "saint_venant_kirchhoff", "neo_hookean"};
    const char* planes[] = {"plane strain", "plane stress", "3D"};
    return std::string(models[static_cast<int>(m)]) + ", " + planes[static_cast<int>(p)] + ", " +
           (k == Kinematics::small ? "small" : "finite");
}

/// One distorted rational element of the given degree on the unit square/cube.
ElementGeometry random_element(int d, int degree, std::mt19937& rng)
{
    const std::vector<int> degrees(static_cast<std::size_t>(d), degree), spans(static_cast<std::size_t>(d), 1);
    // 15% of the control-point spacing and weights in [0.7, 1.3]: curved, rational, det J > 0.
    const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.15, 0.3);
    return element_geometry(patch, patch.elements().front());
}

/// Control-point positions (n_local x d) of an element, in local order.
Matrix local_points(const nurbs::Patch& patch, const ElementGeometry& g)
{
    Matrix X(g.n_local(), g.dim);
    for (int a = 0; a < g.n_local(); ++a)
        X.row(a) = patch.control_points().row(g.indices[static_cast<std::size_t>(a)]);
    return X;
}

void check_tangent(int d, int degree, PlaneMode plane, std::mt19937& rng)
{
    // Central differences, h = 1e-6 on displacements ~1e-2 of a unit element: truncation
    // ~h^2 |f'''| and round-off ~eps |f| / h are both ~1e-10 of |K|; a wrong or missing
    // geometric or material term is O(1e-2) relative.
    constexpr double fd_step = 1e-6;
    constexpr double fd_tolerance = 1e-7;
    const ElementGeometry g = random_element(d, degree, rng);
    for (const MaterialModel model : all_models)
        for (const Kinematics kin : all_kinematics) {
            const Material m{model, 3.0, 0.3, plane};
            const Matrix u = test::random_matrix(g.n_local(), d, rng, 1e-2);
            const ElementResponse r = element_response(g, m, kin, u);
            ASSERT_EQ(r.status, ResponseStatus::ok) << label(model, plane, kin);
            const Matrix K_fd = test::central_difference_jacobian(
                [&](const Vector& v) { return element_response(g, m, kin, test::unflatten(v, d)).f_int; },
                test::flatten(u), fd_step);
            const double err = (r.K - K_fd).norm() / K_fd.norm();
            EXPECT_TRUE(test::at_most(err, fd_tolerance)) << label(model, plane, kin);

            // The force is the gradient of the element energy (hyperelasticity).
            const Matrix grad_fd = test::central_difference_jacobian(
                [&](const Vector& v) {
                    return Vector::Constant(1, element_response(g, m, kin, test::unflatten(v, d)).energy);
                },
                test::flatten(u), fd_step);
            const double grad_err = (r.f_int - grad_fd.row(0).transpose()).norm() / r.f_int.norm();
            EXPECT_TRUE(test::at_most(grad_err, fd_tolerance)) << label(model, plane, kin);
        }
}

TEST(Element, TangentIsDerivativeOfInternalForce2D)
{
    std::mt19937 rng(17);
    check_tangent(2, 2, PlaneMode::strain, rng);
    check_tangent(2, 2, PlaneMode::stress, rng);
}

TEST(Element, TangentIsDerivativeOfInternalForce3D)
{
    std::mt19937 rng(23);
    check_tangent(3, 2, PlaneMode::none, rng);
}

TEST(Element, SmallStrainStiffnessHasRigidModesOnly)
{
    // Eigenvalues below 1e-10 lambda_max are zero to round-off (K ~ E, eps ~ 1e-16
    // amplified by the element's conditioning); the first deformation mode of a unit
    // element lies far above 1e-6 lambda_max.
    constexpr double zero_eigenvalue = 1e-10;
    constexpr double smallest_deformation_mode = 1e-6;
    // K is assembled from B^T D B with symmetric D: symmetric to rounding.
    constexpr double symmetry_round_off = 1e-14;
    std::mt19937 rng(3);
    for (const int d : {2, 3}) {
        const ElementGeometry g = random_element(d, d == 2 ? 2 : 1, rng);
        const Material m{MaterialModel::linear_elastic, 5.0, 0.3, d == 2 ? PlaneMode::strain : PlaneMode::none};
        const Matrix u = test::random_matrix(g.n_local(), d, rng, 1e-2);
        const ElementResponse r = element_response(g, m, Kinematics::small, u);
        EXPECT_TRUE(test::at_most((r.K - r.K.transpose()).norm() / r.K.norm(), symmetry_round_off));
        const Eigen::SelfAdjointEigenSolver<Matrix> eig(0.5 * (r.K + r.K.transpose()));
        const Vector lambda = eig.eigenvalues();  // increasing
        const double lambda_max = lambda(lambda.size() - 1);
        const int n_rigid = d * (d + 1) / 2;
        for (int i = 0; i < n_rigid; ++i)
            EXPECT_TRUE(test::at_most(std::abs(lambda(i)), zero_eigenvalue * lambda_max)) << "d = " << d << ", i = " << i;
        EXPECT_TRUE(test::at_least(lambda(n_rigid), smallest_deformation_mode * lambda_max)) << "d = " << d;
        // Small kinematics is linear: f_int = K u, to the rounding of two summation orders.
        constexpr double linearity_round_off = 1e-13;
        EXPECT_TRUE(test::at_most((r.f_int - r.K * test::flatten(u)).norm() / r.f_int.norm(), linearity_round_off));
    }
}

TEST(Element, RigidRotationGivesNoInternalForce)
{
    // u = (Q - I) X is reproduced exactly by the rational basis, so F = Q and E = 0
    // up to round-off: forces ~eps E |element| (1e-12 leaves room for conditioning).
    constexpr double round_off = 1e-12;
    std::mt19937 rng(8);
    for (const int d : {2, 3}) {
        const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 1);
        const nurbs::Patch patch = test::distorted(test::grid_patch(degrees, spans, VecN::Ones(d)), rng, 0.15, 0.3);
        const ElementGeometry g = element_geometry(patch, patch.elements().front());
        const Matrix X = local_points(patch, g);
        const MatN Q = test::rotation(d, 1.1);  // a large rotation: ~63 degrees
        const Matrix u = X * (Q - MatN::Identity(d, d)).transpose();
        for (const MaterialModel model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hookean}) {
            const Material m{model, 4.0, 0.3, d == 2 ? PlaneMode::strain : PlaneMode::none};
            const ElementResponse r = element_response(g, m, Kinematics::finite, u);
            ASSERT_EQ(r.status, ResponseStatus::ok);
            EXPECT_TRUE(test::at_most(r.f_int.norm(), round_off * m.E)) << label(model, m.plane, Kinematics::finite);
            EXPECT_TRUE(test::at_most(std::abs(r.energy), round_off * m.E));
        }
    }
}

TEST(Element, TheCancellationBoundHoldsWithoutTheTangent)
{
    // The cancellation bound is an entrywise upper bound of |K| |u_e| (triangle
    // inequality), within a small factor of it (a bound that is needlessly loose would
    // let Newton stop early at the round-off floor); a residual-only response has the
    // same force, energy and bound, and no K.
    std::mt19937 rng(21);
    for (const int d : {2, 3}) {
        const ElementGeometry g = random_element(d, 2, rng);
        const Matrix u = Matrix::Random(g.n_local(), d) * 0.05;
        for (const MaterialModel model : all_models)
            for (const Kinematics kin : all_kinematics) {
                const Material m{model, 3.0, 0.3, d == 2 ? PlaneMode::strain : PlaneMode::none};
                const ElementResponse full = element_response(g, m, kin, u);
                const ElementResponse force_only = element_response(g, m, kin, u, false);
                ASSERT_EQ(full.status, ResponseStatus::ok);
                ASSERT_EQ(force_only.status, ResponseStatus::ok);
                const Vector u_flat = u.transpose().reshaped();
                const Vector product = full.K.cwiseAbs() * u_flat.cwiseAbs();
                const std::string what = label(model, m.plane, kin);
                EXPECT_TRUE((full.cancellation.array() >= (1.0 - 1e-12) * product.array()).all()) << what;
                EXPECT_LE(full.cancellation.sum(), 4.0 * product.sum()) << what;  // 1.6-2.4 measured
                EXPECT_EQ(force_only.K.size(), 0) << what;
                EXPECT_EQ((force_only.f_int - full.f_int).norm(), 0.0) << what;
                EXPECT_EQ((force_only.cancellation - full.cancellation).norm(), 0.0) << what;
                EXPECT_EQ(force_only.energy, full.energy) << what;
            }
    }
}

TEST(Element, InvertedElementIsReported)
{
    // u = (M - I) X with M = diag(-1, 1) gives F = M, det F = -1: not admissible in
    // finite kinematics, for every model; the values must be NaN, never silently finite.
    const nurbs::Patch patch = test::grid_patch({2, 2}, {1, 1}, VecN::Ones(2));
    const ElementGeometry g = element_geometry(patch, patch.elements().front());
    MatN M = MatN::Identity(2, 2);
    M(0, 0) = -1.0;
    const Matrix u = local_points(patch, g) * (M - MatN::Identity(2, 2)).transpose();
    for (const MaterialModel model : all_models) {
        const ElementResponse r =
            element_response(g, {model, 1.0, 0.3, PlaneMode::strain}, Kinematics::finite, u);
        EXPECT_EQ(r.status, ResponseStatus::inverted);
        EXPECT_FALSE(std::isfinite(r.f_int(0)));
    }
}

/// Lateral stretch of uniaxial tension with free lateral faces, from the stress-free
/// condition S22 = 0 (and S33 = 0 in plane stress and 3D, where lambda2 = lambda3):
/// mu (lambda2^2 - 1) + lambda ln J = 0, J = lambda1 lambda2^m, m = 1 (plane strain) or 2.
/// Solved by scalar Newton (the left side increases with lambda2 > 0).
double neo_hookean_lateral_stretch(const Lame& l, double stretch, int m)
{
    double lambda2 = 1.0;
    for (int it = 0; it < 50; ++it) {
        const double g = l.mu * (lambda2 * lambda2 - 1.0) + l.lambda * std::log(stretch * std::pow(lambda2, m));
        const double dg = 2.0 * l.mu * lambda2 + l.lambda * m / lambda2;
        lambda2 -= g / dg;
    }
    return lambda2;
}

/// First Piola-Kirchhoff P11 of uniaxial tension at stretch lambda1 (closed forms).
double uniaxial_P11(const Material& m, Kinematics kin, double stretch)
{
    const Lame l = lame_parameters(m);
    const double E_plane = m.plane == PlaneMode::strain ? 4 * l.mu * (l.lambda + l.mu) / (l.lambda + 2 * l.mu) : m.E;
    if (kin == Kinematics::small)
        return E_plane * (stretch - 1.0);  // E/(1 - nu^2) in plane strain, E otherwise
    if (m.model != MaterialModel::neo_hookean)
        return stretch * E_plane * 0.5 * (stretch * stretch - 1.0);  // P11 = lambda1 S11, S11 = E_plane E11
    const int lateral = m.plane == PlaneMode::strain ? 1 : 2;
    const double lambda2 = neo_hookean_lateral_stretch(l, stretch, lateral);
    const double J = stretch * std::pow(lambda2, lateral);
    return (l.mu * (stretch * stretch - 1.0) + l.lambda * std::log(J)) / stretch;
}

/// One element of degree 2 on [0, L] x [0, H] (x [0, W]): x-displacements prescribed as
/// (lambda1 - 1) X, lateral displacements free except on the faces y = 0 (z = 0); a
/// Newton on the free lateral dofs with the element kernel; returns the x-reaction on
/// the face x = L per unit reference area (per unit thickness in 2D).
double uniaxial_reaction(const Material& m, Kinematics kin, double stretch)
{
    // Newton stops at a residual of 1e-13 of the stress scale E |face| (round-off level).
    constexpr double newton_tolerance = 1e-13;
    const int d = spatial_dim(m.plane);
    VecN size(d);
    size(0) = 2.0;
    size(1) = 1.0;
    if (d == 3)
        size(2) = 1.5;
    const std::vector<int> degrees(static_cast<std::size_t>(d), 2), spans(static_cast<std::size_t>(d), 1);
    const nurbs::Patch patch = test::grid_patch(degrees, spans, size);
    const ElementGeometry g = element_geometry(patch, patch.elements().front());
    const Matrix X = local_points(patch, g);
    const double face = d == 2 ? size(1) : size(1) * size(2);

    Matrix u = Matrix::Zero(g.n_local(), d);
    std::vector<int> free_dofs;
    for (int a = 0; a < g.n_local(); ++a) {
        u(a, 0) = (stretch - 1.0) * X(a, 0);
        for (int i = 1; i < d; ++i)
            if (X(a, i) != 0.0)
                free_dofs.push_back(a * d + i);
    }
    const int n_free = static_cast<int>(free_dofs.size());
    for (int it = 0; it < 30; ++it) {
        const ElementResponse r = element_response(g, m, kin, u);
        Vector f(n_free);
        Matrix K(n_free, n_free);
        for (int p = 0; p < n_free; ++p) {
            f(p) = r.f_int(free_dofs[static_cast<std::size_t>(p)]);
            for (int q = 0; q < n_free; ++q)
                K(p, q) = r.K(free_dofs[static_cast<std::size_t>(p)], free_dofs[static_cast<std::size_t>(q)]);
        }
        if (f.norm() <= newton_tolerance * m.E * face)
            break;
        const Vector du = K.lu().solve(-f);
        for (int p = 0; p < n_free; ++p) {
            const int dof = free_dofs[static_cast<std::size_t>(p)];
            u(dof / d, dof % d) += du(p);
        }
    }
    const ElementResponse r = element_response(g, m, kin, u);
    double reaction = 0.0;
    for (int a = 0; a < g.n_local(); ++a)
        if (X(a, 0) == size(0))
            reaction += r.f_int(a * d);
    return reaction / face;
}

TEST(Element, UniaxialStretchMatchesClosedForm)
{
    // A homogeneous state is reproduced exactly and f = P int grad R_a is integrated
    // exactly (affine polynomial element, p + 1 Gauss points), so only round-off and
    // the Newton tolerance remain: 1e-10 relative.
    constexpr double closed_form_tolerance = 1e-10;
    for (const PlaneMode plane : {PlaneMode::strain, PlaneMode::stress, PlaneMode::none})
        for (const MaterialModel model : all_models)
            for (const Kinematics kin : all_kinematics)
                for (const double stretch : {1.25, 0.8}) {
                    const Material m{model, 10.0, 0.3, plane};
                    const double expected = uniaxial_P11(m, kin, stretch);
                    EXPECT_TRUE(test::near_rel(uniaxial_reaction(m, kin, stretch), expected, closed_form_tolerance))
                        << label(model, plane, kin) << ", stretch " << stretch;
                }
}

}  // namespace
}  // namespace iga::mechanics
