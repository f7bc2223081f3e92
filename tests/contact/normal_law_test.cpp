// The normal contact laws of contact/normal_law.hpp: the exponential (softened)
// law's values at its two joints (p(-c0) = 0, p(0) = p0), the continuity of p and
// dp/dg there, dp/dg against central differences on every branch, and the penalty
// law's pressure, activity and Uzawa step.

#include "contact/normal_law.hpp"

#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace iga::contact {
namespace {

// A handful of floating-point operations on O(1) numbers, each rounding by 1.1e-16.
constexpr double round_off = 1e-15;
// Central differences of p with step h = 1e-6 c0: truncation h^2 |p'''| / 6 ~ 1e-12 k0
// and round-off 1e-16 p / h ~ 1e-10 k0 (p ~ p0 ~ k0 c0); 1e-7 of k0 still exposes a
// wrong factor in dp/dg (a missing x e^x term is 60 % of it at touch).
constexpr double fd_step = 1e-6;
constexpr double fd_tolerance = 1e-7;

constexpr double c0 = 0.02, p0 = 3.0;
const double e = std::numbers::e;
/// The slope at touch, k0 = p0 (2e - 1) / ((e - 1) c0), written out independently of the law.
const double k0 = p0 * (2.0 * e - 1.0) / ((e - 1.0) * c0);

TEST(NormalLaw, ExponentialValuesAtItsJoints)
{
    const NormalLaw law = NormalLaw::exponential(c0, p0);
    ASSERT_TRUE(law.valid());
    EXPECT_EQ(law.response(-c0, 0.0).pressure, 0.0) << "no pressure at the clearance";
    EXPECT_EQ(law.response(-c0, 0.0).slope, 0.0);
    EXPECT_EQ(law.response(-2.0 * c0, 0.0).pressure, 0.0) << "nor beyond it";
    EXPECT_FALSE(law.active(-c0, 0.0));
    EXPECT_TRUE(law.active(-0.999 * c0, 0.0)) << "pressed at an open gap inside the clearance";
    EXPECT_TRUE(test::near_rel(law.response(0.0, 0.0).pressure, p0, round_off)) << "p(0) = p0";
    // The formula itself at an interior point: x = 1/2, p = p0/(e-1) x (e^x - 1).
    EXPECT_TRUE(test::near_rel(law.response(-0.5 * c0, 0.0).pressure, p0 / (e - 1.0) * 0.5 * (std::exp(0.5) - 1.0),
                               round_off));
    EXPECT_TRUE(test::near_rel(law.stiffness(), k0, round_off));
    EXPECT_EQ(law.reach(), c0);
    EXPECT_FALSE(law.takes_multipliers());
    EXPECT_EQ(law.updated_multiplier(law.response(0.0, 0.0).pressure), 0.0) << "no multiplier to update";
    EXPECT_THROW(NormalLaw(law).set_penalty(1e3), Error);
    EXPECT_FALSE(NormalLaw::exponential(0.0, p0).valid());
    EXPECT_FALSE(NormalLaw::exponential(c0, -1.0).valid());
    EXPECT_FALSE(NormalLaw::exponential(c0, std::nan("")).valid());
}

// Continuity: at g = 0 the two branches meet with the same value and slope (the linear
// continuation is the tangent at touch); at g = -c0 the slope tends to 0 like
// p''(-c0) delta, p''(-c0) = 2 p0 / ((e - 1) c0^2), so p and p' are C0 there too and
// the tangent of a point entering the clearance has no jump.
TEST(NormalLaw, ExponentialIsContinuouslyDifferentiable)
{
    const NormalLaw law = NormalLaw::exponential(c0, p0);
    const NormalResponse left = law.response(0.0, 0.0);           // the exponential branch at x = 1
    const NormalResponse right = law.response(1e-300, 0.0);       // the linear branch
    EXPECT_TRUE(test::near_rel(right.pressure, left.pressure, round_off));
    EXPECT_TRUE(test::near_rel(right.slope, left.slope, round_off));
    EXPECT_TRUE(test::near_rel(left.slope, k0, round_off));
    // Beyond touch: p = p0 + k0 g exactly linear.
    EXPECT_TRUE(test::near_rel(law.response(0.5 * c0, 0.0).pressure, p0 + k0 * 0.5 * c0, round_off));

    const double curvature = 2.0 * p0 / ((e - 1.0) * c0 * c0);
    for (const double delta : {1e-4 * c0, 1e-6 * c0}) {
        const NormalResponse r = law.response(-c0 + delta, 0.0);
        // p ~ p''/2 delta^2 and p' ~ p'' delta: relative error of the Taylor term ~ delta / c0 (x e^x).
        EXPECT_TRUE(test::near_rel(r.slope, curvature * delta, 4.0 * delta / c0)) << "delta " << delta;
        EXPECT_TRUE(test::near_rel(r.pressure, 0.5 * curvature * delta * delta, 4.0 * delta / c0)) << "delta " << delta;
    }
}

TEST(NormalLaw, SlopeIsTheDerivativeOfThePressure)
{
    const NormalLaw exponential = NormalLaw::exponential(c0, p0);
    const NormalLaw penalty = NormalLaw::penalty(k0);
    for (const NormalLaw* law : {&exponential, &penalty})
        for (const double lambda : {0.0, 0.4 * p0}) {
            // Inside the clearance, near both joints, and beyond touch; not at a kink.
            for (const double g : {-0.9 * c0, -0.5 * c0, -0.1 * c0, -1e-3 * c0, 1e-3 * c0, 0.3 * c0, 2.0 * c0}) {
                if (law == &penalty && !(lambda + k0 * g > 2.0 * k0 * fd_step * c0))
                    continue;  // the penalty law's kink at lambda + eps g = 0
                const double h = fd_step * c0;
                const double fd = (law->response(g + h, lambda).pressure - law->response(g - h, lambda).pressure) /
                                  (2.0 * h);
                EXPECT_TRUE(test::near(law->response(g, lambda).slope, fd, fd_tolerance * k0))
                    << law->name() << ", lambda " << lambda << ", g " << g;
            }
        }
}

TEST(NormalLaw, PenaltyPressureActivityAndUzawaStep)
{
    constexpr double eps = 1e3;
    NormalLaw law = NormalLaw::penalty(eps);
    EXPECT_STREQ(law.name(), "penalty");
    EXPECT_TRUE(law.takes_multipliers());
    EXPECT_EQ(law.stiffness(), eps);
    EXPECT_EQ(law.reach(), 0.0);
    // p = <lambda + eps g>, dp/dg = eps H(lambda + eps g), exactly (one multiply-add).
    EXPECT_EQ(law.response(2e-3, 0.0).pressure, eps * 2e-3);
    EXPECT_EQ(law.response(2e-3, 0.0).slope, eps);
    EXPECT_EQ(law.response(-2e-3, 0.0).pressure, 0.0);
    EXPECT_EQ(law.response(-2e-3, 0.0).slope, 0.0);
    EXPECT_EQ(law.response(-2e-3, 3.0).pressure, 3.0 + eps * -2e-3) << "a multiplier presses at an open gap";
    EXPECT_TRUE(law.active(-2e-3, 3.0));
    EXPECT_FALSE(law.active(-2e-3, 2.0)) << "lambda + eps g = 0 exactly: open (H(0) = 0)";
    EXPECT_FALSE(law.active(0.0, 0.0));
    // The Uzawa step at a fixed gap g > 0: lambda_k = <lambda_{k-1} + eps g> = k eps g.
    constexpr double g = 1.5e-3;
    double lambda = 0.0;
    for (int k = 1; k <= 4; ++k) {
        lambda = law.updated_multiplier(law.response(g, lambda).pressure);
        EXPECT_TRUE(test::near_rel(lambda, k * eps * g, round_off)) << "update " << k;
    }
    // The safeguard raises eps; the multiplier is the caller's state and stays.
    law.set_penalty(4e3);
    EXPECT_EQ(law.stiffness(), 4e3);
    EXPECT_THROW(law.set_penalty(0.0), Error);
    EXPECT_FALSE(NormalLaw().valid()) << "the default law is a placeholder";
}

// An unreleased initial overlap s = u g0 enters as p(g - s, lambda): for the penalty law
// a shifted multiplier (the law is affine in g), for the exponential one a gap offset.
TEST(NormalLaw, OverlapShiftIsAShiftOfTheGap)
{
    constexpr double u = 0.25, g0 = 0.8 * c0, g = 0.1 * c0;
    for (const NormalLaw& law : {NormalLaw::penalty(k0), NormalLaw::exponential(c0, p0)}) {
        const NormalLaw::Shifted s = law.shifted(0.2 * p0, u, g0);
        const double lambda = law.takes_multipliers() ? 0.2 * p0 : 0.0;
        const double expected = law.response(g - u * g0, lambda).pressure;
        EXPECT_TRUE(test::near_rel(law.response(g - s.gap_offset, s.multiplier).pressure, expected, round_off,
                                   round_off * p0))
            << law.name();
    }
}

}  // namespace
}  // namespace iga::contact
