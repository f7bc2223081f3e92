#pragma once
// Built-in exact shapes (2D), the shapes of deck.md's `shape:` key.
//
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

#include "nurbs/patch.hpp"

#include <string>
#include <utility>
#include <vector>

namespace iga::nurbs {

Patch half_disc(const VecN& center, double radius);
Patch quarter_disc(const VecN& center, double radius);
Patch rectangle(const VecN& corner, const VecN& size);

/// Side names and a one-line description for a built-in shape ("half_disc", ...),
/// as shown by `igacontact check` and stored in the results file.
std::vector<std::pair<std::string, std::string>> shape_side_names(const std::string& shape_type);

}  // namespace iga::nurbs
