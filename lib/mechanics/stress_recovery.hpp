#pragma once
// Cauchy stress at a parameter point of a displaced solid patch, for
// post-processing and verification (e.g. Lame's thick cylinder).
//
// Small kinematics: sigma = the linearized stress at eps = sym(grad u).
// Finite kinematics: sigma = F S F^T / J (Bonet & Wood ch. 5), with J the full 3D
// volume ratio: d = 3: det F; plane strain: det F (F33 = 1); plane stress:
// det F * sqrt(1 + 2 E33) with E33 from the local S33 = 0 solve. In 2D `cauchy`
// is the in-plane 2 x 2 block and `cauchy33` the out-of-plane normal stress:
// 0 in plane stress; in plane strain the reaction that keeps eps33 = 0 (E33 = 0),
// from the 3D law (small, linear elastic: nu (sigma11 + sigma22); finite:
// F33 = 1, so sigma33 = S33 / J). In 3D cauchy33 = cauchy(2, 2).
//
// Shapes: displacement is n_cp x d (row A = control point A of the patch, the
// same order as patch.control_points()); xi has n_par = d entries; cauchy is d x d.
// Failure (det F <= 0, material not evaluable) is reported in `status` and the
// stress is NaN; a point with det(dX/dxi) <= 0 throws NonPositiveJacobian.

#include "core/types.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"

namespace iga::mechanics {

struct PointStress {
    VecN X;       ///< reference position
    VecN x;       ///< current position X + u
    MatN cauchy;  ///< d x d
    double cauchy33 = 0.0;  ///< out-of-plane normal stress (see above)
    ResponseStatus status = ResponseStatus::ok;
};

PointStress cauchy_stress(const nurbs::Patch& patch, const Material& material, Kinematics kinematics,
                          const RowMatrix& displacement, const VecN& xi);

}  // namespace iga::mechanics
