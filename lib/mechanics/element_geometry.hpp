#pragma once
// Reference-configuration data of one element (knot span) of a solid patch,
// precomputed once and reused by every residual/tangent evaluation.
//
// The patch is a solid: n_par = d (a surface in 2D, a volume in 3D). At each
// Gauss point of the element's tensor rule (Gauss-Legendre, n per direction):
//   R      rational basis values of the n_local functions non-zero on the element,
//   dR_dX  their gradients in the reference configuration, dR/dX = dR/dxi (dX/dxi)^-1,
//   weight Gauss weight (parametric, span lengths included) times det(dX/dxi),
// so that sum_g f(X_g) weight_g ~ integral of f over the element's reference volume
// (area in 2D, per unit thickness).
//
// Shapes: indices (n_local) are global control-point indices of the patch, in the
// order of nurbs::rational_basis; the local dof of (control point a, component i)
// is a * d + i throughout mechanics/.
//
// A Gauss point with det(dX/dxi) <= 0 (an inverted, degenerate or left-handed
// parametrization) is bad input: NonPositiveJacobian is thrown with the parameter
// point, the reference position and the value, so that the driver can name the
// body in a user message.

#include "core/error.hpp"
#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <string>
#include <vector>

namespace iga::mechanics {

struct QuadraturePoint {
    VecN xi;        ///< parameter point (d)
    VecN X;         ///< reference position (d)
    Vector R;       ///< n_local basis values
    Matrix dR_dX;   ///< n_local x d reference gradients
    double weight;  ///< Gauss weight * det(dX/dxi) > 0
};

struct ElementGeometry {
    std::vector<int> indices;             ///< global control-point index of each local function
    std::vector<QuadraturePoint> points;  ///< Gauss points, u fastest
    int dim = 0;                          ///< spatial dimension d = n_par

    int n_local() const { return static_cast<int>(indices.size()); }
    int n_dofs() const { return n_local() * dim; }
};

/// Thrown when det(dX/dxi) <= 0 (or is not finite) at a Gauss point.
class NonPositiveJacobian : public Error {
public:
    NonPositiveJacobian(const VecN& xi, const VecN& X, double det_J);
    const VecN& xi() const { return xi_; }
    const VecN& X() const { return X_; }
    double det_J() const { return det_J_; }

private:
    VecN xi_;
    VecN X_;
    double det_J_;
};

/// Reference position, gradients dR/dX (n_local x d) and det(dX/dxi) at one point,
/// from basis values with first derivatives (n_derivs >= 1) of a solid patch.
/// No sign check: callers decide what a non-positive det_J means.
struct ReferenceGradient {
    VecN X;
    Matrix dR_dX;
    double det_J;
};
ReferenceGradient reference_gradient(const nurbs::Patch& patch, const nurbs::BasisValues& basis);

/// Default number of Gauss points per direction: max degree + 1.
int default_gauss_points(const nurbs::Patch& patch);

/// Precomputes the element geometry; n_per_direction <= 0 selects default_gauss_points.
/// Precondition: patch.n_par() == patch.dim() (2 or 3). Throws NonPositiveJacobian.
ElementGeometry element_geometry(const nurbs::Patch& patch, const nurbs::Element& element,
                                 int n_per_direction = 0);

/// element_geometry for every element of the patch, in the order of patch.elements().
std::vector<ElementGeometry> patch_geometry(const nurbs::Patch& patch, int n_per_direction = 0);

}  // namespace iga::mechanics
