#pragma once
// Orientation sign of a 2D patch side: which of the two unit normals of the side
// curve points out of its parent patch.
//
// With t = dX/dxi along the side (xi = the parent parameter that varies on the
// side) and n = s (t_y, -t_x) / |t| (gap.hpp), outward_sign returns the s for
// which n points out of the parent: n . dX/deta < 0 on a side where the fixed
// parameter eta is at its start (u0, v0), > 0 where it is at its end (u1, v1).
// The sign is read in the reference configuration and stays valid while
// det F > 0.

#include "core/side.hpp"
#include "nurbs/patch.hpp"

namespace iga::contact {

/// +1 or -1 as above. Throws iga::Error for a parent that is not a 2D surface
/// patch (3D contact is not supported yet), for a collapsed side, and when the
/// sign changes along the side (a folded parametrization).
int outward_sign(const nurbs::Patch& parent, Side side);

}  // namespace iga::contact
