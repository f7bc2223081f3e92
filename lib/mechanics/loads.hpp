#pragma once
// External loads of deck.md: dead traction, total force on a side, follower
// pressure and gravity, as local force vectors (and the pressure's tangent).
//
// Sign convention of the driver: residual r(u) = f_int(u) - lambda f_ext(u)
// (+ contact), tangent dr/du. Every function here returns f_ext at load factor 1;
// the follower pressure also returns df_ext/du, which enters the tangent as
// -lambda df_ext/du (non-symmetric). Dead loads have no tangent.
//
// Side quadrature: a side of a solid patch is read through boundary::PatchSide and
// integrated with boundary::gauss_points (n Gauss points per direction and span, default
// max side degree + 1), grouped here by side element with the PARENT's control-point
// indices. The outward sign, the collapse rule (a collapsed side has measure 0 and
// carries nothing: the driver rejects a `force` on it) and the degenerate-point rule
// are boundary's (boundary/patch_side.hpp). A folded side throws boundary::FoldedSide.
//
// Loads (units per unit thickness in 2D):
//  - dead traction t per unit reference length (area): f_ai = int R_a t_i dA_0;
//  - total force F: a uniform dead traction t = F / A_0, A_0 = reference_measure(side),
//    computed with the same quadrature, so the nodal forces sum to F to round-off;
//  - follower pressure p along the inward normal: f_ext = -p int R_a n da. Finite
//    kinematics: n da = sign * n_raw(x) ds on the CURRENT side x = X + u (n_raw =
//    boundary::raw_normal of the current tangents, sign = the side's outward sign), which
//    is linear (2D) or bilinear (3D) in u, hence the consistent tangent. Small
//    kinematics: the reference normal, no tangent (df_ext_du is empty, 0 x 0);
//  - gravity: f_ai = int R_a rho g_i dV_0 (rho per unit reference volume, area in 2D).
//
// Shapes: local vectors have n_local*d entries with local dof a*d + i, where
// a indexes `indices` (global control-point indices of the parent patch); u_local
// is n_local x d in the same order.

#include "boundary/gauss_points.hpp"
#include "core/side.hpp"
#include "core/types.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::mechanics {

/// The Gauss points of one element of a loaded side (all with the same basis support).
struct SideElement {
    std::vector<int> indices;                  ///< parent control-point index of each local function
    std::vector<boundary::GaussPoint> points;  ///< their `indices` are the side's, in the same order
    int outward_sign = 0;                      ///< the side's: +1 or -1, 0 when it has no outward normal

    int n_local() const { return static_cast<int>(indices.size()); }
};

struct SideQuadrature {
    Side side = Side::u0;
    int dim = 0;                       ///< spatial dimension d
    std::vector<SideElement> elements; ///< one per span of the side
};

/// Precondition: parent.n_par() == parent.dim() (2 or 3), side direction < n_par.
/// n_per_direction <= 0 selects max side degree + 1. Throws boundary::FoldedSide.
SideQuadrature side_quadrature(const nurbs::Patch& parent, Side side, int n_per_direction = 0);

/// Reference length (2D) or area (3D) of the side, with the side's own quadrature.
double reference_measure(const SideQuadrature& side);

struct LocalForce {
    std::vector<int> indices;  ///< n_local global control-point indices
    Vector f_ext;              ///< n_local*d
};

struct LocalForceTangent {
    std::vector<int> indices;
    Vector f_ext;       ///< n_local*d
    Matrix df_ext_du;   ///< (n_local*d)^2, or 0 x 0 when the load is dead (small kinematics)
};

/// Dead traction per unit reference length (area) on one side element.
LocalForce dead_traction(const SideElement& element, int dim, const VecN& traction);

/// Follower pressure (positive pushes into the body) on one side element;
/// u_local (n_local x d) is read only in finite kinematics.
LocalForceTangent follower_pressure(const SideElement& element, int dim, double pressure, Kinematics kinematics,
                                    const Matrix& u_local);

/// Body force rho g per unit reference volume (area) on one solid element.
LocalForce gravity(const ElementGeometry& geometry, double density, const VecN& g);

}  // namespace iga::mechanics
