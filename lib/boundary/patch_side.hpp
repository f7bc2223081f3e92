#pragma once
// The geometry of one side of a solid patch: a curve in 2D, a surface in 3D, as a
// NURBS with n_par = d - 1 (nurbs::extract_side), together with the orientation that
// makes its normal point out of the parent and one rule for collapsed and degenerate
// sides. Loads (mechanics/loads) and contact both read sides through this object, in
// the spirit of deal.II's FEFaceValues<dim, spacedim> and G+Smo's boundaryBasis(side).
//
// Notation (d = 2 or 3, Greek indices alpha, beta = 1..d-1 run over the side's own
// parameters s, in the parent's order with the fixed direction removed):
//   x(s)            point of the side, from the side's control points (reference X or
//                   current X + u: the same weights, any control points);
//   a_alpha = x_,alpha       covariant tangents, the columns of `tangents` (d x (d-1));
//   m_ab = a_a . a_b         metric (first fundamental form), (d-1) x (d-1);
//   n_raw = (a_1y, -a_1x) in 2D, a_1 x a_2 in 3D   the area normal, |n_raw| = sqrt(det m);
//   n = sign * n_raw / |n_raw|  the unit normal, pointing OUT of the parent patch;
//   b_ab = n . x_,ab         curvature (second fundamental form), (d-1) x (d-1).
// With this sign b is negative on a convex side: on a circle of radius R bounding a
// disc, b_11 = -m_11 / R (the outer arc of an annulus); it is +m_11 / R on a side that
// bounds a hole (the inner arc). Weingarten: n_,a = -b_ab m^bc a_c.
//
// Outward sign: sign * n_raw . dX/dxi_f < 0 on a side where the parent's fixed
// parameter xi_f is at its start (u0, v0, w0) and > 0 at its end (u1, v1, w1), with
// dX/dxi_f the parent's reference derivative across the side. It is decided at 3 (3 x 3)
// sample points inside every element of the side, skipping those where |n_raw| is below
// degenerate_relative_jacobian of the side's mean tangent size or n_raw is nearly
// orthogonal to dX/dxi_f; a sign change among the samples is a folded parametrization
// and throws FoldedSide (a fold between samples is not seen).
//
// Collapsed side: all its control points coincide (nurbs/coincidence.hpp: 1e-12 of
// the size of the parent's coordinates) (the corners of the built-in half_disc, the apex
// of a cone). It has jacobian 0 everywhere, outward_sign() == 0 and a zero normal, flagged
// `degenerate`; loads and contact reject a force or a contact surface on it. A side that
// is not collapsed but where no sample decides the sign (zero area everywhere, or the
// parent degenerate across all of it) also has outward_sign() == 0 and zero normals.
//
// Degenerate point of a side that is not collapsed (a pole where one edge of a 3D face
// collapses, a cusp): jacobian <= degenerate_relative_jacobian times the element's
// natural scale (see evaluate). The point is flagged `degenerate`, its jacobian is the
// tiny value computed (so a Gauss point there weighs ~0), and its normal is the limit of
// n from inside the element: along delta = (element centre - s), n_raw(s + t delta) =
// t D n_raw[delta] + O(t^2) when n_raw(s) ~ 0, so n = sign * D n_raw[delta] / |.|, where
// D n_raw[delta] is (x_,1b delta_b) x a_2 + a_1 x (x_,2b delta_b) in 3D. When that limit
// vanishes too, the normal is zero (never NaN) and the point stays flagged.

#include "core/error.hpp"
#include "core/side.hpp"
#include "core/types.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/side_patch.hpp"

#include <string>
#include <vector>

namespace iga::boundary {

/// A point whose |n_raw| is below this times its element's natural scale (see
/// PatchSide::evaluate) is degenerate: there the raw normal has lost about half of its
/// digits to round-off and the limit normal is the accurate one.
inline constexpr double degenerate_relative_jacobian = 1e-8;

/// The side's orientation changes sign (the parametrization folds over at the side):
/// bad input, callers turn it into a DeckError on the key that named the side.
class FoldedSide : public Error {
public:
    explicit FoldedSide(Side side);
    Side side;
};

/// Geometry of a side at one parameter point, for the control points given to evaluate.
struct SurfacePoint {
    VecN x;            ///< d: position
    MatN tangents;     ///< d x (d-1): a_alpha = dx/ds_alpha
    MatN second;       ///< d x (d-1)d/2: x_,ab packed as nurbs::BasisValues::d2R (empty unless n_derivs >= 2)
    MatN metric;       ///< (d-1) x (d-1): m_ab = a_a . a_b
    MatN curvature;    ///< (d-1) x (d-1): b_ab = n . x_,ab (empty unless n_derivs >= 2)
    VecN normal;       ///< d: unit outward normal (its limit at a degenerate point; zero on a collapsed side)
    double jacobian;   ///< |n_raw| = sqrt(det m): length (2D) or area (3D) element; 0 on a collapsed side
    bool degenerate;   ///< outward_sign() == 0, or |n_raw| below degenerate_relative_jacobian of the local scale
};

/// Area normal n_raw of tangents a (d x (d-1)): (a_1y, -a_1x) in 2D, a_1 x a_2 in 3D.
VecN raw_normal(const MatN& tangents);

/// Outward sign of a side, as in the header; 0 when no sample point decides it (the side
/// is collapsed, or the parent is degenerate across all of it). Throws FoldedSide.
/// Precondition: parent.n_par() == parent.dim() (2 or 3), side direction < n_par.
int outward_sign(const nurbs::Patch& parent, Side side);

/// A side (u0..w1) of a patch with n_par = d, as a patch with n_par = d - 1.
class PatchSide {
public:
    /// Extracts the side, decides whether it is collapsed, and finds its outward sign
    /// (throws FoldedSide). Precondition: parent.n_par() == parent.dim() (2 or 3).
    PatchSide(const nurbs::Patch& parent, Side side);

    const nurbs::SidePatch& side() const { return side_; }
    const nurbs::Patch& patch() const { return side_.patch; }
    Side which() const { return side_.side; }
    /// Parent control-point index of each side control point.
    const std::vector<int>& parent_index() const { return side_.parent_index; }
    /// +1 or -1: sign * n_raw points out of the parent; 0 when the side has no outward
    /// normal (collapsed, or undecided as in the header).
    int outward_sign() const { return sign_; }
    /// All control points coincide (nurbs/coincidence.hpp): measure 0, nothing carried.
    bool collapsed() const { return collapsed_; }
    /// Spatial dimension d of the parent (the side has d - 1 parameters).
    int dim() const { return side_.patch.dim(); }
    /// Knot spans of the side in patch order (side().patch.elements()).
    const std::vector<nurbs::Element>& elements() const { return elements_; }
    int n_elements() const { return static_cast<int>(elements_.size()); }

    /// The side point of element `element` at parameter xi (d - 1 entries, inside the
    /// element's closed box), for side control points `points` (n_cp_side x d: reference
    /// side().patch.control_points(), or current = reference + displacement). n_derivs is
    /// 1 (x, tangents, metric, normal, jacobian) or 2 (also second and curvature). When
    /// `basis` is given it receives the side basis used (indices into the side's control
    /// points), with n_derivs derivatives.
    /// Degenerate test: |n_raw| <= degenerate_relative_jacobian * c^(d-1), c = bounding-box
    /// diagonal of the element's control points / largest parametric length of the element.
    SurfacePoint evaluate(const RowMatrix& points, int element, const VecN& xi, int n_derivs,
                          nurbs::BasisValues* basis = nullptr) const;

private:
    nurbs::SidePatch side_;
    std::vector<nurbs::Element> elements_;
    bool collapsed_ = false;
    int sign_ = 0;
};

}  // namespace iga::boundary
