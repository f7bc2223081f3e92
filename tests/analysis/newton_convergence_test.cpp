// Whole-solver tests of when Newton stops (solver/newton.hpp, solver/failure_cause.hpp,
// analysis/failure_advice.hpp): a deck whose residual cannot reach the tolerance in
// double precision completes at its round-off floor, and failing decks say what
// the Newton history shows, with what to change.

#include "run_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <string>

namespace iga::test {
namespace {

bool contains(const std::string& text, const std::string& phrase)
{
    return text.find(phrase) != std::string::npos;
}

// The soft-penalty deck: its relative residual stagnates near 2e-7 (measured floor
// estimate 6e-7), far above the tolerance 1e-10; before the floor-aware criterion it
// failed in increment 1 after 8 cutbacks. Converged, the top's reaction balances the
// floor's force: the free rows of r are the only imbalance, and they are at the
// accepted residual, <= round_off_margin x floor ~ 6e-6 of the force.
TEST(NewtonConvergence, SoftPenaltyDeckCompletesAtItsRoundOffFloor)
{
    const auto dir = scratch_dir("soft_penalty_half_disc");
    const analysis::RunOutcome outcome =
        run_deck(source_path("tests/analysis/decks/soft_penalty_half_disc_2d.yaml"), {}, dir / "run.h5");
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    ASSERT_EQ(outcome.obstacle_forces.size(), 1u);
    // The top's side reaction (the list also holds the body's total and the item's share).
    const auto side = std::find_if(outcome.reactions.begin(), outcome.reactions.end(),
                                   [](const io::Reaction& r) { return r.name.find('/') == std::string::npos; });
    ASSERT_NE(side, outcome.reactions.end());
    const double top = side->force[1];
    const double floor_force = outcome.obstacle_forces[0].second[1];
    constexpr double balance_tolerance = 1e-5;  // above the accepted residual, 10 x floor ~ 6e-6
    const double imbalance = std::abs(top - floor_force) / std::abs(floor_force);
    EXPECT_TRUE(std::isfinite(imbalance) && imbalance < balance_tolerance)
        << "top " << top << ", floor " << floor_force;
    EXPECT_LT(top, 0.0) << "the top is pushed down: its reaction points down";
}

// A finite-strain block carried 1000 sideways and pulled by 1e-3 at its top: its F is
// computed from displacements of 1000, so its residual stagnates near 5e-7 of the
// pull. The floor estimate counts that cancellation (|K_e| |u_e| per element): the
// run completes. Without it the estimate was 1e9 times too small and the run failed
// after 8 cutbacks. The base's reaction balances the pull to the accepted residual,
// <= round_off_margin x floor ~ 6e-5 of the force.
TEST(NewtonConvergence, ABodyCarriedFarCompletesAtItsRoundOffFloor)
{
    const auto dir = scratch_dir("block_carried_far");
    const analysis::RunOutcome outcome =
        run_deck(source_path("tests/analysis/decks/block_carried_far_2d.yaml"), {}, dir / "run.h5");
    ASSERT_EQ(outcome.status, "completed") << outcome.message;
    const auto base = std::find_if(outcome.reactions.begin(), outcome.reactions.end(),
                                   [](const io::Reaction& r) { return r.name == "block.v0"; });
    ASSERT_NE(base, outcome.reactions.end());
    constexpr double pull = 1e-3;                 // traction 1e-3 over a top of length 1
    constexpr double balance_tolerance = 1e-4;    // above the accepted residual, 10 x floor ~ 6e-5
    EXPECT_NEAR(base->force[1], -pull, balance_tolerance * pull);
}

// The extreme penalty (eps = 1e12 E) without line search or cutbacks: the full
// first step dives deep into the plane and the residual grows 1e10-fold. The
// message says so, and does not blame round-off, which the history does not show.
TEST(NewtonConvergence, DivergingDeckSaysItDiverged)
{
    const auto dir = scratch_dir("diverging_message");
    const analysis::RunOutcome outcome =
        run_deck(source_path("verification/hard/penalty_extreme.yaml"),
                 {"newton.line_search=false", "steps.adaptive=false"}, dir / "run.h5");
    ASSERT_EQ(outcome.status, "failed");
    EXPECT_TRUE(contains(outcome.message, "Newton diverged")) << outcome.message;
    EXPECT_TRUE(contains(outcome.message, "smaller increments")) << outcome.message;
    EXPECT_TRUE(contains(outcome.message, "the penalty is 1e+12 times E")) << outcome.message;
    EXPECT_FALSE(contains(outcome.message, "round-off")) << outcome.message;
    EXPECT_FALSE(contains(outcome.message, "stagnates")) << outcome.message;
}

// A rubber quarter cylinder compressed by 1.5 radii in one increment: the start
// state already inverts elements. The message names the inadmissible state.
TEST(NewtonConvergence, InvertedElementSaysInadmissible)
{
    const auto dir = scratch_dir("inverted_message");
    const analysis::RunOutcome outcome =
        run_deck(source_path("inputs/rubber_compression_2d.yaml"),
                 {"constraints.1.displacement=[0.0, -1.5]", "steps.count=1", "steps.adaptive=false"},
                 dir / "run.h5");
    ASSERT_EQ(outcome.status, "failed");
    EXPECT_TRUE(contains(outcome.message, "det F")) << outcome.message;
    EXPECT_TRUE(contains(outcome.message, "inverted element")) << outcome.message;
    EXPECT_TRUE(contains(outcome.message, "smaller increments")) << outcome.message;
    EXPECT_FALSE(contains(outcome.message, "penalty")) << outcome.message;
}

}  // namespace
}  // namespace iga::test
