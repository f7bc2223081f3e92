// Tests for solver/load_stepping.hpp: increments, cutbacks, failure messages,
// rollback to the last converged state, stop requests, linear systems, logging.

#include "solver/load_stepping.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

// Newton's tolerance 1e-10 on O(1) scalar problems with O(1) tangents.
constexpr double solution_tolerance = 1e-8;

SparseMatrix scalar_matrix(double value)
{
    SparseMatrix K(1, 1);
    K.insert(0, 0) = value;
    K.makeCompressed();
    return K;
}

// r(u) = atan(u - lambda s): the solution moves with the load, u = lambda s;
// plain Newton (no line search) diverges when the increment moves the root by
// more than ~1.39, so s = 4 in one increment fails and needs cutbacks.
NonlinearSystem moving_arctan(double s)
{
    NonlinearSystem system;
    system.evaluate = [s](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        const double x = u(0) - lambda * s;
        out.residual = Vector::Constant(1, std::atan(x));
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = scalar_matrix(1.0 / (1.0 + x * x));
    };
    return system;
}

// r(u) = u - lambda, but the evaluation fails beyond lambda_limit (as a contact
// projection may fail past some load).
NonlinearSystem failing_beyond(double lambda_limit)
{
    NonlinearSystem system;
    system.evaluate = [lambda_limit](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        if (lambda > lambda_limit) {
            out.ok = false;
            out.message = "projection failed";
            return;
        }
        out.residual = Vector::Constant(1, u(0) - lambda);
        out.force_scale = lambda;
        if (need_tangent)
            out.tangent = scalar_matrix(1.0);
    };
    return system;
}

struct Recorder {
    std::vector<Vector> states;
    std::vector<double> load_factors;
    int commits = 0;
    int rollbacks = 0;

    SteppingCallbacks callbacks()
    {
        SteppingCallbacks c;
        c.converged = [this](const IncrementRecord& record, const Vector& u) {
            states.push_back(u);
            load_factors.push_back(record.load_factor);
        };
        c.commit = [this] { ++commits; };
        c.rollback = [this] { ++rollbacks; };
        return c;
    }
};

TEST(LoadStepping, CutbacksRescueADivergingIncrement)
{
    NewtonSettings newton;
    newton.line_search = false;
    newton.max_iterations = 12;
    SteppingSettings stepping;  // one increment, adaptive
    LinearSolver solver(LinearSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(moving_arctan(4.0), u, stepping, newton, solver, callbacks, nullptr);

    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_TRUE(result.message.empty());
    EXPECT_GT(result.total_cutbacks, 0);
    EXPECT_GT(result.increments.front().cutbacks, 0);
    EXPECT_EQ(recorder.rollbacks, result.total_cutbacks);
    EXPECT_EQ(recorder.commits, static_cast<int>(result.increments.size()));
    EXPECT_EQ(result.increments.back().load_factor, 1.0);
    EXPECT_TRUE(test::near(u(0), 4.0, solution_tolerance));
    for (std::size_t k = 0; k < result.increments.size(); ++k) {
        EXPECT_EQ(result.increments[k].index, static_cast<int>(k) + 1);
        EXPECT_EQ(result.increments[k].report.status, NewtonStatus::converged);
        if (k > 0) {
            EXPECT_GT(result.increments[k].load_factor, result.increments[k - 1].load_factor);
        }
    }
    int iterations = 0;
    for (const IncrementRecord& r : result.increments)
        iterations += r.report.iterations;
    EXPECT_GT(result.total_iterations, iterations) << "failed attempts count too";
}

TEST(LoadStepping, ExhaustedCutbacksEndTheRunWithAMessage)
{
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.max_cutbacks = 2;
    LinearSolver solver(LinearSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    Vector u = Vector::Constant(1, 0.0);
    // Fails beyond 0.2: attempts 1, 0.5, 0.25 all fail.
    const SteppingResult result =
        run_load_steps(failing_beyond(0.2), u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(result.completed);
    EXPECT_TRUE(result.increments.empty());
    EXPECT_EQ(result.total_cutbacks, 2);
    EXPECT_EQ(recorder.rollbacks, 3);
    EXPECT_NE(result.message.find("increment 1 (load factor 0 -> 0.25)"), std::string::npos) << result.message;
    EXPECT_NE(result.message.find("after 2 cutbacks"), std::string::npos) << result.message;
    EXPECT_NE(result.message.find("projection failed"), std::string::npos) << result.message;
    EXPECT_EQ(u(0), 0.0);
}

TEST(LoadStepping, FailureLeavesTheLastConvergedState)
{
    // count 4, fails beyond 0.6: 0.25, 0.5 converge; 0.75 and 0.625 fail; 0.5625
    // converges after 2 cutbacks at the smallest increment 1/4/2^2; the next
    // attempt (0.65625) fails and cannot be cut below that minimum.
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 4;
    stepping.max_cutbacks = 2;
    LinearSolver solver(LinearSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    Vector u = Vector::Zero(1);
    const SteppingResult result =
        run_load_steps(failing_beyond(0.6), u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(result.completed);
    ASSERT_EQ(result.increments.size(), 3u);
    EXPECT_EQ(result.increments.back().load_factor, 0.5625);
    EXPECT_EQ(result.increments.back().cutbacks, 2);
    ASSERT_FALSE(recorder.states.empty());
    EXPECT_EQ(u, recorder.states.back()) << "u must be the last converged state";
    EXPECT_TRUE(test::near(u(0), 0.5625, solution_tolerance));
    EXPECT_NE(result.message.find("increment 4 (load factor 0.5625 -> 0.65625)"), std::string::npos)
        << result.message;
}

TEST(LoadStepping, NonAdaptiveStepsFailAtOnce)
{
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 4;
    stepping.adaptive = false;
    LinearSolver solver(LinearSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    Vector u = Vector::Zero(1);
    const SteppingResult result =
        run_load_steps(failing_beyond(0.6), u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(result.completed);
    EXPECT_EQ(result.increments.size(), 2u);
    EXPECT_EQ(result.total_cutbacks, 0);
    EXPECT_NE(result.message.find("increment 3 (load factor 0.5 -> 0.75)"), std::string::npos) << result.message;
    EXPECT_EQ(u, recorder.states.back());
}

TEST(LoadStepping, EasyIncrementsNeverGrowBeyondTheInitialOne)
{
    for (bool adaptive : {false, true}) {
        SCOPED_TRACE(adaptive ? "adaptive" : "fixed");
        NewtonSettings newton;
        SteppingSettings stepping;
        stepping.count = 4;
        stepping.adaptive = adaptive;
        LinearSolver solver(LinearSolver::Kind::lu);
        Recorder recorder;
        SteppingCallbacks callbacks = recorder.callbacks();
        Vector u = Vector::Zero(1);
        const SteppingResult result =
            run_load_steps(failing_beyond(2.0), u, stepping, newton, solver, callbacks, nullptr);
        ASSERT_TRUE(result.completed) << result.message;
        ASSERT_EQ(recorder.load_factors.size(), 4u);
        EXPECT_EQ(recorder.load_factors[0], 0.25);
        EXPECT_EQ(recorder.load_factors[1], 0.5);
        EXPECT_EQ(recorder.load_factors[2], 0.75);
        EXPECT_EQ(recorder.load_factors[3], 1.0);
    }
}

TEST(LoadStepping, IncrementGrowsBackAfterCutbacks)
{
    // Fails beyond 0.3 until the first increment has converged, then never: the
    // increment is cut to 0.25 and then grows by 1.5 per easy increment (<= 1).
    bool first_done = false;
    NonlinearSystem system = failing_beyond(2.0);
    NonlinearSystem guarded;
    guarded.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        if (!first_done && lambda > 0.3) {
            out.ok = false;
            out.message = "not yet";
            return;
        }
        system.evaluate(u, lambda, need_tangent, out);
    };
    NewtonSettings newton;
    SteppingSettings stepping;
    LinearSolver solver(LinearSolver::Kind::lu);
    SteppingCallbacks callbacks;
    callbacks.commit = [&] { first_done = true; };
    std::vector<double> lambdas;
    callbacks.converged = [&](const IncrementRecord& r, const Vector&) { lambdas.push_back(r.load_factor); };
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(guarded, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    // 0.25 (2 cutbacks), then increments 0.375 and 0.5625 -> 0.625, 1.0 (capped at the end).
    ASSERT_EQ(lambdas.size(), 3u);
    EXPECT_EQ(lambdas[0], 0.25);
    EXPECT_EQ(lambdas[1], 0.625);
    EXPECT_EQ(lambdas[2], 1.0);
    EXPECT_EQ(result.total_cutbacks, 2);
}

TEST(LoadStepping, StopRequestEndsTheRunAfterTheCurrentIncrement)
{
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 5;
    LinearSolver solver(LinearSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    callbacks.stop_requested = [&] { return recorder.states.size() == 2; };
    Vector u = Vector::Zero(1);
    const SteppingResult result =
        run_load_steps(failing_beyond(2.0), u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(result.completed);
    EXPECT_EQ(result.increments.size(), 2u);
    EXPECT_NE(result.message.find("after increment 2"), std::string::npos) << result.message;
    EXPECT_TRUE(test::near(u(0), 0.4, solution_tolerance));
}

TEST(LoadStepping, LinearSystemTakesOneSolvePerIncrementAndNeverCutsBack)
{
    int n_evaluations = 0;
    NonlinearSystem system;
    system.linear = true;
    system.evaluate = [&](const Vector& u, double lambda, bool, Evaluation& out) {
        ++n_evaluations;
        out.residual = Vector::Constant(1, 2.0 * u(0) - lambda);
        out.force_scale = lambda;
        out.tangent = scalar_matrix(2.0);
    };
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 3;
    LinearSolver solver(LinearSolver::Kind::cholesky);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_EQ(result.increments.size(), 3u);
    EXPECT_EQ(n_evaluations, 3);
    EXPECT_EQ(result.total_iterations, 3);
    EXPECT_TRUE(test::near(u(0), 0.5, solution_tolerance));

    // A singular, inconsistent linear system fails at once, without cutbacks.
    system.evaluate = [](const Vector& u, double lambda, bool, Evaluation& out) {
        out.residual = Vector::Constant(1, 0.0 * u(0) - lambda);
        out.force_scale = lambda;
        out.tangent = scalar_matrix(0.0);
    };
    u.setZero();
    const SteppingResult failed = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(failed.completed);
    EXPECT_EQ(failed.total_cutbacks, 0);
    EXPECT_NE(failed.message.find("linear solve failed"), std::string::npos) << failed.message;
}

TEST(LoadStepping, LogsOneLinePerConvergedIncrement)
{
    std::vector<std::string> lines;
    RunContext context([&](Verbosity, const std::string& line) { lines.push_back(line); }, Verbosity::normal);
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 3;
    LinearSolver solver(LinearSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result =
        run_load_steps(failing_beyond(2.0), u, stepping, newton, solver, callbacks, &context);
    ASSERT_TRUE(result.completed) << result.message;
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0].rfind("increment 1: load factor 0.333333", 0), 0u) << lines[0];
    EXPECT_NE(lines[2].find("load factor 1,"), std::string::npos) << lines[2];
    EXPECT_EQ(context.count("newton_iterations"), result.total_iterations);
}

}  // namespace
}  // namespace iga::solver
