#include "solver/load_stepping.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>

namespace iga::solver {

namespace {

// An increment ending this close (relative to T) to a breakpoint is stretched to
// end on it: the sum of count increments T/count misses T by a few ulps.
constexpr double end_snap = 1e-12;

std::string format_g(double value, int digits = 3)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    return buffer;
}

std::string increment_text(int index, double from, double to)
{
    return "increment " + std::to_string(index) + " (load factor " + format_g(from, 6) + " -> " + format_g(to, 6) +
           ")";
}

}  // namespace

double next_increment_factor(int iterations, const SteppingSettings& stepping)
{
    if (iterations <= 0)
        return stepping.max_growth;
    const double n = iterations;
    double factor = 1.0;
    if (iterations < stepping.target_iterations)
        factor = stepping.target_iterations / n;
    else if (iterations > stepping.slow_iterations)
        factor = stepping.slow_iterations / n;
    return std::clamp(factor, stepping.max_shrink, stepping.max_growth);
}

namespace {

/// One attempt at an increment: the load factor it heads for and how it ended.
struct Attempt {
    double target = 0;
    NewtonReport report;     ///< of all its Newton solves (iterations summed, histories appended)
    OuterDecision decision;  ///< the outer loop's last decision (accept when there is none)
    int first_solve_iterations = 0;  ///< of its first Newton solve: sizes the next increment
    int outer_updates = 0;           ///< resolve decisions (Uzawa updates)

    bool rejected() const
    {
        return report.status == NewtonStatus::converged && decision.action == OuterDecision::Action::reject;
    }
    bool converged() const { return report.status == NewtonStatus::converged && !rejected(); }
};

/// One call of run_load_steps: the state of the path (t, the converged states, the
/// increment) and the steps of the stepping algorithm as members.
class LoadStepper {
public:
    LoadStepper(const NonlinearSystem& system, Vector& u, const SteppingSettings& stepping,
                const NewtonSettings& newton, LinearSolver& solver, SteppingCallbacks& callbacks, RunContext* context)
        : system_(system),
          u_(u),
          stepping_(stepping),
          path_(stepping.path),
          newton_(newton),
          solver_(solver),
          callbacks_(callbacks),
          context_(context),
          initial_increment_(path_.end / stepping.count),
          // The smallest increment: what max_cutbacks halvings of the initial one give.
          // Without it, an adaptive run toward a limit load would creep forever
          // (every increment converging after a few cutbacks, at geometrically shrinking size).
          min_increment_(std::ldexp(initial_increment_, -stepping.max_cutbacks)),
          increment_(initial_increment_),
          u_converged_(u)
    {
        // The forces in play over the path so far (see the header): Newton and the
        // predictor measure residuals against at least the largest force scale of the
        // converged increments, so that a path back to zero load (a release) converges.
        referenced_ = system;
        referenced_.evaluate = [this](const Vector& v, double t, bool need_tangent, Evaluation& out) {
            system_.evaluate(v, t, need_tangent, out);
            last_force_scale_ = out.force_scale;
            out.force_scale = std::max(out.force_scale, reference_force_);
        };
    }
    LoadStepper(const LoadStepper&) = delete;  // referenced_ points at this object
    LoadStepper& operator=(const LoadStepper&) = delete;

    /// The increments from t = 0 to T: each attempted, cut back until it converges,
    /// committed, and the next one sized by its iterations.
    SteppingResult run()
    {
        while (next_stop_ < path_.breakpoints.size()) {
            const int index = static_cast<int>(result_.increments.size()) + 1;
            if ((callbacks_.stop_requested && callbacks_.stop_requested()) || (context_ && context_->stop().requested()))
                return stopped(index, "");
            const auto start = std::chrono::steady_clock::now();
            int cutbacks = 0;
            Attempt attempt;
            while (true) {
                attempt = Attempt{};
                attempt.target = next_target();
                if (!(attempt.target > lambda_)) {
                    result_.message = increment_text(index, lambda_, attempt.target) +
                                      ": the increment fell below the round-off of the load factor";
                    return result_;
                }
                try {
                    solve_increment(index, attempt);
                } catch (const Interrupted&) {
                    // A stop inside the increment (assembly, Newton): abandon it, keep the last converged state.
                    restore_converged();
                    return stopped(index, ", during " + increment_text(index, lambda_, attempt.target) +
                                              ", which was abandoned");
                } catch (const std::bad_alloc&) {
                    // On one process the converged increments are still worth a results
                    // file (the failed attempt's memory is free again); on several ranks the
                    // others wait in a collective, and main() ends them all.
                    if (Communicator::world().size() > 1)
                        throw;
                    return out_of_memory(index, attempt.target);
                }
                if (attempt.converged())
                    break;
                if (!cut_back(index, attempt, cutbacks))
                    return result_;
            }
            commit(index, attempt, cutbacks, start);
            size_next_increment(attempt.first_solve_iterations);
        }
        result_.completed = true;
        result_.last_failure = NewtonReport{};
        return result_;
    }

private:
    double next_target() const;
    void solve_increment(int index, Attempt& attempt);
    double increment_trust_radius(const PredictionReport& prediction, double target) const;
    void outer_loop(Attempt& attempt);
    bool cut_back(int index, const Attempt& attempt, int& cutbacks);
    void restore_converged();
    void commit(int index, const Attempt& attempt, int cutbacks, std::chrono::steady_clock::time_point start);
    void log_increment(const IncrementRecord& record) const;
    void size_next_increment(int iterations);
    SteppingResult stopped(int index, const std::string& during);
    SteppingResult out_of_memory(int index, double target);

    const NonlinearSystem& system_;
    NonlinearSystem referenced_;  ///< system_ with force scales raised to reference_force_
    Vector& u_;
    const SteppingSettings& stepping_;
    const LoadPath& path_;
    const NewtonSettings& newton_;
    LinearSolver& solver_;
    SteppingCallbacks& callbacks_;
    RunContext* context_;

    SteppingResult result_;
    const double initial_increment_;  ///< T/count, also the largest
    const double min_increment_;      ///< T/count / 2^max_cutbacks
    double increment_;                ///< the planned increment
    double lambda_ = 0.0;             ///< t of the last converged state
    Vector u_converged_;
    Vector u_previous_;  ///< the converged state before the last one, for the extrapolating predictor
    double lambda_previous_ = 0.0;
    std::size_t next_stop_ = 0;       ///< the breakpoint the increments are heading for
    double reference_force_ = 0.0;    ///< the largest force scale of the converged increments
    double last_force_scale_ = 0.0;   ///< of the latest evaluation, as the system gave it
};

/// The end of the next increment: the planned increment, never past a breakpoint (the
/// amplitudes are linear within an increment), and on it when it ends within end_snap.
double LoadStepper::next_target() const
{
    const double stop = path_.breakpoints[next_stop_];
    return lambda_ + increment_ > stop - end_snap * path_.end ? stop : lambda_ + increment_;
}

/// The iterations a solve took until its residual was within the tolerance or within
/// round_off_margin of its round-off floor (the header's step control): the iterations
/// after that only polish round-off, and whether one is needed depends on the last bits
/// (an MPI rank's sums): counted, they sized the next increment differently on 3 ranks.
static int iterations_to_round_off_band(const NewtonReport& report, double tolerance)
{
    const std::vector<double>& r = report.residual_history;
    const std::vector<double>& floor = report.floor_history;
    for (std::size_t k = 0; k < r.size() && k < floor.size(); ++k)
        if (r[k] <= std::max(tolerance, round_off_margin * floor[k]))
            return std::min(static_cast<int>(k), report.iterations);
    return report.iterations;
}

/// The trust radius of Newton in this attempt (the header's "Trust radius of an
/// increment"): predicted_step_trust times the increment's own scale where the predictor
/// solved the increment, the system's radius otherwise. u_ holds the predicted state.
double LoadStepper::increment_trust_radius(const PredictionReport& prediction, double target) const
{
    if (!prediction.used || !(system_.max_step > 0))
        return system_.max_step;
    double scale = (u_ - u_converged_).lpNorm<Eigen::Infinity>();
    if (system_.prescribed_motion_between)
        scale = std::max(scale, system_.prescribed_motion_between(lambda_, target));
    return scale > 0.0 ? std::min(system_.max_step, predicted_step_trust * scale) : system_.max_step;
}

/// Predicts the state at the target, solves it by Newton, then runs the outer loop.
void LoadStepper::solve_increment(int index, Attempt& attempt)
{
    PredictionReport prediction;
    u_ = predict(referenced_, stepping_.predictor, u_converged_, lambda_, attempt.target,
                 {u_previous_.size() > 0 ? &u_previous_ : nullptr, lambda_previous_}, solver_, context_, prediction);
    referenced_.max_step = increment_trust_radius(prediction, attempt.target);
    if (!prediction.note.empty()) {
        ++result_.predictor_fallbacks;
        if (context_)
            context_->log(Verbosity::verbose,
                          increment_text(index, lambda_, attempt.target) + ": predictor: " + prediction.note);
    }
    attempt.report = solve_newton(referenced_, attempt.target, u_, newton_, solver_, context_);
    result_.total_iterations += attempt.report.iterations;
    attempt.first_solve_iterations = iterations_to_round_off_band(attempt.report, newton_.tolerance);
    outer_loop(attempt);
}

/// The outer loop: solve again while it asks for it (each solve from the last converged state).
void LoadStepper::outer_loop(Attempt& attempt)
{
    NewtonReport& report = attempt.report;
    while (report.status == NewtonStatus::converged && callbacks_.outer) {
        attempt.decision = callbacks_.outer(u_, attempt.target);
        if (attempt.decision.action != OuterDecision::Action::resolve)
            break;
        ++attempt.outer_updates;
        NewtonReport again = solve_newton(referenced_, attempt.target, u_, newton_, solver_, context_);
        result_.total_iterations += again.iterations;
        again.iterations += report.iterations;
        again.residual_history.insert(again.residual_history.begin(), report.residual_history.begin(),
                                      report.residual_history.end());
        report = std::move(again);
    }
}

void LoadStepper::restore_converged()
{
    u_ = u_converged_;
    if (callbacks_.rollback)
        callbacks_.rollback();
}

/// After a failed attempt: back to the converged state, and the increment tried halved
/// for the next one; false (result_.message says why) when the run cannot cut back.
bool LoadStepper::cut_back(int index, const Attempt& attempt, int& cutbacks)
{
    result_.last_failure = attempt.report;
    restore_converged();
    const NewtonReport& report = attempt.report;
    const bool rejected = attempt.rejected();
    const std::string increment = increment_text(index, lambda_, attempt.target);
    const std::string why = rejected ? ": " + attempt.decision.message
                                     : std::string(" (") + status_name(report.status) + "): " + report.message;
    const std::string what = rejected ? "the outer loop rejected the solution" : "Newton did not converge";
    if (system_.linear && !rejected) {
        result_.message = increment + ": " + report.message;  // "the linear solver did not converge (...)"
        return false;
    }
    // A Krylov method that does not fit the tangents does not fit them at a smaller
    // increment either: each cutback would pay its failed solves again.
    if (!rejected && report.status == NewtonStatus::linear_solver_not_converged) {
        result_.message = increment + ": " + what + why;
        return false;
    }
    if (!stepping_.adaptive) {
        result_.message = increment + ": " + what + " (adaptive stepping is off)" + why;
        return false;
    }
    if (cutbacks == stepping_.max_cutbacks) {
        result_.message = increment + ": " + what + " after " + std::to_string(cutbacks) + " cutbacks" + why;
        return false;
    }
    // Halve the increment tried (shorter than `increment_` when it ended on a breakpoint).
    const double halved = 0.5 * std::min(increment_, attempt.target - lambda_);
    if (halved < min_increment_) {
        result_.message = increment + ": " + what + " and the increment cannot be cut below " +
                          format_g(min_increment_, 6) + " (T/count / 2^max_cutbacks, T the end of the load path)" +
                          why;
        return false;
    }
    ++cutbacks;
    ++result_.total_cutbacks;
    increment_ = halved;
    if (context_)
        context_->log(Verbosity::verbose, increment + ": " +
                                              (rejected ? attempt.decision.message : status_name(report.status)) +
                                              ", cutting back to " + format_g(increment_, 6));
    return true;
}

/// Moves t and the converged states on to the converged attempt, and reports it.
void LoadStepper::commit(int index, const Attempt& attempt, int cutbacks, std::chrono::steady_clock::time_point start)
{
    u_previous_ = std::move(u_converged_);
    lambda_previous_ = lambda_;
    if (attempt.target == path_.breakpoints[next_stop_])
        ++next_stop_;
    reference_force_ = std::max(reference_force_, last_force_scale_);  // Newton's last evaluation: the converged state
    lambda_ = attempt.target;
    u_converged_ = u_;
    if (callbacks_.commit)
        callbacks_.commit();
    IncrementRecord record;
    record.index = index;
    record.load_factor = lambda_;
    record.report = attempt.report;
    record.cutbacks = cutbacks;
    record.outer_updates = attempt.outer_updates;
    record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result_.increments.push_back(record);
    log_increment(record);
    if (callbacks_.converged)
        callbacks_.converged(result_.increments.back(), u_);
}

void LoadStepper::log_increment(const IncrementRecord& record) const
{
    if (!context_)
        return;
    const int cutbacks = record.cutbacks;
    const int outer_updates = record.outer_updates;
    context_->log(Verbosity::normal,
                  "increment " + std::to_string(record.index) + ": load factor " + format_g(record.load_factor, 6) +
                      ", " + std::to_string(record.report.iterations) + " iterations, relative residual " +
                      format_g(record.report.residual_norm) +
                      (cutbacks > 0 ? ", " + std::to_string(cutbacks) + " cutbacks" : std::string()) +
                      (record.report.held_open > 0
                           ? ", " + std::to_string(record.report.held_open) + " cycling contact point(s) held open"
                           : std::string()) +
                      (outer_updates > 0 ? ", " + std::to_string(outer_updates) +
                                               (outer_updates == 1 ? " Uzawa update" : " Uzawa updates")
                                         : std::string()));
}

/// Step control by iteration count (the header): grow, keep or shrink the planned increment.
void LoadStepper::size_next_increment(int iterations)
{
    if (stepping_.adaptive)
        increment_ = std::clamp(increment_ * next_increment_factor(iterations, stepping_), min_increment_,
                                initial_increment_);
}

/// Ends the run on a stop request, worded for the user who pressed Ctrl-C (the app's
/// stop request is SIGINT/SIGTERM).
SteppingResult LoadStepper::stopped(int index, const std::string& during)
{
    result_.message = (index == 1 ? std::string("interrupted (SIGINT/SIGTERM) before the first increment")
                                  : "interrupted (SIGINT/SIGTERM) after increment " + std::to_string(index - 1) +
                                        " (load factor " + format_g(lambda_, 6) + ")") +
                      during;
    result_.last_failure = NewtonReport{};  // a stop, not a failure of Newton
    result_.stopped = true;
    return result_;
}

/// Ends the run when an allocation failed inside an increment: a smaller increment
/// needs the same matrices, so there is nothing to cut back.
SteppingResult LoadStepper::out_of_memory(int index, double target)
{
    restore_converged();
    result_.message = increment_text(index, lambda_, target) +
                      ": out of memory (an allocation failed; the increment was abandoned): the model needs more "
                      "memory than this process may use, the machine's or a limit such as ulimit -v. Refine less, "
                      "or spread the model over more memory with mpirun (docs/parallel.md)";
    result_.last_failure = NewtonReport{};  // not a failure of Newton
    result_.out_of_memory = true;
    return result_;
}

}  // namespace

SteppingResult run_load_steps(const NonlinearSystem& system, Vector& u, const SteppingSettings& stepping,
                              const NewtonSettings& newton, LinearSolver& solver, SteppingCallbacks& callbacks,
                              RunContext* context)
{
    IGA_CHECK(stepping.count >= 1, "run_load_steps: count must be >= 1");
    IGA_CHECK(stepping.max_cutbacks >= 0, "run_load_steps: max_cutbacks must be >= 0");
    IGA_CHECK(stepping.target_iterations >= 1 && stepping.slow_iterations >= stepping.target_iterations &&
                  stepping.max_growth >= 1.0 && stepping.max_shrink > 0.0 &&
                  stepping.max_shrink <= 1.0,
              "run_load_steps: target_iterations >= 1, slow_iterations >= target_iterations, max_growth >= 1 "
              "and max_shrink in (0, 1] are required");
    const LoadPath& path = stepping.path;
    IGA_CHECK(path.end > 0.0 && !path.breakpoints.empty() && path.breakpoints.back() == path.end,
              "run_load_steps: the path must end at its last breakpoint T > 0");
    return LoadStepper(system, u, stepping, newton, solver, callbacks, context).run();
}

}  // namespace iga::solver
