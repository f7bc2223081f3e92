// `penalty: auto` on the two-cylinder deck at --refine-levels 2 (89k dofs), with and
// without the augmented Lagrangian: the deck's one increment and the former rule's
// level-0 accuracy (two_cylinders_auto.hpp). Labelled `slow` (about a minute each on
// an idle core): `ctest -L slow`.

#include "two_cylinders_auto.hpp"

#include <gtest/gtest.h>

namespace iga::test {
namespace {

TEST(PenaltyAuto, TwoCylindersRefinedTwiceTakeOneIncrementAtTheFormerAccuracy)
{
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_l2", "penalty", 2));
}

TEST(PenaltyAuto, TwoCylindersRefinedTwiceWithAugmentedLagrangianTakeOneIncrement)
{
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_al_l2", "augmented_lagrangian", 2));
}

}  // namespace
}  // namespace iga::test
