#pragma once
// A tensor-product NURBS patch: curve (1 parametric direction), surface (2)
// or volume (3), embedded in d = 2 or 3 spatial dimensions.
//
// Control points are stored row-wise (n_cp x d, Cartesian, not homogeneous)
// with one weight each; the u index runs fastest, then v, then w:
//   index(i, j, k) = i + n_u * (j + n_v * k).
// The rational basis is R_A = w_A N_A / sum_B w_B N_B (Piegl & Tiller ch. 4),
// so x(xi) = sum_A R_A(xi) P_A. A displaced patch (current configuration) is the
// same patch with control points P_A + u_A and the same weights.
//
// Invariants, checked on construction (throws iga::Error): 1 <= n_par <= 3,
// control point count = product of n_basis per direction, weights > 0 and finite.

#include "core/types.hpp"
#include "nurbs/knot_vector.hpp"

#include <array>
#include <vector>

namespace iga::nurbs {

/// One knot span of a patch (an "element"): knot index and interval per direction.
struct Element {
    std::array<int, 3> span{0, 0, 0};    ///< knot index i with [u_i, u_{i+1}) (unused directions 0)
    std::array<double, 3> lower{0, 0, 0};
    std::array<double, 3> upper{0, 0, 0};
};

/// The rational basis functions that are non-zero at one parameter point.
struct BasisValues {
    std::vector<int> indices;  ///< global control-point index of each local function (n_local)
    Vector R;                  ///< n_local values
    Matrix dR;                 ///< n_local x n_par: dR/dxi_j (empty when n_derivs < 1)
    /// n_local x n_par*(n_par+1)/2 second derivatives, columns in the order
    /// 1D: uu; 2D: uu, uv, vv; 3D: uu, uv, uw, vv, vw, ww (empty when n_derivs < 2).
    Matrix d2R;
};

/// The column of d^2/dxi_a dxi_b in d2R (and PointDerivatives::d2x), either order of a, b.
constexpr int second_column(int n_par, int a, int b)
{
    if (a > b) {
        const int t = a;
        a = b;
        b = t;
    }
    // Columns before row a: n_par + (n_par - 1) + ... + (n_par - a + 1).
    return a * n_par - a * (a - 1) / 2 + (b - a);
}

/// A point on the patch and its parametric derivatives.
struct PointDerivatives {
    VecN x;      ///< d
    Matrix dx;   ///< d x n_par
    Matrix d2x;  ///< d x n_par*(n_par+1)/2, column order as BasisValues::d2R
};

class Patch {
public:
    Patch(std::vector<KnotVector> knots, RowMatrix control_points, Vector weights);

    int n_par() const { return static_cast<int>(knots_.size()); }
    int dim() const { return static_cast<int>(control_points_.cols()); }
    int degree(int dir) const { return knots_[dir].degree(); }
    const KnotVector& knots(int dir) const { return knots_[dir]; }
    const std::vector<KnotVector>& all_knots() const { return knots_; }
    int n_basis(int dir) const { return knots_[dir].n_basis(); }
    int n_control_points() const { return static_cast<int>(control_points_.rows()); }
    const RowMatrix& control_points() const { return control_points_; }
    const Vector& weights() const { return weights_; }

    int control_point_index(const std::array<int, 3>& ijk) const;
    std::array<int, 3> control_point_ijk(int index) const;

    /// All knot spans of positive length, u fastest.
    std::vector<Element> elements() const;

    /// The same patch with control points replaced (e.g. P + u); weights kept.
    Patch with_control_points(RowMatrix points) const;

private:
    std::vector<KnotVector> knots_;
    RowMatrix control_points_;
    Vector weights_;
};

/// Rational basis at parameter point xi (n_par entries), spans found by find_span.
BasisValues rational_basis(const Patch& patch, const VecN& xi, int n_derivs);
/// Same, on given knot spans (knot index per direction): evaluation on a chosen
/// element, also at its right end.
BasisValues rational_basis(const Patch& patch, const std::array<int, 3>& span, const VecN& xi, int n_derivs);

/// x, dx, d2x from basis values and a control point matrix (n_cp x d), e.g. the
/// current configuration P + u: x = sum_A R_A points_A.
PointDerivatives combine(const BasisValues& basis, const RowMatrix& points);

/// Point and derivatives of the patch itself.
PointDerivatives evaluate(const Patch& patch, const VecN& xi, int n_derivs);

}  // namespace iga::nurbs
