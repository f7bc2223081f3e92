#pragma once
// Element stiffness of linear elasticity (small kinematics), K = int B^T D B dV,
// computed from the gradient moments of the element instead of Gauss point by
// Gauss point.
//
// With a constant elasticity tensor C (Hooke's law: the same D at every point),
//   K_(ai)(bk) = sum_{J,L} C_iJkL A^JL_ab,   A^JL = sum_g w_g dR/dX_J dR/dX_L^T,
// so the element costs d(d+1)/2 products of n_local x n_g by n_g x n_local
// (the moments A^JL; A^LJ = (A^JL)^T) and a few scaled adds, against n_g
// products of n_local*d x n_voigt by n_voigt x n_local*d for B^T D B per point:
// ~7x fewer flops for a degree-2 3D element (27 functions, 27 points).
// The tensor is read from the Voigt matrix, C_iJkL = D_(iJ)(kL) (mechanics/voigt.hpp).
//
// Same shapes and dof order as element_response (mechanics/element.hpp): local dof
// a*d + i, K is (n_local*d)^2 and symmetric. Equal to element_response(...,
// Kinematics::small, 0).K up to round-off (tests/mechanics/small_strain_stiffness_test.cpp).

#include "core/types.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/material.hpp"

namespace iga::mechanics {

Matrix small_strain_stiffness(const ElementGeometry& geometry, const Material& material);

}  // namespace iga::mechanics
