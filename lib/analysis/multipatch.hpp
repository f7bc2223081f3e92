#pragma once
// A deformable body as a list of patches (deck.md "Multi-patch bodies and named
// surfaces"): the refined patches, glued conformingly (nurbs/topology.hpp), with
// the checks that make a set of patches one body, and the resolution of a side
// reference (`side`, `patch.side`, a named surface) into patch sides.
//
// Refinement of a multi-patch body: the body's `refine` on every patch, then
// the patch's own, each in the fixed order (elevate, spans, insert); then
// glue_patches propagates degrees and knots across the interfaces. A body
// given as `nurbs:` or `shape:` is a one-patch list (its patch name is "").
//
// Checks, each a located DeckError naming the body and patch: a patch that is
// not solid (n_par = d), sides whose corners coincide but whose control points
// cannot be matched (non-matching interface), a patch with points inside
// another (overlapping patches), patches not connected through interfaces (a
// side half shared with another patch is not an interface, so such patches are
// reported here), a named surface side that is an interface, a patch thinner
// than the tolerance (its opposite sides coincide: it would be glued on both).
// Coincidence tolerance: glue_relative_tolerance times the body's bounding-box
// diagonal. Every check is near-linear in the number of patches and elements
// (the overlap test inverts a point only into the elements whose box holds it).

#include "analysis/geometry.hpp"
#include "core/side.hpp"
#include "core/stop.hpp"
#include "io/deck.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/topology.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// Control points closer than this fraction of the body size coincide: far above
/// the round-off of refinement and of 16-digit input, far below any feature size.
inline constexpr double glue_relative_tolerance = 1e-9;

/// A side of one patch of a body.
struct BodySide {
    int patch = 0;
    Side side = Side::u0;   ///< of the analysed (placed) patch
    Side named = Side::u0;  ///< as the deck names it: the side of the patch as built (analysis/geometry.hpp)

    bool operator==(const BodySide&) const = default;
};

struct BodyPatches {
    std::vector<std::string> names;     ///< deck names ("" for a single-patch body)
    std::vector<nurbs::Patch> patches;  ///< refined and conforming
    nurbs::Topology topology;
};

/// The located bad-input error of a transform step out of range (analysis/geometry.hpp):
/// at `<transform path>.<step>.<kind>` of the body (`patch`: an item of `patches`, or "").
DeckError transform_error(const io::Deck& deck, const io::Body& body, const std::string& patch,
                          const TransformOutOfRange& e);

/// The patches of deformable deck body `body` (precondition: !body.rigid), refined
/// (then every span halved `halvings` times: RunOptions::refine_levels), glued and
/// checked; throws a located DeckError, and Interrupted once `stop` is requested.
BodyPatches build_body_patches(const io::Deck& deck, const io::Body& body, int halvings = 0,
                               const StopRequest& stop = {});

/// The patch sides a reference names (the reader checked the names): a named
/// surface's sides, or the one side `patch.side` / `side`; names are those of the
/// patch as built, the sides those of the placed patch (analysis/geometry.hpp).
std::vector<BodySide> resolve_sides(const io::Body& body, const std::vector<std::string>& patch_names,
                                    const std::string& patch, Side side, const std::string& surface);

/// Whether the transform of patch `patch` of deck body `body` reversed its u.
bool u_reversed(const io::Body& body, int patch);

/// "left.v0", or "v0" for a single-patch body's side, as the deck names it.
std::string body_side_text(const std::vector<std::string>& patch_names, const BodySide& side);

}  // namespace iga::analysis
