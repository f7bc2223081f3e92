#pragma once
// What the tail of a Newton residual history says about why Newton did not
// converge, so that a failure message can name the cause instead of guessing.
//
// Input: relative residuals at the accepted states of one Newton solve, oldest
// first (NewtonReport::residual_history). Only the last `trend_window` entries
// are looked at; a shorter history gives `none`.
//
//   two_state_cycle: the window alternates between two distinct levels: the
//     even-placed entries agree with each other within `cycle_spread` (relative),
//     so do the odd-placed ones, and the two levels differ by more than that.
//     Newton jumps back and forth between two states and never gets closer: with
//     penalty contact, Gauss points entering and leaving the active set (or a
//     projection switching segments) on alternate iterations.
//   stagnation: no entry of the window after the first is below
//     `stagnation_drop` times the first, and it is not a two-state cycle:
//     the residual sits at a floor (round-off of a stiff system, or a tangent
//     too wrong to make progress).
//   wandering: neither of those, but over a long solve (at least 2 trend_window
//     entries) the residual rose at least twice and its last entry is not below
//     wander_drop times the lowest it reached before the window: the tail may fall
//     for a step or two, yet the solve as a whole has not gained a decade on its own
//     best. Newton is not converging slowly there; the states it visits change (a
//     contact zone whose points press, stick or slip in turn under the steps).
//   none: anything else (still decreasing, too short, or erratic but improving).

#include <vector>

namespace iga::solver {

enum class ResidualTrend { none, two_state_cycle, stagnation, wandering };

const char* trend_name(ResidualTrend trend);

/// Entries of the history examined (6: three periods of a two-state cycle).
inline constexpr int trend_window = 6;
/// Two values are "the same level" within 5 % (a flip-flop repeats its residual
/// closely: the same two active sets give the same two residuals).
inline constexpr double cycle_spread = 0.05;
/// A Newton solve that has not halved its residual in five iterations makes no progress.
inline constexpr double stagnation_drop = 0.5;

/// Wandering: the last residual above this fraction of the best one before the window.
inline constexpr double wander_drop = 0.1;

ResidualTrend residual_trend(const std::vector<double>& history);

/// A history classified wandering: how often it rose, the best entry before the window
/// and where (its index in the history); zeros for any other.
struct Wandering {
    int rises = 0;
    double best = 0;
    int best_at = 0;
};
Wandering wandering(const std::vector<double>& history);

/// The two levels (even-, odd-placed means of the window, the larger first) of a
/// history classified two_state_cycle; {0, 0} for any other.
struct CycleLevels {
    double high = 0;
    double low = 0;
};
CycleLevels cycle_levels(const std::vector<double>& history);

}  // namespace iga::solver
