// Tests of open knot vectors and the univariate B-spline basis (A2.1, A2.3).

#include "core/error.hpp"
#include "nurbs/knot_vector.hpp"
#include "random_patch.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace iga::nurbs {
namespace {

// Values and derivatives are sums/products of O(1) terms over <= 6 functions:
// round-off is a few ulp times the largest derivative scale.
constexpr double identity_tolerance = 1e-12;

/// Cox-de Boor recursion straight from the definition (an independent reference).
double cox_de_boor(const std::vector<double>& U, int i, int p, double u)
{
    if (p == 0) {
        if (U[i] <= u && u < U[i + 1])
            return 1.0;
        // u = back(): the last non-empty span is closed on the right.
        return (u == U.back() && U[i + 1] == U.back() && U[i] < U[i + 1]) ? 1.0 : 0.0;
    }
    double value = 0.0;
    if (U[i + p] > U[i])
        value += (u - U[i]) / (U[i + p] - U[i]) * cox_de_boor(U, i, p - 1, u);
    if (U[i + p + 1] > U[i + 1])
        value += (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * cox_de_boor(U, i + 1, p - 1, u);
    return value;
}

TEST(KnotVector, CountsSpansAndBreakpoints)
{
    const KnotVector kv(2, {0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1});
    EXPECT_EQ(kv.degree(), 2);
    EXPECT_EQ(kv.n_basis(), 6);
    EXPECT_EQ(kv.n_spans(), 3);
    EXPECT_EQ(kv.span_start(0), 2);
    EXPECT_EQ(kv.span_start(1), 3);
    EXPECT_EQ(kv.span_start(2), 5);
    EXPECT_EQ(kv.span_number(5), 2);
    EXPECT_THROW(kv.span_number(4), Error);  // [0.5, 0.5) is empty
    EXPECT_EQ(kv.breakpoints(), (std::vector<double>{0, 0.25, 0.5, 1}));
    EXPECT_EQ(kv.multiplicity(0.5), 2);
    EXPECT_EQ(kv.multiplicity(0.0), 3);
    EXPECT_EQ(kv.multiplicity(0.3), 0);
    EXPECT_EQ(kv.front(), 0.0);
    EXPECT_EQ(kv.back(), 1.0);
}

TEST(KnotVector, FindSpanClampsAndClosesTheLastSpan)
{
    const KnotVector kv(2, {0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1});
    EXPECT_EQ(kv.find_span(0.0), 2);
    EXPECT_EQ(kv.find_span(0.1), 2);
    EXPECT_EQ(kv.find_span(0.25), 3);
    EXPECT_EQ(kv.find_span(0.4999), 3);
    EXPECT_EQ(kv.find_span(0.5), 5);  // skips the empty span [0.5, 0.5)
    EXPECT_EQ(kv.find_span(0.75), 5);
    EXPECT_EQ(kv.find_span(1.0), 5);  // u = back() belongs to the last span
    EXPECT_EQ(kv.find_span(-3.0), 2);
    EXPECT_EQ(kv.find_span(7.0), 5);
}

TEST(KnotVector, InvalidKnotVectorsThrow)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_THROW(KnotVector(0, {0, 1}), Error);                           // degree 0
    EXPECT_THROW(KnotVector(2, {0, 0, 0, 1, 1}), Error);                  // too short
    EXPECT_THROW(KnotVector(1, {0, 0, 0.7, 0.5, 1, 1}), Error);           // decreasing
    EXPECT_THROW(KnotVector(2, {0, 0, 0.1, 0.5, 1, 1, 1}), Error);        // not open at the start
    EXPECT_THROW(KnotVector(2, {0, 0, 0, 0.5, 1, 1, 2}), Error);          // not open at the end
    EXPECT_THROW(KnotVector(2, {0, 0, 0, 0, 1, 1, 1}), Error);            // start repeated p+2 times
    EXPECT_THROW(KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}), Error);  // interior multiplicity > p
    EXPECT_THROW(KnotVector(1, {0, 0, 0, 0}), Error);                     // no span of positive length
    EXPECT_THROW(KnotVector(1, {0, 0, nan, 1, 1}), Error);                // NaN knot
    EXPECT_THROW(KnotVector(1, {0, 0, 1, inf, inf}), Error);              // infinite knot
    try {
        KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1});
        FAIL() << "expected iga::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("multiplicity 3 > degree 2"), std::string::npos) << e.what();
    }
}

TEST(KnotVector, BasisMatchesCoxDeBoorAndIsAPartitionOfUnity)
{
    std::mt19937 rng(20240601);
    SCOPED_TRACE("seed 20240601");
    for (int p = 1; p <= 5; ++p) {
        const KnotVector kv = test::random_knots(rng, p, 6);
        std::uniform_real_distribution<double> unit(kv.front(), kv.back());
        for (int sample = 0; sample < 200; ++sample) {
            const double u = sample == 0 ? kv.back() : (sample == 1 ? kv.front() : unit(rng));
            const int span = kv.find_span(u);
            const Eigen::MatrixXd ders = basis_derivatives(kv, span, u, 2);
            ASSERT_EQ(ders.rows(), 3);
            ASSERT_EQ(ders.cols(), p + 1);
            EXPECT_TRUE(test::near(ders.row(0).sum(), 1.0, identity_tolerance)) << "p " << p << " u " << u;
            EXPECT_TRUE(test::near(ders.row(1).sum(), 0.0, identity_tolerance * std::max(1.0, ders.row(1).cwiseAbs().maxCoeff())));
            EXPECT_TRUE(test::near(ders.row(2).sum(), 0.0, identity_tolerance * std::max(1.0, ders.row(2).cwiseAbs().maxCoeff())));
            for (int j = 0; j <= p; ++j) {
                EXPECT_TRUE(test::at_least(ders(0, j), 0.0));
                const double reference = cox_de_boor(kv.knot_values(), span - p + j, p, u);
                EXPECT_TRUE(test::near(ders(0, j), reference, identity_tolerance)) << "p " << p << " u " << u;
            }
        }
    }
}

TEST(KnotVector, DerivativesMatchFiniteDifferences)
{
    // h = 1e-6 on spans >= 0.02 wide: truncation ~ h^2 (1/0.02)^2 ~ 3e-9 relative,
    // round-off ~ eps/h ~ 2e-10; a wrong factor or sign is O(1).
    constexpr double h = 1e-6;
    constexpr double fd_tolerance = 1e-6;
    std::mt19937 rng(7);
    SCOPED_TRACE("seed 7");
    for (int p = 1; p <= 5; ++p) {
        const KnotVector kv = test::random_knots(rng, p, 5);
        std::uniform_real_distribution<double> unit(kv.front(), kv.back());
        for (int sample = 0; sample < 50; ++sample) {
            const double u = unit(rng);
            const int span = kv.find_span(u);
            // Fixed span: the polynomial piece is smooth even across knots.
            const Eigen::MatrixXd d = basis_derivatives(kv, span, u, 2);
            const Eigen::MatrixXd dp = basis_derivatives(kv, span, u + h, 1);
            const Eigen::MatrixXd dm = basis_derivatives(kv, span, u - h, 1);
            const Eigen::VectorXd fd1 = (dp.row(0) - dm.row(0)).transpose() / (2 * h);
            const Eigen::VectorXd fd2 = (dp.row(1) - dm.row(1)).transpose() / (2 * h);
            const double scale1 = std::max(1.0, d.row(1).norm());
            const double scale2 = std::max(1.0, d.row(2).norm());
            EXPECT_TRUE(test::at_most((d.row(1).transpose() - fd1).norm() / scale1, fd_tolerance)) << "p " << p;
            EXPECT_TRUE(test::at_most((d.row(2).transpose() - fd2).norm() / scale2, fd_tolerance)) << "p " << p;
        }
    }
}

TEST(KnotVector, DerivativesAboveTheDegreeAreZero)
{
    const KnotVector kv(1, {0, 0, 0.5, 1, 1});
    const Eigen::MatrixXd d = basis_derivatives(kv, kv.find_span(0.3), 0.3, 2);
    EXPECT_TRUE(test::near(d(0, 0), 0.4, identity_tolerance));
    EXPECT_TRUE(test::near(d(0, 1), 0.6, identity_tolerance));
    EXPECT_TRUE(test::near(d(1, 0), -2.0, identity_tolerance));
    EXPECT_EQ(d.row(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(KnotVector, NanParameterGivesNanBasis)
{
    // NaN is a numerical failure: it must show in the values, not vanish.
    const KnotVector kv(2, {0, 0, 0, 0.5, 1, 1, 1});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Eigen::MatrixXd d = basis_derivatives(kv, kv.find_span(nan), nan, 0);
    EXPECT_FALSE(d.allFinite());
}

}  // namespace
}  // namespace iga::nurbs
