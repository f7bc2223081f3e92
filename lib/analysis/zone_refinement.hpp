#pragma once
// Knot insertion toward a contact zone: the h-refinement step of `accuracy:`
// (docs/accuracy_on_demand.md). The zone is the box of the pressed Gauss points' reference
// coordinates over both sides of the pair; a margin of half its largest extent on every
// side (at least `min_margin` of the largest contact side) takes in the zone's edge, where it grows
// under refinement, and the depth below it that carries the contact stresses. Every
// knot span of a deformable body of the pair that holds an element meeting that region
// is halved, in every parametric direction: the zone's neighbourhood is refined by 2
// per level, the tangential and the normal direction alike, and the tensor-product
// spans carry it across the patch (whose elements away from the zone gain only in one
// direction). Spans longer than twice a neighbour are then halved as well, until none
// is: a 2:1 grading from the zone out to the deck's spans.
//
// An element meets the region when the bounding box of a grid of points on it does
// (elements much larger than the zone contain it without a point inside it).
// The new knots are written into the deck's `refine.insert` of each body, in the
// parameters of the patch as built (a mirrored body's u runs the other way in the
// analysed patch), so that the final lists are deck text a user can paste.
//
// Single-patch deformable bodies and patch sides only: refining one patch of a multi-patch
// body would break the match of its interfaces (the deck reader refuses such a target).

#include "io/deck.hpp"
#include "io/results_data.hpp"

#include <optional>
#include <string>
#include <vector>

namespace iga::analysis {

/// Smallest margin around the zone, as a fraction of the largest contact side's size (a
/// zone of one Gauss point has no extent).
inline constexpr double min_margin = 0.01;

/// The box of the pressed Gauss points (reference coordinates) of a pair's sides; empty
/// when no point presses.
struct ZoneBox {
    VecN lower, upper;
};
std::optional<ZoneBox> pressed_zone(const io::ContactPairResult& pair);

/// Halves the spans of the deformable bodies of `pair` whose elements meet the zone
/// widened by its margin (model_size: the largest extent of the pair's contact sides); adds the
/// knots to the deck's refine.insert. Returns one line per body and direction refined,
/// e.g. "cylinder: u 12 spans halved in [0.0391, 0.133]".
std::vector<std::string> refine_toward_zone(io::Deck& deck, const std::string& pair, const ZoneBox& zone,
                                            double model_size);

/// The deck text of the bodies' refine.insert lists (what a user pastes into the deck).
std::string refine_text(const io::Deck& deck, const std::string& pair);

}  // namespace iga::analysis
