#pragma once
// From a deck body to the analysed NURBS patch: the raw NURBS data or the
// built-in shape (a 2D shape extruded along z in a 3D deck), then the
// refinement of the deck in its fixed order (elevate, uniform spans, inserted
// knots). Refinement preserves the geometry.

#include "io/deck.hpp"
#include "nurbs/patch.hpp"

#include <string>
#include <utility>
#include <vector>

namespace iga::analysis {

/// A deck coordinate list as a small vector.
inline VecN to_vec(const std::vector<double>& v)
{
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Index>(v.size()));
}

/// Side name -> one-line meaning for a body made from a built-in shape (extruded
/// or not), as `check` prints them and the results file stores them; empty for
/// a body given as raw NURBS.
std::vector<std::pair<std::string, std::string>> side_meanings(const io::Body& body);

/// The refined patch of a single-patch deformable body (nurbs or shape).
/// Precondition: !body.rigid && !body.multi_patch(). `halvings` > 0 then halves
/// every knot span that many times (nurbs::halve_spans: the uniform h-refinement
/// of `igacontact study`, RunOptions::refine_levels).
nurbs::Patch build_patch(const io::Body& body, int dimension, int halvings = 0);

/// The patch of raw NURBS data (rows [x, y, (z,) w]).
nurbs::Patch raw_patch(const io::NurbsData& data, int dimension);

/// Applies `refine` in its fixed order: elevate, uniform spans, inserted knots.
nurbs::Patch refined(nurbs::Patch patch, const io::Refine& refine);

}  // namespace iga::analysis
