#pragma once
// Built-in exact shapes, the shapes of deck.md's `shape:` key: 2D patches
// (bivariate, in the x-y plane) and 3D solids (trivariate), all of positive
// Jacobian determinant inside (det dx/d(u, v[, w]) > 0: right-handed).
//
// 2D
// half_disc (center c, radius R): the lower half of the disc, flat side up.
//   u runs along the arc from (c_x - R, c_y) through the lowest point to
//   (c_x + R, c_y), as a single-span rational cubic (weights 1, 1/3, 1/3, 1:
//   no interior knot, so nothing special happens at the lowest point); v runs
//   from the arc (v = 0) to the diameter (v = 1), linear. Each diameter control
//   point lies straight above its arc control point, so x(u, v) = x_arc(u).
//   Sides: v0 = arc (contact side), v1 = flat top (diameter), u0 and u1 are
//   collapsed to the two ends of the diameter.
// quarter_disc (center c, radius R): the right half of half_disc, x >= c_x.
//   u runs along the quarter arc from the lowest point (c_x, c_y - R) to
//   (c_x + R, c_y), degree 2 (weights 1, sqrt(2)/2, 1); v from the arc (v = 0)
//   to the top line (v = 1), linear.
//   Sides: v0 = arc (contact side), v1 = flat top, u0 = symmetry line x = c_x,
//   u1 collapsed to (c_x + R, c_y).
// rectangle (corner c, size s): bilinear, u along x, v along y.
//   Sides: u0 = left (x = c_x), u1 = right, v0 = bottom (y = c_y), v1 = top.
//
// 3D
// sphere_octant (center c, radius R): the solid x >= c_x, y >= c_y, z <= c_z of
//   the ball: a quarter of its lower half, flat top z = c_z, whose lowest point
//   (c_x, c_y, c_z - R) can rest on a floor. Exact NURBS by revolution (Piegl &
//   Tiller, The NURBS Book, ch. 8.5): the quarter_disc above, placed in the
//   plane y = c_y with its y coordinate read as z, is revolved by 90 degrees
//   about the line through c parallel to x, with the rational quadratic arc
//   (weights 1, sqrt(2)/2, 1). u and v are those of the quarter_disc (u along
//   the meridian from the lowest point to the pole (c_x + R, c_y, c_z), v from
//   the sphere to the axis); w is the angle of revolution, from the top plane
//   z = c_z (w = 0) down to the plane y = c_y (w = 1), the direction that
//   makes the map right-handed. Degrees [2, 1, 2], one span per direction.
//   The pole of the revolution lies on the axis, away from the contact point:
//   the lowest point is the regular corner (u, w) = (0, 1) of the spherical
//   face, whose normal there is -z.
//   Sides: v0 = spherical face (contact face), w0 = flat top z = c_z (load
//   face), u0 = symmetry face x = c_x, w1 = symmetry face y = c_y,
//   v1 collapsed to the axis segment from c to the pole (c_x + R, c_y, c_z),
//   u1 collapsed to the pole. det J vanishes on v1 and u1 only.
// box (corner c, size s): trilinear, u along x, v along y, w along z.
//   Sides: u0/u1 = x min/max, v0/v1 = y min/max, w0/w1 = z min/max.
// extrude(planar, L): any bivariate patch of the x-y plane (a 2D shape above)
//   swept along z from z = 0 to z = L, degree 1 in w. Sides u*, v* as in 2D
//   (now faces, or lines where the 2D side is a collapsed point), w0 = the face
//   z = 0, w1 = the face z = L.

#include "nurbs/patch.hpp"

#include <string>
#include <utility>
#include <vector>

namespace iga::nurbs {

Patch half_disc(const VecN& center, double radius);
Patch quarter_disc(const VecN& center, double radius);
Patch rectangle(const VecN& corner, const VecN& size);

/// center: 3 coordinates; radius > 0.
Patch sphere_octant(const VecN& center, double radius);
/// corner, size: 3 entries each, size > 0.
Patch box(const VecN& corner, const VecN& size);
/// A bivariate patch in 2D (n_par = 2, dim = 2) extruded along z over [0, length], length > 0.
Patch extrude(const Patch& planar, double length);

/// Side names and a one-line description for a built-in shape ("half_disc", ...,
/// "sphere_octant", "box"), as shown by `igacontact check` and stored in the
/// results file. extruded: a 2D shape extruded along z (then six sides).
std::vector<std::pair<std::string, std::string>> shape_side_names(const std::string& shape_type,
                                                                  bool extruded = false);

}  // namespace iga::nurbs
