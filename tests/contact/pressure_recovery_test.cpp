// Sauer's pressure post-processing: force preserved exactly, p_A >= 0 and within
// the range of the Gauss-point pressures, a uniform pressure recovered exactly.

#include "contact/pressure_recovery.hpp"

#include "fixtures.hpp"
#include "support/tolerance.hpp"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

namespace iga::contact {
namespace {

using test::vec2;

// Sums of O(100) positive terms: a few ulps each.
constexpr double sum_tolerance = 1e-12;
// The Gauss rule integrates |dX/deta| of a rational parametrization (a rational
// function) only approximately: the length 2.2 comes out to ~1e-4.
constexpr double length_quadrature_tolerance = 1e-3;
// Random perturbation of the disc's control points, small against the 0.02 overlap.
constexpr double noise = 1e-3;

/// A block whose top side (v1) is the straight line y = 1 with a rational,
/// non-uniform parametrization: 3 spans, degree 2.
nurbs::Patch flat_top_block()
{
    const std::vector<double> x{-1.0, -0.6, 0.1, 0.5, 1.2};
    const std::vector<double> w{1.0, 0.7, 1.4, 0.9, 1.1};
    RowMatrix P(10, 2);
    Vector weights(10);
    for (int i = 0; i < 5; ++i) {
        P.row(i) << x[i], 0.0;
        P.row(5 + i) << x[i], 1.0;
        weights(i) = weights(5 + i) = w[i];
    }
    return nurbs::Patch({nurbs::KnotVector(2, {0, 0, 0, 0.3, 0.7, 1, 1, 1}), nurbs::KnotVector(1, {0, 0, 1, 1})},
                        std::move(P), std::move(weights));
}

TEST(PressureRecovery, UniformPressureIsRecoveredExactly)
{
    const DeformableSide top = DeformableSide::make(flat_top_block(), Side::v1);
    const double delta = 0.01, eps = 2e3;
    const RigidPlane lid = RigidPlane::make(vec2(0.0, 1.0 - delta), vec2(0.0, -1.0));  // obstacle above
    const ContactPair pair({.law = NormalLaw::penalty(eps)}, top, lid);
    const RowMatrix u = RowMatrix::Zero(pair.n_control_points(0), 2);
    const PairEvaluation ev = pair.evaluate(u, RowMatrix(0, 2), false);
    ASSERT_TRUE(ev.ok);
    ASSERT_EQ(ev.carriers.size(), 1u);
    const double p = eps * delta;
    // Every Gauss point sees the same gap, up to the round-off of x(eta).
    for (Index g = 0; g < ev.carriers[0].pressure.size(); ++g)
        ASSERT_TRUE(test::near_rel(ev.carriers[0].pressure(g), p, sum_tolerance));

    const RecoveredPressure r = recover_pressure(top.pieces[0].side.patch, u, ev.carriers[0], 4);
    // A weighted average of equal values, and a partition of unity of them.
    constexpr double uniform_tolerance = 1e-12;
    for (Index A = 0; A < r.control_point_pressure.size(); ++A)
        EXPECT_TRUE(test::near_rel(r.control_point_pressure(A), p, uniform_tolerance)) << "A = " << A;
    for (Index s = 0; s < r.pressure.size(); ++s)
        EXPECT_TRUE(test::near_rel(r.pressure(s), p, uniform_tolerance)) << "sample " << s;
    // 3 spans x 4 intervals, every interval end once; first and last sample at the side's ends.
    ASSERT_EQ(r.pressure.size(), 13);
    EXPECT_TRUE(test::at_most((r.reference_coordinates.row(0) - RowMatrix(vec2(-1.0, 1.0).transpose())).norm(), sum_tolerance));
    EXPECT_TRUE(test::at_most((r.coordinates.row(12) - RowMatrix(vec2(1.2, 1.0).transpose())).norm(), sum_tolerance));
    ASSERT_EQ(r.parameter.cols(), 1);
    EXPECT_TRUE(std::is_sorted(r.parameter.col(0).begin(), r.parameter.col(0).end()));
    EXPECT_TRUE(test::near(r.parameter(4), 0.3, 0.0));  // span ends are sampled
    EXPECT_TRUE(test::near_rel(r.normal_force, ev.carriers[0].pressure.dot(ev.carriers[0].weight), 0.0));
    // The top is 2.2 long; its Gauss rule integrates |dX/deta| of this rational
    // parametrization only approximately (rational integrand).
    EXPECT_TRUE(test::near_rel(r.normal_force, p * 2.2, length_quadrature_tolerance));
}

/// Disc pressed onto a rigid floor: a Hertz-like, non-uniform pressure.
struct DiscOnFloor {
    DeformableSide disc = DeformableSide::make(test::refined_half_disc(16), Side::v0);
    RigidPlane floor = RigidPlane::make(vec2(0.0, 0.0), vec2(0.0, 1.0));
    ContactPair pair{{.law = NormalLaw::penalty(1e4)}, disc, floor};
    RowMatrix u;
    PairEvaluation ev;

    DiscOnFloor()
    {
        std::mt19937 rng(21);
        u = test::shifted(pair.n_control_points(0), vec2(0.0, -0.02), noise, rng);
        ev = pair.evaluate(u, RowMatrix(0, 2), false);
    }
};

TEST(PressureRecovery, TotalForceIsPreservedAndPressuresArePositive)
{
    const DiscOnFloor s;
    ASSERT_TRUE(s.ev.ok);
    ASSERT_GE(s.ev.n_active, 3);
    const CarrierResult& c = s.ev.carriers[0];
    const nurbs::Patch& side = s.disc.pieces[0].side.patch;
    const RecoveredPressure r = recover_pressure(side, s.u, c, 8);

    // sum_A p_A sum_g R_A(eta_g) W_g = sum_g p_g W_g, with R_A re-evaluated here.
    Vector D = Vector::Zero(side.n_control_points());
    for (Index g = 0; g < c.parameter.rows(); ++g) {
        VecN eta(1);
        eta(0) = c.parameter(g, 0);
        const nurbs::BasisValues b = nurbs::rational_basis(side, eta, 0);
        for (std::size_t a = 0; a < b.indices.size(); ++a)
            D(b.indices[a]) += b.R(static_cast<Index>(a)) * c.weight(static_cast<Index>(g));
    }
    const double force = c.pressure.dot(c.weight);
    ASSERT_GT(force, 0.0);
    EXPECT_TRUE(test::near_rel(r.control_point_pressure.dot(D), force, sum_tolerance));
    EXPECT_TRUE(test::near_rel(r.normal_force, force, sum_tolerance));

    const double p_max = c.pressure.maxCoeff();
    int n_positive = 0;
    for (Index A = 0; A < r.control_point_pressure.size(); ++A) {
        EXPECT_TRUE(test::at_least(r.control_point_pressure(A), 0.0));
        EXPECT_TRUE(test::at_most(r.control_point_pressure(A), p_max * (1 + sum_tolerance)));  // an average
        n_positive += r.control_point_pressure(A) > 0.0 ? 1 : 0;
    }
    EXPECT_GE(n_positive, 2);
    EXPECT_LT(n_positive, r.control_point_pressure.size());  // far control points carry nothing
    for (Index k = 0; k < r.pressure.size(); ++k)
        EXPECT_TRUE(test::at_least(r.pressure(k), 0.0));
    // Current coordinates of the samples are the reference ones plus the displacement field.
    EXPECT_TRUE(test::at_most((r.coordinates - r.reference_coordinates).cwiseAbs().maxCoeff(), 0.03));
}

TEST(PressureRecovery, ControlPointPressureOfNoContactIsZero)
{
    const nurbs::Patch side = test::quarter_arc(1.0);
    const std::vector<double> eta{0.2, 0.5, 0.8};
    const Vector p = Vector::Zero(3), W = Vector::Constant(3, 0.3);
    const Vector p_A = control_point_pressure(side, eta, p, W);
    EXPECT_EQ(p_A.size(), 3);
    EXPECT_EQ(p_A.norm(), 0.0);
}

}  // namespace
}  // namespace iga::contact
