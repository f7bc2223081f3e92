// Tests of geometry-preserving refinement (knot insertion, degree elevation)
// and of Bezier extraction.

#include "core/error.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"
#include "random_patch.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace iga::nurbs {
namespace {

// Refinement is exact in exact arithmetic; each step forms convex combinations
// of O(1) homogeneous points, so only a few ulp per step accumulate.
constexpr double geometry_tolerance = 1e-13;
// Bezier extraction operators are products of convex-combination factors.
constexpr double extraction_tolerance = 1e-13;

/// Max over random points of |x_a - x_b| and of |dx_a - dx_b| / max(1, |dx_b|).
void expect_same_geometry(const Patch& a, const Patch& b, std::mt19937& rng, const std::string& what)
{
    ASSERT_EQ(a.n_par(), b.n_par());
    for (int sample = 0; sample < 100; ++sample) {
        const VecN xi = test::random_point(rng, a);
        const PointDerivatives x = evaluate(a, xi, 1);
        const PointDerivatives y = evaluate(b, xi, 1);
        EXPECT_TRUE(test::at_most((x.x - y.x).norm(), geometry_tolerance)) << what;
        EXPECT_TRUE(test::at_most((x.dx - y.dx).norm() / std::max(1.0, y.dx.norm()), geometry_tolerance)) << what;
    }
}

int n_distinct_interior(const KnotVector& k) { return k.n_spans() - 1; }

TEST(Refine, KnotInsertionKeepsTheGeometry)
{
    std::mt19937 rng(41);
    SCOPED_TRACE("seed 41");
    for (const auto& degrees : std::vector<std::vector<int>>{{1}, {2}, {3}, {5}, {2, 3}, {3, 1, 2}}) {
        const Patch patch = test::random_patch(rng, degrees, 3, 3);
        for (int dir = 0; dir < patch.n_par(); ++dir) {
            const KnotVector& k = patch.knots(dir);
            // New values, a repeated new value, and an existing knot raised once (if allowed).
            std::vector<double> values{0.13, 0.77, 0.61};
            if (k.degree() >= 2)
                values.push_back(0.61);
            const double existing = k.breakpoints()[1];
            if (k.multiplicity(existing) < k.degree())
                values.push_back(existing);
            const Patch refined = insert_knots(patch, dir, values);
            EXPECT_EQ(refined.n_basis(dir), patch.n_basis(dir) + static_cast<int>(values.size()));
            EXPECT_EQ(refined.knots(dir).multiplicity(existing), k.multiplicity(existing) + (values.back() == existing));
            for (int other = 0; other < patch.n_par(); ++other)
                if (other != dir) {
                    EXPECT_EQ(refined.knots(other).knot_values(), patch.knots(other).knot_values());
                }
            expect_same_geometry(refined, patch, rng, "insert dir " + std::to_string(dir));
        }
    }
}

TEST(Refine, KnotInsertionRejectsInvalidValues)
{
    std::mt19937 rng(42);
    const Patch patch = test::random_patch(rng, {2, 1}, 2, 2);
    EXPECT_THROW(insert_knots(patch, 0, {0.0}), Error);
    EXPECT_THROW(insert_knots(patch, 0, {1.2}), Error);
    EXPECT_THROW(insert_knots(patch, 1, {0.4, 0.4}), Error);  // multiplicity 2 > degree 1
    EXPECT_THROW(insert_knots(patch, 0, {std::nan("")}), Error);
    EXPECT_THROW(insert_knots(patch, 2, {0.5}), Error);
    EXPECT_EQ(insert_knots(patch, 0, {}).n_basis(0), patch.n_basis(0));
}

TEST(Refine, DegreeElevationKeepsTheGeometryAndContinuity)
{
    std::mt19937 rng(43);
    SCOPED_TRACE("seed 43");
    for (const auto& degrees : std::vector<std::vector<int>>{{1}, {2}, {3}, {4}, {5}, {6}, {2, 1}, {1, 3}, {2, 1, 2}}) {
        for (int times = 1; times <= 3; ++times) {
            const Patch patch = test::random_patch(rng, degrees, 4, 3);
            for (int dir = 0; dir < patch.n_par(); ++dir) {
                const KnotVector& k = patch.knots(dir);
                const Patch elevated = elevate_degree(patch, dir, times);
                const KnotVector& e = elevated.knots(dir);
                EXPECT_EQ(e.degree(), k.degree() + times);
                EXPECT_EQ(e.n_spans(), k.n_spans());
                // Every distinct knot (ends included) gains `times` in multiplicity.
                EXPECT_EQ(e.n_basis(), k.n_basis() + times * (n_distinct_interior(k) + 1));
                for (const double b : k.breakpoints())
                    EXPECT_EQ(e.multiplicity(b), k.multiplicity(b) + times) << "knot " << b;
                expect_same_geometry(elevated, patch, rng,
                                     "elevate dir " + std::to_string(dir) + " by " + std::to_string(times));
            }
        }
    }
}

TEST(Refine, CombinedRefinementOnRationalSurfaces)
{
    std::mt19937 rng(44);
    SCOPED_TRACE("seed 44");
    const Patch patch = test::random_patch(rng, {2, 3}, 2, 2);
    const Patch a = refine_uniform(elevate_degree(elevate_degree(patch, 0, 1), 1, 2), 0, 8);
    const Patch b = elevate_degree(insert_knots(patch, 1, {0.2, 0.2, 0.55}), 0, 2);
    const Patch c = insert_knots(elevate_degree(refine_uniform(patch, 1, 5), 1, 1), 0, {0.31, 0.9});
    expect_same_geometry(a, patch, rng, "elevate, elevate, refine");
    expect_same_geometry(b, patch, rng, "insert, elevate");
    expect_same_geometry(c, patch, rng, "refine, elevate, insert");
}

TEST(Refine, RefinedHalfDiscIsStillExact)
{
    // Circle tolerance: |x - c| is an O(R) difference after a few refinement steps.
    constexpr double circle_tolerance = 1e-14;
    const VecN c = (VecN(2) << 0.0, 1.0).finished();
    const Patch coarse = half_disc(c, 1.0);
    const Patch fine = refine_uniform(elevate_degree(refine_uniform(coarse, 0, 16), 1, 1), 1, 4);
    EXPECT_EQ(fine.knots(0).n_spans(), 16);
    EXPECT_EQ(fine.knots(1).n_spans(), 4);
    for (int i = 0; i <= 500; ++i) {
        const double u = i / 500.0;
        const VecN x = evaluate(fine, (VecN(2) << u, 0.0).finished(), 0).x;
        EXPECT_TRUE(test::near((x - c).norm(), 1.0, circle_tolerance)) << "u " << u;
    }
    std::mt19937 rng(45);
    expect_same_geometry(fine, coarse, rng, "half disc");
}

TEST(Refine, UniformRefinementSpanCounts)
{
    const KnotVector k1(2, {0, 0, 0, 1, 1, 1});
    const KnotVector kv(1, {0, 0, 1, 1});
    const Patch single({k1, kv}, RowMatrix::Random(6, 2), Vector::Ones(6));
    EXPECT_EQ(refine_uniform(single, 0, 1).knots(0).n_spans(), 1);
    EXPECT_EQ(refine_uniform(single, 0, 7).knots(0).n_spans(), 7);
    EXPECT_EQ(refine_uniform(single, 1, 3).knots(1).n_spans(), 3);
    // Existing breakpoints on the grid are reused; off-grid ones add spans.
    const Patch halves({KnotVector(2, {0, 0, 0, 0.5, 1, 1, 1}), kv}, RowMatrix::Random(8, 2), Vector::Ones(8));
    EXPECT_EQ(refine_uniform(halves, 0, 4).knots(0).n_spans(), 4);
    EXPECT_EQ(refine_uniform(halves, 0, 4).knots(0).multiplicity(0.5), 1);
    EXPECT_EQ(refine_uniform(halves, 0, 3).knots(0).n_spans(), 4);
    const Patch twice = refine_uniform(refine_uniform(single, 0, 3), 0, 6);
    EXPECT_EQ(twice.knots(0).n_spans(), 6);
    // Non-unit domain.
    const Patch shifted({KnotVector(1, {2, 2, 5, 5}), kv}, RowMatrix::Random(4, 2), Vector::Ones(4));
    const Patch shifted_fine = refine_uniform(shifted, 0, 3);
    EXPECT_EQ(shifted_fine.knots(0).breakpoints(), (std::vector<double>{2, 3, 4, 5}));
}

TEST(Refine, HalvingSpansDoublesEverySpanAndKeepsTheGeometry)
{
    std::mt19937 rng(43);
    SCOPED_TRACE("seed 43");
    for (const auto& degrees : std::vector<std::vector<int>>{{2, 1}, {3, 2}, {2, 1, 3}}) {
        // Random rational patch with 3 spans per direction (non-uniform interior knots).
        const Patch patch = test::random_patch(rng, degrees, 3, 3);
        for (int times : {0, 1, 2}) {
            const Patch refined = halve_spans(patch, times);
            for (int dir = 0; dir < patch.n_par(); ++dir) {
                const KnotVector& k = patch.knots(dir);
                EXPECT_EQ(refined.knots(dir).n_spans(), k.n_spans() << times);
                // Each old interior breakpoint keeps its multiplicity (continuity unchanged).
                for (double b : k.breakpoints())
                    EXPECT_EQ(refined.knots(dir).multiplicity(b), k.multiplicity(b)) << b;
                // Spans are halved, not merely counted: each new span is 2^-times of an old one.
                const std::vector<double> old_b = k.breakpoints(), new_b = refined.knots(dir).breakpoints();
                for (std::size_t s = 0; s + 1 < new_b.size(); ++s) {
                    const std::size_t parent = s >> times;
                    // Each midpoint is rounded once per halving, on a domain of length 1:
                    // the scaled lengths agree to a few ulp of 1 (times <= 2 here).
                    constexpr double span_length_tolerance = 16 * std::numeric_limits<double>::epsilon();
                    EXPECT_TRUE(test::at_most(std::abs((new_b[s + 1] - new_b[s]) * (1 << times) -
                                                       (old_b[parent + 1] - old_b[parent])),
                                              span_length_tolerance));
                }
            }
            expect_same_geometry(refined, patch, rng, "halve " + std::to_string(times));
        }
    }
}

/// Bernstein polynomials of degree p at t in [0, 1].
Eigen::VectorXd bernstein(int p, double t)
{
    Eigen::VectorXd B = Eigen::VectorXd::Zero(p + 1);
    B(0) = 1.0;
    for (int j = 1; j <= p; ++j) {  // de Casteljau-style recursion
        for (int k = j; k >= 1; --k)
            B(k) = (1 - t) * B(k) + t * B(k - 1);
        B(0) *= (1 - t);
    }
    return B;
}

TEST(Refine, BezierExtractionReproducesTheBasis)
{
    std::mt19937 rng(46);
    SCOPED_TRACE("seed 46");
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int p = 1; p <= 5; ++p)
        for (int trial = 0; trial < 3; ++trial) {
            const KnotVector k = test::random_knots(rng, p, 6);
            const std::vector<Eigen::MatrixXd> C = bezier_extraction(k);
            ASSERT_EQ(static_cast<int>(C.size()), k.n_spans());
            const std::vector<double> breaks = k.breakpoints();
            for (int e = 0; e < k.n_spans(); ++e) {
                ASSERT_EQ(C[e].rows(), p + 1);
                for (int sample = 0; sample < 10; ++sample) {
                    const double t = unit(rng);
                    const double u = breaks[e] + t * (breaks[e + 1] - breaks[e]);
                    const Eigen::VectorXd N = basis_derivatives(k, k.span_start(e), u, 0).row(0).transpose();
                    const Eigen::VectorXd NB = C[e] * bernstein(p, t);
                    EXPECT_TRUE(test::at_most((N - NB).norm(), extraction_tolerance)) << "p " << p << " e " << e;
                }
            }
        }
}

/// Convex hull of 2D points (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> pts)
{
    std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<Eigen::Vector2d> hull(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0)
            --k;
        hull[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0)
            --k;
        hull[k++] = pts[i - 1];
    }
    hull.resize(k - 1);
    return hull;
}

/// Largest signed distance of x outside the convex polygon (<= 0 inside).
double outside_distance(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& x)
{
    double worst = -1e300;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
        const Eigen::Vector2d edge = (b - a).normalized();
        const Eigen::Vector2d outward(edge.y(), -edge.x());
        worst = std::max(worst, outward.dot(x - a));
    }
    return worst;
}

TEST(Refine, BezierControlPointsBoundTheirElement)
{
    // Points on the element lie in the hull up to round-off of O(1) coordinates.
    constexpr double hull_tolerance = 1e-12;
    std::mt19937 rng(47);
    SCOPED_TRACE("seed 47");
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const auto& degrees : std::vector<std::vector<int>>{{2}, {3}, {2, 2}, {3, 1}}) {
        const Patch patch = test::random_patch(rng, degrees, 3, 2);
        for (const Element& e : patch.elements()) {
            const RowMatrix Q = bezier_control_points(patch, e);
            int expected = 1;
            for (const int p : degrees)
                expected *= p + 1;
            ASSERT_EQ(Q.rows(), expected);
            std::vector<Eigen::Vector2d> pts;
            for (Index a = 0; a < Q.rows(); ++a)
                pts.emplace_back(Q(a, 0), Q(a, 1));
            const std::vector<Eigen::Vector2d> hull = convex_hull(pts);
            for (int sample = 0; sample < 30; ++sample) {
                VecN xi(patch.n_par());
                for (int d = 0; d < patch.n_par(); ++d)
                    xi(d) = e.lower[d] + unit(rng) * (e.upper[d] - e.lower[d]);
                const VecN x = evaluate(patch, xi, 0).x;
                EXPECT_TRUE(test::at_most(outside_distance(hull, Eigen::Vector2d(x(0), x(1))), hull_tolerance));
            }
        }
    }
    // Polynomial case: the Bezier points with the Bernstein basis reproduce the element exactly.
    const Patch rational = test::random_patch(rng, {3, 2}, 3, 2);
    const Patch poly(rational.all_knots(), rational.control_points(), Vector::Ones(rational.n_control_points()));
    const Element e = poly.elements()[4];
    const RowMatrix Q = bezier_control_points(poly, e);
    const double s = 0.3, t = 0.8;
    const Eigen::VectorXd Bu = bernstein(3, s), Bv = bernstein(2, t);
    VecN x = VecN::Zero(2);
    for (int j = 0; j <= 2; ++j)
        for (int i = 0; i <= 3; ++i)
            x += Bu(i) * Bv(j) * Q.row(i + 4 * j).transpose();
    const VecN xi = (VecN(2) << e.lower[0] + s * (e.upper[0] - e.lower[0]), e.lower[1] + t * (e.upper[1] - e.lower[1])).finished();
    EXPECT_TRUE(test::at_most((x - evaluate(poly, xi, 0).x).norm(), geometry_tolerance));
}

}  // namespace
}  // namespace iga::nurbs
