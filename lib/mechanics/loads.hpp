#pragma once
// External loads of deck.md: dead traction, total force on a side, follower
// pressure and gravity, as local force vectors (and the pressure's tangent).
//
// Sign convention of the driver: residual r(u) = f_int(u) - lambda f_ext(u)
// (+ contact), tangent dr/du. Every function here returns f_ext at load factor 1;
// the follower pressure also returns df_ext/du, which enters the tangent as
// -lambda df_ext/du (non-symmetric). Dead loads have no tangent.
//
// Side quadrature: a side of a solid patch (nurbs::extract_side) is integrated
// span by span with n Gauss points per direction (default max side degree + 1).
// At each point we keep the side basis R and its derivatives dR/ds (s = the side's
// parameters, the parent's order with the fixed direction removed), the reference
// tangents dX/ds, the reference line/area element |dX/ds| (2D) or |X_s x X_t| (3D),
// and an orientation sign. The raw normal is n_raw = (t_2, -t_1) for t = dX/ds in
// 2D and X_s x X_t in 3D; orientation * n_raw points OUT of the patch, the sign
// being fixed in the reference configuration from the parent's derivative across
// the side, dX/dxi_fixed: outward normals have n . dX/dxi_fixed < 0 on u0/v0/w0 and
// > 0 on u1/v1/w1. On a collapsed side (nurbs::is_collapsed to 1e-12 of the patch's
// bounding-box diagonal, e.g. the corners of the built-in half_disc) the measure and
// orientation are 0 and the side carries nothing: reference_measure is then 0, and the
// driver should reject a `force` or `pressure` on such a side as bad input.
//
// Loads (units per unit thickness in 2D):
//  - dead traction t per unit reference length (area): f_ai = int R_a t_i dA_0;
//  - total force F: a uniform dead traction t = F / A_0, A_0 = reference_measure(side),
//    computed with the same quadrature, so the nodal forces sum to F to round-off;
//  - follower pressure p along the inward normal: f_ext = -p int R_a n da. Finite
//    kinematics: n da = orientation * n_raw(x) ds on the CURRENT side x = X + u, which
//    is linear (2D) or bilinear (3D) in u, hence the consistent tangent. Small
//    kinematics: the reference normal, no tangent (df_ext_du is empty, 0 x 0);
//  - gravity: f_ai = int R_a rho g_i dV_0 (rho per unit reference volume, area in 2D).
//
// Shapes: local vectors have n_local*d entries with local dof a*d + i, where
// a indexes `indices` (global control-point indices of the parent patch); u_local
// is n_local x d in the same order.

#include "core/side.hpp"
#include "core/types.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::mechanics {

struct SidePoint {
    VecN xi;             ///< parameter point of the side (d - 1 entries)
    VecN X;              ///< reference position (d)
    Vector R;            ///< n_local side basis values
    Matrix dR;           ///< n_local x (d - 1): dR/ds
    Matrix dX;           ///< d x (d - 1): reference tangents dX/ds
    double weight;       ///< parametric Gauss weight (span lengths included)
    double measure;      ///< reference line (area) element, >= 0
    double orientation;  ///< +1 or -1 (0 on a collapsed side): orientation * n_raw is outward
};

struct SideElement {
    std::vector<int> indices;       ///< parent control-point index of each local function
    std::vector<SidePoint> points;

    int n_local() const { return static_cast<int>(indices.size()); }
};

struct SideQuadrature {
    Side side;
    int dim;                           ///< spatial dimension d
    std::vector<SideElement> elements; ///< one per span of the side
};

/// Precondition: parent.n_par() == parent.dim() (2 or 3), side direction < n_par.
/// n_per_direction <= 0 selects max side degree + 1.
SideQuadrature side_quadrature(const nurbs::Patch& parent, Side side, int n_per_direction = 0);

/// Reference length (2D) or area (3D) of the side, with the side's own quadrature.
double reference_measure(const SideQuadrature& side);

/// Unnormalized normal n_raw from tangents (d x (d - 1)): (t_2, -t_1) or t_s x t_t.
VecN raw_normal(const Matrix& tangents);

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
