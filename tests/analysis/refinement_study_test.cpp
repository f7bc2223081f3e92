// Richardson extrapolation and the study table (analysis/refinement_study.hpp):
// exact on a sequence with a known order, the stated fall-backs where the levels
// show no order, and the table's rows (levels, reaction noise, true errors).

#include "analysis/refinement_study.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace iga::analysis {
namespace {

// The extrapolation of an exact q + C h^p sequence involves a handful of
// operations on values of order 1: a few ulp.
constexpr double round_off = 1e-13;

/// q + C h^p on levels 0..n-1 with h_k = 2^-k.
std::vector<double> sequence(double q, double C, double p, int n)
{
    std::vector<double> v;
    for (int k = 0; k < n; ++k)
        v.push_back(q + C * std::pow(std::exp2(-k), p));
    return v;
}

TEST(Richardson, SecondOrderSequenceIsExtrapolatedExactly)
{
    for (const double C : {0.3, -2.0}) {
        const std::vector<double> v = sequence(1.5, C, 2.0, 4);
        const auto e = richardson(v, 1.0);
        ASSERT_TRUE(e.has_value());
        ASSERT_TRUE(e->observed_order.has_value());
        EXPECT_TRUE(test::near(*e->observed_order, 2.0, round_off));
        EXPECT_TRUE(test::near(e->extrapolated, 1.5, round_off));
    }
    // A fractional order (contact: limited regularity) is observed as well.
    const auto e = richardson(sequence(-4.0, 1.0, 1.5, 3), 2.0);
    ASSERT_TRUE(e && e->observed_order);
    EXPECT_TRUE(test::near(*e->observed_order, 1.5, round_off));
    EXPECT_TRUE(test::near(e->extrapolated, -4.0, round_off));
}

TEST(Richardson, TwoLevelsUseTheAssumedOrder)
{
    // q + C h^2 with the order assumed right is exact; the order is not "observed".
    const auto e = richardson(sequence(2.0, 1.0, 2.0, 2), 2.0);
    ASSERT_TRUE(e.has_value());
    EXPECT_FALSE(e->observed_order.has_value());
    EXPECT_TRUE(test::near(e->extrapolated, 2.0, round_off));
    EXPECT_EQ(e->order_used, 2.0);
    EXPECT_FALSE(richardson(std::vector<double>{1.0}, 2.0).has_value());
}

TEST(Richardson, NonMonotoneOrGrowingDifferencesFallBackToTheAssumedOrder)
{
    // Differences that change sign: q2 + d2 / (2^p - 1) with the assumed p = 1.
    const auto oscillating = richardson(std::vector<double>{1.0, 1.2, 1.1}, 1.0);
    ASSERT_TRUE(oscillating.has_value());
    EXPECT_FALSE(oscillating->observed_order.has_value());
    EXPECT_TRUE(test::near(oscillating->extrapolated, 1.1 + (1.1 - 1.2), round_off));
    // Differences that grow (no convergence shown yet).
    const auto growing = richardson(std::vector<double>{1.0, 1.01, 1.05}, 2.0);
    ASSERT_TRUE(growing.has_value());
    EXPECT_FALSE(growing->observed_order.has_value());
    EXPECT_TRUE(test::near(growing->extrapolated, 1.05 + 0.04 / 3.0, round_off));
    // The finest levels agree: that value, whatever came before.
    const auto converged = richardson(std::vector<double>{3.0, 5.0, 5.0}, 2.0);
    ASSERT_TRUE(converged.has_value());
    EXPECT_FALSE(converged->observed_order.has_value());
    EXPECT_EQ(converged->extrapolated, 5.0);
}

TEST(StudyRows, EstimatedErrorsTrueErrorsAndReactionNoise)
{
    std::vector<StudyLevel> levels;
    const std::vector<double> force = sequence(10.0, 1.0, 2.0, 3);
    for (int k = 0; k < 3; ++k) {
        StudyLevel l;
        l.level = k;
        l.dofs = 100LL << (2 * k);
        l.wall_s = 0.1 * (k + 1);
        l.quantities = {{"peak_pressure:p:b.v0", force[static_cast<std::size_t>(k)]},
                        {"reaction:b.u0:x", -5.0},
                        {"reaction:b.u0:y", 1e-14 * (k + 1)}};
        l.reference_values = {{"peak_pressure:p:b.v0", 10.5}};
        levels.push_back(l);
    }
    const std::vector<io::StudyRow> rows = study_rows(levels, 1.0);
    // The y reaction is round-off of a side held in x only: left out.
    ASSERT_EQ(rows.size(), 6u);
    for (int k = 0; k < 3; ++k) {
        const io::StudyRow& r = rows[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.quantity, "peak_pressure:p:b.v0");
        EXPECT_EQ(r.level, k);
        EXPECT_EQ(r.dofs, 100LL << (2 * k));
        ASSERT_TRUE(r.extrapolated && r.observed_order && r.estimated_rel_error && r.true_rel_error);
        EXPECT_TRUE(test::near(*r.observed_order, 2.0, round_off));
        // Estimated error = C h^2 / q exactly, true error against 10.5.
        EXPECT_TRUE(test::near(*r.estimated_rel_error, std::pow(0.25, k) / 10.0, round_off));
        EXPECT_TRUE(test::near(*r.true_rel_error, std::abs(force[static_cast<std::size_t>(k)] - 10.5) / 10.5, round_off));
    }
    // A constant quantity: extrapolated to itself, zero estimated error, no observed order.
    const io::StudyRow& reaction = rows[3];
    EXPECT_EQ(reaction.quantity, "reaction:b.u0:x");
    ASSERT_TRUE(reaction.extrapolated && reaction.estimated_rel_error);
    EXPECT_FALSE(reaction.observed_order.has_value());
    EXPECT_EQ(*reaction.estimated_rel_error, 0.0);
    EXPECT_FALSE(reaction.true_rel_error.has_value());
}

TEST(StudyRows, AFailedLevelBreaksTheChain)
{
    // Levels 0, 2, 3 completed (1 failed): Richardson uses 2 and 3 only (assumed order).
    std::vector<StudyLevel> levels;
    for (int k : {0, 2, 3}) {
        StudyLevel l;
        l.level = k;
        l.quantities = {{"max_penetration:p", 1.0 + std::pow(0.5, k)}};
        levels.push_back(l);
    }
    const std::vector<io::StudyRow> rows = study_rows(levels, 1.0);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_FALSE(rows[0].observed_order.has_value());
    ASSERT_TRUE(rows[0].extrapolated.has_value());
    // First order assumed and exact here: 1 + 2^-3 - 2^-3 = 1.
    EXPECT_TRUE(test::near(*rows[0].extrapolated, 1.0, round_off));
}

}  // namespace
}  // namespace iga::analysis
