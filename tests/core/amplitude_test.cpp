// Amplitude (core/amplitude.hpp): piecewise-linear evaluation at, between and
// beyond the points, the default ramp, the rules of valid points, and the load
// path's end and breakpoints.
#include "core/amplitude.hpp"

#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace iga {
namespace {

// Linear interpolation between points of size O(1): a few ulps of rounding.
constexpr double interpolation_tolerance = 1e-15;

const Amplitude press_release({{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}});

TEST(Amplitude, ValuesAtThePointsAreExact)
{
    const Amplitude a({{0.0, 0.5}, {0.25, -1.0}, {1.5, 3.0}});
    for (const AmplitudePoint& p : a.points())
        EXPECT_EQ(a(p.time), p.value) << "t = " << p.time;
    EXPECT_EQ(press_release(1.0), 1.0);
    EXPECT_EQ(press_release(2.0), 0.0);
}

TEST(Amplitude, LinearBetweenThePoints)
{
    EXPECT_TRUE(test::near(press_release(0.5), 0.5, interpolation_tolerance));
    EXPECT_TRUE(test::near(press_release(1.5), 0.5, interpolation_tolerance));
    EXPECT_TRUE(test::near(press_release(1.9), 0.1, interpolation_tolerance));
    const Amplitude a({{0.0, 0.5}, {0.25, -1.0}, {1.5, 3.0}});
    EXPECT_TRUE(test::near(a(0.125), -0.25, interpolation_tolerance));
    EXPECT_TRUE(test::near(a(0.875), 1.0, interpolation_tolerance));
}

TEST(Amplitude, HoldsItsEndValueBeyondTheLastPoint)
{
    EXPECT_EQ(press_release(2.5), 0.0);
    EXPECT_EQ(press_release(1e6), 0.0);
    const Amplitude hold({{0.0, 0.0}, {0.5, 2.0}});
    EXPECT_EQ(hold(0.75), 2.0);
    EXPECT_EQ(hold.end_time(), 0.5);
}

TEST(Amplitude, TheDefaultRampIsTheLoadFactor)
{
    // a(t) = t exactly on [0, 1]: a deck without amplitudes scales as before.
    const Amplitude ramp;
    for (double t : {0.0, 0.1, 1.0 / 3.0, 0.7, 0.999999, 1.0})
        EXPECT_EQ(ramp(t), t) << "t = " << t;
    EXPECT_EQ(ramp(1.5), 1.0);
    EXPECT_EQ(ramp.end_time(), 1.0);
    EXPECT_EQ(ramp, Amplitude({{0.0, 0.0}, {1.0, 1.0}}));
}

TEST(Amplitude, InvalidPointsAreRefused)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<std::vector<AmplitudePoint>> bad = {
        {},
        {{0.0, 1.0}},
        {{0.0, 0.0}, {1.0, nan}},
        {{0.0, 0.0}, {std::numeric_limits<double>::infinity(), 1.0}},
        {{0.5, 0.0}, {1.0, 1.0}},
        {{0.0, 0.0}, {1.0, 1.0}, {1.0, 2.0}},
        {{0.0, 0.0}, {2.0, 1.0}, {1.0, 2.0}},
    };
    for (const auto& points : bad) {
        EXPECT_STRNE(amplitude_problem(points), "") << points.size() << " points";
        EXPECT_THROW(Amplitude{points}, Error);
    }
    EXPECT_STREQ(amplitude_problem({{0.0, 0.0}, {1.0, -1.0}}), "");
}

TEST(LoadPath, EndsAtTheLastTimeAndStopsAtEveryKink)
{
    const LoadPath none = load_path({});
    EXPECT_EQ(none.end, 1.0);
    EXPECT_EQ(none.breakpoints, std::vector<double>{1.0});

    const LoadPath ramps = load_path({Amplitude(), Amplitude()});
    EXPECT_EQ(ramps.end, 1.0);
    EXPECT_EQ(ramps.breakpoints, std::vector<double>{1.0});

    const Amplitude shear({{0.0, 0.0}, {1.0, 0.0}, {2.0, 1.0}});
    const LoadPath path = load_path({press_release, shear, Amplitude({{0.0, 0.0}, {0.3, 1.0}})});
    EXPECT_EQ(path.end, 2.0);
    EXPECT_EQ(path.breakpoints, (std::vector<double>{0.3, 1.0, 2.0}));
}

TEST(LoadPath, TimesWithinRoundOffAreOneBreakpoint)
{
    const LoadPath path = load_path({Amplitude({{0.0, 0.0}, {1.0, 1.0}, {2.0, 1.0}}),
                                     Amplitude({{0.0, 0.0}, {1.0 + 1e-14, 1.0}})});
    ASSERT_EQ(path.breakpoints.size(), 2u);
    EXPECT_EQ(path.breakpoints.back(), 2.0);
}

}  // namespace
}  // namespace iga
