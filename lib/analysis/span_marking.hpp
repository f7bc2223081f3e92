#pragma once
// Which knot spans of a contact side the next level of `accuracy:` halves
// (docs/accuracy_on_demand.md, "Where the levels refine").
//
// From two levels, Dörfler's bulk criterion on the levels' pressure difference: with
// eta_e^2 = || p_k - p_{k-1} ||^2_L2(e) on each element e of the side (the error indicator
// of the two-level estimate, level_estimate.hpp), a direction's span i gathers the
// elements of its slab, eta_i^2 = sum over e in span i of eta_e^2, and the fewest spans
// whose eta_i^2 add up to bulk_fraction of the total are marked, all directions together.
// difference is largest where the pressure is least resolved (Hertz's edge, where it
// falls to zero as a square root; a punch's corner); the zone's inside, where it is
// smooth, is marked only once the edge has caught up.
//
// From one level (the first refinement, with no difference yet), the spans of the
// elements of the side that meet the pressed zone widened by half its extent (at least
// min_margin of the largest contact side): the zone and its edge.
//
// A side's directions are its parent patch's with the side's own direction removed
// (nurbs/side_patch.hpp), so a mark's knot index is the parent's as well.

#include "io/results_data.hpp"
#include "nurbs/patch.hpp"

#include <optional>
#include <set>
#include <vector>

namespace iga::analysis {

/// Share of a direction's indicator the marked spans carry (Dörfler's theta).
inline constexpr double bulk_fraction = 0.9;

/// Indicators within this relative distance of each other tie: the slabs that tie with the
/// last one Dörfler's criterion takes are marked too (a symmetric zone's mirror spans; sums
/// in another order on another number of ranks differ by about 1e-12 of them).
inline constexpr double tie_tolerance = 1e-6;

/// Smallest margin around the zone, as a fraction of the largest contact side's size (a
/// zone of one Gauss point has no extent).
inline constexpr double min_margin = 0.01;

/// An axis-aligned box in space.
struct ZoneBox {
    VecN lower, upper;
};

/// The box of the pressed Gauss points (reference coordinates) of a pair's sides; empty
/// when no point presses.
std::optional<ZoneBox> pressed_zone(const io::ContactPairResult& pair);

/// The zone widened by half its largest extent, at least min_margin * model_size.
ZoneBox widened(const ZoneBox& zone, double model_size);

/// The spans of a contact side to halve.
struct SurfaceMarks {
    std::vector<std::set<int>> spans;  ///< per direction of the side: knot index i of [t_i, t_{i+1})
    VecN center;                       ///< parameters of a point of the side in the zone
    bool empty() const;
};

/// Dörfler's marking of `side` from the squared indicator of each of its elements (rows in
/// side.elements() order), split over the directions (columns), with the slabs that tie
/// with the last one taken; the center is the first element that ties with the largest
/// indicator.
SurfaceMarks marks_from_indicators(const nurbs::Patch& side, const RowMatrix& element_indicator2,
                                   double fraction = bulk_fraction);
/// The same over the pieces of a named surface together (their slabs compete for one
/// bulk): one SurfaceMarks per piece, each piece's center its own.
std::vector<SurfaceMarks> marks_from_indicators(const std::vector<const nurbs::Patch*>& sides,
                                                const std::vector<RowMatrix>& element_indicator2,
                                                double fraction = bulk_fraction);

/// Marks made on side `marked`, on the same side `now` after other knots went in (another
/// piece of a named surface refined first, and gluing carried its knots across): each
/// marked span [t_i, t_{i+1}) of `marked` by its index in `now`, or dropped where `now`
/// has split it already (it is halved).
SurfaceMarks remap_marks(const SurfaceMarks& marks, const nurbs::Patch& marked, const nurbs::Patch& now);

/// The squared indicator of a stick zone's edge on each element of `side` (rows in
/// side.elements() order, split over the directions in the columns), from the side's own
/// Gauss points: where a sticking point and one that does not stick (slipping or open)
/// meet, in one element or in two neighbours, the edge lies somewhere within the element,
/// and the stick zone's measure is uncertain by the element's (eta_e = the weights of its
/// points). A neighbour across direction k that differs marks direction k; an element
/// whose own points differ and whose neighbours do not, every direction alike. Zero
/// elsewhere.
RowMatrix stick_edge_indicator(const nurbs::Patch& side, const io::GaussPointData& points, int stick_status);

/// The spans of the elements of `side` whose points' box meets `region`; the center is the
/// middle of the marked elements' parameters.
SurfaceMarks marks_from_zone(const nurbs::Patch& side, const ZoneBox& region);

/// The box of a grid of points on one element of `patch` (elements much larger than a
/// zone contain it without a point inside it, so the box, not the points, is tested).
ZoneBox element_box(const nurbs::Patch& patch, const nurbs::Element& element);

}  // namespace iga::analysis
