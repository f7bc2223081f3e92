#pragma once
// Exact trivariate NURBS solids for the side-geometry tests, built directly.
//
// quarter_cylinder_shell(r_in, r_out, H): u along the quarter circle (degree 2, weights
//   1, sqrt(2)/2, 1) from the x axis to the y axis, v radial (degree 1) from r_in to
//   r_out, w axial (degree 1) from z = 0 to z = H. Faces and outward normals:
//   u0 plane y = 0: -e_y; u1 plane x = 0: -e_x; v0 inner cylinder: -e_r; v1 outer
//   cylinder: +e_r, area (pi / 2) r_out H; w0 z = 0: -e_z; w1 z = H: +e_z.
// octant_ball(R): the solid sphere octant x, y, z >= 0 as a surface of revolution
//   (Piegl & Tiller 8.5) scaled radially: u around the z axis from the x axis to the y
//   axis and v along the meridian from the equator to the pole (both quarter circles of
//   degree 2), w radial (degree 1) from the centre to the sphere. A degenerate hexahedral
//   patch: w0 collapses to the centre (a collapsed face); v1 is the segment from the
//   centre to the pole (a face of zero area); the sphere face w1 has its edge v = 1
//   collapsed to the pole; u0 (plane y = 0, -e_y), u1 (plane x = 0, -e_x) and v0 (plane
//   z = 0, -e_z) each have their edge w = 0 collapsed to the centre. w1 has normal
//   x / R and area pi R^2 / 2.
// transformed(patch, Q, t): control points X -> Q X + t, weights kept.

#include "core/types.hpp"
#include "nurbs/knot_vector.hpp"
#include "nurbs/patch.hpp"

#include <cmath>
#include <vector>

namespace iga::test {

inline nurbs::Patch quarter_cylinder_shell(double r_in, double r_out, double H)
{
    const double s = std::sqrt(0.5);
    const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    const double arc_w[3] = {1, s, 1};
    RowMatrix points(12, 3);
    Vector weights(12);
    int a = 0;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 3; ++i, ++a) {
                const double r = j == 0 ? r_in : r_out;
                points.row(a) << r * arc[i][0], r * arc[i][1], k * H;
                weights(a) = arc_w[i];
            }
    return nurbs::Patch({nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1}),
                         nurbs::KnotVector(1, {0, 0, 1, 1})},
                        points, weights);
}

inline nurbs::Patch octant_ball(double R)
{
    const double s = std::sqrt(0.5);
    const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};  // (cos, sin) control points of a quarter circle
    const double arc_w[3] = {1, s, 1};
    RowMatrix points(18, 3);
    Vector weights(18);
    int a = 0;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j)      // meridian: radius arc[j][0], height arc[j][1]
            for (int i = 0; i < 3; ++i, ++a) {  // around z
                const double rho = arc[j][0], z = arc[j][1];
                points.row(a) << k * R * rho * arc[i][0], k * R * rho * arc[i][1], k * R * z;
                weights(a) = arc_w[i] * arc_w[j];
            }
    const nurbs::KnotVector quadratic(2, {0, 0, 0, 1, 1, 1});
    return nurbs::Patch({quadratic, quadratic, nurbs::KnotVector(1, {0, 0, 1, 1})}, points, weights);
}

inline nurbs::Patch transformed(const nurbs::Patch& patch, const MatN& Q, const VecN& t)
{
    RowMatrix points = patch.control_points() * Q.transpose();
    points.rowwise() += t.transpose();
    return patch.with_control_points(points);
}

}  // namespace iga::test
