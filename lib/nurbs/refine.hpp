#pragma once
// Geometry-preserving refinement of NURBS patches: knot insertion (A5.1/A5.4)
// and degree elevation (A5.9), applied direction by direction in homogeneous
// coordinates (P w, w), so the rational map and the weights' parametrization are
// unchanged (Piegl & Tiller ch. 5).

#include "nurbs/patch.hpp"

#include <array>
#include <vector>

namespace iga::nurbs {

/// Inserts each value of `values` once into direction `dir` (a value already
/// present raises its multiplicity). Values must lie strictly inside (front, back)
/// and may not push a multiplicity above the degree.
Patch insert_knots(const Patch& patch, int dir, const std::vector<double>& values);

/// Raises the degree in direction `dir` by `times`; interior multiplicities rise
/// with it, so the continuity is kept.
Patch elevate_degree(const Patch& patch, int dir, int times);

/// Inserts the uniform values front + k (back - front) / n_spans, k = 1..n_spans-1,
/// that are not already knots: n_spans spans when the existing breakpoints lie on
/// that grid, more otherwise.
Patch refine_uniform(const Patch& patch, int dir, int n_spans);

/// Halves every knot span of positive length `times` times in every parametric
/// direction (inserts each span's midpoint, then again): n_spans * 2^times spans
/// per direction, continuity at the existing knots unchanged. This is the uniform
/// h-refinement of `igacontact study` (--refine-levels), applied after the deck's
/// own refinement; on a conforming multi-patch body it keeps the interfaces
/// conforming (both sides of an interface get the same midpoints).
Patch halve_spans(const Patch& patch, int times);

/// Bezier extraction operators of a knot vector (Borden et al. 2011): one
/// (p+1) x (p+1) matrix C_e per span with N^e(u) = C_e B(u~), B the Bernstein
/// basis on the span mapped to [0, 1].
std::vector<Eigen::MatrixXd> bezier_extraction(const KnotVector& knots);

/// Bezier control points (projected, n_local x d) of element `element` of a patch,
/// whose convex hull contains that piece (weights > 0): used for bounding boxes.
RowMatrix bezier_control_points(const Patch& patch, const Element& element);
/// The same with the extraction operators of every direction computed once
/// (extraction[k] = bezier_extraction(patch.knots(k)), k < n_par): for loops over elements.
RowMatrix bezier_control_points(const Patch& patch, const Element& element,
                                const std::array<std::vector<Eigen::MatrixXd>, 3>& extraction);

}  // namespace iga::nurbs
