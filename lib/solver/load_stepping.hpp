#pragma once
// Load stepping: drives the pseudo-time t of the load path (core/amplitude.hpp)
// from 0 to its end T in increments, each solved by Newton (solver/newton.hpp),
// with adaptive cutbacks (docs/solver.md "Load stepping and cutbacks"; load paths:
// docs/theory.md "Load paths"). The system sees t as its "load factor": every item
// scales by its amplitude at t. Without amplitudes T = 1 and t is the classic load
// factor lambda (the names below keep lambda).
//
// Rules: the initial increment is T/count, which is also the largest: the
// user's count is an upper bound on the step size, never exceeded. An increment
// never steps past a breakpoint of the path: one that would is shortened to end
// on it, so each increment sees every amplitude linear (no kink inside), and the
// planned increment is taken up again after it. A failed increment restores u
// to the last converged state, calls rollback, halves the increment tried
// (adaptive only) and retries from the same t, at most max_cutbacks times per
// increment; then the run ends with completed = false and a message naming the
// increment, its load factors and the reason. The increment never falls below
// T/count / 2^max_cutbacks either: a cutback that would go below it also ends
// the run (else an adaptive run toward a limit load creeps on forever with
// geometrically shrinking increments).
//
// Step control by iteration count (adaptive only): after an increment that
// converged in n Newton iterations, the next increment is the last planned one
// times a factor (next_increment_factor): target_iterations / n below the target,
// 1 from the target to slow_iterations, slow_iterations / n above, bounded to
// [max_shrink, max_growth] (n = 0: max_growth); the result is bounded to
// [T/count / 2^max_cutbacks, T/count]. n counts the iterations until the residual was
// within the tolerance or within round_off_margin of its round-off floor: the ones after
// only polish round-off, and whether one is needed depends on the last bits of a sum,
// which differ between MPI rank counts (a frictional roller took 6 iterations serially
// and 7 on 3 ranks in one increment, and the two runs' steps parted from there on).
// An increment that needs many iterations
// shrinks the next one before it fails; an easy one lets it grow back quickly after
// cutbacks. The band between keeps the size: a frictional increment takes 7-9
// iterations as its stick/slip states settle at any size, and shrinking on every
// one of them made a press-then-shear deck take 177 increments for its planned 10.
//
// Reference force: Newton's relative residual is ||r|| / force_scale, force_scale
// the forces in play at the state (Evaluation). Along a path that returns to zero
// load (a release) those forces vanish with the load, and so would any residual
// the solve can reach: every force is round-off and the ratio stays O(1). So the
// stepper raises each evaluation's force_scale to at least the largest one of the
// converged increments so far, as Abaqus measures residuals against the
// time-averaged force of the step. Under a load that only grows the current
// forces are the largest, and nothing changes.
//
// Predictor (systems with prescribed_motion, solver/predictor.hpp): each attempt
// starts Newton from the predicted state instead of the last converged one.
// Force-driven systems (no prescribed_motion) start from the converged state.
//
// Trust radius of an increment: where the predictor solved the increment's linearized
// step, Newton's steps in that attempt are capped (NonlinearSystem::max_step) at
// predicted_step_trust times the increment's own scale, the larger of the predicted
// step ||u_pred - u_n||_inf and the motion the path prescribes over the increment
// (NonlinearSystem::prescribed_motion_between), never above the system's own radius. A
// Newton correction several times the increment's motion extrapolates the linearization
// across the contact's active set and stick/slip states: in the 2D ironing benchmark the
// full steps moved the substrate by 0.4 for a die slide of 0.09, lifted the die off all
// but a few Gauss points and inverted elements. A cutback shrinks the radius with the
// increment. Where the predictor could not solve (a body held only by contact at first
// touch: singular) or was not used, the system's radius stands, so a first touch moves
// as far as it must.
//
// Outer loop (callbacks.outer; the augmented Lagrangian's Uzawa updates): after
// each converged Newton solve of an attempt the callback decides to accept the
// increment, to solve it again from the converged state (it changed the system,
// e.g. updated multipliers; the step is not predicted again), or to reject the
// attempt, which then counts as failed: rolled back and cut back like a Newton
// failure, its message naming the outer loop's reason. Newton iterations of all
// solves of the converged attempt are summed in its report (residual histories
// appended in order); the next increment is sized by the first solve's iterations.
//
// An increment that would end within 1e-12 T of a breakpoint ends on it, so the
// run ends at exactly T and lands exactly on every kink. Linear systems never
// cut back (a smaller increment cannot cure a failed linear solve). Non-adaptive
// stepping takes exactly `count` increments, plus one for each breakpoint that
// falls inside one of them. Load factors are monotone:
// lambda_k = lambda_{k-1} + (increment k).
//
// Stopping (SIGINT/SIGTERM): callbacks.stop_requested and context->stop() are
// checked before each increment; a stop requested inside one (Interrupted thrown
// by an evaluation, core/stop.hpp) abandons it: u is restored to the last converged
// state, rollback is called, and the run ends with a message naming both.

#include "core/amplitude.hpp"
#include "core/run_context.hpp"
#include "core/types.hpp"
#include "solver/linear.hpp"
#include "solver/newton.hpp"
#include "solver/predictor.hpp"

#include <functional>
#include <string>
#include <vector>

namespace iga::solver {

struct SteppingSettings {
    LoadPath path;          ///< [0, T] and the breakpoints to land on; default [0, 1]
    int count = 1;          ///< initial number of increments: increment T/count, also the largest
    bool adaptive = true;   ///< halve a failed increment and retry; size the next one by the iterations
    int max_cutbacks = 8;   ///< per increment
    /// Newton iterations an increment should take; 6: a finite-strain or contact
    /// increment converging quadratically from a predicted state needs 4-6, so an
    /// increment at the target is as large as Newton handles without strain.
    int target_iterations = 6;
    /// Up to this many iterations the next increment keeps its size; above, it shrinks
    /// by slow_iterations / n. 10: twice the iterations a quadratic Newton needs from a
    /// predicted state, still well inside newton.max_iterations (25 by default).
    int slow_iterations = 10;
    double max_growth = 2.0;  ///< bound on the factor target / n that grows the next increment
    double max_shrink = 0.5;  ///< bound on the factor that shrinks it (the same as a cutback)
    Predictor predictor = Predictor::linearized;
};

/// The trust radius of an increment over its scale (see the header). 0.25, measured on
/// verification/scenes: the 2D ironing die pressed 1.0 completes (199 increments, 7.96
/// Newton iterations each, 1 cutback; with the radius of the model size it failed at
/// t = 8.07), pressed 0.3 takes 162 increments and no cutback (184 and 4); 0.5 left
/// the press 1.0 failing at t = 8.96.
inline constexpr double predicted_step_trust = 0.25;

/// The factor by which an increment that converged in `iterations` Newton
/// iterations scales the next one (the step control above).
double next_increment_factor(int iterations, const SteppingSettings& stepping);

/// What the outer loop decides after a converged Newton solve (see the header paragraph).
struct OuterDecision {
    enum class Action { accept, resolve, reject };
    Action action = Action::accept;
    std::string message;  ///< reject: why, in words
};

struct IncrementRecord {
    int index = 0;           ///< 1-based, counts converged increments
    double load_factor = 0;  ///< lambda at the end of the increment
    NewtonReport report;     ///< of the attempt that converged (iterations of all its solves)
    int cutbacks = 0;        ///< failed attempts before the one that converged
    int outer_updates = 0;   ///< resolve decisions of the converged attempt (Uzawa updates)
    double wall_s = 0;       ///< wall time of the increment, failed attempts included
};

struct SteppingCallbacks {
    /// After each converged increment (after commit), with the converged state.
    std::function<void(const IncrementRecord&, const Vector& u)> converged;
    /// State hook after convergence (e.g. accept history variables); may be empty.
    std::function<void()> commit;
    /// After a failed attempt, once u is back at the last converged state; may be empty.
    std::function<void()> rollback;
    /// After each converged Newton solve, with the state and the load factor; may be empty (accept).
    std::function<OuterDecision(const Vector& u, double load_factor)> outer;
    /// Checked before each increment; true stops the run cleanly (e.g. on SIGINT); may be empty.
    /// (Inside an increment the stop comes from context->stop(): see the header paragraph.)
    std::function<bool()> stop_requested;
};

struct SteppingResult {
    bool completed = false;  ///< the end T of the path reached
    bool stopped = false;    ///< a stop request (SIGINT/SIGTERM) ended the run: no failure to diagnose
    bool out_of_memory = false;  ///< an allocation failed inside an increment: nothing to diagnose either
    /// Empty when completed; else why, e.g. "increment 7 (load factor 0.44 -> 0.47):
    /// Newton did not converge after 8 cutbacks; last relative residual 3.1e-04
    /// (tolerance 1e-10)", or that a stop was requested.
    std::string message;
    int total_cutbacks = 0;
    int total_iterations = 0;  ///< Newton iterations of all attempts, failed ones included
    int predictor_fallbacks = 0;  ///< attempts whose predicted state was scaled back or not admissible
    /// The report of the attempt that ended the run (default when completed or stopped).
    NewtonReport last_failure;
    std::vector<IncrementRecord> increments;
};

/// Runs the increments from u (the state at t = 0). On return u holds the
/// last converged state (lambda = increments.back().load_factor, or the input u
/// if none converged). Logs one line per converged increment at Verbosity::normal.
SteppingResult run_load_steps(const NonlinearSystem& system, Vector& u, const SteppingSettings& stepping,
                              const NewtonSettings& newton, LinearSolver& solver, SteppingCallbacks& callbacks,
                              RunContext* context);

}  // namespace iga::solver
