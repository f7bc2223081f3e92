#include "analysis/zone_symmetry.hpp"

#include "analysis/geometry.hpp"
#include "analysis/multipatch.hpp"
#include "nurbs/side_patch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iga::analysis {

namespace {

/// Coordinates within this fraction of a patch's size count as equal.
constexpr double plane_tolerance = 1e-9;

double size_of(const RowMatrix& points)
{
    return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

}  // namespace

std::vector<SymmetryPlane> symmetry_planes(const io::Deck& deck, const io::Body& body)
{
    std::vector<SymmetryPlane> planes;
    if (body.rigid)
        return planes;
    const BodyPatches parts = build_body_patches(deck, body);
    double size = 0.0;
    for (const nurbs::Patch& patch : parts.patches)
        size = std::max(size, size_of(patch.control_points()));
    const double tolerance = plane_tolerance * size;
    for (const io::Constraint& c : deck.constraints) {
        if (c.body != body.name)
            continue;
        const auto held = static_cast<int>(std::count(c.fixed.begin(), c.fixed.end(), true));
        if (held == 0 || held == static_cast<int>(c.fixed.size()))
            continue;  // free, or a clamp
        // Every patch side the constraint names (a named surface: all of them) lies in the plane.
        for (const BodySide& at : resolve_sides(body, parts.names, c.patch, c.side, c.surface)) {
            const RowMatrix x =
                nurbs::extract_side(parts.patches[static_cast<std::size_t>(at.patch)], at.side).patch.control_points();
            for (int i = 0; i < static_cast<int>(x.cols()); ++i) {
                const auto k = static_cast<std::size_t>(i);
                const bool flat = x.col(i).maxCoeff() - x.col(i).minCoeff() <= tolerance;
                const double coordinate = x.col(i).mean();
                const bool known = std::any_of(planes.begin(), planes.end(), [&](const SymmetryPlane& p) {
                    return p.axis == i && std::abs(p.coordinate - coordinate) <= tolerance;
                });  // two patches' sides on one plane, or two constraints on one side
                if (flat && c.fixed[k] && c.value[k] == 0.0 && !known)
                    planes.push_back({i, coordinate});
            }
        }
    }
    return planes;
}

int zone_mirrors(const std::vector<SymmetryPlane>& planes, const RowMatrix& side_points, const io::GaussPointData& g,
                 const std::vector<Index>& zone)
{
    const double tolerance = plane_tolerance * size_of(side_points);
    int mirrors = 0;
    for (const SymmetryPlane& plane : planes) {
        const auto distance = [&](Index k) { return std::abs(g.reference_coordinates(k, plane.axis) - plane.coordinate); };
        if ((side_points.col(plane.axis).array() - plane.coordinate).abs().minCoeff() > tolerance)
            continue;  // the side does not reach the plane
        // The zone's first row along the plane, or a zone nearer to the plane than its own
        // extent across it (a coarse level's zone that has lifted off the plane in a ring).
        double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0, width = 0.0;
        for (const Index k : zone) {
            if (distance(k) < nearest) {
                nearest = distance(k);
                width = g.reference_coordinates.cols() == 2 ? g.weight(k) : std::sqrt(g.weight(k));
            }
            farthest = std::max(farthest, distance(k));
        }
        const bool cut = !zone.empty() && (nearest < 0.75 * width || nearest < farthest - nearest);
        if (cut)
            ++mirrors;
    }
    return mirrors;
}

}  // namespace iga::analysis
