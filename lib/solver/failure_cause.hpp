#pragma once
// Why a Newton solve failed, read from its report (status and histories), so that
// the failure message says only what holds. The classes, in the order they are tested:
//
//   linear_solver:   an iterative linear solver stopped short of its tolerance even
//                    with Levenberg-Marquardt (status singular, linear status
//                    not_converged): a singular tangent or one its preconditioner
//                    does not suit, which the run cannot tell apart.
//   free_mode:       the tangent was singular even with Levenberg-Marquardt
//                    (status singular), or the last step still needed the
//                    regularization: a zero-energy mode, e.g. a body not held.
//   inadmissible:    an evaluation failed (status evaluation_failed): a
//                    non-positive Jacobian, a failed projection, a non-finite residual.
//   growth:          the residual grew: status diverged, or ||r|| at the last
//                    state is above growth_factor times the initial one (norm_ratio).
//   round_off_floor: the last residual is within round_off_margin of its own
//                    round-off floor (NewtonReport::floor_history), yet Newton did
//                    not accept it: the correction was not yet small (an
//                    ill-conditioned tangent amplifies the round-off into the step).
//   cycle:           the tail alternates between two levels (residual_trend.hpp:
//                    an active-set or projection flip-flop).
//   stagnation:      the tail stagnates above its floor: the step does not reduce
//                    the residual (a tangent that does not fit it, or steps cut
//                    to nothing by the line search).
//   wandering:       a long solve whose residual rose and fell without gaining a
//                    decade on its best (residual_trend.hpp): not converging, though
//                    its last step or two may have fallen.
//   slow:            none of these: the residual was still falling when the
//                    iterations ran out.
//   none:            the solve converged.

#include "solver/newton.hpp"

#include <string>

namespace iga::solver {

enum class FailureCause {
    none,
    linear_solver,
    free_mode,
    inadmissible,
    growth,
    round_off_floor,
    cycle,
    stagnation,
    wandering,
    slow
};

const char* cause_name(FailureCause cause);

/// A residual above 10 times the initial one has grown, not merely wandered: the line
/// search only accepts decreases, so this much growth means Newton is leaving the solution.
inline constexpr double growth_factor = 10.0;

FailureCause failure_cause(const NewtonReport& report);

/// One clause naming the cause with the report's numbers, physics-agnostic (e.g.
/// "the relative residual stagnates at 3e-07, its round-off floor 1e-07"); empty for none.
std::string cause_text(const NewtonReport& report);

}  // namespace iga::solver
