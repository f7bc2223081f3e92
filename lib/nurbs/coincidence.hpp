#pragma once
// When control points coincide: one tolerance for every check of a collapsed side
// (boundary/patch_side: sides that carry nothing; contact/contact_pair: a contact
// side that is a point; the `check` listing of collapsed sides and lines).

#include "core/types.hpp"

namespace iga::nurbs {

/// Control points closer than this times the size of their coordinates coincide: a
/// few thousand ulps, the round-off of the shapes' and transforms' arithmetic, far
/// below any real side length.
inline constexpr double coincidence_relative_tolerance = 1e-12;

/// The distance below which control points of one patch (n x d) coincide:
/// coincidence_relative_tolerance * (1 + max |x_i|), absolute near the origin.
inline double coincidence_tolerance(const RowMatrix& points)
{
    const double size = points.size() > 0 ? points.cwiseAbs().maxCoeff() : 0.0;
    return coincidence_relative_tolerance * (1.0 + size);
}

}  // namespace iga::nurbs
