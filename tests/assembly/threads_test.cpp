// The thread-count rule of assembly/threads.hpp: a request wins, the automatic
// choice is serial below the work threshold, takes the idle cores above it, and
// is bounded on both sides.

#include "assembly/threads.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace iga::assembly {
namespace {

constexpr double idle = 0.0;

TEST(Threads, RequestedCountIsUsedAsGiven)
{
    EXPECT_EQ(choose_threads(1, 10 * parallel_work_threshold, 8, idle), 1);
    EXPECT_EQ(choose_threads(2, 0, 2, 5.0), 2);  // a loaded machine: the user's call
    EXPECT_EQ(choose_threads(1024, 0, 2, 0.0), 2);  // more than the cores: the cores (threads cost memory)
}

TEST(Threads, AutomaticIsSerialBelowTheWorkThreshold)
{
    EXPECT_EQ(choose_threads(0, parallel_work_threshold - 1, 8, idle), 1);
    EXPECT_EQ(choose_threads(0, 0, 8, idle), 1);
}

TEST(Threads, AutomaticAboveTheThresholdUsesTheIdleCoresUpToTheBound)
{
    const std::int64_t work = parallel_work_threshold;
    EXPECT_EQ(choose_threads(0, work, 2, idle), 2);
    EXPECT_EQ(choose_threads(0, work, 64, idle), max_automatic_threads);
    EXPECT_EQ(choose_threads(0, work, 1, idle), 1);
    EXPECT_EQ(choose_threads(0, work, 0, idle), 1);  // unknown core count
    EXPECT_EQ(choose_threads(0, work, 2, 0.4), 2);   // rounds to 0 busy cores
    EXPECT_EQ(choose_threads(0, work, 2, 0.6), 1);   // one core busy elsewhere
    EXPECT_EQ(choose_threads(0, work, 2, 4.0), 1);   // oversubscribed: serial
    EXPECT_EQ(choose_threads(0, work, 8, 5.0), 3);
    EXPECT_EQ(choose_threads(0, work, 2, std::nan("")), 2);  // unknown load
}

}  // namespace
}  // namespace iga::assembly
