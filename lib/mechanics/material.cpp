#include "mechanics/material.hpp"

#include "core/error.hpp"

#include <Eigen/LU>

#include <cmath>
#include <limits>

namespace iga::mechanics {

namespace {

using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// 3D response; `admissible` false when the strain is outside the law's domain.
struct Response3 {
    Mat3 S;
    Mat6 D;
    double W = 0.0;
    bool admissible = true;
};

/// S = lambda tr(E) I + 2 mu E (Hooke's law, and Saint Venant-Kirchhoff in E).
Response3 hooke_3d(const Lame& lame, const Mat3& E)
{
    Response3 r;
    const double trace = E.trace();
    r.S = lame.lambda * trace * Mat3::Identity() + 2.0 * lame.mu * E;
    r.D.setZero();
    r.D.topLeftCorner<3, 3>().setConstant(lame.lambda);
    for (int I = 0; I < 3; ++I)
        r.D(I, I) += 2.0 * lame.mu;
    for (int I = 3; I < 6; ++I)
        r.D(I, I) = lame.mu;  // engineering shear: S_12 = mu gamma_12
    r.W = 0.5 * lame.lambda * trace * trace + lame.mu * E.squaredNorm();
    return r;
}

/// Compressible neo-Hookean, W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2.
Response3 neo_hookean_3d(const Lame& lame, const Mat3& E)
{
    Response3 r;
    const Mat3 C = Mat3::Identity() + 2.0 * E;
    const double det_C = C.determinant();
    if (!(det_C > 0.0)) {
        r.admissible = false;
        return r;
    }
    const double ln_J = 0.5 * std::log(det_C);
    const Mat3 C_inv = C.inverse();
    r.S = lame.mu * (Mat3::Identity() - C_inv) + lame.lambda * ln_J * C_inv;
    const double c = lame.mu - lame.lambda * ln_J;
    for (int I = 0; I < 6; ++I) {
        const auto [i, j] = voigt_pair(3, I);
        for (int J = 0; J < 6; ++J) {
            const auto [k, l] = voigt_pair(3, J);
            r.D(I, J) = lame.lambda * C_inv(i, j) * C_inv(k, l) +
                        c * (C_inv(i, k) * C_inv(j, l) + C_inv(i, l) * C_inv(j, k));
        }
    }
    r.W = 0.5 * lame.mu * (C.trace() - 3.0) - lame.mu * ln_J + 0.5 * lame.lambda * ln_J * ln_J;
    return r;
}

enum class Law { hooke, neo_hookean };

Response3 evaluate_3d(Law law, const Lame& lame, const Mat3& E)
{
    return law == Law::hooke ? hooke_3d(lame, E) : neo_hookean_3d(lame, E);
}

StressResponse failed(int dim, ResponseStatus status)
{
    StressResponse out;
    out.stress = MatN::Constant(dim, dim, nan);
    out.tangent = VoigtMatrix::Constant(n_voigt(dim), n_voigt(dim), nan);
    out.energy = nan;
    out.strain33 = nan;
    out.status = status;
    return out;
}

/// 3D Voigt positions of the 2D Voigt components (11, 22, 12).
constexpr int in_plane_voigt[3] = {0, 1, 5};

/// In-plane part of a 3D response: the 2 x 2 stress block and the (11, 22, 12) tangent block.
StressResponse in_plane(const Response3& r)
{
    const auto& map = in_plane_voigt;
    StressResponse out;
    out.stress = r.S.topLeftCorner<2, 2>();
    out.tangent.resize(3, 3);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            out.tangent(a, b) = r.D(map[a], map[b]);
    out.energy = r.W;
    return out;
}

/// Plane stress: Newton on E33 for S33(E33) = 0, then static condensation of E33.
StressResponse plane_stress(Law law, const Lame& lame, const MatN& E2)
{
    // Converged when S33 is round-off relative to the stress scale (lambda + 2 mu)|E|,
    // or when the Newton step no longer changes E33 beyond round-off.
    constexpr double stress_tolerance = 1e-13;
    constexpr double step_tolerance = 1e-15;
    constexpr int max_iterations = 50;

    Mat3 E = Mat3::Zero();
    E.topLeftCorner<2, 2>() = E2;
    const double scale = (lame.lambda + 2.0 * lame.mu) * E2.cwiseAbs().maxCoeff();
    for (int iteration = 0; iteration < max_iterations; ++iteration) {
        const Response3 r = evaluate_3d(law, lame, E);
        if (!r.admissible)
            return failed(2, ResponseStatus::inverted);
        const double S33 = r.S(2, 2);
        const double D33 = r.D(2, 2);
        const double step = -S33 / D33;
        const bool converged = std::abs(S33) <= stress_tolerance * scale ||
                               std::abs(step) <= step_tolerance * (1.0 + std::abs(E(2, 2)));
        if (converged) {
            const auto& map = in_plane_voigt;
            StressResponse out = in_plane(r);
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    out.tangent(a, b) -= r.D(map[a], 2) * r.D(2, map[b]) / D33;
            out.strain33 = E(2, 2);
            return out;
        }
        if (!std::isfinite(step))
            break;
        // Keep C33 = 1 + 2 E33 positive: go at most halfway to the limit E33 = -1/2.
        double next = E(2, 2) + step;
        if (law == Law::neo_hookean && !(1.0 + 2.0 * next > 0.0))
            next = 0.5 * (E(2, 2) - 0.5);
        E(2, 2) = next;
    }
    return failed(2, ResponseStatus::plane_stress_not_converged);
}

StressResponse respond(Law law, const Material& material, const MatN& strain)
{
    const int dim = spatial_dim(material.plane);
    IGA_CHECK(strain.rows() == dim && strain.cols() == dim,
              "strain size does not match the material's dimension (2 for plane modes, 3 for none)");
    const Lame lame = lame_parameters(material);

    switch (material.plane) {
    case PlaneMode::none: {
        const Response3 r = evaluate_3d(law, lame, strain);
        if (!r.admissible)
            return failed(3, ResponseStatus::inverted);
        StressResponse out;
        out.stress = r.S;
        out.tangent = r.D;
        out.energy = r.W;
        return out;
    }
    case PlaneMode::strain: {
        Mat3 E = Mat3::Zero();
        E.topLeftCorner<2, 2>() = strain;
        const Response3 r = evaluate_3d(law, lame, E);
        if (!r.admissible)
            return failed(2, ResponseStatus::inverted);
        return in_plane(r);
    }
    case PlaneMode::stress:
        return plane_stress(law, lame, strain);
    }
    IGA_CHECK(false, "unknown plane mode");
    return {};
}

}  // namespace

Lame lame_parameters(const Material& material)
{
    const double E = material.E;
    const double nu = material.nu;
    IGA_CHECK(E > 0.0 && nu > -1.0 && nu < 0.5, "material needs E > 0 and -1 < nu < 0.5");
    return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

StressResponse small_strain_response(const Material& material, const MatN& strain)
{
    return respond(Law::hooke, material, strain);
}

StressResponse finite_strain_response(const Material& material, const MatN& green_lagrange)
{
    const Law law = material.model == MaterialModel::neo_hookean ? Law::neo_hookean : Law::hooke;
    return respond(law, material, green_lagrange);
}

StressResponse stress_response(const Material& material, Kinematics kinematics, const MatN& strain)
{
    return kinematics == Kinematics::small ? small_strain_response(material, strain)
                                           : finite_strain_response(material, strain);
}

}  // namespace iga::mechanics
