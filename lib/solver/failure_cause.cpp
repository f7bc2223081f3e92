#include "solver/failure_cause.hpp"

#include "solver/residual_trend.hpp"

#include <cstdio>
#include <string>

namespace iga::solver {

namespace {

std::string format_g(double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

bool at_floor(const NewtonReport& report)
{
    const std::vector<double>& r = report.residual_history;
    const std::vector<double>& f = report.floor_history;
    return !r.empty() && r.size() == f.size() && f.back() > 0 && r.back() <= round_off_margin * f.back();
}

}  // namespace

const char* cause_name(FailureCause cause)
{
    switch (cause) {
    case FailureCause::none: return "none";
    case FailureCause::linear_solver: return "linear_solver";
    case FailureCause::free_mode: return "free_mode";
    case FailureCause::inadmissible: return "inadmissible";
    case FailureCause::growth: return "growth";
    case FailureCause::round_off_floor: return "round_off_floor";
    case FailureCause::cycle: return "cycle";
    case FailureCause::stagnation: return "stagnation";
    case FailureCause::wandering: return "wandering";
    case FailureCause::slow: return "slow";
    }
    return "unknown";
}

FailureCause failure_cause(const NewtonReport& report)
{
    const std::vector<double>& r = report.residual_history;
    switch (report.status) {
    case NewtonStatus::converged: return FailureCause::none;
    case NewtonStatus::singular: return FailureCause::free_mode;
    case NewtonStatus::linear_solver_not_converged: return FailureCause::linear_solver;
    case NewtonStatus::evaluation_failed: return FailureCause::inadmissible;
    case NewtonStatus::diverged: return FailureCause::growth;
    case NewtonStatus::max_iterations: break;
    }
    if (report.last_step_regularized)  // a Krylov method that stopped short has not shown a free mode
        return report.krylov_stopped ? FailureCause::linear_solver : FailureCause::free_mode;
    if (!(report.norm_ratio <= growth_factor))  // NaN grows too
        return FailureCause::growth;
    if (at_floor(report))
        return FailureCause::round_off_floor;
    switch (residual_trend(r)) {
    case ResidualTrend::two_state_cycle: return FailureCause::cycle;
    case ResidualTrend::stagnation: return FailureCause::stagnation;
    case ResidualTrend::wandering: return FailureCause::wandering;
    case ResidualTrend::none: break;
    }
    return FailureCause::slow;
}

std::string cause_text(const NewtonReport& report)
{
    const std::vector<double>& r = report.residual_history;
    const std::vector<double>& f = report.floor_history;
    const double last = r.empty() ? 0.0 : r.back();
    const double floor = f.size() == r.size() && !f.empty() ? f.back() : 0.0;
    switch (failure_cause(report)) {
    case FailureCause::none: return {};
    case FailureCause::linear_solver:
        return "the iterative linear solver did not converge (the tangent may be singular, or hard for its "
               "preconditioner)";
    case FailureCause::free_mode:
        return "the tangent is singular (a zero-energy mode: a body may be unconstrained)";
    case FailureCause::inadmissible: return "a state along the Newton path is inadmissible";
    case FailureCause::growth:
        return "Newton diverged: the residual grew to " + format_g(report.norm_ratio) + " times the initial one";
    case FailureCause::round_off_floor:
        return "the relative residual " + format_g(last) + " is at its round-off floor " + format_g(floor) +
               ", but the corrections (" + format_g(report.correction) +
               " of u) do not settle: the tangent is ill-conditioned";
    case FailureCause::cycle: {
        const CycleLevels levels = cycle_levels(r);
        return "the relative residual alternates between " + format_g(levels.high) + " and " +
               format_g(levels.low) + " (a two-state cycle)";
    }
    case FailureCause::stagnation:
        return "the relative residual stagnates at " + format_g(last) + ", " +
               (floor > 0 ? format_g(last / floor) + " times its round-off floor" : std::string("no round-off floor known")) +
               ": the Newton steps do not reduce it";
    case FailureCause::wandering: {
        const Wandering w = wandering(r);
        return "the relative residual wandered: it rose in " + std::to_string(w.rises) + " of " +
               std::to_string(r.size() - 1) + " iterations and ends at " + format_g(last) +
               ", not a tenth of the " + format_g(w.best) + " it reached at iteration " + std::to_string(w.best_at);
    }
    case FailureCause::slow:
        return "the relative residual was still falling (" + format_g(last) + ")";
    }
    return {};
}

}  // namespace iga::solver
