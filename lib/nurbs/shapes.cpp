#include "nurbs/shapes.hpp"

#include "core/error.hpp"

#include <cmath>
#include <string>

namespace iga::nurbs {

namespace {

void check_point(const VecN& p, const char* what, Index n_coordinates = 2)
{
    IGA_CHECK(p.size() == n_coordinates, std::string(what) + " must have " + std::to_string(n_coordinates) +
                                             " coordinates");
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

/// The planar patch swept along z over [z0, z1]: degree 1 in w (the slowest control-point index).
Patch sweep_along_z(const Patch& planar, double z0, double z1)
{
    IGA_CHECK(planar.n_par() == 2 && planar.dim() == 2, "extrude: needs a bivariate patch in 2D");
    IGA_CHECK(std::isfinite(z0) && std::isfinite(z1) && z1 > z0, "extrude: the length must be finite and > 0");
    const Index n = planar.n_control_points();
    RowMatrix points(2 * n, 3);
    Vector weights(2 * n);
    for (int k = 0; k < 2; ++k)
        for (Index a = 0; a < n; ++a) {
            points.row(k * n + a) << planar.control_points()(a, 0), planar.control_points()(a, 1), k ? z1 : z0;
            weights(k * n + a) = planar.weights()(a);
        }
    std::vector<KnotVector> knots = planar.all_knots();
    knots.emplace_back(1, std::vector<double>{0, 0, 1, 1});
    return Patch(std::move(knots), std::move(points), std::move(weights));
}

}  // namespace

Patch half_disc(const VecN& center, double radius)
{
    check_point(center, "half_disc center");
    check_radius(radius);
    const double R = radius;
    // Single-span rational cubic lower half circle (docs/theory.md "Exact circles", rotated by pi):
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
    // Degree-2 quarter arc from the lowest point to the right end (docs/theory.md "Exact circles").
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

Patch extrude(const Patch& planar, double length)
{
    return sweep_along_z(planar, 0.0, length);
}

Patch box(const VecN& corner, const VecN& size)
{
    check_point(corner, "box corner", 3);
    check_point(size, "box size", 3);
    IGA_CHECK(size(0) > 0 && size(1) > 0 && size(2) > 0, "box size must be > 0 in all three directions");
    return sweep_along_z(rectangle(corner.head(2), size.head(2)), corner(2), corner(2) + size(2));
}

Patch sphere_octant(const VecN& center, double radius)
{
    check_point(center, "sphere_octant center", 3);
    check_radius(radius);
    // The profile: quarter_disc about the origin in the (x, z) plane; rho = -z >= 0
    // is the distance of each control point from the axis (the line z = 0).
    const Patch profile = quarter_disc(VecN::Zero(2), radius);
    const Index n = profile.n_control_points();
    const double s = std::sqrt(2.0) / 2.0;
    // Revolution arc from the top plane (w = 0, angle 90 degrees) to the plane
    // y = c_y (w = 1, angle 0): a profile point at distance rho from the axis is
    // at (y, z) = rho (sin t, -cos t); the arc's control points for t = 90, the
    // corner, t = 0 are rho (1, 0), rho (1, -1), rho (0, -1) with weights 1, s, 1.
    constexpr double arc_y[3] = {1, 1, 0};
    constexpr double arc_z[3] = {0, -1, -1};
    const double arc_w[3] = {1, s, 1};
    RowMatrix points(3 * n, 3);
    Vector weights(3 * n);
    for (int k = 0; k < 3; ++k)
        for (Index a = 0; a < n; ++a) {
            const double x = profile.control_points()(a, 0);
            const double rho = -profile.control_points()(a, 1);
            points.row(k * n + a) << center(0) + x, center(1) + rho * arc_y[k], center(2) + rho * arc_z[k];
            weights(k * n + a) = profile.weights()(a) * arc_w[k];
        }
    std::vector<KnotVector> knots = profile.all_knots();
    knots.emplace_back(2, std::vector<double>{0, 0, 0, 1, 1, 1});
    return Patch(std::move(knots), std::move(points), std::move(weights));
}

std::vector<std::pair<std::string, std::string>> shape_side_names(const std::string& shape_type, bool extruded)
{
    if (extruded) {
        IGA_CHECK(shape_type == "half_disc" || shape_type == "quarter_disc" || shape_type == "rectangle",
                  "shape_side_names: only 2D shapes are extruded, not '" + shape_type + "'");
        std::vector<std::pair<std::string, std::string>> names;
        for (auto [side, text] : shape_side_names(shape_type, false)) {
            const std::string collapsed = "collapsed: ";
            if (text.rfind(collapsed, 0) == 0)
                text = "collapsed to a line along z: " + text.substr(collapsed.size());
            else
                text += " (face swept along z)";
            names.emplace_back(side, text);
        }
        names.emplace_back("w0", "face z = 0");
        names.emplace_back("w1", "face z = extrude length");
        return names;
    }
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
    if (shape_type == "sphere_octant")
        return {{"v0", "spherical face (contact face)"},
                {"w0", "flat top z = center z (load face)"},
                {"u0", "symmetry face x = center x"},
                {"w1", "symmetry face y = center y"},
                {"v1", "collapsed to a line: the axis from the center to the pole (center x + R)"},
                {"u1", "collapsed to a point: the pole (center x + R, center y, center z)"}};
    if (shape_type == "box")
        return {{"u0", "x = corner x"},
                {"u1", "x = corner x + size x"},
                {"v0", "y = corner y"},
                {"v1", "y = corner y + size y"},
                {"w0", "bottom (z = corner z)"},
                {"w1", "top (z = corner z + size z)"}};
    throw Error("shape_side_names: unknown shape type '" + shape_type +
                "' (expected half_disc, quarter_disc, rectangle, sphere_octant or box)");
}

}  // namespace iga::nurbs
