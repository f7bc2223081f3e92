#pragma once
// Newton-Raphson for a nonlinear system r(u; lambda) = 0 on the free dofs, with
// a backtracking line search on ||r||, a trust-radius cap on the step and a
// Levenberg-Marquardt fallback for singular tangents. Physics-agnostic: the
// system is a callback returning the residual and tangent K = dr/du (the driver
// sums the elastic, load and contact terms); nothing here knows what they are.
//
// Sign convention: r = f_int - f_ext (zero at equilibrium), K = dr/du, so the
// Newton step solves K du = -r. Shapes: u and r have n_free entries, K is
// n_free x n_free. References: Nocedal & Wright, "Numerical Optimization", 2nd
// ed., §3.1 (Armijo backtracking) and §11.2 (Levenberg-Marquardt), applied to
// the merit function ||r||; docs/solver.md "The first touch" (why contact needs them).
//
// Convergence: the residual is small against the forces in play, or it is at its
// own round-off floor and the displacement no longer moves:
//   ||r|| <= tolerance * force_scale, or
//   ||r|| <= round_off_margin * residual_floor and ||du||_inf <= 1e-9 ||u||_inf, or
//   that floor test in two iterations in a row and ||du||_inf <= 1e-7 ||u||_inf (a
//   stall at the floor of an ill-conditioned tangent, whose corrections are noise),
// force_scale and residual_floor from the system (Evaluation), du the last full
// Newton correction. The second test (FEBio and Abaqus combine a force with a
// displacement criterion the same way) ends a solve whose residual cannot reach
// the tolerance in double precision: a soft penalty whose reaction is tiny against
// the internal forces, a stiff penalty whose gaps carry eps * penalty * |x|, a
// stress-free rigid motion where every force is round-off. A residual far above
// its floor is never accepted, however small the step (docs/theory.md, "When Newton
// has converged").
//
// Singular tangent (a body held only by contact at first touch, a frictionless
// rigid-body mode): when the factorization or the solve reports singular, solve
// (K + mu D) du = -r instead, D = diag(|K_ii|) with zero diagonal entries
// replaced by the mean nonzero |K_ii| (or 1 if K has a zero diagonal), mu =
// 1e-10, 1e-8, ... 1e0 until the solve succeeds (LinearSolver::factorize_shifted,
// which knows the summed diagonal on several ranks). The residual is unchanged, so a
// converged solution is exact; the huge steps along near-null directions are
// tamed by max_step and the line search. When the system knows the tangent is
// singular (Evaluation::singular_tangent: a body that only contact holds, no
// contact point carrying yet), K is not factorized at all and the shifts start at
// mu = 1e-8 (LinearSolver::factorize_shifted_taking): for a residual along the null
// mode, mu = 1e-10 fails the solver's backward-error check (newton.cpp).
//
// Line search: the full step is taken when ||r(u + du)|| <= (1 - 1e-4) ||r(u)||.
// Otherwise, first the directional search of Crisfield (Non-linear FE Analysis
// of Solids and Structures, vol. 1, §9.3): the root of s(alpha) = du . r(u + alpha du)
// by Illinois regula falsi, accepted at |s| <= 0.1 |s(0)| — for a potential
// problem the energy minimum along du, and for penalty contact the step length
// at which the contact forces balance the load (a full step that dives deep into
// the obstacle is cut back to the right depth in a few evaluations). If du is
// not a descent direction (s(0) >= 0) or the search fails: backtracking on ||r||,
// accept alpha when ||r(u + alpha du)|| <= (1 - 1e-4 alpha) ||r(u)||,
// else halve alpha, up to max_backtracks times. A trial whose residual is not
// finite, or whose evaluation fails, is rejected. If no trial is accepted, the
// finite trial with the smallest ||r|| is taken (ties go to the longer step, so
// that Newton walks across regions where r is flat, e.g. an open contact gap,
// instead of creeping by 2^-max_backtracks per iteration).
//
// Inadmissible trial states (an inverted element, det F <= 0; a material or a
// contact projection that cannot be evaluated; a non-finite residual): the
// evaluation reports ok = false and the trial is rejected like one that raises
// ||r||, so the backtracking above halves the step (up to max_backtracks times)
// inside the iteration; only when every trial along the direction is
// inadmissible does Newton stop with evaluation_failed (the load stepper then
// cuts the increment back). Counted in NewtonReport::inadmissible_trials. With
// line_search off, an inadmissible full step ends the solve at once.
//
// Failure diagnosis: on any failure the report is classified (solver/failure_cause.hpp:
// free mode, inadmissible state, growth, cycle, round-off floor, stagnation, slow)
// and the message ends with what holds.
//
// On any failure status, u is restored to its value on entry. A stop request
// (context->stop(), core/stop.hpp) throws Interrupted out of the solve, leaving u
// at the last trial state: the caller restores what it needs.

#include "core/run_context.hpp"
#include "core/types.hpp"
#include "solver/linear.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace iga::solver {

/// What one call of the system's evaluate() produces.
struct Evaluation {
    Vector residual;       ///< r(u; lambda), n_free
    SparseMatrix tangent;  ///< K = dr/du, n_free x n_free; filled only when asked for
    /// Norm of the forces in play (e.g. ||f_ext|| + ||reactions||), the scale of
    /// the relative residual. Zero only when no force acts at all.
    double force_scale = 0;
    /// Estimated round-off of ||residual|| (absolute): machine epsilon times the norm
    /// of the per-dof sums of |term| over the terms summed into r (a residual this
    /// small cannot be reduced in double precision). 0: unknown, no floor is used.
    double residual_floor = 0;
    /// The system knows the tangent is singular (a body that only contact holds, and no
    /// contact point carries yet: a first touch): Newton solves with K + mu D at once,
    /// without the factorization of K that could only fail. Only with the tangent.
    bool singular_tangent = false;
    /// false: the evaluation itself failed (a projection failed, a non-positive
    /// Jacobian); Newton reports evaluation_failed with this message.
    bool ok = true;
    std::string message;
    /// Per contact Gauss point (every pair's carrying sides in order), 1 where it presses
    /// and 0 elsewhere: Newton watches it for points that flip at every step (a cycle).
    /// Empty without contact.
    std::vector<std::uint8_t> contact_active;
};

/// Member-wise: Eigen 3.4's sparse matrix cannot be moved, so std::swap of two
/// evaluations would copy a tangent three times.
inline void swap(Evaluation& a, Evaluation& b) noexcept
{
    a.residual.swap(b.residual);
    a.tangent.swap(b.tangent);
    std::swap(a.force_scale, b.force_scale);
    std::swap(a.residual_floor, b.residual_floor);
    std::swap(a.singular_tangent, b.singular_tangent);
    std::swap(a.ok, b.ok);
    a.message.swap(b.message);
    a.contact_active.swap(b.contact_active);
}

struct NonlinearSystem {
    /// Fills out.residual (always) and out.tangent (when need_tangent) at state u
    /// and load factor lambda. Newton resets out.ok = true, out.singular_tangent = false
    /// and out.message before each call; out.tangent keeps its previous storage, so it may be refilled in place.
    std::function<void(const Vector& u, double load_factor, bool need_tangent, Evaluation& out)> evaluate;
    bool linear = false;     ///< r is affine in u: one solve per increment, refined with residuals r(u + du)
    bool symmetric = true;   ///< K symmetric: Cholesky may be used, else LU is forced
    /// > 0: cap on ||du||_inf (trust radius) at the start of a solve; a capped full step that
    /// leaves ||r|| above 0.9 of the last doubles it for that solve (docs/solver.md); 0: no cap
    double max_step = 0;
    /// The load factor moves constrained dofs (prescribed displacements): the load
    /// stepper predicts each increment's free dofs (solver/predictor.hpp).
    bool prescribed_motion = false;
    /// On several MPI ranks each rank's tangent is its summand of K (solver/linear.hpp):
    /// a product K x is the sum of the ranks' products, which this sums in place.
    /// Empty on one process.
    std::function<void(Vector&)> sum_over_ranks;
    /// The largest motion the load path prescribes between two load factors (constrained
    /// dofs, moving obstacles), ||.||_inf; the load stepper sizes an increment's trust
    /// radius with it (solver/load_stepping.hpp). May be empty (none).
    std::function<double(double, double)> prescribed_motion_between;
    /// Holds the listed contact points (indices into Evaluation::contact_active) open:
    /// Newton asks for it where they cycle (docs/solver.md, "A point held open"). Returns
    /// how many it held; it refuses a point that presses too deep to be left without
    /// force. A hold lasts until the next solve starts (it frees every hold with
    /// release_holds), or until release_deep_holds frees it. Empty: Newton never asks.
    std::function<int(const std::vector<int>&)> hold_open;
    /// Frees every held contact point: a solve starts from the contact law itself.
    std::function<void()> release_holds;
    /// At a state Newton finds converged: frees the held points that now press too deep
    /// to be left without force; how many. Newton goes on from there when any.
    std::function<int()> release_deep_holds;
};

struct NewtonSettings {
    double tolerance = 1e-10;  ///< on the relative residual
    int max_iterations = 25;
    bool line_search = true;
    int max_backtracks = 12;
    double divergence_factor = 1e8;  ///< ||r|| > this * ||r_0|| (or not finite): diverged
};

/// ||r|| within this factor of Evaluation::residual_floor is round-off. The estimate,
/// eps_mach times sums of |terms|, already bounds what was measured where Newton
/// stalls (||r|| / floor = 0.3-0.6 on the soft-penalty deck and Hertz, 0.01 at
/// penalty 1e12 E); 10 allows for sums whose errors add up less kindly, and no more.
inline constexpr double round_off_margin = 10.0;

/// singular: the tangent could not be solved, even shifted (a direct solver met a zero
/// pivot, or its solution failed the backward-error check); linear_solver_not_converged:
/// an iterative solver stopped short of its tolerance, even shifted, which a singular
/// tangent and a merely hard one both cause.
enum class NewtonStatus {
    converged,
    max_iterations,
    diverged,
    singular,
    linear_solver_not_converged,
    evaluation_failed
};

const char* status_name(NewtonStatus status);

struct NewtonReport {
    NewtonStatus status = NewtonStatus::max_iterations;
    int iterations = 0;             ///< Newton steps taken (linear systems: 1)
    double residual_norm = 0;       ///< final relative residual
    /// Relative residual at each accepted state, starting with the initial one
    /// (size iterations + 1 unless the run stopped on a failed evaluation).
    std::vector<double> residual_history;
    /// Relative round-off floor (residual_floor / force_scale) at the same states.
    std::vector<double> floor_history;
    /// Last full Newton correction over the displacement, ||du||_inf / ||u||_inf.
    double correction = 0;
    bool last_step_regularized = false;  ///< the last step needed K + mu D
    /// The last step was shifted because an iterative solver stopped short on K, not
    /// because K was found singular.
    bool krylov_stopped = false;
    /// ||r|| at the last accepted state over ||r|| at the start (absolute, unlike the
    /// relative history, whose force scale grows with a diverging residual).
    double norm_ratio = 1;
    int regularized_iterations = 0;  ///< steps that needed K + mu D
    int line_search_cuts = 0;        ///< backtracking halvings over all steps
    int inadmissible_trials = 0;     ///< trial states rejected because their evaluation failed
    int held_open = 0;               ///< contact points held open because they cycled (NonlinearSystem::hold_open)
    std::string message;             ///< why it stopped, human readable
};

/// Solves r(u; load_factor) = 0 starting from u. On success u holds the solution;
/// on failure u is restored to its input value. Which factorization or method
/// solves the steps (Cholesky for a symmetric system, LU otherwise, ...) is the
/// solver's, chosen once by make_linear_solver (solver/linear.hpp). context may be
/// null; when given, the time in evaluate() is added to "assembly", factorize +
/// solve to "linear_solve", and the steps to the counter "newton_iterations".
NewtonReport solve_newton(const NonlinearSystem& system, double load_factor, Vector& u,
                          const NewtonSettings& settings, LinearSolver& solver, RunContext* context);

}  // namespace iga::solver
