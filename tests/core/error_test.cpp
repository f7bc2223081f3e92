#include "core/error.hpp"

#include <gtest/gtest.h>

namespace iga {

TEST(DeckIssue, FormatsFileLineColumnPathValueReason)
{
    const DeckIssue issue{{"hertz.yaml", 14, 7}, "materials.steel.nu", "0.6", "must lie in (-1, 0.5)"};
    EXPECT_EQ(issue.format(), "hertz.yaml:14:7: error: materials.steel.nu = 0.6: must lie in (-1, 0.5)");
}

TEST(DeckIssue, CommandLineValuesHaveNoLine)
{
    const DeckIssue issue{{"<command line>", 0, 0}, "contact.cyl_floor.penalty", "abc", "expected a number"};
    EXPECT_EQ(issue.format(), "<command line>: error: contact.cyl_floor.penalty = abc: expected a number");
}

TEST(DeckError, ListsEveryIssueOnItsOwnLine)
{
    const DeckError error({DeckIssue{{"a.yaml", 1, 2}, "x", "", "missing"}, DeckIssue{{"a.yaml", 3, 4}, "y", "1", "bad"}});
    EXPECT_EQ(std::string(error.what()), "a.yaml:1:2: error: x: missing\na.yaml:3:4: error: y = 1: bad");
    EXPECT_EQ(error.issues().size(), 2u);
}

TEST(Check, ThrowsErrorWithConditionAndLocation)
{
    try {
        IGA_CHECK(1 + 1 == 3, "arithmetic is broken");
        FAIL() << "IGA_CHECK did not throw";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("arithmetic is broken"), std::string::npos) << what;
        EXPECT_NE(what.find("1 + 1 == 3"), std::string::npos) << what;
        EXPECT_NE(what.find("error_test.cpp"), std::string::npos) << what;
    }
}

}  // namespace iga
