// Tests for solver/residual_trend.hpp on synthetic residual histories, one table
// row per shape: an active-set flip-flop, a round-off floor, quadratic and slow
// convergence, histories too short to judge, and non-finite entries.

#include "solver/residual_trend.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct TrendCase {
    std::string name;
    std::vector<double> history;
    ResidualTrend expected;
};

const std::vector<TrendCase>& trend_cases()
{
    static const std::vector<TrendCase> cases = {
        // Converges to the contact zone, then two active sets alternate: 8.2e-3 / 3.1e-4
        // repeated within 2 % (what `-v` shows for a high-penalty flip-flop).
        {"flip_flop", {1.0, 0.2, 1.1e-2, 3.1e-4, 8.2e-3, 3.12e-4, 8.1e-3, 3.09e-4, 8.25e-3}, ResidualTrend::two_state_cycle},
        // The same cycle starting on the low level.
        {"flip_flop_low_first", {1.0, 3.0e-4, 8.0e-3, 3.05e-4, 8.1e-3, 3.0e-4, 7.9e-3}, ResidualTrend::two_state_cycle},
        // Quadratic convergence down to a round-off floor near 1e-9, then noise
        // within a factor of 3 that never halves the residual of five iterations before.
        {"round_off_floor", {1.0, 1e-3, 1e-7, 2.1e-9, 7e-10, 1.6e-9, 4e-10, 9e-10, 1.2e-9, 6e-10}, ResidualTrend::stagnation},
        // One level repeated: stagnation, not a two-state cycle.
        {"constant_level", {1.0, 0.5, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3}, ResidualTrend::stagnation},
        {"quadratic", {1.0, 0.1, 1e-2, 1e-4, 1e-8, 1e-12}, ResidualTrend::none},
        // Linear convergence by 2/3 per iteration: slow, but progress (halves in 2 steps).
        {"slow_linear", {1.0, 0.67, 0.44, 0.3, 0.2, 0.13, 0.088, 0.059}, ResidualTrend::none},
        // A decreasing alternation (a zig-zag that still converges) is not a cycle.
        {"converging_zigzag", {1.0, 0.5, 0.8, 0.2, 0.4, 0.05, 0.1, 0.01}, ResidualTrend::none},
        // The press of a friction pair at a fine mesh (Cattaneo-Mindlin, accuracy level 10):
        // 25 iterations that rise and fall between 2e-3 and 5e-2; the last two fall, but
        // not below a tenth of the 3.07e-3 reached at iteration 2.
        {"wandering", {0.2, 3.09e-3, 3.07e-3, 4.74e-2, 1.43e-2, 9.15e-3, 4.26e-3, 4.04e-3, 3.86e-3, 5.68e-3, 4.94e-3,
                       9.45e-3, 8.64e-3, 1e-2, 1.14e-2, 8.54e-3, 8.1e-3, 8.03e-3, 1.44e-2, 1.16e-2, 8.03e-3, 7.88e-3,
                       1.1e-2, 1.05e-2, 2.98e-3, 1.93e-3},
         ResidualTrend::wandering},
        // The same rises, then a fall by more than a decade below the early best: converging.
        {"wandering_then_converging", {0.2, 3.09e-3, 3.07e-3, 4.74e-2, 1.43e-2, 9.15e-3, 4.26e-3, 5e-3, 3.86e-3,
                                       5.68e-3, 1e-3, 1e-4, 1e-6},
         ResidualTrend::none},
        // Slow monotone convergence over many iterations never rises: slow, not wandering.
        {"slow_monotone_long", {1.0, 0.8, 0.64, 0.51, 0.41, 0.33, 0.26, 0.21, 0.17, 0.13, 0.11, 0.09, 0.07},
         ResidualTrend::none},
        {"too_short", {1.0, 0.3, 1.0, 0.3, 1.0}, ResidualTrend::none},
        {"empty", {}, ResidualTrend::none},
        {"nan_in_window", {1.0, 3.1e-4, 8.2e-3, nan, 8.1e-3, 3.09e-4, 8.25e-3}, ResidualTrend::none},
        {"inf_in_window", {1.0, 1.0, 1.0, INFINITY, 1.0, 1.0, 1.0}, ResidualTrend::none},
    };
    return cases;
}

TEST(ResidualTrend, ClassifiesEachHistoryShape)
{
    for (const TrendCase& c : trend_cases()) {
        SCOPED_TRACE(c.name);
        EXPECT_STREQ(trend_name(residual_trend(c.history)), trend_name(c.expected));
    }
}

TEST(ResidualTrend, AWanderingHistoryReportsItsRisesAndItsEarlyBest)
{
    const std::vector<double> history = {1.0, 0.5, 0.1, 0.3, 0.2, 0.4, 0.3, 0.25, 0.35, 0.3, 0.2, 0.15, 0.12};
    ASSERT_EQ(residual_trend(history), ResidualTrend::wandering);
    const Wandering w = wandering(history);
    EXPECT_EQ(w.rises, 3);  // 0.1 -> 0.3, 0.2 -> 0.4, 0.25 -> 0.35
    EXPECT_EQ(w.best, 0.1);
    EXPECT_EQ(w.best_at, 2);
    EXPECT_EQ(wandering({1.0, 0.1, 1e-2, 1e-4, 1e-8, 1e-12}).rises, 0) << "not wandering: no facts";
}

TEST(ResidualTrend, CycleLevelsAreTheTwoAlternatingValues)
{
    // The levels are the means of the window's even and odd entries: within
    // cycle_spread of every entry of their group by the classification itself.
    const std::vector<double> history = {1.0, 0.2, 1.1e-2, 3.1e-4, 8.2e-3, 3.12e-4, 8.1e-3, 3.09e-4, 8.25e-3};
    const CycleLevels levels = cycle_levels(history);
    EXPECT_TRUE(test::near(levels.high, 8.2e-3, cycle_spread * 8.2e-3)) << levels.high;
    EXPECT_TRUE(test::near(levels.low, 3.1e-4, cycle_spread * 3.1e-4)) << levels.low;
    const CycleLevels none = cycle_levels({1.0, 0.1, 1e-2, 1e-4, 1e-8, 1e-12});
    EXPECT_EQ(none.high, 0.0);
    EXPECT_EQ(none.low, 0.0);
}

}  // namespace
}  // namespace iga::solver
