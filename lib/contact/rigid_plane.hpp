#pragma once
// A rigid plane obstacle (a line in 2D): the points y with (y - point) . normal <= 0
// are inside the obstacle; `normal` is the unit normal pointing OUT of it.
//
// It plays the master: its outward normal is `normal`, and the gap of a slave
// point x follows gap.hpp, g_N = -(x - point) . normal: negative (open) above the
// plane, positive (penetration) inside the obstacle. The residual of the slave
// uses this normal, which does not depend on any unknown (no master dofs).

#include "contact/gap.hpp"
#include "core/error.hpp"
#include "core/types.hpp"

#include <cmath>

namespace iga::contact {

struct RigidPlane {
    VecN point;   ///< a point on the plane, d
    VecN normal;  ///< unit normal out of the obstacle, d

    /// Normalizes `normal`; throws iga::Error for mismatched sizes, non-finite
    /// values or a zero normal (the deck reader rejects these first).
    static RigidPlane make(const VecN& point, const VecN& normal)
    {
        IGA_CHECK(point.size() == normal.size() && (point.size() == 2 || point.size() == 3),
                  "contact: rigid plane point and normal need the same dimension, 2 or 3");
        IGA_CHECK(point.allFinite() && normal.allFinite() && normal.norm() > 0.0,
                  "contact: rigid plane needs a finite point and a non-zero finite normal");
        return RigidPlane{point, normal.normalized()};
    }

    /// g_N of x: positive = penetration into the obstacle.
    double gap(const VecN& x) const { return normal_gap(x, point, normal); }
};

}  // namespace iga::contact
