#pragma once
// Placing a patch in space: affine maps x -> A x + b applied to the Cartesian
// control points, weights kept. A NURBS x(xi) = sum_A R_A(xi) P_A with
// sum_A R_A = 1 is mapped exactly this way: A x(xi) + b = sum_A R_A (A P_A + b)
// (docs/theory.md, "Placing geometry"), rational patches included.
//
// The deck's `transform:` steps (docs/deck.md) are built here one by one and
// composed in list order: a step listed later acts on the result of the ones
// before it. Angles are in degrees, counter-clockwise about the axis by the
// right-hand rule; multiples of 90 degrees give exact 0 and +-1 entries.
//
// A map with det A < 0 (an odd number of mirrors) would turn a right-handed
// patch (det dx/dxi > 0) into a left-handed one; `transformed` then reverses
// the first parametric direction u, so the patch stays right-handed and its
// sides u0 and u1 trade places (the side at u = 0 after the transform is the
// image of the side that was at u = 1).

#include "nurbs/patch.hpp"

#include <Eigen/LU>  // MatN::determinant

#include <utility>

namespace iga::nurbs {

/// x -> A x + b in d = 2 or 3 dimensions.
struct Affine {
    MatN A;  ///< d x d
    VecN b;  ///< d

    int dim() const { return static_cast<int>(b.size()); }
    /// True when the map turns orientations over (det A < 0).
    bool reverses_orientation() const { return A.determinant() < 0; }
    /// The map `next` applied after this one: x -> next.A (A x + b) + next.b.
    Affine then(const Affine& next) const;
    VecN apply(const VecN& x) const { return A * x + b; }
};

/// The identity in d dimensions.
Affine identity(int dim);
/// x -> x + offset.
Affine translation(const VecN& offset);
/// Rotation by `angle_deg` about the line through `about` along `axis` (3D; any
/// non-zero length), by Rodrigues' formula. Precondition: finite, axis non-zero.
Affine rotation(const VecN& axis, double angle_deg, const VecN& about);
/// 2D rotation by `angle_deg` counter-clockwise about the point `about`.
Affine rotation_2d(double angle_deg, const VecN& about);
/// Reflection across the plane (a line in 2D) through `point` with normal
/// `normal` (any non-zero length): x -> x - 2 ((x - point) . n) n, n = normal / |normal|.
Affine mirror(const VecN& normal, const VecN& point);
/// Uniform scaling about the origin by `factor` > 0.
Affine scaling(double factor, int dim);

/// cos and sin of an angle in degrees; exact (0, +-1) at multiples of 90 degrees,
/// and accurate to round-off for large angles (reduced before the conversion).
std::pair<double, double> cos_sin_deg(double angle_deg);

/// The patch with control points A P + b and the same weights; if the map
/// reverses orientations, u is then reversed (reverse_direction(.., 0)).
/// Precondition: map.dim() == patch.dim(), patch.n_par() >= 1.
Patch transformed(const Patch& patch, const Affine& map);

/// The same geometry parametrized backwards in direction `dir`: the knots
/// u -> front + back - u, in reverse order; the control points (and weights)
/// in reverse order along `dir`. Sides dir0 and dir1 trade places.
Patch reverse_direction(const Patch& patch, int dir);

}  // namespace iga::nurbs
