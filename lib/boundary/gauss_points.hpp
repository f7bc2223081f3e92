#pragma once
// Quadrature on a patch side (boundary/patch_side.hpp), fixed in the reference
// configuration: tensor Gauss-Legendre points per knot span of the side, with the
// side basis at each point, shared by loads and contact.
//
// For a side of measure A_0 = int |n_raw| ds (length in 2D, area in 3D):
//   int_side f dA_0 ~ sum_g f(x_g) weight_g,  weight_g = parametric_weight_g * jacobian_g,
// where parametric_weight_g is the Gauss weight on [0, 1]^(d-1) times the span lengths
// (quadrature::element_rule) and jacobian_g = |n_raw(X_g)| the reference area element.
// A follower load on the current side uses n da = sign n_raw(x) ds, hence needs
// parametric_weight and dN, not weight. On a collapsed side every jacobian and weight
// is 0; at a degenerate point (a pole) the weight is ~0 and the normal its limit.
//
// Shapes: n_local side control points have non-zero basis at a point (the same for
// every point of an element); indices are SIDE control-point indices (rows of
// PatchSide::patch().control_points()); map them to the parent with
// PatchSide::parent_index(). Points are in element order (PatchSide::elements()),
// u fastest inside an element.

#include "boundary/patch_side.hpp"
#include "core/types.hpp"

#include <vector>

namespace iga::boundary {

struct GaussPoint {
    int element = 0;                 ///< index into PatchSide::elements()
    VecN xi;                         ///< d - 1 side parameters
    double parametric_weight = 0.0;  ///< Gauss weight times the span lengths
    double weight = 0.0;             ///< parametric_weight * reference.jacobian
    SurfacePoint reference;          ///< reference geometry at the point (first derivatives only)
    std::vector<int> indices;        ///< n_local side control-point indices with non-zero basis
    Vector N;                        ///< n_local basis values
    Matrix dN;                       ///< n_local x (d - 1): dN/ds
};

/// n_per_direction points per direction of each element (<= 0: max side degree + 1),
/// elements in PatchSide::elements() order.
std::vector<GaussPoint> gauss_points(const PatchSide& side, int n_per_direction);

/// Sum of the weights of gauss_points(side, n_per_direction): the reference length (2D)
/// or area (3D) of the side, 0 on a collapsed side.
double reference_measure(const PatchSide& side, int n_per_direction);

/// Sum of the weights of the given points, in their order.
double reference_measure(const std::vector<GaussPoint>& points);

}  // namespace iga::boundary
