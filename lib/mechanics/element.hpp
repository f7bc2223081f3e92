#pragma once
// Internal force vector, tangent stiffness and strain energy of one element.
//
// Small kinematics: eps = sym(grad u), f_int = int B^T sigma dV, K = int B^T D B dV
// (constant, f_int = K u). Finite kinematics, total Lagrangian (Bonet & Wood ch. 7-9;
// Wriggers, "Nonlinear Finite Element Methods", ch. 4): F = I + grad_X u,
// E = (F^T F - I)/2, f_int_ai = int P_iJ dR_a/dX_J dV with P = F S, and
// K = int B_F^T D B_F dV (material) + int (dR_a . S dR_b) delta_ik dV (geometric),
// where B_F maps local displacements to Voigt variations of E (engineering shear):
//   dE_JJ = F_iJ dR_a/dX_J du_ai,   2 dE_JL = (F_iJ dR_a/dX_L + F_iL dR_a/dX_J) du_ai.
// Small kinematics is the same with F = I in B and no geometric term.
//
// Sign convention of the driver: residual r(u) = f_int(u) - lambda f_ext(u) (+ contact),
// tangent dr/du; this file supplies f_int and d f_int / du.
//
// Shapes: u_local is n_local x d (row a = displacement of control point
// geometry.indices[a]); f_int has n_local*d entries and K is (n_local*d)^2, with
// local dof a*d + i. K is symmetric (hyperelastic material, conservative forces).
// The energy is int W dV over the element (reference volume), so f_int = dEnergy/du.
//
// Failure (finite kinematics: det F <= 0 at a Gauss point, or a material point
// that could not be evaluated) is reported in `status` (numerical failure: the
// Newton line search backs off, the load stepper cuts back); f_int, K and energy
// are then NaN, and `failed_point` / `det_F` say where and how (the driver names
// the body, the parameter point and the reference and current positions).

#include "core/types.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/material.hpp"

namespace iga::mechanics {

struct ElementResponse {
    Vector f_int;    ///< n_local*d
    Matrix K;        ///< (n_local*d) x (n_local*d); empty when the tangent was not asked for
    /// An entrywise upper bound of |K| |u_e| (n_local*d), formed without K (see below):
    /// the size of the round-off f_int carries where F = I + grad u loses eps |grad u|.
    Vector cancellation;
    double energy = 0.0;
    ResponseStatus status = ResponseStatus::ok;
    int failed_point = -1;  ///< index into geometry.points of the first failed Gauss point, -1 if none
    double det_F = 0.0;     ///< det F at failed_point (finite kinematics)
};

/// Displacement gradient grad_X u = sum_a u_a (dR_a/dX)^T (d x d) at a Gauss point.
MatN displacement_gradient(const QuadraturePoint& point, const Matrix& u_local);

/// Displacement sum_a R_a u_a (d) at a Gauss point.
VecN point_displacement(const QuadraturePoint& point, const Matrix& u_local);

/// f_int, the energy, the cancellation bound and, with need_tangent, K.
///
/// The cancellation bound sums, per Gauss point, |B_F|^T |C| |B_F| |u_e| (material part) and
/// |dR| |S| |dR|^T |u_e| on each component (geometric part): by the triangle inequality an
/// entrywise bound of |K| |u_e|, at the cost of matrix-vector products instead of K's
/// (n_local d)^2 entries, so that a residual-only evaluation (a line-search probe) needs
/// no K and still knows its round-off. Small kinematics: the same with F = I.
ElementResponse element_response(const ElementGeometry& geometry, const Material& material, Kinematics kinematics,
                                 const Matrix& u_local, bool need_tangent = true);

}  // namespace iga::mechanics
