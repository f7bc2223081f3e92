// The thread-count rule of assembly/threads.hpp: a request wins, the automatic
// choice is serial below the work threshold and bounded above.

#include "assembly/threads.hpp"

#include <gtest/gtest.h>

namespace iga::assembly {
namespace {

TEST(Threads, RequestedCountIsUsedAsGiven)
{
    EXPECT_EQ(choose_threads(1, 10 * parallel_work_threshold, 8), 1);
    EXPECT_EQ(choose_threads(3, 0, 2), 3);  // more than the cores: the user's call
}

TEST(Threads, AutomaticIsSerialBelowTheWorkThreshold)
{
    EXPECT_EQ(choose_threads(0, parallel_work_threshold - 1, 8), 1);
    EXPECT_EQ(choose_threads(0, 0, 8), 1);
}

TEST(Threads, AutomaticAboveTheThresholdUsesTheCoresUpToTheBound)
{
    EXPECT_EQ(choose_threads(0, parallel_work_threshold, 2), 2);
    EXPECT_EQ(choose_threads(0, parallel_work_threshold, 64), max_automatic_threads);
    EXPECT_EQ(choose_threads(0, parallel_work_threshold, 1), 1);
    EXPECT_EQ(choose_threads(0, parallel_work_threshold, 0), 1);  // unknown core count
}

}  // namespace
}  // namespace iga::assembly
