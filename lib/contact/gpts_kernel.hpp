#pragma once
// Gauss-point-to-segment (GPTS) contact kernel: the residual and consistent
// tangent of one slave Gauss point against a master side (a curve in 2D, a
// surface in 3D) or a rigid obstacle, in tensor form for any dimension d.
//
// Reference: Kopacka et al. eqs. (1), (3), (5), (7); the linearization is derived
// in docs/theory.md ("GPTS tangent"), with the gap sign of gap.hpp: g_N > 0 is
// penetration. The pressure p = p(g_N, lambda) and its slope p' = dp/dg_N come from
// the pair's normal law (normal_law.hpp): for the penalty law p = <lambda + eps g_N>
// and p' = eps H(lambda + eps g_N), where lambda >= 0 is the Gauss point's
// augmented-Lagrangian multiplier (0 for plain penalty, which gives p = eps <g_N>;
// docs/theory.md "Augmented Lagrangian"); the exponential law presses at gaps down
// to -c0. The kernel runs where the law says the point is active (p > 0).
//
//   Pi_c = W P(g_N), P' = p (penalty: P = <lambda + eps g_N>^2 / (2 eps)),
//   r = dPi_c/du = p W dg_N/du,   K = dr/du,
//   W = Gauss weight * area element of the slave: held fixed (the reference one), or
//       the current one, W = w_g j(u), whose variation dW/du_slave the caller passes
//       (two-half-pass: both passes integrate over the current surface, docs/theory.md
//       "Two-half-pass balance"); the tangent then gains -p Nn dW^T on the slave columns.
//   slave rows  a: r_a = -p W N_a n      (the force +p W N_a n pushes the slave out)
//   master rows b: r_b = +p W R_b(xibar) n
// Foot point xibar (q = d - 1 parameters), covariant tangents a_al, metric m_ab,
// curvature b_ab = n . x_m,ab and A = m + g_N b (positive definite at a distance
// minimum). Over the dofs [slave ; master]: Nn = [N_a n ; -R_b n],
// T_al = [N_a a_al ; -R_b a_al], Nd_al = [0 ; R_b,al n], D = (T - g_N Nd) A^-1
// (the variation of xibar), and
//   K = p' W Nn Nn^T + p W [ Nd D^T + T m^-1 (Nd + D b)^T ],
// the second term being the variation of the projection and of the normal. It is
// symmetric; single pass assembles slave and master rows (K is then the Hessian of
// Pi_c), a half pass of the two-half-pass algorithm only the slave rows, with slave
// and master columns. Rigid plane: K = p' W Nn Nn^T; a rigid sphere adds the
// turning of its normal (gpts_rigid_kernel).
//
// Local numbering (shapes): dofs [slave cps (n_s x d) ; master cps (n_m x d)],
// dof = cp * d + component, cp counted within the kernel's lists (N's order, then
// the master basis order). Residual has (n_s + n_m) d entries; the tangent is
// (n_s + n_m) d square. Rows not assembled are zero.

#include "contact/normal_law.hpp"
#include "contact/projection.hpp"
#include "core/types.hpp"

#include <limits>

namespace iga::contact {

struct KernelSettings {
    NormalLaw law;              ///< p(g_N, lambda) and dp/dg_N
    double multiplier = 0.0;    ///< lambda >= 0 of this Gauss point (augmented Lagrangian); 0: penalty
    double gap_offset = 0.0;    ///< s: the law is evaluated at g_N - s (an unreleased overlap, NormalLaw::shifted)
    bool master_rows = false;   ///< true: single pass (slave and master rows); false: half pass
    bool need_tangent = true;   ///< false: residual only
    /// The point touches at its kink (a penalty point at g_N = 0 to round-off, e.g. two
    /// flat faces at rest): no pressure, but the tangent takes the pressing branch's slope,
    /// so that Newton's step from there presses both bodies together instead of letting
    /// one move into the other freely (the generalized derivative's other branch).
    bool touching = false;
};

struct KernelResult {
    bool ok = true;         ///< false: the foot point is not a distance minimum (c <= 0)
    double pressure = 0.0;  ///< p = p(g_N - s, lambda), e.g. <lambda + eps g_N>
    double slope = 0.0;     ///< p' = dp/dg_N at the same point (0 where inactive)
    Vector residual;        ///< (n_s + n_m) d
    Matrix tangent;         ///< (n_s + n_m) d square; empty when need_tangent is false
};

/// What the kernel needs of the master's foot point, in any dimension d = 2, 3
/// (q = d - 1 parameters): the outward unit normal, the covariant tangent basis
/// a_al = dx_m/dxi^al, the metric m_ab = a_a . a_b, the curvature b_ab = n . x_m,ab,
/// the gap g_N, and the master basis R_b (n_m) with derivatives dR (n_m x q).
struct MasterFoot {
    VecN normal;       ///< d
    Matrix tangents;   ///< d x q
    Matrix metric;     ///< q x q
    Matrix curvature;  ///< q x q
    double gap = 0.0;  ///< g_N, positive = penetration
    Vector R;          ///< n_m
    Matrix dR;         ///< n_m x q
    Matrix second;     ///< d x q(q+1)/2: x_m,ab packed like BasisValues::d2R (friction only; may be empty)
};

/// The first variation of the foot point at a slave point with basis N, as
/// columns over the dofs [slave cps ; master cps] (see the header paragraph):
/// dg_N/du = -Nn, dxibar/du = D^T, and the pieces Nd, T of the linearization.
struct FootVariation {
    bool ok = true;  ///< false: A = m + g_N b is not positive definite (not a distance minimum)
    Vector Nn;       ///< n_dofs
    Matrix T;        ///< n_dofs x q
    Matrix Nd;       ///< n_dofs x q
    Matrix D;        ///< n_dofs x q
};
FootVariation foot_variation(const Vector& N, const MasterFoot& master);

/// Slave Gauss point with basis values N (n_s) and weight W against the master
/// foot point (a distance minimum: m + g_N b positive definite, else ok = false).
/// dW (n_s d, or empty when W is held fixed): dW/du of the slave's control points.
KernelResult gpts_kernel(const Vector& N, double W, const MasterFoot& master, const KernelSettings& settings,
                         const Vector& dW = Vector());

/// A projection's foot point (curve in 2D, surface in 3D) as a MasterFoot.
MasterFoot master_foot(const Projection& projection);
/// 2D convenience: the kernel at a curve projection (status ok).
KernelResult gpts_kernel(const Vector& N, double W, const Projection& master, const KernelSettings& settings,
                         const Vector& dW = Vector());

/// Slave Gauss point against a rigid obstacle with outward unit normal `normal`
/// and gap g_N `gap`: only slave dofs (n_s d), any d. `normal_radius` is the
/// distance over which the normal turns as the slave point moves (|x - c| for a
/// sphere, dn/dx = (I - n n)/normal_radius); infinite for a plane:
///   K_ab = W N_a N_b [ p' n n - (p / normal_radius) (I - n n) ].
KernelResult gpts_rigid_kernel(const Vector& N, double W, const VecN& normal, double gap,
                               const KernelSettings& settings,
                               double normal_radius = std::numeric_limits<double>::infinity());

}  // namespace iga::contact
