#pragma once
// Gauss-point-to-segment (GPTS) penalty kernel: the residual and consistent
// tangent of one slave Gauss point against a master curve (2D) or a rigid plane.
//
// Reference: Kopacka et al. eqs. (1), (3), (5), (7); linearization physics.md
// section 3.3 (FD-checked), translated once to the gap sign of gap.hpp:
// g_N = -g (positive = penetration), p = eps <g_N>, H = H(g_N).
//
//   Pi_c = 1/2 eps W <g_N>^2,   r = dPi_c/du,   K = dr/du,
//   W = Gauss weight * |dX/deta| (REFERENCE slave Jacobian, held fixed).
//   slave rows  a: r_a = -p W N_a n      (the force +p W N_a n pushes the slave out)
//   master rows b: r_b = +p W R_b(xibar) n
// With Nn = [N_a n ; -R_b n], T = [N_a tau ; -R_b tau - g_N R_b' n],
// c = m + g_N b (= f' of the projection at its solution, > 0 at a distance minimum),
// D = [0 ; R_b' n] + (b / c) T:
//   K_a = eps H W (N_a n) (x) Nn + p W (N_a tau / m) (x) D
//   K_b = -eps H W (R_b n) (x) Nn + p W [ (R_b' n) (x) T / c - (R_b tau / m) (x) D ]
// Single pass assembles slave and master rows (K is then symmetric, the Hessian
// of Pi_c); a half pass of the two-half-pass algorithm only the slave rows, with
// slave and master columns. Rigid plane: K_a = eps H W (N_a n) (x) (N_c n); a rigid
// sphere adds the turning of its normal (gpts_rigid_kernel).
//
// Local numbering (shapes): dofs [slave cps (n_s x d) ; master cps (n_m x d)],
// dof = cp * d + component, cp counted within the kernel's lists (N's order, then
// the projection's basis order). Residual has (n_s + n_m) d entries; the tangent
// is (n_s + n_m) d square. Rows not assembled are zero. d = 2.

#include "contact/projection.hpp"
#include "core/types.hpp"

#include <limits>

namespace iga::contact {

struct KernelSettings {
    double penalty = 0.0;       ///< eps_N > 0
    bool master_rows = false;   ///< true: single pass (slave and master rows); false: half pass
    bool need_tangent = true;   ///< false: residual only
};

struct KernelResult {
    bool ok = true;         ///< false: the foot point is not a distance minimum (c <= 0)
    double pressure = 0.0;  ///< p = eps <g_N>
    Vector residual;        ///< (n_s + n_m) d
    Matrix tangent;         ///< (n_s + n_m) d square; empty when need_tangent is false
};

/// Slave Gauss point with basis values N (n_s) and weight W against the master
/// foot point `master` (status ok; its basis gives R_b, R_b' with n_m entries).
KernelResult gpts_kernel(const Vector& N, double W, const Projection& master, const KernelSettings& settings);

/// Slave Gauss point against a rigid obstacle with outward unit normal `normal`
/// and gap g_N `gap`: only slave dofs (n_s d), any d. `normal_radius` is the
/// distance over which the normal turns as the slave point moves (|x - c| for a
/// sphere, dn/dx = (I - n n)/normal_radius); infinite for a plane:
///   K_ab = W N_a N_b [ eps H n n - (p / normal_radius) (I - n n) ].
KernelResult gpts_rigid_kernel(const Vector& N, double W, const VecN& normal, double gap,
                               const KernelSettings& settings,
                               double normal_radius = std::numeric_limits<double>::infinity());

}  // namespace iga::contact
