#pragma once
// Small patches for the mechanics tests, built directly with nurbs::Patch.
//
// grid_patch: uniform open knot vectors on [0, 1] per direction, control points
// at the Greville abscissae scaled by `size`, unit weights, so X(xi) = size .* xi
// exactly (an affine map: polynomial integrands, exact Gauss quadrature).
// distorted: the same with control points moved by up to `amount` (relative to
// the smallest control-point spacing) and weights drawn in [1 - spread, 1 + spread]:
// a rational, curved element that still has det J > 0 for small amounts.
// quarter_annulus: u radial (degree 1) from r_in to r_out, v along the quarter arc
// (degree 2, exact circle) from the x axis to the y axis, right-handed.
// Sides: u0 inner arc, u1 outer arc, v0 on the x axis, v1 on the y axis.

#include "core/types.hpp"
#include "nurbs/knot_vector.hpp"
#include "nurbs/patch.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace iga::test {

inline nurbs::KnotVector uniform_knots(int degree, int n_spans)
{
    std::vector<double> k(static_cast<std::size_t>(degree + 1), 0.0);
    for (int s = 1; s < n_spans; ++s)
        k.push_back(static_cast<double>(s) / n_spans);
    k.insert(k.end(), static_cast<std::size_t>(degree + 1), 1.0);
    return nurbs::KnotVector(degree, k);
}

/// Greville abscissa i of a knot vector: (u_{i+1} + ... + u_{i+p}) / p.
inline double greville(const nurbs::KnotVector& kv, int i)
{
    double sum = 0.0;
    for (int j = 1; j <= kv.degree(); ++j)
        sum += kv.knot_values()[static_cast<std::size_t>(i + j)];
    return sum / kv.degree();
}

inline nurbs::Patch grid_patch(const std::vector<int>& degrees, const std::vector<int>& n_spans, const VecN& size)
{
    const int d = static_cast<int>(degrees.size());
    std::vector<nurbs::KnotVector> knots;
    for (int dir = 0; dir < d; ++dir)
        knots.push_back(uniform_knots(degrees[static_cast<std::size_t>(dir)], n_spans[static_cast<std::size_t>(dir)]));
    int n_cp = 1;
    for (const auto& kv : knots)
        n_cp *= kv.n_basis();
    RowMatrix points(n_cp, d);
    for (int index = 0; index < n_cp; ++index) {
        int rest = index;
        for (int dir = 0; dir < d; ++dir) {
            const int n = knots[static_cast<std::size_t>(dir)].n_basis();
            points(index, dir) = size(dir) * greville(knots[static_cast<std::size_t>(dir)], rest % n);
            rest /= n;
        }
    }
    return nurbs::Patch(knots, points, Vector::Ones(n_cp));
}

inline nurbs::Patch distorted(const nurbs::Patch& patch, std::mt19937& rng, double amount, double weight_spread)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    double spacing = 1e300;
    for (int dir = 0; dir < patch.n_par(); ++dir) {
        const auto& k = patch.knots(dir);
        for (int i = 0; i + 1 < k.n_basis(); ++i)
            spacing = std::min(spacing, greville(k, i + 1) - greville(k, i));
    }
    double scale = patch.control_points().cwiseAbs().maxCoeff();
    RowMatrix points = patch.control_points();
    for (Index i = 0; i < points.rows(); ++i)
        for (Index j = 0; j < points.cols(); ++j)
            points(i, j) += amount * spacing * scale * unit(rng);
    Vector weights(points.rows());
    for (Index i = 0; i < weights.size(); ++i)
        weights(i) = 1.0 + weight_spread * unit(rng);
    return nurbs::Patch(patch.all_knots(), points, weights);
}

inline nurbs::Patch quarter_annulus(double r_in, double r_out)
{
    const double s = std::sqrt(0.5);
    std::vector<nurbs::KnotVector> knots{nurbs::KnotVector(1, {0, 0, 1, 1}),
                                         nurbs::KnotVector(2, {0, 0, 0, 1, 1, 1})};
    const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    const double arc_w[3] = {1, s, 1};
    RowMatrix points(6, 2);
    Vector weights(6);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 2; ++i) {
            const double r = i == 0 ? r_in : r_out;
            points.row(i + 2 * j) << r * arc[j][0], r * arc[j][1];
            weights(i + 2 * j) = arc_w[j];
        }
    return nurbs::Patch(knots, points, weights);
}

/// Random matrix with entries uniform in [-scale, scale].
inline Matrix random_matrix(Index rows, Index cols, std::mt19937& rng, double scale)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Matrix m(rows, cols);
    for (Index i = 0; i < rows; ++i)
        for (Index j = 0; j < cols; ++j)
            m(i, j) = scale * unit(rng);
    return m;
}

/// Stacks an n x d matrix row by row into a vector (local dof a*d + i) and back.
inline Vector flatten(const Matrix& m)
{
    Vector v(m.size());
    for (Index a = 0; a < m.rows(); ++a)
        for (Index i = 0; i < m.cols(); ++i)
            v(a * m.cols() + i) = m(a, i);
    return v;
}
inline Matrix unflatten(const Vector& v, Index d)
{
    Matrix m(v.size() / d, d);
    for (Index a = 0; a < m.rows(); ++a)
        for (Index i = 0; i < d; ++i)
            m(a, i) = v(a * d + i);
    return m;
}

/// Rotation by `angle` in 2D, or about the unit axis (1, 2, 3)/sqrt(14) in 3D.
inline MatN rotation(int d, double angle)
{
    if (d == 2) {
        MatN Q(2, 2);
        Q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
        return Q;
    }
    const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
    return MatN(Eigen::AngleAxisd(angle, axis).toRotationMatrix());
}

}  // namespace iga::test
