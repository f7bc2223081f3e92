#pragma once
// A side of a patch as a NURBS of one parametric dimension less (a curve for a
// 2D surface patch, a surface for a 3D volume patch), with the map from the
// side's control points to the parent patch's control points. Because the
// parent is open (interpolatory at its ends), the side's basis is exactly the
// parent basis restricted to the side.
//
// Parametric directions of the side keep the parent's order with the fixed
// direction removed (side v0 of a surface is parametrized by u).

#include "core/side.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::nurbs {

struct SidePatch {
    Side side;
    Patch patch;                    ///< n_par - 1 parametric directions, same spatial dimension
    std::vector<int> parent_index;  ///< parent control-point index of each side control point
};

/// Extracts side `side` of `patch`. Precondition: side direction < patch.n_par() and n_par >= 2.
SidePatch extract_side(const Patch& patch, Side side);

/// True when all control points of the side coincide (a collapsed side, e.g. a
/// degenerate corner of a disc patch): it has zero length and carries nothing.
bool is_collapsed(const SidePatch& side, double tolerance);

/// True when a face (the side of a volume) is a curve: its control points coincide
/// along one of its directions (the axis of a revolved solid, an extruded corner).
bool is_collapsed_to_line(const SidePatch& side, double tolerance);

}  // namespace iga::nurbs
