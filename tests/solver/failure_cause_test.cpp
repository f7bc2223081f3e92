// Tests for solver/failure_cause.hpp on synthetic Newton reports, one table row per
// cause: what the history shows decides the class, and the clause names only that.

#include "solver/failure_cause.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

struct CauseCase {
    std::string name;
    NewtonStatus status;
    std::vector<double> residual;  ///< relative residual history
    std::vector<double> floor;     ///< relative round-off floor at the same states
    double norm_ratio;             ///< ||r|| last / ||r|| initial
    bool last_regularized;
    FailureCause expected;
    std::string text;  ///< a phrase the clause must contain
};

std::vector<double> constant(std::size_t n, double value)
{
    return std::vector<double>(n, value);
}

const std::vector<CauseCase>& cause_cases()
{
    const std::vector<double> falling = {1.0, 0.67, 0.44, 0.3, 0.2, 0.13, 0.088, 0.059};
    static const std::vector<CauseCase> cases = {
        {"converged", NewtonStatus::converged, {1.0, 1e-3, 1e-11}, constant(3, 1e-14), 1e-11, false,
         FailureCause::none, ""},
        // The solver could not factorize even K + mu D.
        {"singular_tangent", NewtonStatus::singular, {1.0}, {1e-15}, 1.0, true, FailureCause::free_mode,
         "unconstrained"},
        // Every step needed the regularization, up to the last: the mode is still there.
        {"regularized_to_the_end", NewtonStatus::max_iterations, constant(8, 0.9), constant(8, 1e-15), 0.9, true,
         FailureCause::free_mode, "singular"},
        {"inverted_element", NewtonStatus::evaluation_failed, {1.0, 0.5}, {1e-15, 1e-15}, 0.5, false,
         FailureCause::inadmissible, "inadmissible"},
        // The residual grew 2e10-fold (penalty_extreme with the line search off).
        {"diverged", NewtonStatus::diverged, {1.25, 1.0}, {1e-12, 1e-4}, 2.2e10, false, FailureCause::growth,
         "diverged"},
        // Ran out of iterations with ||r|| 50 times the initial one, although the
        // relative residual (scaled by forces that grew with it) looks flat.
        {"grew_slowly", NewtonStatus::max_iterations, constant(8, 0.8), constant(8, 1e-14), 50.0, false,
         FailureCause::growth, "50 times"},
        // Stuck at 1.7e-6 against a floor of 6e-7: round-off, yet the corrections
        // did not settle (the soft-penalty deck before the floor-aware criterion).
        {"at_round_off_floor", NewtonStatus::max_iterations,
         {0.2, 2.3e-6, 1.7e-6, 1.8e-6, 1.66e-6, 1.83e-6, 1.68e-6}, constant(7, 6e-7), 1.7e-6, false,
         FailureCause::round_off_floor, "round-off floor 6e-07"},
        // Two active sets alternate, far above the floor.
        {"flip_flop", NewtonStatus::max_iterations, {1.0, 0.2, 1.1e-2, 3.1e-4, 8.2e-3, 3.12e-4, 8.1e-3, 3.09e-4, 8.25e-3},
         constant(9, 1e-14), 8.25e-3, false, FailureCause::cycle, "alternates between 0.00818 and 0.00031"},
        // Flat at 0.78, 1e13 times the floor: no round-off story here.
        {"stagnation_above_floor", NewtonStatus::max_iterations, {1.0, 0.8, 0.78, 0.79, 0.78, 0.78, 0.78, 0.78},
         constant(8, 1e-14), 0.78, false, FailureCause::stagnation, "7.8e+13 times its round-off floor"},
        // Rose and fell for 12 iterations, the last ones falling, but not a decade below the
        // best before them: wandering, and the clause must not say "still falling".
        {"wandering", NewtonStatus::max_iterations,
         {1.0, 0.5, 0.1, 0.3, 0.2, 0.4, 0.3, 0.25, 0.35, 0.3, 0.2, 0.15, 0.12}, constant(13, 1e-14), 0.12, false,
         FailureCause::wandering, "rose in 3 of 12 iterations and ends at 0.12, not a tenth of the 0.1 it reached at iteration 2"},
        // Still halving every two iterations when they ran out.
        {"slow_linear", NewtonStatus::max_iterations, falling, constant(falling.size(), 1e-14), 0.059, false,
         FailureCause::slow, "still falling"},
    };
    return cases;
}

TEST(FailureCause, ClassifiesEachHistory)
{
    for (const CauseCase& c : cause_cases()) {
        SCOPED_TRACE(c.name);
        NewtonReport report;
        report.status = c.status;
        report.residual_history = c.residual;
        report.floor_history = c.floor;
        report.norm_ratio = c.norm_ratio;
        report.last_step_regularized = c.last_regularized;
        report.correction = 1e-3;
        EXPECT_STREQ(cause_name(failure_cause(report)), cause_name(c.expected));
        const std::string text = cause_text(report);
        EXPECT_NE(text.find(c.text), std::string::npos) << text;
        if (c.expected == FailureCause::wandering) {
            EXPECT_EQ(text.find("still falling"), std::string::npos) << text;
        }
        // Only the round-off class may speak of round-off as the cause.
        if (c.expected != FailureCause::round_off_floor) {
            EXPECT_EQ(text.find("is at its round-off"), std::string::npos) << text;
        }
    }
}

// A NaN in the last norm ratio is growth, never "converging".
TEST(FailureCause, NonFiniteGrowthIsGrowth)
{
    NewtonReport report;
    report.status = NewtonStatus::max_iterations;
    report.residual_history = constant(8, 0.5);
    report.floor_history = constant(8, 1e-14);
    report.norm_ratio = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(failure_cause(report), FailureCause::growth);
}

// Only a direct method's singular tangent is called a free mode; an iterative method
// that stopped short is reported as such (NewtonStatus::linear_solver_not_converged).
TEST(FailureCause, AnIterativeSolverThatStoppedShortIsNotCalledAFreeMode)
{
    NewtonReport report;
    report.residual_history = {1.0};
    report.status = NewtonStatus::linear_solver_not_converged;
    EXPECT_EQ(failure_cause(report), FailureCause::linear_solver);
    EXPECT_NE(cause_text(report).find("iterative linear solver did not converge"), std::string::npos);
    report.status = NewtonStatus::singular;
    EXPECT_EQ(failure_cause(report), FailureCause::free_mode);
}

}  // namespace
}  // namespace iga::solver
