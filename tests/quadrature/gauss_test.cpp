// Tests of Gauss-Legendre rules on [0, 1] and tensor rules on elements.

#include "core/error.hpp"
#include "nurbs/shapes.hpp"
#include "quadrature/gauss.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace iga::quadrature {
namespace {

// Sum of n <= 20 products of O(1) numbers, each point accurate to ~1 ulp.
constexpr double exactness_tolerance = 1e-14;

TEST(Gauss, PointsAndWeights)
{
    for (int n = 1; n <= 20; ++n) {
        const Rule1D rule = gauss_legendre(n);
        ASSERT_EQ(static_cast<int>(rule.points.size()), n);
        ASSERT_EQ(static_cast<int>(rule.weights.size()), n);
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            EXPECT_TRUE(test::at_least(rule.points[i], 1e-300)) << n;  // strictly inside (0, 1)
            EXPECT_TRUE(test::at_most(rule.points[i], 1.0 - 1e-16)) << n;
            EXPECT_TRUE(test::at_least(rule.weights[i], 1e-300)) << n;
            if (i > 0) {
                EXPECT_LT(rule.points[i - 1], rule.points[i]);
            }
            sum += rule.weights[i];
        }
        EXPECT_TRUE(test::near(sum, 1.0, exactness_tolerance)) << n;
    }
    // Known values: the 2-point rule sits at 1/2 -+ 1/(2 sqrt 3).
    const Rule1D two = gauss_legendre(2);
    EXPECT_TRUE(test::near(two.points[0], 0.5 - 0.5 / std::sqrt(3.0), exactness_tolerance));
    EXPECT_TRUE(test::near(two.weights[1], 0.5, exactness_tolerance));
    EXPECT_THROW(gauss_legendre(0), Error);
}

TEST(Gauss, ExactUpToDegree2nMinus1AndNotBeyond)
{
    // Monomials of t = 2x - 1 (orthogonal to nothing special, but symmetric).
    // The n-point error for t^{2n} on [0, 1] is 2^{2n} (n!)^4 / ((2n+1) ((2n)!)^2),
    // >= 9e-8 for n <= 12: far above round-off, so the "not exact" check can
    // fail only if the rule were of higher degree (x^{2n} itself would not do:
    // its error is 2^{2n} times smaller and lost in round-off at n = 12).
    constexpr double inexact_floor = 1e-10;
    for (int n = 1; n <= 12; ++n) {
        const Rule1D rule = gauss_legendre(n);
        for (int k = 0; k <= 2 * n; ++k) {
            double q = 0.0;
            for (int i = 0; i < n; ++i)
                q += rule.weights[i] * std::pow(2.0 * rule.points[i] - 1.0, k);
            // int_0^1 (2x-1)^k dx = (1 + (-1)^k) / (2 (k+1)).
            const double exact = (k % 2 == 0) ? 1.0 / (k + 1) : 0.0;
            if (k <= 2 * n - 1)
                EXPECT_TRUE(test::near(q, exact, exactness_tolerance)) << "n " << n << " k " << k;
            else
                EXPECT_TRUE(test::at_least(std::abs(q - exact), inexact_floor)) << "n " << n << " k " << k;
        }
    }
}

TEST(Gauss, ElementRuleWeightsSumToTheElementVolume)
{
    const nurbs::Patch patch = nurbs::half_disc((VecN(2) << 0, 0).finished(), 1.0);
    nurbs::Element element;
    element.span = {3, 1, 0};
    element.lower = {0.25, 0.0, 0.0};
    element.upper = {0.75, 0.5, 0.0};
    const TensorRule rule = element_rule(patch, element, 3);
    ASSERT_EQ(rule.points.rows(), 9);
    ASSERT_EQ(rule.points.cols(), 2);
    EXPECT_TRUE(test::near(rule.weights.sum(), 0.25, exactness_tolerance));
    // u fastest, points inside the element.
    EXPECT_EQ(rule.points(0, 1), rule.points(1, 1));
    EXPECT_LT(rule.points(0, 0), rule.points(1, 0));
    EXPECT_TRUE(test::at_least(rule.points.col(0).minCoeff(), 0.25));
    EXPECT_TRUE(test::at_most(rule.points.col(1).maxCoeff(), 0.5));
    // A tensor polynomial of degree 5 per direction is integrated exactly:
    // int_{0.25}^{0.75} u^5 du * int_0^{0.5} v^4 dv.
    double q = 0.0;
    for (Index a = 0; a < rule.points.rows(); ++a)
        q += rule.weights(a) * std::pow(rule.points(a, 0), 5) * std::pow(rule.points(a, 1), 4);
    const double exact = (std::pow(0.75, 6) - std::pow(0.25, 6)) / 6.0 * std::pow(0.5, 5) / 5.0;
    EXPECT_TRUE(test::near(q, exact, exactness_tolerance));
}

TEST(Gauss, AreaOfTheBuiltInShapes)
{
    // The Jacobian of a rational patch is a rational function, so Gauss is not
    // exact but converges spectrally; the half disc's weights 1/3 put poles near
    // [0, 1] (observed error ~1e-6 with 12 points, below 1e-9 with 20). Exact for
    // the bilinear rectangle.
    constexpr double rational_area_tolerance = 1e-9;
    constexpr double R = 1.3;
    const VecN c = (VecN(2) << 0.2, -0.4).finished();
    auto area = [](const nurbs::Patch& patch, int n) {
        double sum = 0.0;
        for (const nurbs::Element& e : patch.elements()) {
            const TensorRule rule = element_rule(patch, e, n);
            for (Index a = 0; a < rule.points.rows(); ++a) {
                const nurbs::PointDerivatives x = nurbs::evaluate(patch, rule.points.row(a).transpose(), 1);
                sum += rule.weights(a) * (x.dx(0, 0) * x.dx(1, 1) - x.dx(0, 1) * x.dx(1, 0));
            }
        }
        return sum;
    };
    EXPECT_TRUE(test::near(area(nurbs::half_disc(c, R), 20), std::numbers::pi * R * R / 2, rational_area_tolerance));
    EXPECT_TRUE(test::near(area(nurbs::quarter_disc(c, R), 12), std::numbers::pi * R * R / 4, rational_area_tolerance));
    EXPECT_TRUE(test::near(area(nurbs::rectangle(c, (VecN(2) << 2, 3).finished()), 1), 6.0, exactness_tolerance));
}

}  // namespace
}  // namespace iga::quadrature
