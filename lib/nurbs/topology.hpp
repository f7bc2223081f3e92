#pragma once
// Multi-patch topology: which sides of a body's patches are glued together
// (interfaces), how to make the patches conforming across them, and one
// numbering of the body's control points ("nodes") in which the control points
// of an interface are shared.
//
// Interfaces. A side of one patch and a side of another patch (never of the same
// patch, never a collapsed side) form a candidate interface when their corner
// control points coincide under one of the orientations of the side grids: in
// 2D the side curves run the same way or opposite ways (2 orientations); in 3D a
// side's two directions map onto the other side's two directions, swapped or
// not, each reversed or not (8 orientations). Candidates are made conforming
// (below); then every control point of the two sides must coincide (to the
// tolerance) and their weights must be proportional, else the interface does not
// match (NonMatchingInterface). Among several orientations that fit the corners
// (a side with a collapsed edge), the first in the order above whose control
// points all coincide is taken.
//
// The search is near-linear in the number of patches: the corners of every side
// go into a hash of cells at least the tolerance wide, and a side is compared
// only with the sides that have a corner in the 3^d cells around its first
// corner. Candidates are kept in (patch, side, patch, side) order.
//
// Conforming refinement. Along an interface, direction k of side a and its image
// direction of side b must carry the same degree and the same knots in
// normalized parameters t = (u - u_front) / (u_back - u_front) (reversed: 1 - t).
// glue_patches raises the lower degree and inserts into each side the knots of
// the other it lacks, at the multiplicity of the side that has more, until no
// interface changes any more (a knot propagates along a chain of patches).
//
// Nodes. node[p][a] is the body node of control point a of patch p: nodes are
// numbered in patch order, then control-point order, and the control points
// that interfaces pair (transitively: the patches around one vertex or along one
// edge) share one node. A single patch is numbered 0 .. n_cp - 1.

#include "core/error.hpp"
#include "core/side.hpp"
#include "core/stop.hpp"
#include "nurbs/patch.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace iga::nurbs {

/// How the grid of side b lies on the grid of side a: side a's own direction k
/// (0 .. n_par - 2) runs along side b's direction `dir[k]`, reversed when flip[k].
struct SideOrientation {
    std::array<int, 2> dir{0, 1};
    std::array<bool, 2> flip{false, false};
};

/// Two glued sides: patch_a's side_a and patch_b's side_b (patch_a < patch_b).
struct Interface {
    int patch_a = 0;
    Side side_a = Side::u0;
    int patch_b = 0;
    Side side_b = Side::u0;
    SideOrientation orientation;
};

/// The sides' corners coincide but, after conforming refinement, their control
/// points (or weights) do not: the patches cannot be glued.
class NonMatchingInterface : public Error {
public:
    NonMatchingInterface(int patch_a, Side side_a, int patch_b, Side side_b, const std::string& reason);
    int patch_a, patch_b;
    Side side_a, side_b;
};

struct Topology {
    std::vector<Interface> interfaces;
    std::vector<std::vector<int>> node;  ///< per patch: control point -> body node
    int n_nodes = 0;

    /// True when side `side` of patch p is glued to another patch.
    bool is_interface(int p, Side side) const;
};

/// Finds the interfaces of `patches` (all with the same n_par >= 2 and dimension),
/// refines the patches in place until they conform across them, and numbers the
/// nodes. `tolerance`: absolute distance under which two control points coincide.
/// Throws NonMatchingInterface, and Interrupted once `stop` is requested (polled per
/// patch and per interface candidate).
Topology glue_patches(std::vector<Patch>& patches, double tolerance, const StopRequest& stop = {});

/// Parameter point of `patch` (solid: n_par = dim) whose image is x, found by
/// Newton from the nearest of a few samples per element; nullopt when x is not
/// inside the patch's parameter box (to `parameter_margin`, a fraction of each
/// direction's range, counted inward) or Newton does not converge.
std::optional<VecN> invert_point(const Patch& patch, const VecN& x, double parameter_margin);
/// The same, Newton started from the nearest of the samples of one element only
/// (a local search: e.g. the element whose bounding box holds x).
std::optional<VecN> invert_point(const Patch& patch, const VecN& x, double parameter_margin, const Element& start);

}  // namespace iga::nurbs
