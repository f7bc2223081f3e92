#pragma once
// From a deck body to the analysed NURBS patch: the raw NURBS data or the
// built-in shape (a 2D shape extruded along z in a 3D deck) as built, refined in
// the deck's fixed order (elevate, uniform spans, inserted knots), then placed by
// its `transform:` (nurbs/transform.hpp). Knot insertion and elevation commute
// with an affine map of the control points, so the order changes no geometry;
// it keeps `refine` in the parameters of the shape as built.
//
// A transform places a body; it does not rename its faces. A mirror leaves the
// placed patch left-handed, which the element code cannot use, so the placed
// patch has u reversed; side names in a deck (constraints, loads, contact,
// surfaces) and in everything printed or stored refer to the patch AS BUILT, and
// named_side() translates between the two (u0 and u1 trade places, nothing else).

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
/// a body given as raw NURBS. After a transform the meanings say so.
std::vector<std::pair<std::string, std::string>> side_meanings(const io::Body& body);

/// The refined patch of a single-patch deformable body (nurbs or shape).
/// Precondition: !body.rigid && !body.multi_patch(). `halvings` > 0 then halves
/// every knot span that many times (nurbs::halve_spans: the uniform h-refinement
/// of `igacontact study`, RunOptions::refine_levels).
nurbs::Patch build_patch(const io::Body& body, int dimension, int halvings = 0);

/// The patch of raw NURBS data (rows [x, y, (z,) w]), as given (not placed).
nurbs::Patch raw_patch(const io::NurbsData& data, int dimension);

/// The patch placed by `steps` (a mirror reverses u: see above).
nurbs::Patch placed(const nurbs::Patch& patch, const std::vector<io::TransformStep>& steps);

/// The side of the analysed (placed) patch that a deck's side names, and back: the
/// same exchange of u0 and u1 when the placement reversed u, else the side itself.
inline Side named_side(Side side, bool u_reversed)
{
    if (!u_reversed)
        return side;
    return side == Side::u0 ? Side::u1 : side == Side::u1 ? Side::u0 : side;
}

/// The affine map of a deck's `transform:` steps in `dimension` D, composed in
/// list order (identity for no steps). Precondition: the steps passed the reader.
nurbs::Affine placement(const std::vector<io::TransformStep>& steps, int dimension);

/// Applies `refine` in its fixed order: elevate, uniform spans, inserted knots.
nurbs::Patch refined(nurbs::Patch patch, const io::Refine& refine);

}  // namespace iga::analysis
