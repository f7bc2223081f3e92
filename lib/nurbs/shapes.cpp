#include "nurbs/shapes.hpp"

#include "core/error.hpp"

#include <cmath>

namespace iga::nurbs {

namespace {

void check_point(const VecN& p, const char* what)
{
    IGA_CHECK(p.size() == 2, std::string(what) + " must have 2 coordinates");
    IGA_CHECK(p.allFinite(), std::string(what) + " must be finite");
}

void check_radius(double radius)
{
    IGA_CHECK(std::isfinite(radius) && radius > 0, "radius must be finite and > 0");
}

/// Two rows of control points (v = 0 then v = 1, u fastest) relative to `origin`.
Patch two_row_patch(KnotVector u_knots, const VecN& origin, const std::vector<std::array<double, 2>>& rows,
                    const std::vector<double>& row_weights)
{
    const int n_u = static_cast<int>(row_weights.size());
    RowMatrix points(2 * n_u, 2);
    Vector weights(2 * n_u);
    for (int a = 0; a < 2 * n_u; ++a) {
        points(a, 0) = origin(0) + rows[a][0];
        points(a, 1) = origin(1) + rows[a][1];
        weights(a) = row_weights[a % n_u];
    }
    return Patch({std::move(u_knots), KnotVector(1, {0, 0, 1, 1})}, std::move(points), std::move(weights));
}

}  // namespace

Patch half_disc(const VecN& center, double radius)
{
    check_point(center, "half_disc center");
    check_radius(radius);
    const double R = radius;
    // Single-span rational cubic lower half circle (physics.md 5.2, rotated by pi):
    // weights 1, 1/3, 1/3, 1. The diameter row has the same x and weights, so
    // x(u, v) has the x-coordinate of the arc point at every v.
    return two_row_patch(KnotVector(3, {0, 0, 0, 0, 1, 1, 1, 1}), center,
                         {{-R, 0}, {-R, -2 * R}, {R, -2 * R}, {R, 0},  // v = 0: arc
                          {-R, 0}, {-R, 0}, {R, 0}, {R, 0}},           // v = 1: diameter
                         {1.0, 1.0 / 3.0, 1.0 / 3.0, 1.0});
}

Patch quarter_disc(const VecN& center, double radius)
{
    check_point(center, "quarter_disc center");
    check_radius(radius);
    const double R = radius;
    const double s = std::sqrt(2.0) / 2.0;
    // Degree-2 quarter arc from the lowest point to the right end (physics.md 5.2).
    return two_row_patch(KnotVector(2, {0, 0, 0, 1, 1, 1}), center,
                         {{0, -R}, {R, -R}, {R, 0},  // v = 0: arc
                          {0, 0}, {R, 0}, {R, 0}},   // v = 1: top line
                         {1.0, s, 1.0});
}

Patch rectangle(const VecN& corner, const VecN& size)
{
    check_point(corner, "rectangle corner");
    check_point(size, "rectangle size");
    IGA_CHECK(size(0) > 0 && size(1) > 0, "rectangle size must be > 0 in both directions");
    return two_row_patch(KnotVector(1, {0, 0, 1, 1}), corner,
                         {{0, 0}, {size(0), 0}, {0, size(1)}, {size(0), size(1)}}, {1.0, 1.0});
}

std::vector<std::pair<std::string, std::string>> shape_side_names(const std::string& shape_type)
{
    if (shape_type == "half_disc")
        return {{"v0", "arc (contact side)"},
                {"v1", "flat top (diameter)"},
                {"u0", "collapsed: left end of the diameter"},
                {"u1", "collapsed: right end of the diameter"}};
    if (shape_type == "quarter_disc")
        return {{"v0", "arc (contact side)"},
                {"v1", "flat top"},
                {"u0", "symmetry line x = center x"},
                {"u1", "collapsed: right end of the top line"}};
    if (shape_type == "rectangle")
        return {{"u0", "left (x = corner x)"},
                {"u1", "right (x = corner x + size x)"},
                {"v0", "bottom (y = corner y)"},
                {"v1", "top (y = corner y + size y)"}};
    throw Error("shape_side_names: unknown shape type '" + shape_type +
                "' (expected half_disc, quarter_disc or rectangle)");
}

}  // namespace iga::nurbs
