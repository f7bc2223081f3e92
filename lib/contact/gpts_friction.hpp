#pragma once
// The tangential (Coulomb friction) part of the GPTS kernel at one slave Gauss
// point: against a rigid obstacle (add_tangential) and against a deformable
// master (gpts_friction); docs/theory.md "Coulomb friction".
//
// Against a deformable master the anchor is a MATERIAL point of the master,
// stored in the master's reference configuration (A), so it belongs to no
// patch's parameters and survives a slide onto the next patch. Near the foot
// point xibar the master maps reference to current by its surface deformation
// gradient F_s = a_al (x) G^al (G_al reference tangents, G^al = G_be M^be,al,
// M = reference metric), so the slave point's tangential offset from the anchor
// is -F_s (A - Xbar) = -a_al c^al with c = M^-1 G^T (A - Xbar), Xbar = X(xibar):
//
//   trial traction   s = eps_T a c          (a rigid rotation of the master turns it along)
//
// and the return map of friction.hpp. The slave rows gain r_a = -W N_a t_T, the
// master rows (single pass) r_b = +W R_b(xibar) t_T. Linearization over the
// kernel's dofs [slave ; master], with dxibar = D^T du (gpts_kernel.hpp):
//   ds/du = eps_T [ (R_b,al c^al) I on master b ; 0 on slave ] + eps_T (x_m,al ga c^al + a_al C^al_ga) D_ga^T,
//   C = dc/dxibar:  C_ga = -e_ga + M^-1 (X,al ga . (A - Xbar) - dM/dxi^ga c),
// dp/du = -eps_N Nn (p > 0), and the master rows' foot moving: W t_T (R_b,al D_al)^T.
// The anchor of a converged slip state is moved so that the traction is
// reproduced: A = Xbar + G m^-1 a^T t_T / eps_T. The augmented Lagrangian's tangential
// multiplier Lambda is kept in the same frame, a vector of the master's reference space
// with F_s Lambda = lambda_T: it shifts the anchor, c = M^-1 G^T (A + Lambda / eps_T - Xbar),
// and changes nothing else above (Lambda is fixed within Newton). An Uzawa update adopts
// Lambda <- G m^-1 a^T t_T (frame_traction), and a slipping anchor then reproduces t_T
// with Lambda kept: A = Xbar + (G m^-1 a^T t_T - Lambda) / eps_T.
//
// First touch. An open point has no anchor: its foot while open is not where it will
// touch (on a curved master the closest point moves as the gap closes, and anchoring
// there would load two identical cylinders pressed together with tangential
// tractions). It keeps its converged gap g_n < 0, and in the increment in which it
// first presses (g > 0) it carries the traction of its slide since touching: the
// increment taken as linear, the gap closed at theta = g_n / (g_n - g), and the slide
// since is (1 - theta) of the increment's tangential relative motion of the slave
// point and the master's MATERIAL point under its foot. With y_n and X_n(xi) the
// converged positions of the slave point and of the master surface, and
// P (y - x_m(xibar)) = 0 at the foot, that motion is P (X_n(xibar) - y_n), and the
// traction opposes it (as s = -eps_T P (y - anchor) against an obstacle):
//
//   s = eps_T (1 - theta) P w,   w = y_n - X_n(xibar).
//
// Identical cylinders pressed together move their facing material points apart only
// along the normal, so they take none; a die's leading edge, sliding over the points
// it presses in every increment, gives them their traction at once (without it they
// carried none, and the die's friction force dipped with their number). The point is
// then anchored where its traction is reproduced, as after a slip. A point with no
// converged gap (it came from out of reach) sticks without traction in the increment
// it touches, anchored where it touches. The linearization is touch_trial's
// (gpts_friction.cpp).

#include "contact/friction.hpp"
#include "contact/gpts_kernel.hpp"
#include "core/types.hpp"

namespace iga::contact {

/// The master's REFERENCE geometry at the foot point: Xbar, G_al and X,ab (packed
/// like BasisValues::d2R), from the reference control points with the foot's basis.
struct MasterReference {
    VecN point;      ///< d
    Matrix tangents; ///< d x q
    Matrix second;   ///< d x q(q+1)/2
};

/// The converged positions a first touch measures its slide from: the slave point y_n
/// (d) and the master's control points of the foot's basis (n_m x d, in its order).
/// Empty: not known (the point sticks where it touches).
struct ConvergedPositions {
    VecN slave;
    RowMatrix master;
};

/// Adds the tangential traction of a slave Gauss point against a deformable
/// master foot (gpts_kernel's `master`, with `second` filled) to `result`, the
/// normal kernel's result at the same point (its pressure is used); rows as
/// settings.master_rows, dW as in gpts_kernel; `multiplier` is the tangential
/// multiplier Lambda (d, master reference space; zeros for the penalty law). Returns
/// the response (status, traction, slip increment, the history to commit). `before`:
/// the converged positions, used at a first touch.
TangentialResponse gpts_friction(KernelResult& result, const Vector& N, double W, const MasterFoot& master,
                                 const MasterReference& reference, const FrictionLaw& law,
                                 const FrictionHistory& committed, const VecN& multiplier,
                                 const KernelSettings& settings, const Vector& dW = Vector(),
                                 const ConvergedPositions& before = {});

/// The history of a point that does not press (open) at effective gap g_N <= 0: no
/// anchor, its foot and gap kept for the increment in which it touches (its slip is kept).
FrictionHistory open_history(const FrictionHistory& committed, const MasterReference& reference, double gap);

/// Adds a slave Gauss point's tangential traction (basis N, fixed weight W) to a
/// rigid-obstacle kernel result: r_a -= W N_a t_T and K_ab -= W N_a N_b dt_T/dy
/// (friction.hpp; y moves with the slave point, the obstacle's motion is no unknown).
void add_tangential(KernelResult& result, const Vector& N, double W, const TangentialResponse& friction);

}  // namespace iga::contact
