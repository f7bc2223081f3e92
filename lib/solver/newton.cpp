#include "solver/newton.hpp"

#include "core/error.hpp"
#include "solver/failure_cause.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

namespace iga::solver {

namespace {

// Armijo constant: demand a decrease of ||r|| of at least 1e-4 alpha ||r||, the
// usual value (Nocedal & Wright §3.1): any real descent passes, a flat or
// rising residual does not.
constexpr double armijo = 1e-4;
// Convergence at round-off (see the header): ||r|| within round_off_margin of the
// system's round-off estimate Evaluation::residual_floor, and a Newton correction
// below correction_tolerance of the displacement. The estimate is eps_mach times
// sums of |terms| (round_off_margin in newton.hpp). A correction of 1e-9 of u is far
// below any discretisation error, and far above the round-off of u itself (1e-16).
constexpr double correction_tolerance = 1e-9;
// An ill-conditioned tangent (a fine graded mesh, penalties 1e3 E, a frictional
// contact's tangential penalty) turns a round-off residual into corrections of
// kappa(K) eps_mach ~ 1e-8 of u: Newton then sits at its floor and its corrections
// are noise. Two iterations in a row at the floor with a correction below
// stalled_correction_tolerance of u end such a solve; 1e-7 of u is still far below
// any discretisation error (measured: verification/friction/cattaneo_mindlin_2d.yaml
// stalls at ||r|| ~ 0.3 of its floor with corrections 5e-9 to 5e-8 of u).
constexpr double stalled_correction_tolerance = 1e-7;
/// A capped full Newton step whose ||r|| is above this fraction of the last one made no
/// progress: the trust radius, not the direction, holds Newton back (NewtonSolve::iterate).
constexpr double stalled_reduction = 0.9;
/// Contact points that flip at every step are held open only where the residuals repeat
/// too, each within this fraction of its value two steps before: a cycle revisits its
/// states (the dragged block's: 2.79e-4, 2.84e-4, 2.79e-4, 2.84e-4), while Newton that
/// grows a contact zone moves its edge points back and forth with ||r|| changing by
/// per cents a step (the two spheres' first touch: 0.99, 0.98, 0.95, 1.06, 0.97).
constexpr double cycle_repeat = 1e-3;
/// The longest cycle looked for, in Newton steps (the dragged block's longest was 7: a
/// full step, then six steps the line search cut ever shorter).
constexpr std::size_t max_cycle = 8;
// Levenberg-Marquardt: mu = 1e-10 perturbs K at the level of its round-off for
// a well-scaled K; x100 per retry up to mu = 1 (6 tries).
constexpr double first_mu = 1e-10;
constexpr double mu_growth = 100.0;
constexpr int max_regularizations = 6;
double largest_mu() { return first_mu * std::pow(mu_growth, max_regularizations - 1); }
// A tangent the system knows to be singular starts one rung up. Along its null mode
// v the shifted solve gives x ~ (v.b) / (mu v^T D v), and a backward-stable solve
// leaves ||K x - b|| ~ eps ||K|| ||x||: at mu = 1e-10 that is ~ 2e-6 ||K|| / d ||b||
// for a b along v (d the D-weighted scale of v, d <= ||K||), above the solver's
// bound 1e-6 ||b|| (solver/linear.hpp): the solve is rejected, its factorization
// wasted. Measured at the first touch of inputs/hertz.yaml: 3.6e-6 ||b|| at 1e-10,
// 1.4e-8 ||b|| at 1e-8 (the 3D sphere octant: 2.6e-8 at 1e-8). Where 1e-10 would
// pass (inputs/disc_on_plane_2d.yaml), 1e-8 changes the capped step by ~1e-3 of
// its length: along the null mode both are the trust radius.
constexpr int first_singular_attempt = 1;  // mu = first_mu * mu_growth
// Newton stops after this many iterations in a row whose Krylov solve stopped short on
// the unshifted tangent (a preconditioner that does not fit it; NewtonSolve::iterate).
constexpr int max_krylov_stops_in_a_row = 2;
// Linear systems: extra solves with the same factorization (iterative refinement)
// while the algebraic residual is above the tolerance.
constexpr int max_refinements = 2;
// The share of the tolerance a linear solve is asked for (LinearSolver::solve_to):
// the rest is left to the nonlinearity, and the residual is measured after the step.
constexpr double linear_accuracy_margin = 0.5;
// Newton's steps are solved to a relative residual of 1e-8, which keeps the
// convergence quadratic down to the tolerances in use (1e-10 after two or three
// steps), or to what the tolerance needs of the step where that asks for less (the
// last step of a solve) or for a little more (below); an iterative solver stops there
// (a direct one solves to round-off anyway).
constexpr double newton_linear_accuracy = 1e-8;
// A step whose needed accuracy is within this factor of newton_linear_accuracy can be
// the last one: it asks for what finishing needs, down to newton_linear_accuracy /
// last_step_reach. A Krylov solve to 1e-9 instead of 1e-8 costs about a tenth more
// iterations; stopping at 1e-8 cost a Newton iteration on the stiff sphere octant under
// BoomerAMG (1.25e-10 left against the tolerance 1e-10, where a direct solve finished).
constexpr double last_step_reach = 10.0;

std::string format_g(double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

double relative(double norm, double force_scale)
{
    return norm / std::max(force_scale, DBL_MIN);
}

/// The relative residual of K du = -r that brings ||r(u + du)|| within the tolerance,
/// with linear_accuracy_margin (r the residual at u, in force_scale units).
double accuracy_needed(double tolerance, double residual_norm, double force_scale)
{
    return std::max(linear_accuracy_margin * tolerance * force_scale / residual_norm, DBL_MIN);
}

double finite_norm_or_inf(const Evaluation& e)
{
    if (!e.ok)
        return std::numeric_limits<double>::infinity();
    const double n = e.residual.norm();
    return std::isfinite(n) ? n : std::numeric_limits<double>::infinity();
}

void evaluate(const NonlinearSystem& system, const Vector& u, double load_factor, bool need_tangent,
              Evaluation& out, RunContext* context)
{
    if (context)
        context->stop().check();  // every trial state: a stop request ends the solve within one evaluation
    out.ok = true;
    out.singular_tangent = false;
    out.message.clear();
    {
        ScopedTimer timer(context, "assembly");
        system.evaluate(u, load_factor, need_tangent, out);
    }
    if (!out.ok)
        return;
    IGA_CHECK(out.residual.size() == u.size(), "NonlinearSystem::evaluate: residual size differs from u");
    if (need_tangent)
        IGA_CHECK(out.tangent.rows() == u.size() && out.tangent.cols() == u.size(),
                  "NonlinearSystem::evaluate: tangent is not n_free x n_free");
}

struct StepResult {
    LinearStatus status = LinearStatus::ok;
    bool regularized = false;
    double mu = 0;
    /// Why the step was shifted: an iterative solver that stopped short on K (not a K
    /// found singular), with what it saw.
    bool krylov_stopped = false;
    std::string krylov_detail;
};

/// The first Krylov solve of a run that stops short on an unshifted tangent is a
/// warning, printed under -q too: Newton goes on with shifted tangents, which slows it
/// or stops it, and only a setting changes that. Counted in /counters (krylov_stops).
void warn_krylov_stop(const std::string& detail, RunContext* context)
{
    if (!context)
        return;
    if (context->count("krylov_stops") == 0)
        context->log(Verbosity::quiet,
                     "warning: the iterative linear solver did not converge" +
                         (detail.empty() ? std::string() : " (" + detail + ")") +
                         "; Newton shifts the tangent instead, which slows it or stops it. solver.type: direct "
                         "solves any tangent; solver.options sets another Krylov method or preconditioner");
    context->add_count("krylov_stops", 1);
}

// Solves K du = -r; on a singular K retries with K + mu D (see the header). With
// `consume` the solver may take K's storage and K is left empty (the caller needs it no more).
// known_singular (Evaluation::singular_tangent): K is not factorized, and the shifts
// start at first_singular_attempt. accuracy > 0: the relative residual of K du = -r
// that suffices (LinearSolver::solve_to), else the solver's own.
StepResult newton_step(SparseMatrix& K, const Vector& r, LinearSolver& solver, RunContext* context, Vector& du,
                       bool consume, bool known_singular, double accuracy = 0)
{
    ScopedTimer timer(context, "linear_solve");
    const Vector rhs = -r;
    auto solve = [&] { return accuracy > 0 ? solver.solve_to(rhs, du, accuracy) : solver.solve(rhs, du); };
    StepResult result;
    const bool shift_at_once = known_singular && consume;
    if (!shift_at_once) {
        const int refusals = solver.statistics().cholesky_fallbacks;
        result.status = consume ? solver.factorize_taking(K) : solver.factorize(K);
        if (context && solver.statistics().cholesky_fallbacks > refusals)
            context->log(Verbosity::verbose, "  tangent not positive definite: factorized by LU");
        if (result.status == LinearStatus::ok)
            result.status = solve();
        // An iterative method that stopped short may have met a singular K (the first
        // touch) as well as a hard one: the shift helps either.
        if (result.status != LinearStatus::singular && result.status != LinearStatus::not_converged)
            return result;
        result.krylov_stopped = result.status == LinearStatus::not_converged;
        if (result.krylov_stopped) {
            result.krylov_detail = solver.failure_detail();
            warn_krylov_stop(result.krylov_detail, context);
        }
    }

    const int first_attempt = shift_at_once ? first_singular_attempt : 0;
    double mu = first_mu * std::pow(mu_growth, first_attempt);
    for (int attempt = first_attempt; attempt < max_regularizations; ++attempt, mu *= mu_growth) {
        result.status = shift_at_once && attempt == first_attempt ? solver.factorize_shifted_taking(K, mu)
                                                                  : solver.factorize_shifted(mu);
        if (result.status == LinearStatus::ok)
            result.status = solve();
        if (result.status == LinearStatus::ok) {
            result.regularized = true;
            result.mu = mu;
            return result;
        }
    }
    return result;
}

/// How a step that could not be solved ends Newton: a Krylov method that stopped short
/// says only that (a singular tangent and a hard one both stop it); a direct method
/// found the tangent singular. The clause carries what the solver saw.
struct LinearFailure {
    NewtonStatus status;
    std::string text;  // "the linear solver did not converge (cg + gamg stopped after ...)"
};
LinearFailure linear_failure(LinearStatus status, const LinearSolver& solver)
{
    const std::string detail = solver.failure_detail();
    const std::string seen = detail.empty() ? std::string() : " (" + detail + ")";
    switch (status) {
    case LinearStatus::not_converged:
        return {NewtonStatus::linear_solver_not_converged, "the linear solver did not converge" + seen};
    case LinearStatus::failed: return {NewtonStatus::singular, "the linear solve failed" + seen};
    case LinearStatus::singular:
    case LinearStatus::ok: break;
    }
    return {NewtonStatus::singular, "the tangent is singular" + seen};
}

/// What a step of Newton hands back: go on, or the solve has finished (its report is final).
enum class Progress { going_on, finished };

/// The line search along a Newton direction du from u (the header's "Line search"):
/// the full step when it lowers ||r|| enough, else the root of the directional
/// residual (slope_root), else backtracking on ||r|| (backtrack). `trial` holds the
/// evaluation at u + du, with the tangent; `probe` is the storage for shorter steps.
class LineSearch {
public:
    struct Result {
        double alpha = 1.0;
        Evaluation* chosen = nullptr;  ///< the evaluation at u + alpha du: &trial or &probe
        bool chosen_has_tangent = true;
        /// No acceptable state along du: how Newton ends, and why.
        bool failed = false;
        NewtonStatus status = NewtonStatus::converged;
        std::string message;
    };

    LineSearch(const NonlinearSystem& system, double load_factor, const NewtonSettings& settings,
               RunContext* context, NewtonReport& report)
        : system_(system), load_factor_(load_factor), settings_(settings), context_(context), report_(report)
    {
    }

    /// r_norm: ||r(u)||; new_norm: ||r(u + du)|| (infinite when not finite or not admissible).
    Result search(const Vector& u, const Vector& du, double r_norm, double new_norm, const Evaluation& current,
                  Evaluation& trial, Evaluation& probe, int iteration) const
    {
        Result result;
        result.chosen = &trial;
        if (new_norm <= (1.0 - armijo) * r_norm)
            return result;  // the full step
        if (slope_root(u, du, current, trial, probe, result.alpha)) {
            // The root of s(alpha) = du . r(u + alpha du) was found (or the full step is still
            // downhill): the step length that balances the forces along du.
            if (result.alpha != 1.0) {
                result.chosen = &probe;
                result.chosen_has_tangent = false;
            }
            return result;
        }
        return backtrack(u, du, r_norm, new_norm, trial, probe, iteration);
    }

private:
    bool slope_root(const Vector& u, const Vector& du, const Evaluation& current, const Evaluation& trial,
                    Evaluation& probe, double& alpha) const;
    Result backtrack(const Vector& u, const Vector& du, double r_norm, double new_norm, Evaluation& trial,
                     Evaluation& probe, int iteration) const;

    const NonlinearSystem& system_;
    double load_factor_;
    const NewtonSettings& settings_;
    RunContext* context_;
    NewtonReport& report_;  ///< counts the evaluations (line_search_cuts) and the inadmissible trials
};

/// Line search on the directional residual s(alpha) = du . r(u + alpha du)
/// (Crisfield, "Non-linear Finite Element Analysis of Solids and Structures",
/// vol. 1, §9.3): for a potential problem s is the slope of the energy along du,
/// and its root is the energy minimum on the line. This is what a penalty contact
/// step needs: at first touch or when many Gauss points enter contact, the full
/// step overshoots into a deep penetration whose residual norm is huge, and
/// halving alpha on ||r|| crawls; the root of s is where the contact forces
/// balance the load along du. Regula falsi with the Illinois modification and a
/// bisection safeguard, within settings.max_backtracks evaluations; accepts
/// |s(alpha)| <= 0.1 |s(0)|.
/// Returns false (the caller falls back to backtracking on ||r||) when du is not a
/// descent direction (s(0) >= 0) or s(1) is not finite. On success `alpha` is set
/// and, when alpha != 1, `probe` holds the evaluation at u + alpha du.
bool LineSearch::slope_root(const Vector& u, const Vector& du, const Evaluation& current, const Evaluation& trial,
                            Evaluation& probe, double& alpha) const
{
    const double s0 = du.dot(current.residual);
    if (!(s0 < 0.0) || !trial.ok || !trial.residual.allFinite())
        return false;
    const double s1 = du.dot(trial.residual);
    if (!std::isfinite(s1))
        return false;
    if (s1 <= 0.0) {
        alpha = 1.0;  // still downhill at the full step: take it
        return true;
    }
    // Crisfield accepts |s| <= 0.5 |s0|; the closer root saves a third of the Newton
    // iterations of a 3D point contact at first touch (sphere on a plane: 13 -> 9,
    // two cylinders 18 -> 15) for 1-3 more on small 2D first touches (hard cases).
    constexpr double slope_reduction = 0.1;
    double a = 0.0, sa = s0, b = 1.0, sb = s1;
    int retained = 0;  // which end was kept last: -1 left, +1 right
    std::vector<double> width{b - a};  // the bracket's width after each step
    for (int k = 0; k < settings_.max_backtracks; ++k) {
        double c = b - sb * (b - a) / (sb - sa);
        // Regula falsi creeps from one end when s is strongly curved (a penalty that
        // stiffens by orders of magnitude along the step: s(0) = -1e-2, s(1) = +1e2).
        // When the bracket has not halved in two steps, bisect -- geometrically when
        // it spans decades, as the root of a first touch may lie anywhere in 1e-4..1.
        if (width.size() >= 3 && b - a > 0.5 * width[width.size() - 3])
            c = (a > 0.0 && b > 4.0 * a) ? std::sqrt(a * b) : 0.5 * (a + b);
        ++report_.line_search_cuts;
        evaluate(system_, u + c * du, load_factor_, false, probe, context_);
        if (!probe.ok || !probe.residual.allFinite()) {
            ++report_.inadmissible_trials;
            return false;
        }
        const double sc = du.dot(probe.residual);
        if (std::abs(sc) <= slope_reduction * std::abs(s0)) {
            alpha = c;
            return true;
        }
        if (sc > 0.0) {
            b = c;
            sb = sc;
            if (retained == -1)
                sa *= 0.5;  // Illinois: the left end was kept twice
            retained = -1;
        } else {
            a = c;
            sa = sc;
            if (retained == +1)
                sb *= 0.5;
            retained = +1;
        }
        width.push_back(b - a);
    }
    return false;
}

/// Armijo backtracking on ||r||: halve alpha until ||r(u + alpha du)|| <= (1 - 1e-4 alpha)
/// ||r(u)||, at most max_backtracks times; if none passes, the finite trial with the
/// smallest ||r|| (ties to the longer step). Fails when no trial is finite.
LineSearch::Result LineSearch::backtrack(const Vector& u, const Vector& du, double r_norm, double new_norm,
                                         Evaluation& trial, Evaluation& probe, int iteration) const
{
    double alpha = 1.0;
    double best_alpha = std::isfinite(new_norm) ? 1.0 : 0.0;
    double best_norm = new_norm;
    bool best_is_probe = false;  // the best trial is the one held in `probe`
    bool accepted = false;
    std::string failure_message = trial.ok ? std::string() : trial.message;
    for (int cut = 1; cut <= settings_.max_backtracks; ++cut) {
        alpha *= 0.5;
        ++report_.line_search_cuts;
        evaluate(system_, u + alpha * du, load_factor_, false, probe, context_);
        if (!probe.ok) {
            failure_message = probe.message;
            ++report_.inadmissible_trials;
        }
        const double probe_norm = finite_norm_or_inf(probe);
        if (probe_norm <= (1.0 - armijo * alpha) * r_norm) {
            accepted = true;
            best_alpha = alpha;
            best_norm = probe_norm;
            best_is_probe = true;
            break;
        }
        if (probe_norm < best_norm) {  // strict: ties keep the longer step
            best_alpha = alpha;
            best_norm = probe_norm;
            best_is_probe = true;
        } else {
            best_is_probe = false;  // `probe` now holds a worse trial than the best
        }
    }

    Result result;
    const std::string at = "iteration " + std::to_string(iteration);
    if (!std::isfinite(best_norm)) {
        result.failed = true;
        result.status = failure_message.empty() ? NewtonStatus::diverged : NewtonStatus::evaluation_failed;
        result.message = failure_message.empty()
                             ? at + ": no finite residual along the Newton direction"
                             : at + ": evaluation failed along the whole line search: " + failure_message;
        return result;
    }
    result.alpha = best_alpha;
    if (best_alpha == 1.0) {
        result.chosen = &trial;
        return result;
    }
    result.chosen = &probe;
    result.chosen_has_tangent = false;
    if (!accepted && !best_is_probe) {  // `probe` holds a later, worse trial: evaluate the best again
        evaluate(system_, u + best_alpha * du, load_factor_, false, probe, context_);
        if (!probe.ok) {  // it evaluated fine a moment ago: a non-deterministic evaluate
            result.failed = true;
            result.status = NewtonStatus::evaluation_failed;
            result.message = at + ": evaluation failed: " + probe.message;
        }
    }
    return result;
}

/// One call of solve_newton: the state of the iteration, and its steps as members.
class NewtonSolve {
public:
    NewtonSolve(const NonlinearSystem& system, double load_factor, Vector& u, const NewtonSettings& settings,
                LinearSolver& solver, RunContext* context)
        : system_(system),
          load_factor_(load_factor),
          u_(u),
          u_start_(u),
          settings_(settings),
          solver_(solver),
          context_(context),
          line_search_(system, load_factor, settings, context, report_),
          radius_(system.max_step)
    {
    }

    /// Newton's method: from the start state, one solve for an affine system, else
    /// iterations until the convergence test passes or a step fails.
    NewtonReport run()
    {
        if (evaluate_start() == Progress::finished)
            return report_;
        if (system_.linear) {
            solve_affine();
            return report_;
        }
        for (int iteration = 1; iteration <= settings_.max_iterations; ++iteration)
            if (iterate(iteration) == Progress::finished)
                return report_;
        finish(NewtonStatus::max_iterations, "no convergence in " + std::to_string(settings_.max_iterations) +
                                                 " iterations; last relative residual " + format_g(rel_) +
                                                 tolerance_text());
        return report_;
    }

private:
    Progress evaluate_start();
    void solve_affine();
    Progress iterate(int iteration);
    Progress evaluate_tangent(int iteration);
    StepResult solve_step(Vector& du);
    bool cap_step(Vector& du) const;
    Progress try_full_step(const Vector& du, int iteration, double& new_norm);
    void accept(const LineSearch::Result& line, Vector u_new);
    void record_residual(const Evaluation& e, double rel);
    void log_iteration(int iteration, double step_size, double alpha, const StepResult& step) const;
    Progress test_convergence(int iteration, double correction);
    Progress hold_cycling_points(int iteration);
    Progress restart_here(int iteration);
    Progress converged(int iteration, std::string message);
    void remember_activity();
    Progress finish(NewtonStatus status, std::string message);
    std::string tolerance_text() const { return " (tolerance " + format_g(settings_.tolerance) + ")"; }

    const NonlinearSystem& system_;
    double load_factor_;
    Vector& u_;
    const Vector u_start_;  ///< restored on failure
    const NewtonSettings& settings_;
    LinearSolver& solver_;
    RunContext* context_;
    NewtonReport report_;
    LineSearch line_search_;

    Evaluation current_;  ///< at u_
    Evaluation trial_;    ///< at the full step u_ + du, with the tangent
    Evaluation probe_;    ///< at a shorter step, without
    double r_norm_ = 0;   ///< ||r(u_)||
    double radius_ = 0;   ///< the trust radius in use: system.max_step, doubled after capped steps that stall
    double rel_ = 0;      ///< ||r(u_)|| / force scale
    double r_initial_ = 0;
    bool have_tangent_ = true;        ///< current_ holds the tangent at u_
    bool previous_at_floor_ = false;  ///< the last iteration ended at the round-off floor
    int krylov_stops_in_a_row_ = 0;   ///< iterations whose Krylov solve stopped short on the unshifted K
    /// Evaluation::contact_active of the last max_cycle + 2 accepted states, oldest first.
    std::vector<std::vector<std::uint8_t>> activity_;
};

void NewtonSolve::remember_activity()
{
    if (current_.contact_active.empty())
        return;
    if (activity_.size() == max_cycle + 2)
        activity_.erase(activity_.begin());
    activity_.push_back(current_.contact_active);
}

Progress NewtonSolve::finish(NewtonStatus status, std::string message)
{
    if (status != NewtonStatus::converged)
        u_ = u_start_;
    report_.status = status;
    if (!system_.linear && status == NewtonStatus::max_iterations)
        message += "; " + cause_text(report_);
    report_.message = std::move(message);
    return Progress::finished;
}

void NewtonSolve::record_residual(const Evaluation& e, double rel)
{
    report_.residual_history.push_back(rel);
    report_.floor_history.push_back(relative(e.residual_floor, e.force_scale));
    report_.residual_norm = rel;
}

/// The residual and tangent at the start state; finished when it fails or already converged.
Progress NewtonSolve::evaluate_start()
{
    if (system_.release_holds)
        system_.release_holds();  // the last solve's holds were for its own cycles
    evaluate(system_, u_, load_factor_, true, current_, context_);
    if (!current_.ok)
        return finish(NewtonStatus::evaluation_failed, "evaluation failed at the start state: " + current_.message);
    r_norm_ = current_.residual.norm();
    if (!std::isfinite(r_norm_))
        return finish(NewtonStatus::diverged, "residual is not finite at the start state");
    rel_ = relative(r_norm_, current_.force_scale);
    record_residual(current_, rel_);
    remember_activity();
    if (rel_ <= settings_.tolerance)
        return finish(NewtonStatus::converged,
                      "converged at the start state (relative residual " + format_g(rel_) + ")");
    r_initial_ = r_norm_;
    return Progress::going_on;
}

/// An affine system: r(u + du) = r(u) + K du, so the refinement below needs the
/// system's residuals, not K; the tangent is handed to the solver (a copying
/// backend would otherwise hold it twice while it factorizes).
/// An iterative solver is asked for what the tolerance needs in one solve, not
/// for its own 1e-8 and a refinement solve, which would restart its Krylov method.
void NewtonSolve::solve_affine()
{
    Vector du;
    const StepResult step = newton_step(current_.tangent, current_.residual, solver_, context_, du, true, false,
                                        accuracy_needed(settings_.tolerance, r_norm_, current_.force_scale));
    if (step.status != LinearStatus::ok) {
        const LinearFailure failure = linear_failure(step.status, solver_);
        finish(failure.status, failure.text + ", even with regularization up to mu = " + format_g(largest_mu()));
        return;
    }
    report_.regularized_iterations = step.regularized ? 1 : 0;
    report_.last_step_regularized = step.regularized;
    report_.krylov_stopped = step.krylov_stopped;
    auto residual_at = [&](const Vector& state) {
        evaluate(system_, state, load_factor_, false, trial_, context_);
        return trial_.ok ? relative(trial_.residual.norm(), trial_.force_scale) : NAN;
    };
    u_ += du;
    double rel = residual_at(u_);
    for (int k = 0; k < max_refinements && trial_.ok && !(rel <= settings_.tolerance); ++k) {
        Vector correction;
        {
            ScopedTimer timer(context_, "linear_solve");
            if (solver_.solve_to(-trial_.residual, correction,
                                 accuracy_needed(settings_.tolerance, trial_.residual.norm(), trial_.force_scale)) !=
                LinearStatus::ok)
                break;
        }
        u_ += correction;
        rel = residual_at(u_);
    }
    if (!trial_.ok) {
        finish(NewtonStatus::evaluation_failed, "evaluation failed after the linear solve: " + trial_.message);
        return;
    }
    report_.iterations = 1;
    if (context_)
        context_->add_count("newton_iterations", 1);
    record_residual(trial_, rel);
    if (rel <= settings_.tolerance)
        finish(NewtonStatus::converged, "linear solve, relative residual " + format_g(rel));
    else if (trial_.residual_floor > 0 && trial_.residual.norm() <= round_off_margin * trial_.residual_floor)
        finish(NewtonStatus::converged, "linear solve, relative residual " + format_g(rel) +
                                            " at its round-off floor " + format_g(report_.floor_history.back()) +
                                            tolerance_text());
    else if (step.krylov_stopped)  // the shift was what it could solve, not what the system is
        finish(NewtonStatus::linear_solver_not_converged,
               "the linear solver did not converge" +
                   (step.krylov_detail.empty() ? std::string() : " (" + step.krylov_detail + ")") +
                   "; on the tangent shifted by mu = " + format_g(step.mu) + " it did, but that leaves a relative residual " +
                   format_g(rel) + tolerance_text());
    else
        finish(NewtonStatus::max_iterations, "linear solve left a relative residual " + format_g(rel) +
                                                 tolerance_text() + ": the tangent is singular or ill-conditioned");
}

/// One Newton iteration: the tangent, the step K du = -r solved to the accuracy it
/// needs, the trust-radius cap, the line search, and the convergence test.
Progress NewtonSolve::iterate(int iteration)
{
    if (!have_tangent_ && evaluate_tangent(iteration) == Progress::finished)
        return Progress::finished;

    Vector du;
    const StepResult step = solve_step(du);
    if (step.status != LinearStatus::ok) {
        const LinearFailure failure = linear_failure(step.status, solver_);
        return finish(failure.status, "iteration " + std::to_string(iteration) + ": " + failure.text +
                                          ", even with regularization up to mu = " + format_g(largest_mu()) +
                                          "; last relative residual " + format_g(rel_) + tolerance_text());
    }
    if (step.regularized)
        ++report_.regularized_iterations;
    report_.last_step_regularized = step.regularized;
    report_.krylov_stopped = step.krylov_stopped;
    // Once may be a tangent near a singular one; twice in a row the preconditioner does
    // not fit the tangents, and shifted steps (and cutbacks) would only crawl.
    krylov_stops_in_a_row_ = step.krylov_stopped ? krylov_stops_in_a_row_ + 1 : 0;
    if (krylov_stops_in_a_row_ >= max_krylov_stops_in_a_row)
        return finish(NewtonStatus::linear_solver_not_converged,
                      "iteration " + std::to_string(iteration) + ": the linear solver did not converge on " +
                          std::to_string(krylov_stops_in_a_row_) + " tangents in a row" +
                          (step.krylov_detail.empty() ? std::string() : " (" + step.krylov_detail + ")") +
                          "; last relative residual " + format_g(rel_) + tolerance_text());
    const bool capped = cap_step(du);

    double new_norm = 0;
    if (try_full_step(du, iteration, new_norm) == Progress::finished)
        return Progress::finished;
    LineSearch::Result line;
    line.chosen = &trial_;
    if (settings_.line_search) {
        line = line_search_.search(u_, du, r_norm_, new_norm, current_, trial_, probe_, iteration);
        if (line.failed)
            return finish(line.status, std::move(line.message));
    }

    const double correction = du.lpNorm<Eigen::Infinity>();  // the full Newton correction (capped)
    const double step_size = line.alpha * correction;
    // A capped step that the line search took whole and that left ||r|| where it was: the
    // radius, not the model, holds Newton back (still downhill at the radius, the
    // correction it needs is longer). Double it for the next step; else Newton creeps by
    // one radius per iteration and a cutback, which shrinks the radius, only makes it
    // creep slower (the 3D ironing die stalled so with its residual at 5e-4).
    const double r_before = r_norm_;
    accept(line, u_ + line.alpha * du);
    if (capped && line.alpha == 1.0 && r_norm_ > stalled_reduction * r_before)
        radius_ *= 2.0;
    report_.iterations = iteration;
    if (context_)
        context_->add_count("newton_iterations", 1);
    log_iteration(iteration, step_size, line.alpha, step);
    if (test_convergence(iteration, correction) == Progress::finished)
        return Progress::finished;
    return hold_cycling_points(iteration);
}

/// Newton in a cycle: the accepted states come back, p steps apart (p = 2 .. max_cycle):
/// the same contact points press as p steps before, at both of the last two states, and
/// the residuals repeat. The points that pressed and opened within the cycle are where
/// no state of theirs has an equilibrium nearby -- pressed, Newton's step opens them;
/// open, it presses them (a frictional point whose own friction drives it in,
/// docs/solver.md "A point held open"). The system holds them open, and Newton goes on
/// from the same state.
Progress NewtonSolve::hold_cycling_points(int iteration)
{
    if (!system_.hold_open || current_.contact_active.empty())
        return Progress::going_on;
    const auto& a = activity_;
    const std::vector<double>& h = report_.residual_history;
    const std::size_t k = a.size() - 1, n = h.size() - 1;  // the current state in each
    auto repeats = [&](std::size_t back, std::size_t p) {
        return a[k - back] == a[k - back - p] && std::abs(h[n - back] - h[n - back - p]) <= cycle_repeat * h[n - back];
    };
    std::vector<int> cycling;
    for (std::size_t p = 2; p <= max_cycle && cycling.empty(); ++p) {
        if (a.size() < p + 2 || h.size() < p + 2 || !repeats(0, p) || !repeats(1, p))
            continue;
        for (std::size_t i = 0; i < a[k].size(); ++i)
            for (std::size_t j = k - p; j < k; ++j)
                if (a[j][i] != a[k][i]) {
                    cycling.push_back(static_cast<int>(i));
                    break;
                }
    }
    if (cycling.empty())
        return Progress::going_on;
    const int held = system_.hold_open(cycling);
    if (held == 0)
        return Progress::going_on;
    report_.held_open += held;
    if (context_)
        context_->log(Verbosity::verbose, "  newton " + std::to_string(iteration) + ": " + std::to_string(held) +
                                              " contact point(s) pressed and opened in turn in a cycle of Newton steps: held open");
    return restart_here(iteration);
}

/// The holds changed the system: the residual and tangent at u_ again, and the
/// history of states (cycles, round-off stalls) starts afresh from here.
Progress NewtonSolve::restart_here(int iteration)
{
    activity_.clear();
    previous_at_floor_ = false;
    evaluate(system_, u_, load_factor_, true, current_, context_);
    if (!current_.ok)
        return finish(NewtonStatus::evaluation_failed,
                      "iteration " + std::to_string(iteration) + ": evaluation failed: " + current_.message);
    have_tangent_ = true;
    r_norm_ = current_.residual.norm();
    rel_ = relative(r_norm_, current_.force_scale);
    remember_activity();
    return Progress::going_on;
}

/// The tangent at u_, when the accepted state came without it (a shortened step).
Progress NewtonSolve::evaluate_tangent(int iteration)
{
    current_.tangent.swap(trial_.tangent);  // the rejected full step's tangent: its storage, not a second one
    evaluate(system_, u_, load_factor_, true, current_, context_);
    if (!current_.ok)
        return finish(NewtonStatus::evaluation_failed,
                      "iteration " + std::to_string(iteration) + ": evaluation failed: " + current_.message);
    have_tangent_ = true;
    return Progress::going_on;
}

/// K du = -r, to the accuracy the tolerance asks of this step (or newton_linear_accuracy).
/// The tangent is handed to the solver: neither Newton nor the trial needs it, and a
/// copying solver would hold it twice while it factorizes.
StepResult NewtonSolve::solve_step(Vector& du)
{
    const double needed = accuracy_needed(settings_.tolerance, r_norm_, current_.force_scale);
    const double accuracy = needed * last_step_reach >= newton_linear_accuracy ? needed : newton_linear_accuracy;
    return newton_step(current_.tangent, current_.residual, solver_, context_, du, true, current_.singular_tangent,
                       accuracy);
}

/// The trust radius: ||du||_inf <= radius_ (system.max_step, doubled where capped steps
/// stall). Whether it shortened du.
bool NewtonSolve::cap_step(Vector& du) const
{
    if (!(radius_ > 0))
        return false;
    const double size = du.lpNorm<Eigen::Infinity>();
    if (!(size > radius_))
        return false;
    du *= radius_ / size;
    return true;
}

/// The full step, with the tangent: it is accepted most of the time, and then the next
/// iteration needs no second assembly. Without a line search an inadmissible or
/// non-finite full step ends the solve.
Progress NewtonSolve::try_full_step(const Vector& du, int iteration, double& new_norm)
{
    evaluate(system_, u_ + du, load_factor_, true, trial_, context_);
    new_norm = finite_norm_or_inf(trial_);
    if (!trial_.ok) {
        ++report_.inadmissible_trials;
        if (context_ && settings_.line_search)
            context_->log(Verbosity::verbose, "  newton " + std::to_string(iteration) +
                                                  ": full step inadmissible, backing off (" + trial_.message + ")");
    }
    if (settings_.line_search)
        return Progress::going_on;
    if (!trial_.ok)
        return finish(NewtonStatus::evaluation_failed,
                      "iteration " + std::to_string(iteration) + ": evaluation failed: " + trial_.message);
    if (!std::isfinite(new_norm))
        return finish(NewtonStatus::diverged, "iteration " + std::to_string(iteration) + ": residual is not finite");
    return Progress::going_on;
}

/// Moves to the state the line search chose and records its residual.
void NewtonSolve::accept(const LineSearch::Result& line, Vector u_new)
{
    u_ = std::move(u_new);
    swap(current_, *line.chosen);  // member-wise (newton.hpp)
    remember_activity();
    have_tangent_ = line.chosen_has_tangent;
    r_norm_ = current_.residual.norm();
    rel_ = relative(r_norm_, current_.force_scale);
    record_residual(current_, rel_);
    report_.norm_ratio = r_norm_ / r_initial_;
}

void NewtonSolve::log_iteration(int iteration, double step_size, double alpha, const StepResult& step) const
{
    if (context_)
        context_->log(Verbosity::verbose, "  newton " + std::to_string(iteration) + ": relative residual " +
                                              format_g(rel_) + " (floor " + format_g(report_.floor_history.back()) +
                                              "), step " + format_g(step_size) +
                                              (alpha < 1.0 ? ", alpha " + format_g(alpha) : std::string()) +
                                              (step.regularized ? ", regularized mu " + format_g(step.mu)
                                                                : std::string()));
}

/// Divergence, then the convergence tests of the header: the tolerance, or the
/// round-off floor with a small correction (once, or twice in a row for a stall).
Progress NewtonSolve::test_convergence(int iteration, double correction)
{
    if (!std::isfinite(r_norm_) || r_norm_ > settings_.divergence_factor * r_initial_)
        return finish(NewtonStatus::diverged, "iteration " + std::to_string(iteration) + ": residual grew to " +
                                                  format_g(r_norm_ / r_initial_) + " times the initial one");
    if (rel_ <= settings_.tolerance)
        return converged(iteration, "converged in " + std::to_string(iteration) + " iterations, relative residual " +
                                        format_g(rel_));
    const double u_size = u_.lpNorm<Eigen::Infinity>();
    report_.correction = u_size > 0 ? correction / u_size : std::numeric_limits<double>::infinity();
    const bool at_floor = r_norm_ <= round_off_margin * current_.residual_floor;
    const bool stalled = at_floor && previous_at_floor_ && correction <= stalled_correction_tolerance * u_size;
    previous_at_floor_ = at_floor;
    if ((at_floor && correction <= correction_tolerance * u_size) || stalled)
        return converged(iteration, "converged in " + std::to_string(iteration) +
                                                   " iterations at round-off: relative residual " + format_g(rel_) +
                                                   tolerance_text() + " within " + format_g(round_off_margin) +
                                                   " of its round-off floor " +
                                                   format_g(report_.floor_history.back()) + ", correction " +
                                                   format_g(report_.correction) + " of u");
    return Progress::going_on;
}

/// Converged, unless held contact points now press deep: those are freed (a hold is for
/// a contact edge, not for a point the load has since pressed), and Newton goes on.
Progress NewtonSolve::converged(int iteration, std::string message)
{
    const int released = system_.release_deep_holds ? system_.release_deep_holds() : 0;
    if (released == 0)
        return finish(NewtonStatus::converged, std::move(message));
    if (context_)
        context_->log(Verbosity::verbose, "  newton " + std::to_string(iteration) + ": " + std::to_string(released) +
                                              " held contact point(s) now press deep: released");
    return restart_here(iteration);
}

}  // namespace

const char* status_name(NewtonStatus status)
{
    switch (status) {
    case NewtonStatus::converged: return "converged";
    case NewtonStatus::max_iterations: return "max_iterations";
    case NewtonStatus::diverged: return "diverged";
    case NewtonStatus::singular: return "singular";
    case NewtonStatus::linear_solver_not_converged: return "linear_solver_not_converged";
    case NewtonStatus::evaluation_failed: return "evaluation_failed";
    }
    return "unknown";
}

NewtonReport solve_newton(const NonlinearSystem& system, double load_factor, Vector& u,
                          const NewtonSettings& settings, LinearSolver& solver, RunContext* context)
{
    IGA_CHECK(static_cast<bool>(system.evaluate), "solve_newton: the system has no evaluate callback");
    IGA_CHECK(settings.tolerance > 0 && settings.max_iterations >= 1 && settings.max_backtracks >= 0 &&
                  settings.divergence_factor > 1,
              "solve_newton: settings out of range (tolerance > 0, max_iterations >= 1, "
              "max_backtracks >= 0, divergence_factor > 1)");
    return NewtonSolve(system, load_factor, u, settings, solver, context).run();
}

}  // namespace iga::solver
