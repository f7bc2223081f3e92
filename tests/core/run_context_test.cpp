#include "core/run_context.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace iga {

TEST(RunContext, LogRespectsVerbosity)
{
    std::vector<std::string> lines;
    RunContext context([&](Verbosity, const std::string& line) { lines.push_back(line); }, Verbosity::normal);
    context.log(Verbosity::normal, "shown");
    context.log(Verbosity::verbose, "hidden");
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0], "shown");
}

TEST(RunContext, TimersAndCountersAccumulate)
{
    RunContext context;
    context.add_time("assembly", 0.25);
    context.add_time("assembly", 0.5);
    context.add_count("projections", 3);
    context.add_count("projections", 4);
    EXPECT_DOUBLE_EQ(context.time("assembly"), 0.75);
    EXPECT_EQ(context.count("projections"), 7);
    EXPECT_EQ(context.count("absent"), 0);
    {
        ScopedTimer timer(&context, "scoped");
    }
    EXPECT_GE(context.time("scoped"), 0.0);
    EXPECT_EQ(context.timers().count("scoped"), 1u);
}

}  // namespace iga
