#include "solver/predictor.hpp"

#include <cmath>
#include <cstdio>

namespace iga::solver {

namespace {

bool evaluate(const NonlinearSystem& system, const Vector& u, double load_factor, bool need_tangent, Evaluation& out,
              RunContext* context)
{
    out.ok = true;
    out.message.clear();
    ScopedTimer timer(context, "assembly");
    system.evaluate(u, load_factor, need_tangent, out);
    return out.ok && out.residual.size() == u.size() && out.residual.allFinite();
}

/// The linearized step du (see the header); false when it cannot be formed.
bool linearized_step(const NonlinearSystem& system, const Vector& u_n, double lambda_n, double lambda_next,
                     LinearSolver& solver, RunContext* context, Vector& du, std::string& note)
{
    Evaluation at_n, perturbed;
    if (!evaluate(system, u_n, lambda_n, true, at_n, context)) {
        note = "the converged state does not evaluate: " + at_n.message;
        return false;
    }
    const double increment = lambda_next - lambda_n;
    const double delta = predictor_fd_fraction * increment;
    if (!evaluate(system, u_n, lambda_n + delta, false, perturbed, context)) {
        note = "the perturbed state does not evaluate: " + perturbed.message;
        return false;
    }
    const Vector rhs = -(at_n.residual + (increment / delta) * (perturbed.residual - at_n.residual));

    ScopedTimer timer(context, "linear_solve");
    // Handed over (at_n needs it no more): a copying solver would hold it twice.
    LinearStatus status = solver.factorize_taking(at_n.tangent);  // Cholesky falls back to LU itself
    if (status == LinearStatus::ok)
        status = solver.solve(rhs, du);
    if (status != LinearStatus::ok || !du.allFinite()) {
        note = std::string("the tangent at the converged state could not be solved (") + status_name(status) + ")";
        return false;
    }
    return true;
}

}  // namespace

Vector predict(const NonlinearSystem& system, Predictor kind, const Vector& u_n, double lambda_n, double lambda_next,
               const PredictorInput& previous, LinearSolver& solver, RunContext* context, PredictionReport& report)
{
    report = {};
    if (kind == Predictor::none || system.linear || !system.prescribed_motion || !(lambda_next > lambda_n))
        return u_n;

    Vector du;
    const double increment = lambda_next - lambda_n;
    const double previous_increment = lambda_n - previous.lambda_previous;
    if (kind == Predictor::extrapolated && previous.u_previous && previous_increment > 0) {
        du = (increment / previous_increment) * (u_n - *previous.u_previous);
    } else if (!linearized_step(system, u_n, lambda_n, lambda_next, solver, context, du, report.note)) {
        return u_n;
    }

    Evaluation trial, unpredicted;
    double beta = 1.0;
    for (int halving = 0; halving <= predictor_max_halvings; ++halving, beta *= 0.5) {
        Vector u = u_n + beta * du;
        if (evaluate(system, u, lambda_next, false, trial, context)) {
            // Safeguard: the prediction must not start Newton further from equilibrium
            // than no prediction (a contact that the linearization does not see).
            if (evaluate(system, u_n, lambda_next, false, unpredicted, context) &&
                unpredicted.residual.norm() <= trial.residual.norm()) {
                report.note = "the unpredicted start has the smaller residual";
                return u_n;
            }
            report.used = true;
            report.fraction = beta;
            if (beta < 1.0) {
                char text[96];
                std::snprintf(text, sizeof text, "predicted step scaled back to %g to stay admissible", beta);
                report.note = text;
            }
            return u;
        }
    }
    report.note = "no admissible predicted state (" + trial.message + ")";
    return u_n;
}

}  // namespace iga::solver
