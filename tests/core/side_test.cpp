#include "core/side.hpp"

#include <gtest/gtest.h>

namespace iga {

TEST(Side, NamesRoundTripAndDirections)
{
    for (int k = 0; k < 6; ++k) {
        const Side s = static_cast<Side>(k);
        EXPECT_EQ(parse_side(side_name(s)), s);
        EXPECT_EQ(side_direction(s), k / 2);
        EXPECT_EQ(side_at_end(s), k % 2 == 1);
    }
    EXPECT_FALSE(parse_side("v3").has_value());
    EXPECT_FALSE(parse_side("").has_value());
}

}  // namespace iga
