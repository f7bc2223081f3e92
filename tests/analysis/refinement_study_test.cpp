// Richardson extrapolation and the study table (analysis/refinement_study.hpp):
// exact on a sequence with a known order, the stated fall-backs where the levels
// show no order, the grid convergence index and the flags (asymptotic range, not
// converging, zero limit) on a worked example, and the table's rows (levels,
// reaction noise, true errors).

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
        EXPECT_TRUE(e->extrapolated && test::near(*e->extrapolated, 1.5, round_off));
    }
    // A fractional order (contact: limited regularity) is observed as well.
    const auto e = richardson(sequence(-4.0, 1.0, 1.5, 3), 2.0);
    ASSERT_TRUE(e && e->observed_order);
    EXPECT_TRUE(test::near(*e->observed_order, 1.5, round_off));
    EXPECT_TRUE(e->extrapolated && test::near(*e->extrapolated, -4.0, round_off));
}

TEST(Richardson, TwoLevelsUseTheAssumedOrder)
{
    // q + C h^2 with the order assumed right is exact; the order is not "observed".
    const auto e = richardson(sequence(2.0, 1.0, 2.0, 2), 2.0);
    ASSERT_TRUE(e.has_value());
    EXPECT_FALSE(e->observed_order.has_value());
    EXPECT_TRUE(e->extrapolated && test::near(*e->extrapolated, 2.0, round_off));
    EXPECT_EQ(e->order_used, 2.0);
    EXPECT_FALSE(richardson(std::vector<double>{1.0}, 2.0).has_value());
}

TEST(Richardson, NonMonotoneDifferencesFallBackToTheAssumedOrder)
{
    // Differences that change sign while shrinking: q2 + d2 / (2^p - 1) with the assumed p = 1.
    const auto oscillating = richardson(std::vector<double>{1.0, 1.2, 1.1}, 1.0);
    ASSERT_TRUE(oscillating.has_value());
    EXPECT_FALSE(oscillating->observed_order.has_value());
    EXPECT_EQ(oscillating->support, EstimateSupport::assumed_order);
    EXPECT_TRUE(oscillating->extrapolated && test::near(*oscillating->extrapolated, 1.1 + (1.1 - 1.2), round_off));
    // The finest levels agree: that value, whatever came before.
    const auto converged = richardson(std::vector<double>{3.0, 5.0, 5.0}, 2.0);
    ASSERT_TRUE(converged.has_value());
    EXPECT_FALSE(converged->observed_order.has_value());
    EXPECT_EQ(converged->support, EstimateSupport::converged);
    EXPECT_EQ(converged->extrapolated, 5.0);
}

// Worked example: the MOOSE hertz_cyl case on a uniform mesh, peak pressure on three
// levels f3 = 774.8, f2 = 732.7, f1 = 717.9 (coarsest first), gold 716.58. By hand:
//   e21 = f1 - f2 = -14.8, e32 = f2 - f3 = -42.1, r^p = e32 / e21 = 42.1 / 14.8,
//   p = log2(42.1 / 14.8) = 1.508, r^p - 1 = 27.3 / 14.8,
//   f_extr = f1 + e21 / (r^p - 1) = 717.9 - 14.8^2 / 27.3 = 709.877  (-0.94 % from gold),
//   GCI = 1.25 |e21| / (r^p - 1) = 1.25 * 14.8^2 / 27.3 = 10.03, 1.413 % of f_extr.
TEST(GridConvergenceIndex, ThreeLevelsWorkedExample)
{
    const std::vector<double> peak = {774.8, 732.7, 717.9};
    const double shift = 14.8 * 14.8 / 27.3;  // |f_extr - f1|
    const double extrapolated = 717.9 - shift;
    const auto e = richardson(peak, 2.0);
    ASSERT_TRUE(e && e->observed_order && e->extrapolated && e->rel_band);
    EXPECT_TRUE(test::near(*e->observed_order, std::log2(42.1 / 14.8), round_off));
    EXPECT_TRUE(test::near_rel(*e->extrapolated, extrapolated, round_off));
    EXPECT_EQ(e->safety_factor, 1.25);
    EXPECT_TRUE(test::near(*e->rel_band, 1.25 * shift / extrapolated, round_off));
    // Order 1.51 against the formal 2 of quadratic patches: outside the asymptotic range.
    EXPECT_EQ(e->support, EstimateSupport::not_asymptotic);
    // The bare extrapolation misses the gold value by 0.94 %; the band holds it.
    constexpr double gold = 716.58;
    EXPECT_GT(std::abs(*e->extrapolated - gold) / gold, 0.009);
    EXPECT_LT(std::abs(*e->extrapolated - gold), *e->rel_band * std::abs(*e->extrapolated));
    // Against a formal order of 1.5 the same levels are in the asymptotic range (|1.508 - 1.5| < 0.15).
    EXPECT_EQ(richardson(peak, 1.5)->support, EstimateSupport::asymptotic);
}

// Two levels: the formal order is assumed and the band carries Fs = 3:
//   f_extr = 717.9 - 14.8 / (2^2 - 1), GCI = 3 * 14.8 / 3 = 14.8 (2.08 % of f_extr).
TEST(GridConvergenceIndex, TwoLevelsUseFsThree)
{
    const auto e = richardson(std::vector<double>{732.7, 717.9}, 2.0);
    ASSERT_TRUE(e && e->extrapolated && e->rel_band);
    const double extrapolated = 717.9 - 14.8 / 3.0;
    EXPECT_TRUE(test::near_rel(*e->extrapolated, extrapolated, round_off));
    EXPECT_EQ(e->safety_factor, 3.0);
    EXPECT_TRUE(test::near(*e->rel_band, 14.8 / extrapolated, round_off));
    EXPECT_EQ(e->support, EstimateSupport::assumed_order);
}

TEST(GridConvergenceIndex, NoEstimateWhereTheLevelsDoNotConverge)
{
    // Differences that grow: no extrapolation at all.
    const auto growing = richardson(std::vector<double>{1.0, 1.01, 1.05}, 2.0);
    ASSERT_TRUE(growing.has_value());
    EXPECT_EQ(growing->support, EstimateSupport::not_converging);
    EXPECT_FALSE(growing->extrapolated.has_value());
    EXPECT_FALSE(growing->rel_band.has_value());
    // A penetration under an auto penalty ~ 1/h halves with h: its limit is 0, within
    // a band of 1.25 * 0.25e-3 / 0.92 around it; relative errors mean nothing.
    const auto vanishing = richardson(std::vector<double>{1.0e-3, 0.52e-3, 0.27e-3}, 2.0);
    ASSERT_TRUE(vanishing && vanishing->extrapolated);
    EXPECT_EQ(vanishing->support, EstimateSupport::zero_limit);
    EXPECT_FALSE(vanishing->rel_band.has_value());
    EXPECT_EQ(richardson(std::vector<double>{4.0, 2.0, 1.0}, 2.0)->support, EstimateSupport::zero_limit);
}

TEST(GridConvergenceIndex, LevelsThatAgreeToTheSolversNoiseHaveConverged)
{
    // A force-controlled normal force: the applied 5 at every level, to Newton's
    // tolerance. Differences of 1e-12 that happen to grow are noise, not divergence.
    const auto e = richardson(std::vector<double>{5.0, 5.0 + 1e-12, 5.0 - 3e-12}, 2.0);
    ASSERT_TRUE(e && e->extrapolated && e->rel_band);
    EXPECT_EQ(e->support, EstimateSupport::converged);
    EXPECT_EQ(*e->extrapolated, 5.0 - 3e-12);
    EXPECT_TRUE(test::near(*e->rel_band, 4e-12 / 5.0, round_off));
}

TEST(StudyRows, FlagsLevelsOutsideTheAsymptoticRangeAndVanishingLimits)
{
    // Peak: differences 0.4, 0.2, 0.05: order 1 over levels 0-2, order 2 over levels 1-3.
    // Penetration: halves with h, limit 0.
    const std::vector<double> peak = {10.65, 10.25, 10.05, 10.0};
    std::vector<StudyLevel> levels;
    for (int k = 0; k < 4; ++k) {
        StudyLevel l;
        l.level = k;
        l.quantities = {{"peak_pressure:p:b.v0", peak[static_cast<std::size_t>(k)]},
                        {"max_penetration:p", 1e-3 * std::exp2(-k)}};
        levels.push_back(l);
    }
    const std::vector<io::StudyRow> rows = study_rows(levels, 2.0);
    ASSERT_EQ(rows.size(), 8u);
    for (int k = 0; k < 4; ++k) {
        const io::StudyRow& r = rows[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.estimate, "asymptotic");  // the finest three levels show order 2
        ASSERT_TRUE(r.extrapolated_rel_band.has_value());
        // Extrapolated 10.0 - 0.05 / 3, band 1.25 * 0.05 / 3 of it.
        EXPECT_TRUE(test::near(*r.extrapolated_rel_band, 1.25 * (0.05 / 3.0) / (10.0 - 0.05 / 3.0), round_off));
    }
    EXPECT_FALSE(rows[0].asymptotic.has_value());
    EXPECT_FALSE(rows[1].asymptotic.has_value());
    EXPECT_EQ(rows[2].asymptotic, std::optional<bool>(false));  // order 1 against 2
    EXPECT_EQ(rows[3].asymptotic, std::optional<bool>(true));
    for (int k = 4; k < 8; ++k) {
        const io::StudyRow& r = rows[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.quantity, "max_penetration:p");
        EXPECT_EQ(r.estimate, "zero_limit");
        EXPECT_FALSE(r.estimated_rel_error.has_value()) << "level " << r.level;
        EXPECT_FALSE(r.extrapolated_rel_band.has_value());
    }
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
