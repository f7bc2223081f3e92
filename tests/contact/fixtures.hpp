#pragma once
// Small geometries shared by the contact tests: exact circular arcs
// (docs/theory.md "Exact circles"), a curved rational master, two curved deformable bodies that
// overlap a little, and helpers to turn a pair evaluation into dense matrices.

#include "contact/contact_pair.hpp"
#include "core/types.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace iga::test {

inline VecN vec2(double x, double y)
{
    VecN v(2);
    v << x, y;
    return v;
}

/// A curve (n_par = 1, d = 2) from degree, knots, control points (rows) and weights.
inline nurbs::Patch make_curve(int degree, std::vector<double> knots, const std::vector<std::array<double, 2>>& points,
                               const std::vector<double>& weights)
{
    RowMatrix P(static_cast<Index>(points.size()), 2);
    Vector w(static_cast<Index>(weights.size()));
    for (std::size_t a = 0; a < points.size(); ++a) {
        P(static_cast<Index>(a), 0) = points[a][0];
        P(static_cast<Index>(a), 1) = points[a][1];
        w(static_cast<Index>(a)) = weights[a];
    }
    return nurbs::Patch({nurbs::KnotVector(degree, std::move(knots))}, std::move(P), std::move(w));
}

/// Exact quarter circle of radius R about the origin, from (R, 0) to (0, R).
/// Orientation sign +1 gives the normal pointing away from the centre.
inline nurbs::Patch quarter_arc(double R)
{
    const double s = std::sqrt(2.0) / 2.0;
    return make_curve(2, {0, 0, 0, 1, 1, 1}, {{R, 0}, {R, R}, {0, R}}, {1.0, s, 1.0});
}

/// Exact upper half circle of radius R from two quarters joined by a double
/// knot at 1/2 (C0 in the basis, C1 as a curve). Sign +1: away from the centre.
inline nurbs::Patch two_quarter_half_circle(double R)
{
    const double s = std::sqrt(2.0) / 2.0;
    return make_curve(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}, {{R, 0}, {R, R}, {0, R}, {-R, R}, {-R, 0}},
                      {1.0, s, 1.0, s, 1.0});
}

/// Curved rational quadratic master (weights 1, 0.8, 1.3), an arch over [0, 2]
/// bulging up; with sign -1 its normal points up, out of the body below it.
inline nurbs::Patch rational_arch() { return make_curve(2, {0, 0, 0, 1, 1, 1}, {{0, 0}, {1, 0.6}, {2, 0}}, {1.0, 0.8, 1.3}); }
constexpr int rational_arch_sign = -1;

/// Lower half disc (centre (0, 1), radius 1, lowest point at the origin) with its
/// contact arc (side v0) split into `n_spans` spans.
inline nurbs::Patch refined_half_disc(int n_spans)
{
    nurbs::Patch disc = nurbs::half_disc(vec2(0.0, 1.0), 1.0);
    std::vector<double> knots;
    for (int k = 1; k < n_spans; ++k)
        knots.push_back(static_cast<double>(k) / n_spans);
    return nurbs::insert_knots(disc, 0, knots);
}

/// A block under the disc, x in [-1.5, 1.5], y in [-1, ~0], degree (2, 1), with a
/// curved rational top side (v1) whose lowest region is near the origin.
inline nurbs::Patch curved_block()
{
    const std::vector<double> u_knots{0, 0, 0, 0.5, 1, 1, 1};
    const double top[4][2] = {{-1.5, 0.06}, {-0.5, -0.01}, {0.5, 0.01}, {1.5, 0.08}};
    const double w[4] = {1.0, 0.8, 1.3, 1.0};
    RowMatrix P(8, 2);
    Vector weights(8);
    for (int i = 0; i < 4; ++i) {
        P(i, 0) = top[i][0];
        P(i, 1) = -1.0;  // v = 0: bottom
        P(4 + i, 0) = top[i][0];
        P(4 + i, 1) = top[i][1];
        weights(i) = weights(4 + i) = w[i];
    }
    return nurbs::Patch({nurbs::KnotVector(2, u_knots), nurbs::KnotVector(1, {0, 0, 1, 1})}, std::move(P),
                        std::move(weights));
}

/// n x d displacement: a rigid translation plus uniform noise of size `noise`.
inline RowMatrix shifted(int n_cp, const VecN& shift, double noise, std::mt19937& rng)
{
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    RowMatrix u(n_cp, 2);
    for (int a = 0; a < n_cp; ++a)
        for (int i = 0; i < 2; ++i)
            u(a, i) = shift(i) + noise * unit(rng);
    return u;
}

/// The pair's tangent as one dense n x n matrix (the blocks summed): for checks on
/// small test pairs only; the library never forms it.
inline Matrix dense(const std::vector<contact::LocalBlock>& blocks, int n)
{
    Matrix K = Matrix::Zero(n, n);
    for (const contact::LocalBlock& block : blocks)
        for (std::size_t j = 0; j < block.dofs.size(); ++j)
            for (std::size_t i = 0; i < block.dofs.size(); ++i)
                K(block.dofs[i], block.dofs[j]) += block.K(static_cast<Index>(i), static_cast<Index>(j));
    return K;
}

/// Stacks the two sides' displacements into one local dof vector (pair numbering).
inline Vector stack(const RowMatrix& first, const RowMatrix& second)
{
    Vector v(first.size() + second.size());
    Index k = 0;
    for (Index a = 0; a < first.rows(); ++a)
        for (Index i = 0; i < first.cols(); ++i)
            v(k++) = first(a, i);
    for (Index a = 0; a < second.rows(); ++a)
        for (Index i = 0; i < second.cols(); ++i)
            v(k++) = second(a, i);
    return v;
}

/// Inverse of stack for sides with n_first and n_second control points (d = 2).
inline std::pair<RowMatrix, RowMatrix> unstack(const Vector& v, int n_first, int n_second)
{
    RowMatrix first(n_first, 2), second(n_second, 2);
    Index k = 0;
    for (int a = 0; a < n_first; ++a)
        for (int i = 0; i < 2; ++i)
            first(a, i) = v(k++);
    for (int a = 0; a < n_second; ++a)
        for (int i = 0; i < 2; ++i)
            second(a, i) = v(k++);
    return {first, second};
}

}  // namespace iga::test
