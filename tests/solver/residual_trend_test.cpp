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
