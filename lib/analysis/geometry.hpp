#pragma once
// From a deck body to the analysed NURBS patch: the raw NURBS data or the
// built-in shape (a 2D shape extruded along z in a 3D deck), placed by its
// `transform:` (nurbs/transform.hpp; a mirror reverses u), then the refinement
// of the deck in its fixed order (elevate, uniform spans, inserted knots).
// Refinement preserves the geometry; side names refer to the placed patch.

#include "io/deck.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/transform.hpp"

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
/// a body given as raw NURBS. After a transform the meanings say so (they
/// describe the shape as built), and a mirror's u0/u1 exchange is applied.
std::vector<std::pair<std::string, std::string>> side_meanings(const io::Body& body);

/// The refined patch of a single-patch deformable body (nurbs or shape).
/// Precondition: !body.rigid && !body.multi_patch(). `halvings` > 0 then halves
/// every knot span that many times (nurbs::halve_spans: the uniform h-refinement
/// of `igacontact study`, RunOptions::refine_levels).
nurbs::Patch build_patch(const io::Body& body, int dimension, int halvings = 0);

/// The patch of raw NURBS data (rows [x, y, (z,) w]), placed by its transform.
nurbs::Patch raw_patch(const io::NurbsData& data, int dimension);

/// The affine map of a deck's `transform:` steps in `dimension` D, composed in
/// list order (identity for no steps). Precondition: the steps passed the reader.
nurbs::Affine placement(const std::vector<io::TransformStep>& steps, int dimension);

/// Applies `refine` in its fixed order: elevate, uniform spans, inserted knots.
nurbs::Patch refined(nurbs::Patch patch, const io::Refine& refine);

}  // namespace iga::analysis
