#pragma once
// Exact NURBS surfaces in 3D for the projection and search tests: a quarter
// cylinder and a sphere octant (the surface of revolution of a quarter circle,
// collapsed to a pole on its side v = 1), built from their control points here.
// Both have orientation sign +1 for the normal pointing away from the axis /
// centre. Control points u fastest: index(i, j) = i + n_u j.

#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace iga::test {

inline VecN vec3(double x, double y, double z)
{
    VecN v(3);
    v << x, y, z;
    return v;
}

/// Tensor-product surface (n_par = 2, d = 3) from control points (n_u n_v x 3) and weights.
inline nurbs::Patch make_surface(nurbs::KnotVector u, nurbs::KnotVector v, RowMatrix points, Vector weights)
{
    return nurbs::Patch({std::move(u), std::move(v)}, std::move(points), std::move(weights));
}

/// Quarter circle of radius 1 in the xy-plane from (1, 0) to (0, 1): control
/// points (x, y) and weights (degree 2, one span).
struct QuarterCircle {
    std::array<std::array<double, 2>, 3> points{{{1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}};
    std::array<double, 3> weights{1.0, std::sqrt(2.0) / 2.0, 1.0};
};

/// Quarter cylinder x^2 + y^2 = R^2, x, y >= 0, z in [0, L]: u along the arc from
/// (R, 0, z) to (0, R, z) (degree 2), v along z (degree 1).
inline nurbs::Patch quarter_cylinder(double R, double L)
{
    const QuarterCircle c;
    RowMatrix P(6, 3);
    Vector w(6);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            P.row(i + 3 * j) << R * c.points[i][0], R * c.points[i][1], L * j;
            w(i + 3 * j) = c.weights[i];
        }
    return make_surface(nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1}), P, w);
}

/// Sphere octant of radius R about the origin, x, y, z >= 0: u is the azimuth
/// from the x-axis to the y-axis, v the meridian from the equator (v = 0) to the
/// pole (0, 0, R) (v = 1, a collapsed edge). Degree 2 x 2, weights w_i w_j.
inline nurbs::Patch sphere_octant(double R)
{
    const QuarterCircle c;  // reused as the azimuth circle (x, y) and as the meridian (r, z)
    RowMatrix P(9, 3);
    Vector w(9);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const double r = R * c.points[j][0], z = R * c.points[j][1];
            P.row(i + 3 * j) << r * c.points[i][0], r * c.points[i][1], z;
            w(i + 3 * j) = c.weights[i] * c.weights[j];
        }
    const nurbs::KnotVector quadratic(2, {0, 0, 0, 1, 1, 1});
    return make_surface(quadratic, quadratic, P, w);
}

}  // namespace iga::test
