#pragma once
// Knot insertion toward a contact zone: the h-refinement step of `accuracy:`
// (docs/accuracy_on_demand.md, "Where the levels refine").
//
// One contact side of a body at a time, from its marks (span_marking.hpp):
// - along the side, the marked spans are halved;
// - every direction is then graded, in lengths measured in space along the parametric
//   line through the zone: a span is halved while it is longer than smooth_ratio times
//   another span plus growth times the distance between the two (with a slack of a
//   quarter for a curved line's uneven speed). Neighbours stay within a factor of 2, and
//   away from the zone the spans grow about as fast as their distance from it;
// - the side's own direction, the depth below it, is graded from the side: its first
//   span is at most depth_aspect times the shortest span marked along the side, and the
//   growth carries it into the body.
// growth and depth_aspect are measured, not derived: on the 2D and 3D Hertz starts of
// docs/accuracy_on_demand.md, growth 1 against 0.5 and depth_aspect 6 against 2 reach
// the same error with 20-45 % fewer dofs (2D level 8: 990 dofs and 0.80 % against Hertz,
// with 0.5 and 2: 1 976 dofs and 0.89 %; 3D level 6: 14 904 dofs and 2.73 % against
// 43 200 and 2.78 %). The hand-graded decks of inputs/ are flat at the side as well
// (the 3D sphere's first depth span is 3 times its finest span along the side).
// A tensor-product patch carries each direction's new knots across the whole patch; the
// grading keeps what that costs to about a logarithm of the size ratio per direction.
//
// The new knots are written into the deck's `refine.insert` of the body, in the
// parameters of the patch as built (a mirrored body's u runs the other way in the
// analysed patch), so that the final lists are deck text a user can paste.
//
// A patch side of a multi-patch body (`patch.side`): the spans are those of the patch as
// analysed, glued (nurbs/topology.hpp), and the knots go into that patch's own
// `refine.insert`; gluing carries them across its interfaces into the neighbours, whole
// lines as within one patch, so the body stays conforming. The grading then goes on
// through the interfaces (grade_neighbours): a neighbour's direction across the interface
// is graded from the refined patch's span there, and so on outward. Without it a thin
// contact patch (a tenth of the 2D Hertz quarter's depth) left its neighbour at 2 spans:
// the levels stalled at 1.6 % against Hertz while their differences fell to 0.5 %, an
// estimate of half the error. A named surface is refined piece by piece, each patch side
// by this function with the marks of that piece (accuracy.cpp; span_marking.hpp,
// remap_marks, for the spans an earlier piece split through gluing).

#include "analysis/span_marking.hpp"
#include "core/side.hpp"
#include "io/deck.hpp"

#include <functional>
#include <string>
#include <vector>

namespace iga::analysis {

/// Neighbouring spans differ by at most this factor after the grading.
inline constexpr double smooth_ratio = 2.0;
/// How fast spans may grow with the distance from a shorter span (length per length).
inline constexpr double growth = 1.0;
/// The first span below the side, against the shortest span marked along it.
inline constexpr double depth_aspect = 6.0;

/// Halves the marked spans of side `side` (as the deck names it) of patch `patch` of body
/// `body` ("" for a single-patch body), grades every direction of that patch, and adds the
/// knots to the deck's refine.insert of the body or the patch. Returns one line per
/// direction refined, e.g. "cylinder: u 12 span(s) halved at the zone, 5 more to grade".
std::vector<std::string> refine_side(io::Deck& deck, const std::string& body, const std::string& patch, Side side,
                                     const SurfaceMarks& marks);

/// Grades the patches of multi-patch `body` glued to patch `refined`, outward through the
/// interfaces, breadth first: each neighbour's direction across its interface, from the
/// span of the patch it is reached from that meets the interface (growth as within a
/// patch), the knots into the neighbour's own refine.insert. Returns one line per patch
/// refined.
std::vector<std::string> grade_neighbours(io::Deck& deck, io::Body& body, int refined);

/// Where a direction's grading starts besides its own spans: the side's end of the
/// depth direction, with the largest length of the span there (h0 > 0).
struct GradingSource {
    bool at_end = false;  ///< the source is at breaks.back() (else at breaks.front())
    double h0 = 0.0;      ///< 0: no source
};

/// Span lengths in space of sorted breakpoints (one per span).
using SpanLengths = std::function<std::vector<double>(const std::vector<double>& breaks)>;

/// Halves spans of the sorted breakpoints `breaks` until every span i satisfies
/// L_i <= smooth_ratio L_j + growth dist(i, j) for every other span j and, with a source,
/// L_i <= h0 + growth dist(i, source); L = lengths(breaks), dist the lengths between.
/// Returns the knots added.
std::vector<double> graded_knots(std::vector<double> breaks, const SpanLengths& lengths, GradingSource source = {});

/// Every knot span of every deformable body halved `halvings` times, written into the
/// bodies' (a multi-patch body: each patch's) refine.insert lists, in the deck's
/// parameters: --refine-levels folded into an `accuracy:` deck, whose levels refine from
/// the deck's knots.
void fold_halvings(io::Deck& deck, int halvings);

/// The deck text of the refine.insert lists of the pair's bodies, or of each of their
/// patches (what a user pastes into the deck).
std::string refine_text(const io::Deck& deck, const std::string& pair);

}  // namespace iga::analysis
