#pragma once
// The symmetry planes that cut a contact zone. A half or quarter model holds half or a
// quarter of its contact zone: the zone's measure (a sum of Gauss point weights,
// level_estimate.hpp) is then that fraction of the whole zone's, and its half-width or
// radius is read from the whole zone by mirroring the part across each plane that cuts it.
//
// A symmetry plane is what a deck writes for one: a flat side of the body perpendicular to
// a coordinate axis, held along that axis and free along the others (`fix: [x]` on the face
// x = c). A side held in every direction is a clamp, and one given a displacement is
// driven: neither is a mirror.

#include "io/deck.hpp"
#include "io/results_data.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::analysis {

/// The plane x_axis = coordinate of the reference configuration.
struct SymmetryPlane {
    int axis = 0;
    double coordinate = 0.0;
};

/// The symmetry planes of a body (above), from the deck's constraints on it (on a
/// multi-patch body, on its patch sides and named surfaces), each plane once.
std::vector<SymmetryPlane> symmetry_planes(const io::Deck& deck, const io::Body& body);

/// How many of `planes` cut the zone made of the Gauss points `zone` of a contact side: a
/// plane cuts it when the side reaches the plane (one of `side_points`, the control points
/// of its patch sides, lies on it)
/// and the zone reaches the plane: its nearest point lies within three quarters of its own
/// width of it (w on a curve, sqrt(w) on a surface; with n Gauss points per span the first
/// row lies 0.11 (n = 3) to 0.05 (n = 5) of a span from the span's end and is 0.28 to 0.12
/// of it wide, the second lies 0.5 to 0.23 from it, farther than its width), or the zone
/// is nearer to the plane than its own extent across it (a coarse level's zone can lift
/// off the plane in a ring: a roller on a soft block at 312 dofs pressed from 0.02 to 0.06).
int zone_mirrors(const std::vector<SymmetryPlane>& planes, const RowMatrix& side_points, const io::GaussPointData& g,
                 const std::vector<Index>& zone);

}  // namespace iga::analysis
