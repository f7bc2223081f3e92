#pragma once
// Predictor for an increment lambda_n -> lambda_{n+1} of a system whose load
// factor moves constrained dofs (prescribed displacements): the starting state
// of Newton for the new increment.
//
// Without a predictor Newton starts from u_n at lambda_{n+1}: the constrained
// control points jump by (lambda_{n+1} - lambda_n) u_bar while every free one
// stays put, so the whole increment is concentrated in the elements next to the
// constrained side. Thin elements there (a collapsed corner) invert, and the
// very first evaluation fails. Both predictors below spread the increment into
// the interior.
//
//   linearized: one Newton step of the linearization about the converged state,
//     with the increment of the load factor as the load:
//       K(u_n; lambda_n) du = -( r(u_n; lambda_n) + dlambda dr/dlambda(u_n; lambda_n) ),
//     dr/dlambda (prescribed displacements through the free-constrained coupling
//     K_fc u_bar, dead loads, obstacle motion) by a forward difference in lambda
//     over delta = fd_fraction * dlambda: small enough that the perturbed state is
//     as admissible as the converged one and the truncation error (relative,
//     ~fd_fraction times the curvature of r in lambda over the increment) is far
//     below what one Newton iteration removes, large enough that the round-off of
//     the difference (eps ||f|| / delta for forces f in play) stays ~1e-10 of them.
//   extrapolated: u_n + (dlambda / dlambda_prev) (u_n - u_{n-1}) (the linearized
//     predictor on the first increment, where there is no previous one).
//
// Admissibility: the predicted state u_n + beta du is evaluated at lambda_{n+1}
// for beta = 1, 1/2, ..., 1/2^max_halvings; the first whose evaluation succeeds
// is kept. If none does, or the linearization cannot be formed (failed
// evaluation, singular tangent), u_n is returned and Newton starts there as it
// would without a predictor. Safeguard: the unpredicted start u_n is also
// evaluated at lambda_{n+1}; when it is admissible and its ||r|| is not larger
// than the prediction's, u_n is returned. The linearization does not see contact
// that the increment closes (two bodies driven towards each other are predicted
// to overlap by the whole increment), and such a prediction starts Newton far
// from equilibrium. Shapes: every vector has n_free entries.

#include "core/run_context.hpp"
#include "core/types.hpp"
#include "solver/linear.hpp"
#include "solver/newton.hpp"

namespace iga::solver {

enum class Predictor { none, linearized, extrapolated };

/// Forward-difference step in lambda, as a fraction of the increment (see above).
inline constexpr double predictor_fd_fraction = 1e-6;
/// Halvings of the predicted step tried before falling back to u_n.
inline constexpr int predictor_max_halvings = 4;

struct PredictorInput {
    const Vector* u_previous = nullptr;  ///< u_{n-1}; null on the first increment
    double lambda_previous = 0;          ///< lambda_{n-1}
};

struct PredictionReport {
    bool used = false;    ///< false: Newton starts from u_n
    double fraction = 0;  ///< beta of the admissible predicted step (1, 1/2, ...)
    std::string note;     ///< why the predictor was skipped or scaled back (for the verbose log)
};

/// The start state for Newton on lambda_n -> lambda_next from the converged u_n.
/// The linear solver is used for the linearized step (it may switch Cholesky to LU
/// as solve_newton does). context may be null; evaluations count as "assembly",
/// the solve as "linear_solve".
Vector predict(const NonlinearSystem& system, Predictor kind, const Vector& u_n, double lambda_n, double lambda_next,
               const PredictorInput& previous, LinearSolver& solver, RunContext* context, PredictionReport& report);

}  // namespace iga::solver
