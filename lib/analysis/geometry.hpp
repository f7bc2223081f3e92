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

#include "core/error.hpp"

#include <string>
#include <string_view>
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

/// A transform step that takes the control points out of the range the geometry can
/// be computed in: not finite, beyond max_placed_coordinate (a Jacobian multiplies d
/// such lengths), a body smaller than min_placed_size, or one so far from the origin
/// against its size (min_size_to_distance) that round-off moves its control points by
/// a visible part of it. Thrown by placed() only for a step that made it so (raw
/// control points already out of range are not the transform's doing); the callers
/// locate it at the step, `<transform path>.<step>.<kind>`.
class TransformOutOfRange : public Error {
public:
    TransformOutOfRange(std::size_t step, std::string_view kind, const std::string& reason)
        : Error(reason), step_(step), kind_(kind)
    {
    }
    std::size_t step() const { return step_; }     ///< 0-based index in the list
    const std::string& kind() const { return kind_; }  ///< translate, rotate, mirror or scale

private:
    std::size_t step_;
    std::string kind_;
};

/// Largest coordinate a placed patch may have: the Jacobian determinant is a product of
/// d <= 3 lengths and the element code squares lengths, so 1e100 keeps them below
/// the largest double (1.8e308) with room to spare.
inline constexpr double max_placed_coordinate = 1e100;
/// Smallest size (largest extent of the bounding box) of a placed patch, the same bound from below
/// (a scale of 1e-300 made every Jacobian 0).
inline constexpr double min_placed_size = 1e-100;
/// Smallest size of a placed patch against its largest coordinate: below it the
/// round-off of the coordinates (2.2e-16 of them) exceeds 2e-4 of the body's size
/// (a translation by 1e300 collapsed a unit block to a point).
inline constexpr double min_size_to_distance = 1e-12;

/// The patch placed by `steps` (a mirror reverses u: see above). Throws
/// TransformOutOfRange for a step that leaves the range above.
nurbs::Patch placed(const nurbs::Patch& patch, const std::vector<io::TransformStep>& steps);

/// The key path of a body's transform steps ("bodies.b.shape.transform",
/// "bodies.b.nurbs.transform", "bodies.b.geometry.transform" or, for an item of
/// `patches`, "bodies.b.patches.<name>.nurbs.transform"), for locating a
/// TransformOutOfRange: append ".<step>.<kind>".
std::string transform_path(const io::Body& body, const std::string& patch);

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
