#pragma once
// Closed-form homogeneous uniaxial stretch of a block in plane strain with the
// lateral stress free, under a nominal (first Piola-Kirchhoff) stress P11
// (Bonet & Wood, "Nonlinear Continuum Mechanics for FEA", 2nd ed., ch. 6).
//
// Deformation x = l1 X, y = l2 Y, z = Z: C = diag(l1^2, l2^2, 1), J = l1 l2,
// Green-Lagrange E_ii = (l_i^2 - 1)/2; 3D Lame parameters lambda, mu from E, nu.
//   SVK: S = lambda tr(E) I + 2 mu E; S22 = 0 gives E22 = -lambda E11/(lambda + 2 mu),
//        P11 = l1 S11 = l1 4 mu (lambda + mu)/(lambda + 2 mu) (l1^2 - 1)/2.
//   neo-Hookean, W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
//        S = mu (I - C^-1) + lambda ln J C^-1:
//        l2^2 S22 = mu (l2^2 - 1) + lambda ln J = 0,
//        P11 = l1 S11 = mu (l1 - 1/l1) + lambda ln J / l1,
//   solved for (l1, l2) by Newton on these two equations, continued in 20 load
//   levels from l = 1 (a single Newton from l = 1 overshoots to l2 < 0 beyond
//   P11 ~ 1000); the callers check the result against the equations.

#include <Eigen/Dense>

#include <cmath>

namespace iga::test {

struct Stretch {
    double l1 = 1.0, l2 = 1.0;
};

struct LameParameters {
    double lambda, mu;
};

inline LameParameters lame_parameters_3d(double E, double nu)
{
    return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

/// Saint Venant-Kirchhoff; the branch through l1 = 1 (P11 above the limit load
/// -k/(3 sqrt 3), k = E/(1 - nu^2), reached at l1 = 1/sqrt 3).
inline Stretch svk_stretch(double E, double nu, double P11)
{
    const auto [lambda, mu] = lame_parameters_3d(E, nu);
    const double k = 4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu);
    double l1 = 1.0;
    constexpr int levels = 20, iterations = 30;
    for (int level = 1; level <= levels; ++level)
        for (int it = 0; it < iterations; ++it) {
            const double g = l1 * k * (l1 * l1 - 1.0) / 2.0 - P11 * level / levels;
            const double dg = k * (3.0 * l1 * l1 - 1.0) / 2.0;
            l1 -= g / dg;
        }
    const double E11 = (l1 * l1 - 1.0) / 2.0;
    const double E22 = -lambda * E11 / (lambda + 2.0 * mu);
    return {l1, std::sqrt(1.0 + 2.0 * E22)};
}

inline Stretch neo_hookean_stretch(double E, double nu, double P11)
{
    const auto [lambda, mu] = lame_parameters_3d(E, nu);
    double l1 = 1.0, l2 = 1.0;
    constexpr int levels = 20, iterations = 30;
    for (int level = 1; level <= levels; ++level) {
        const double P = P11 * level / levels;
        for (int it = 0; it < iterations; ++it) {
            const double lnJ = std::log(l1 * l2);
            const Eigen::Vector2d f(mu * (l1 - 1.0 / l1) + lambda * lnJ / l1 - P, mu * (l2 * l2 - 1.0) + lambda * lnJ);
            Eigen::Matrix2d df;
            df << mu * (1.0 + 1.0 / (l1 * l1)) + lambda * (1.0 - lnJ) / (l1 * l1), lambda / (l1 * l2),  //
                lambda / l1, 2.0 * mu * l2 + lambda / l2;
            const Eigen::Vector2d step = df.partialPivLu().solve(f);
            l1 -= step(0);
            l2 -= step(1);
        }
    }
    return {l1, l2};
}

}  // namespace iga::test
