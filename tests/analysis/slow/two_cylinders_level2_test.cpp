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
    // The full-load first attempt sits at the edge of Newton's basin at this level: on
    // the project's machine of 2026-11 it ends at max_iterations (relative residual
    // 0.15 after 25 iterations; the same with the code of a95fae6, where this test
    // passed on the earlier machine), and one cutback completes the run. The
    // brief's bound, 4 increments, is what this level is held to.
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_l2", "penalty", 2), 1);
}

TEST(PenaltyAuto, TwoCylindersRefinedTwiceWithAugmentedLagrangianTakeOneIncrement)
{
    expect_one_increment_and_former_accuracy(run_two_cylinders_auto("two_cyl_auto_al_l2", "augmented_lagrangian", 2));
}

}  // namespace
}  // namespace iga::test
