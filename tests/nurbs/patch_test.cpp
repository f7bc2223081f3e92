// Tests of the tensor-product rational basis and patch evaluation:
// partition of unity, positivity, derivative consistency, exact circles.

#include "core/error.hpp"
#include "nurbs/patch.hpp"
#include "random_patch.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace iga::nurbs {
namespace {

// Sums of <= 216 terms of size <= 1 (values) or <= ~1e4 (second derivatives on
// spans >= 0.02 wide): round-off stays below 1e-12 of the largest term.
constexpr double identity_tolerance = 1e-12;
// Central differences with h = 1e-6 on spans >= 0.02 wide: truncation
// ~ h^2 / 0.02^2 ~ 3e-9 relative, round-off ~ eps / h ~ 2e-10; an error in the
// quotient rule or a column mix-up is O(1).
constexpr double fd_step = 1e-6;
constexpr double fd_tolerance = 1e-6;
// |x - c| of an exact circle: a handful of roundings of O(R) quantities.
constexpr double circle_tolerance = 1e-14;

/// Degrees 1..5 for curves, 1..4 for surfaces, 1..3 for volumes (keeps the test fast).
std::vector<std::vector<int>> degree_sets()
{
    return {{1}, {2}, {3}, {4}, {5}, {1, 2}, {2, 2}, {3, 1}, {4, 3}, {1, 1, 1}, {2, 3, 1}, {3, 3, 2}};
}

std::array<int, 3> spans_of(const Patch& patch, const VecN& xi)
{
    std::array<int, 3> span{0, 0, 0};
    for (int d = 0; d < patch.n_par(); ++d)
        span[d] = patch.knots(d).find_span(xi(d));
    return span;
}

double relative(const Matrix& actual, const Matrix& expected)
{
    return (actual - expected).norm() / std::max(1.0, expected.norm());
}

TEST(Patch, ConstructorChecksCountsAndWeights)
{
    const KnotVector k(1, {0, 0, 1, 1});
    RowMatrix P = RowMatrix::Zero(4, 2);
    EXPECT_NO_THROW(Patch({k, k}, P, Vector::Ones(4)));
    EXPECT_THROW(Patch({k, k}, RowMatrix::Zero(3, 2), Vector::Ones(3)), Error);
    EXPECT_THROW(Patch({k, k}, P, Vector::Ones(3)), Error);
    Vector w = Vector::Ones(4);
    w(2) = 0.0;
    EXPECT_THROW(Patch({k, k}, P, w), Error);
    w(2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(Patch({k, k}, P, w), Error);
    EXPECT_THROW(Patch({}, RowMatrix::Zero(1, 2), Vector::Ones(1)), Error);
    EXPECT_THROW(Patch({k, k, k, k}, RowMatrix::Zero(16, 2), Vector::Ones(16)), Error);
}

TEST(Patch, IndexingElementsAndWithControlPoints)
{
    std::mt19937 rng(11);
    const Patch patch = test::random_patch(rng, {2, 1, 3}, 3, 3);
    for (int a = 0; a < patch.n_control_points(); ++a)
        EXPECT_EQ(patch.control_point_index(patch.control_point_ijk(a)), a);
    EXPECT_EQ(patch.control_point_index({1, 0, 0}), 1);
    EXPECT_EQ(patch.control_point_index({0, 1, 0}), patch.n_basis(0));
    EXPECT_EQ(patch.control_point_index({0, 0, 1}), patch.n_basis(0) * patch.n_basis(1));

    const std::vector<Element> elements = patch.elements();
    ASSERT_EQ(static_cast<int>(elements.size()),
              patch.knots(0).n_spans() * patch.knots(1).n_spans() * patch.knots(2).n_spans());
    // u fastest: the second element differs from the first in u only.
    EXPECT_EQ(elements[1].span[1], elements[0].span[1]);
    EXPECT_EQ(elements[1].span[0], patch.knots(0).span_start(1));
    double volume = 0.0;
    for (const Element& e : elements) {
        for (int d = 0; d < 3; ++d) {
            EXPECT_LT(e.lower[d], e.upper[d]);
            EXPECT_EQ(e.lower[d], patch.knots(d).knot_values()[e.span[d]]);
        }
        volume += (e.upper[0] - e.lower[0]) * (e.upper[1] - e.lower[1]) * (e.upper[2] - e.lower[2]);
    }
    EXPECT_TRUE(test::near(volume, 1.0, identity_tolerance));  // the elements tile [0,1]^3

    const RowMatrix moved = patch.control_points().array() + 1.0;
    const Patch shifted = patch.with_control_points(moved);
    EXPECT_EQ(shifted.weights(), patch.weights());
    EXPECT_EQ(shifted.knots(1).knot_values(), patch.knots(1).knot_values());
    EXPECT_EQ(shifted.control_points(), moved);
    EXPECT_THROW(patch.with_control_points(RowMatrix::Zero(2, 3)), Error);
}

TEST(Patch, RationalBasisIsAPartitionOfUnity)
{
    std::mt19937 rng(20240602);
    SCOPED_TRACE("seed 20240602");
    for (const auto& degrees : degree_sets()) {
        const Patch patch = test::random_patch(rng, degrees, 4, 3);
        const int n = patch.n_par();
        for (int sample = 0; sample < 40; ++sample) {
            const VecN xi = test::random_point(rng, patch);
            const BasisValues b = rational_basis(patch, xi, 2);
            int expected_local = 1;
            for (const int p : degrees)
                expected_local *= p + 1;
            ASSERT_EQ(static_cast<int>(b.indices.size()), expected_local);
            ASSERT_EQ(b.dR.cols(), n);
            ASSERT_EQ(b.d2R.cols(), n * (n + 1) / 2);
            EXPECT_TRUE(test::near(b.R.sum(), 1.0, identity_tolerance));
            EXPECT_TRUE(test::at_least(b.R.minCoeff(), 0.0));
            const double scale1 = std::max(1.0, b.dR.cwiseAbs().maxCoeff());
            const double scale2 = std::max(1.0, b.d2R.cwiseAbs().maxCoeff());
            for (int c = 0; c < n; ++c)
                EXPECT_TRUE(test::near(b.dR.col(c).sum(), 0.0, identity_tolerance * scale1));
            for (int c = 0; c < b.d2R.cols(); ++c)
                EXPECT_TRUE(test::near(b.d2R.col(c).sum(), 0.0, identity_tolerance * scale2));
            // Local order: u fastest, indices are the global control points of the element.
            const std::array<int, 3> span = spans_of(patch, xi);
            std::array<int, 3> first{0, 0, 0};
            for (int d = 0; d < n; ++d)
                first[d] = span[d] - patch.degree(d);
            EXPECT_EQ(b.indices[0], patch.control_point_index(first));
            EXPECT_EQ(b.indices[1], b.indices[0] + 1);
            // x = sum R_A P_A reproduces the control net's affine functions: a
            // linear map of the control points moves x by the same map.
            const PointDerivatives x = evaluate(patch, xi, 0);
            const RowMatrix moved = (patch.control_points() * 2.0).array() + 0.5;
            const PointDerivatives y = combine(b, moved);
            EXPECT_TRUE(test::at_most((y.x - (2.0 * x.x).array().matrix() - VecN::Constant(3, 0.5)).norm(),
                                      identity_tolerance));
        }
    }
}

TEST(Patch, EqualWeightsGiveTheBSplineBasis)
{
    std::mt19937 rng(5);
    Patch patch = test::random_patch(rng, {3, 2}, 3, 2);
    const Patch polynomial(patch.all_knots(), patch.control_points(), Vector::Constant(patch.n_control_points(), 1.7));
    const VecN xi = test::random_point(rng, polynomial);
    const BasisValues b = rational_basis(polynomial, xi, 1);
    const std::array<int, 3> span = spans_of(polynomial, xi);
    const Eigen::MatrixXd Nu = basis_derivatives(polynomial.knots(0), span[0], xi(0), 1);
    const Eigen::MatrixXd Nv = basis_derivatives(polynomial.knots(1), span[1], xi(1), 1);
    for (int j = 0; j <= 2; ++j)
        for (int i = 0; i <= 3; ++i) {
            const int a = i + 4 * j;
            EXPECT_TRUE(test::near(b.R(a), Nu(0, i) * Nv(0, j), identity_tolerance));
            EXPECT_TRUE(test::near(b.dR(a, 0), Nu(1, i) * Nv(0, j), identity_tolerance * 100));
            EXPECT_TRUE(test::near(b.dR(a, 1), Nu(0, i) * Nv(1, j), identity_tolerance * 100));
        }
}

/// dR, d2R of the basis and dx, d2x of evaluate() against central differences,
/// on a fixed span so that the function is one smooth rational piece.
void check_derivatives(const Patch& patch, std::mt19937& rng, int n_samples)
{
    const int n = patch.n_par();
    for (int sample = 0; sample < n_samples; ++sample) {
        const VecN xi = test::random_point(rng, patch);
        const std::array<int, 3> span = spans_of(patch, xi);
        const BasisValues b = rational_basis(patch, span, xi, 2);
        const PointDerivatives x = combine(b, patch.control_points());
        const PointDerivatives x_eval = evaluate(patch, xi, 2);
        EXPECT_TRUE(test::at_most((x.x - x_eval.x).norm(), identity_tolerance));
        EXPECT_TRUE(test::at_most(relative(x_eval.d2x, x.d2x), identity_tolerance));

        Matrix dR_fd(b.R.size(), n), dx_fd(patch.dim(), n);
        Matrix d2R_fd(b.R.size(), n * (n + 1) / 2), d2x_fd(patch.dim(), n * (n + 1) / 2);
        for (int p = 0; p < n; ++p) {
            VecN plus = xi, minus = xi;
            plus(p) += fd_step;
            minus(p) -= fd_step;
            const BasisValues bp = rational_basis(patch, span, plus, 1);
            const BasisValues bm = rational_basis(patch, span, minus, 1);
            ASSERT_EQ(bp.indices, b.indices);
            dR_fd.col(p) = (bp.R - bm.R) / (2 * fd_step);
            const PointDerivatives xp = combine(bp, patch.control_points());
            const PointDerivatives xm = combine(bm, patch.control_points());
            dx_fd.col(p) = (xp.x - xm.x) / (2 * fd_step);
            // d/dxi_p of dR_q fills the column of the pair (min, max).
            for (int q = 0; q < n; ++q) {
                const int k = std::min(p, q), l = std::max(p, q);
                const int c = k * n - k * (k - 1) / 2 + (l - k);
                d2R_fd.col(c) = (bp.dR.col(q) - bm.dR.col(q)) / (2 * fd_step);
                d2x_fd.col(c) = (xp.dx.col(q) - xm.dx.col(q)) / (2 * fd_step);
            }
        }
        EXPECT_TRUE(test::at_most(relative(b.dR, dR_fd), fd_tolerance)) << "n_par " << n;
        EXPECT_TRUE(test::at_most(relative(b.d2R, d2R_fd), fd_tolerance)) << "n_par " << n;
        EXPECT_TRUE(test::at_most(relative(x.dx, dx_fd), fd_tolerance)) << "n_par " << n;
        EXPECT_TRUE(test::at_most(relative(x.d2x, d2x_fd), fd_tolerance)) << "n_par " << n;
    }
}

TEST(Patch, DerivativesMatchFiniteDifferencesCurve)
{
    std::mt19937 rng(101);
    SCOPED_TRACE("seed 101");
    for (int p = 1; p <= 5; ++p)
        check_derivatives(test::random_patch(rng, {p}, 4, 2), rng, 20);
}

TEST(Patch, DerivativesMatchFiniteDifferencesSurface)
{
    std::mt19937 rng(102);
    SCOPED_TRACE("seed 102");
    for (const auto& degrees : std::vector<std::vector<int>>{{1, 1}, {2, 1}, {2, 3}, {4, 2}})
        check_derivatives(test::random_patch(rng, degrees, 3, 3), rng, 20);
}

TEST(Patch, DerivativesMatchFiniteDifferencesVolume)
{
    std::mt19937 rng(103);
    SCOPED_TRACE("seed 103");
    for (const auto& degrees : std::vector<std::vector<int>>{{1, 1, 1}, {2, 2, 2}, {3, 1, 2}})
        check_derivatives(test::random_patch(rng, degrees, 2, 3), rng, 10);
}

TEST(Patch, RejectsBadDerivativeOrderAndPointSize)
{
    std::mt19937 rng(3);
    const Patch patch = test::random_patch(rng, {2, 2}, 2, 2);
    EXPECT_THROW(rational_basis(patch, VecN::Constant(2, 0.5), 3), Error);
    EXPECT_THROW(rational_basis(patch, VecN::Constant(1, 0.5), 1), Error);
}

/// Circle arcs of docs/theory.md "Exact circles" (R = 1.5, center (0.3, -0.2)): |x - c| = R everywhere.
void expect_on_circle(const KnotVector& knots, const std::vector<std::array<double, 2>>& unit_points,
                      const std::vector<double>& weights)
{
    constexpr double R = 1.5;
    const VecN c = (VecN(2) << 0.3, -0.2).finished();
    RowMatrix P(static_cast<Index>(unit_points.size()), 2);
    for (std::size_t a = 0; a < unit_points.size(); ++a)
        P.row(static_cast<Index>(a)) << c(0) + R * unit_points[a][0], c(1) + R * unit_points[a][1];
    const Patch arc({knots}, P, Eigen::Map<const Vector>(weights.data(), static_cast<Index>(weights.size())));
    double worst = 0.0;
    for (int i = 0; i <= 2000; ++i) {
        const VecN u = VecN::Constant(1, knots.front() + (knots.back() - knots.front()) * i / 2000.0);
        const PointDerivatives x = evaluate(arc, u, 1);
        const double deviation = std::abs((x.x - c).norm() - R);
        worst = std::isfinite(deviation) ? std::max(worst, deviation) : deviation;
        // The tangent is perpendicular to the radius.
        EXPECT_TRUE(test::at_most(std::abs((x.x - c).dot(x.dx.col(0))), 1e3 * circle_tolerance * x.dx.norm()));
    }
    EXPECT_TRUE(test::at_most(worst, circle_tolerance * R));
}

TEST(Patch, ExactCircles)
{
    const double s = std::sqrt(2.0) / 2.0;
    expect_on_circle(KnotVector(2, {0, 0, 0, 1, 1, 1}), {{1, 0}, {1, 1}, {0, 1}}, {1, s, 1});
    expect_on_circle(KnotVector(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}), {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}},
                     {1, s, 1, s, 1});
    expect_on_circle(KnotVector(3, {0, 0, 0, 0, 1, 1, 1, 1}), {{1, 0}, {1, 2}, {-1, 2}, {-1, 0}},
                     {1, 1.0 / 3.0, 1.0 / 3.0, 1});
    expect_on_circle(KnotVector(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}),
                     {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}},
                     {1, s, 1, s, 1, s, 1, s, 1});
}

TEST(Patch, NanParameterPropagates)
{
    std::mt19937 rng(9);
    const Patch patch = test::random_patch(rng, {2, 2}, 2, 2);
    VecN xi = VecN::Constant(2, 0.5);
    xi(1) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(evaluate(patch, xi, 1).x.allFinite());
}

}  // namespace
}  // namespace iga::nurbs
