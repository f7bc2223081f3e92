#include "solver/load_stepping.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

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

    SteppingResult result;
    const double initial_increment = path.end / stepping.count;
    // The smallest increment: what max_cutbacks halvings of the initial one give.
    // Without it, an adaptive run toward a limit load would creep forever
    // (every increment converging after a few cutbacks, at geometrically shrinking size).
    const double min_increment = std::ldexp(initial_increment, -stepping.max_cutbacks);
    double increment = initial_increment;
    double lambda = 0.0;
    Vector u_converged = u;
    // The converged state before the last one, for the extrapolating predictor.
    Vector u_previous;
    double lambda_previous = 0.0;
    std::size_t next_stop = 0;  // the breakpoint the increments are heading for

    // The forces in play over the path so far (see the header): Newton and the
    // predictor measure residuals against at least the largest force scale of the
    // converged increments, so that a path back to zero load (a release) converges.
    double reference_force = 0.0;
    double last_force_scale = 0.0;  // of the latest evaluation, as the system gave it
    NonlinearSystem referenced = system;
    referenced.evaluate = [&](const Vector& v, double t, bool need_tangent, Evaluation& out) {
        system.evaluate(v, t, need_tangent, out);
        last_force_scale = out.force_scale;
        out.force_scale = std::max(out.force_scale, reference_force);
    };

    while (next_stop < path.breakpoints.size()) {
        const int index = static_cast<int>(result.increments.size()) + 1;
        // Worded for the user who pressed Ctrl-C: the app's stop request is SIGINT/SIGTERM.
        auto stopped = [&](const std::string& during) {
            result.message = (index == 1 ? std::string("interrupted (SIGINT/SIGTERM) before the first increment")
                                         : "interrupted (SIGINT/SIGTERM) after increment " + std::to_string(index - 1) +
                                               " (load factor " + format_g(lambda, 6) + ")") +
                             during;
            result.last_failure = NewtonReport{};  // a stop, not a failure of Newton
            result.stopped = true;
            return result;
        };
        if ((callbacks.stop_requested && callbacks.stop_requested()) || (context && context->stop().requested()))
            return stopped("");

        const auto start = std::chrono::steady_clock::now();
        int cutbacks = 0;
        double target = lambda;
        NewtonReport report;
        int first_solve_iterations = 0;  // of the converged attempt's first solve: sizes the next increment
        int outer_updates = 0;
        while (true) {
            // Never past a breakpoint: the amplitudes are linear within an increment.
            const double stop = path.breakpoints[next_stop];
            target = lambda + increment > stop - end_snap * path.end ? stop : lambda + increment;
            if (!(target > lambda)) {
                result.message = increment_text(index, lambda, target) +
                                 ": the increment fell below the round-off of the load factor";
                return result;
            }
            OuterDecision decision;
            try {
                PredictionReport prediction;
                u = predict(referenced, stepping.predictor, u_converged, lambda, target,
                            {u_previous.size() > 0 ? &u_previous : nullptr, lambda_previous}, solver, context,
                            prediction);
                if (!prediction.note.empty()) {
                    ++result.predictor_fallbacks;
                    if (context)
                        context->log(Verbosity::verbose, increment_text(index, lambda, target) + ": predictor: " +
                                                             prediction.note);
                }
                report = solve_newton(referenced, target, u, newton, solver, context);
                result.total_iterations += report.iterations;
                first_solve_iterations = report.iterations;
                outer_updates = 0;
                // The outer loop: solve again while it asks for it (each solve from the last converged state).
                while (report.status == NewtonStatus::converged && callbacks.outer) {
                    decision = callbacks.outer(u, target);
                    if (decision.action != OuterDecision::Action::resolve)
                        break;
                    ++outer_updates;
                    NewtonReport again = solve_newton(referenced, target, u, newton, solver, context);
                    result.total_iterations += again.iterations;
                    again.iterations += report.iterations;
                    again.residual_history.insert(again.residual_history.begin(), report.residual_history.begin(),
                                                  report.residual_history.end());
                    report = std::move(again);
                }
            } catch (const Interrupted&) {
                // A stop inside the increment (assembly, Newton): abandon it, keep the last converged state.
                u = u_converged;
                if (callbacks.rollback)
                    callbacks.rollback();
                return stopped(", during " + increment_text(index, lambda, target) + ", which was abandoned");
            }
            const bool rejected =
                report.status == NewtonStatus::converged && decision.action == OuterDecision::Action::reject;
            if (report.status == NewtonStatus::converged && !rejected)
                break;
            result.last_failure = report;

            u = u_converged;
            if (callbacks.rollback)
                callbacks.rollback();
            const std::string why = rejected ? ": " + decision.message
                                             : std::string(" (") + status_name(report.status) + "): " + report.message;
            const std::string what = rejected ? "the outer loop rejected the solution" : "Newton did not converge";
            if (system.linear && !rejected) {
                result.message = increment_text(index, lambda, target) + ": " + report.message;  // "the linear solver did not converge (...)"
                return result;
            }
            if (!stepping.adaptive) {
                result.message = increment_text(index, lambda, target) + ": " + what + " (adaptive stepping is off)" +
                                 why;
                return result;
            }
            if (cutbacks == stepping.max_cutbacks) {
                result.message = increment_text(index, lambda, target) + ": " + what + " after " +
                                 std::to_string(cutbacks) + " cutbacks" + why;
                return result;
            }
            // Halve the increment tried (shorter than `increment` when it ended on a breakpoint).
            const double halved = 0.5 * std::min(increment, target - lambda);
            if (halved < min_increment) {
                result.message = increment_text(index, lambda, target) + ": " + what +
                                 " and the increment cannot be cut below " + format_g(min_increment, 6) +
                                 " (T/count / 2^max_cutbacks, T the end of the load path)" + why;
                return result;
            }
            ++cutbacks;
            ++result.total_cutbacks;
            increment = halved;
            if (context)
                context->log(Verbosity::verbose, increment_text(index, lambda, target) + ": " +
                                                     (rejected ? decision.message : status_name(report.status)) +
                                                     ", cutting back to " + format_g(increment, 6));
        }

        u_previous = std::move(u_converged);
        lambda_previous = lambda;
        if (target == path.breakpoints[next_stop])
            ++next_stop;
        reference_force = std::max(reference_force, last_force_scale);  // Newton's last evaluation: the converged state
        lambda = target;
        u_converged = u;
        if (callbacks.commit)
            callbacks.commit();
        IncrementRecord record;
        record.index = index;
        record.load_factor = lambda;
        record.report = report;
        record.cutbacks = cutbacks;
        record.outer_updates = outer_updates;
        record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        result.increments.push_back(record);
        if (context)
            context->log(Verbosity::normal,
                         "increment " + std::to_string(index) + ": load factor " + format_g(lambda, 6) + ", " +
                             std::to_string(report.iterations) + " iterations, relative residual " +
                             format_g(report.residual_norm) +
                             (cutbacks > 0 ? ", " + std::to_string(cutbacks) + " cutbacks" : std::string()) +
                             (outer_updates > 0 ? ", " + std::to_string(outer_updates) +
                                                      (outer_updates == 1 ? " Uzawa update" : " Uzawa updates")
                                                : std::string()));
        if (callbacks.converged)
            callbacks.converged(result.increments.back(), u);

        if (stepping.adaptive) {
            increment = std::clamp(increment * next_increment_factor(first_solve_iterations, stepping),
                                   min_increment, initial_increment);
        }
    }
    result.completed = true;
    result.last_failure = NewtonReport{};
    return result;
}

}  // namespace iga::solver
