// Tests for solver/load_stepping.hpp: increments, cutbacks, failure messages,
// rollback to the last converged state, stop requests, linear systems, logging.

#include "solver/load_stepping.hpp"
#include "solver/suitesparse_solver.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <new>
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
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
    // increment doubles (one iteration), 0.6875 fails, is cut back to 0.625, fails
    // again and cannot be cut below that minimum.
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 4;
    stepping.max_cutbacks = 2;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
    EXPECT_NE(result.message.find("increment 4 (load factor 0.5625 -> 0.625)"), std::string::npos)
        << result.message;
}

// Issue 32: an allocation that fails inside an increment (a factorization out of
// memory) ended the run as an internal error, exit 3, with nothing written. It ends
// the path like a failure, with the converged increments and the state of the last
// one kept, and no cutback: a smaller increment needs the same matrices.
TEST(LoadStepping, AnAllocationFailureEndsThePathKeepingTheConvergedIncrements)
{
    NonlinearSystem system;
    system.evaluate = [](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        if (lambda > 0.6)
            throw std::bad_alloc();
        out.residual = Vector::Constant(1, u(0) - lambda);
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = scalar_matrix(1.0);
    };
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 4;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    Recorder recorder;
    SteppingCallbacks callbacks = recorder.callbacks();
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    EXPECT_FALSE(result.completed);
    EXPECT_TRUE(result.out_of_memory);
    EXPECT_EQ(result.total_cutbacks, 0);
    ASSERT_EQ(result.increments.size(), 2u);
    EXPECT_EQ(u, recorder.states.back()) << "u must be the last converged state";
    EXPECT_EQ(recorder.rollbacks, 1);
    EXPECT_NE(result.message.find("increment 3 (load factor 0.5 -> 0.75): out of memory"), std::string::npos)
        << result.message;
}

TEST(LoadStepping, NonAdaptiveStepsFailAtOnce)
{
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 4;
    stepping.adaptive = false;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
        SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
    // increment is cut to 0.25; r = u - lambda converges in one iteration, so the
    // next increment grows by max_growth = 2 (target 6 / 1 iteration, bounded) to 0.5.
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
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    callbacks.commit = [&] { first_done = true; };
    std::vector<double> lambdas;
    callbacks.converged = [&](const IncrementRecord& r, const Vector&) { lambdas.push_back(r.load_factor); };
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(guarded, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    // 0.25 (2 cutbacks), then increments 0.5 and 1.0 -> 0.25 (capped at the end).
    ASSERT_EQ(lambdas.size(), 3u);
    EXPECT_EQ(lambdas[0], 0.25);
    EXPECT_EQ(lambdas[1], 0.75);
    EXPECT_EQ(lambdas[2], 1.0);
    EXPECT_EQ(result.total_cutbacks, 2);
}

// r(u) = (u - lambda s)^3: Newton converges only linearly (the error shrinks by
// 2/3 per iteration, the root is triple), so a large increment takes many more
// iterations than the target and the next one must shrink; small increments take
// few and the next one grows back.
// The root stops moving at lambda = 1/2: from there every increment starts
// converged (0 iterations), and the increments grow back.
NonlinearSystem moving_triple_root(double s)
{
    NonlinearSystem system;
    system.evaluate = [s](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        const double x = u(0) - std::min(lambda, 0.5) * s;
        out.residual = Vector::Constant(1, x * x * x);
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = scalar_matrix(3.0 * x * x);
    };
    return system;
}

TEST(LoadStepping, NextIncrementFollowsTheIterationCount)
{
    // The rule of load_stepping.hpp: next = last * clamp(f(n), max_shrink, max_growth),
    // f = target / n below the target, 1 up to slow_iterations, slow_iterations / n
    // above; bounded to [1/count / 2^max_cutbacks, 1/count]. The load factors are sums
    // of increments: equal to the rule up to a few ulps of lambda <= 1.
    constexpr double lambda_round_off = 1e-14;
    NewtonSettings newton;
    newton.max_iterations = 40;  // a triple root from x = 0.25 needs ~16 linear-rate iterations
    SteppingSettings stepping;
    stepping.count = 8;  // from 14 iterations at 1/8 down to 10, which keeps the size
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result =
        run_load_steps(moving_triple_root(1.0), u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    ASSERT_EQ(result.total_cutbacks, 0) << "the rule is checked on uncut increments";

    const double largest = 1.0 / stepping.count;
    const double smallest = std::ldexp(largest, -stepping.max_cutbacks);
    bool shrank = false, grew = false, kept = false;
    double previous_lambda = 0.0;
    for (std::size_t k = 0; k + 1 < result.increments.size(); ++k) {
        const IncrementRecord& r = result.increments[k];
        const double increment = r.load_factor - previous_lambda;
        const double next = result.increments[k + 1].load_factor - r.load_factor;
        const int n = r.report.iterations;
        const double f = n < stepping.target_iterations ? double(stepping.target_iterations) / n
                         : n > stepping.slow_iterations ? double(stepping.slow_iterations) / n
                                                        : 1.0;
        const double factor = n == 0 ? stepping.max_growth : std::clamp(f, stepping.max_shrink, stepping.max_growth);
        const double expected = std::clamp(increment * factor, smallest, largest);
        const bool last = k + 2 == result.increments.size();  // the final one may be cut to end at 1
        if (last)
            EXPECT_TRUE(test::at_most(next, expected + lambda_round_off)) << "increment " << k + 2;
        else
            EXPECT_TRUE(test::near(next, expected, lambda_round_off))
                << "increment " << k + 2 << " after " << r.report.iterations << " iterations";
        shrank = shrank || next < increment * (1.0 - lambda_round_off);
        kept = kept || (!last && n >= stepping.target_iterations && test::near(next, increment, lambda_round_off));
        grew = grew || (!last && next > increment * (1.0 + lambda_round_off));
        previous_lambda = r.load_factor;
    }
    EXPECT_TRUE(shrank) << "no increment shrank: the test no longer exercises the shrinking rule";
    EXPECT_TRUE(grew) << "no increment grew: the test no longer exercises the growth rule";
    EXPECT_TRUE(kept) << "no increment kept its size: the test no longer exercises the band";
    // Newton stops at |x|^3 <= 1e-10: |x| <= 4.7e-4 (and 1e-3 with margin).
    constexpr double triple_root_tolerance = 1e-3;
    EXPECT_TRUE(test::near(u(0), 0.5, triple_root_tolerance));
}

// A chain of two nonlinear springs between a wall at X = 0 and a control point
// at X = 2 whose displacement lambda * u_bar is prescribed; the free node sits at
// X = 1. Stretches J1 = 1 + u, J2 = 1 + lambda u_bar - u; spring force ln J, so
// r(u; lambda) = ln J1 - ln J2, and the state is inadmissible (as an inverted
// element) when J1 <= 0 or J2 <= 0. The solution is u = lambda u_bar / 2 (J1 = J2).
// Without a predictor, u_bar = -1.5 in one increment starts Newton from
// u = 0 with J2 = -0.5: inadmissible, the increment must be cut back.
NonlinearSystem spring_chain(double u_bar, int* inadmissible = nullptr)
{
    NonlinearSystem system;
    system.prescribed_motion = true;
    system.evaluate = [u_bar, inadmissible](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        const double J1 = 1.0 + u(0), J2 = 1.0 + lambda * u_bar - u(0);
        if (!(J1 > 0.0) || !(J2 > 0.0)) {
            if (inadmissible)
                ++*inadmissible;
            out.ok = false;
            out.message = "inverted spring";
            return;
        }
        out.residual = Vector::Constant(1, std::log(J1) - std::log(J2));
        out.force_scale = std::abs(std::log(J1)) + std::abs(std::log(J2));
        if (need_tangent)
            out.tangent = scalar_matrix(1.0 / J1 + 1.0 / J2);
    };
    return system;
}

TEST(LoadStepping, PredictorSpreadsAPrescribedDisplacementIntoTheInterior)
{
    constexpr double u_bar = -1.5;
    NewtonSettings newton;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;

    SteppingSettings plain;
    plain.predictor = Predictor::none;
    Vector u = Vector::Zero(1);
    const SteppingResult without = run_load_steps(spring_chain(u_bar), u, plain, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(without.completed) << without.message;
    EXPECT_GT(without.total_cutbacks, 0) << "the unpredicted start state must be inadmissible";

    for (Predictor kind : {Predictor::linearized, Predictor::extrapolated}) {
        SCOPED_TRACE(kind == Predictor::linearized ? "linearized" : "extrapolated");
        SteppingSettings stepping;
        stepping.predictor = kind;
        u.setZero();
        const SteppingResult with = run_load_steps(spring_chain(u_bar), u, stepping, newton, solver, callbacks, nullptr);
        ASSERT_TRUE(with.completed) << with.message;
        EXPECT_EQ(with.total_cutbacks, 0);
        ASSERT_EQ(with.increments.size(), 1u);
        // By symmetry the linearized step about u = 0 is the exact solution u_bar / 2,
        // up to the forward difference in lambda (relative error ~ predictor_fd_fraction):
        // one Newton iteration at most (the extrapolated predictor has no previous
        // increment on the first one and uses the linearized step too).
        EXPECT_LE(with.increments[0].report.iterations, 1);
        EXPECT_TRUE(test::near(u(0), 0.5 * u_bar, solution_tolerance));
    }
}

// r(u) = atan(u) - 1.4 lambda, prescribed-motion style: the linearized predictor from
// u = 0 (tangent 1) predicts u = 1.4, where the residual is smaller than at the start,
// and Newton's full step from there is 1.33 (the tangent is 1 / (1 + u^2) = 0.34). The
// increment's trust radius caps every step of that attempt at 0.25 x 1.4 = 0.35 (the
// predicted step, no motion prescribed); without a prediction the system's radius stands.
TEST(LoadStepping, AnIncrementsTrustRadiusIsAQuarterOfItsPredictedStep)
{
    constexpr double load = 1.4;
    std::vector<double> states;
    NonlinearSystem system;
    system.prescribed_motion = true;
    system.max_step = 100.0;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        states.push_back(u(0));
        out.residual = Vector::Constant(1, std::atan(u(0)) - lambda * load);
        out.force_scale = load;
        if (need_tangent)
            out.tangent = scalar_matrix(1.0 / (1.0 + u(0) * u(0)));
    };
    NewtonSettings newton;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    // The largest change between consecutive evaluated states from `start` on.
    auto largest_step_from = [&](std::size_t start) {
        double largest = 0.0;
        for (std::size_t k = start + 1; k < states.size(); ++k)
            largest = std::max(largest, std::abs(states[k] - states[k - 1]));
        return largest;
    };
    // ... from Newton's start: the last evaluation of the predicted state (the predictor
    // compares it with the unpredicted start first; on this path linear in lambda the
    // prediction is exact).
    auto largest_step_after_prediction = [&] {
        std::size_t start = 0;
        for (std::size_t k = 0; k < states.size(); ++k)
            if (std::abs(states[k] - load) < 1e-12)
                start = k;
        return largest_step_from(start);
    };

    SteppingSettings stepping;  // one increment, linearized predictor
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_TRUE(test::near(u(0), std::tan(load), solution_tolerance));
    const double radius = predicted_step_trust * load;
    EXPECT_LE(largest_step_after_prediction(), radius * (1.0 + 1e-12));
    EXPECT_GE(largest_step_after_prediction(), radius * (1.0 - 1e-12)) << "the cap was never reached";

    states.clear();
    SteppingSettings unpredicted;
    unpredicted.predictor = Predictor::none;
    u.setZero();
    const SteppingResult plain = run_load_steps(system, u, unpredicted, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(plain.completed) << plain.message;
    EXPECT_GT(largest_step_from(0), 2.0 * radius) << "without a prediction the system's radius stands";
}

TEST(LoadStepping, InadmissiblePredictionIsScaledBack)
{
    // Five increments of u_bar = -1.9 on the spring chain, extrapolating: from the
    // second increment on the extrapolation is exact for this linear path, so check the
    // first. A predictor whose state is inadmissible must fall back, never fail:
    // make every state with u < -0.5 inadmissible (a stiffer stop at J1 = 0.5).
    constexpr double u_bar = -1.9;
    NonlinearSystem chain = spring_chain(u_bar);
    int refused = 0;
    NonlinearSystem guarded = chain;
    guarded.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        if (u(0) < -0.5) {
            ++refused;
            out.ok = false;
            out.message = "beyond the stop";
            return;
        }
        chain.evaluate(u, lambda, need_tangent, out);
    };
    NewtonSettings newton;
    SteppingSettings stepping;  // one increment: the predicted u = -0.95 is beyond the stop
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    std::vector<std::string> lines;
    RunContext context([&](Verbosity, const std::string& line) { lines.push_back(line); }, Verbosity::verbose);
    const SteppingResult result = run_load_steps(guarded, u, stepping, newton, solver, callbacks, &context);
    // The exact solution -0.95 is inadmissible, so the run cannot complete; what
    // matters is that the predictor scaled back (no exception, a Newton failure
    // with cutbacks, and the predictor's note in the log).
    EXPECT_FALSE(result.completed);
    EXPECT_GT(refused, 0);
    EXPECT_GT(result.predictor_fallbacks, 0);
    bool logged = false;
    for (const std::string& line : lines)
        logged = logged || line.find("predictor: predicted step scaled back to 0.5") != std::string::npos;
    EXPECT_TRUE(logged) << "the verbose log names the scaled-back prediction";
}

TEST(LoadStepping, LineSearchBacksOffAnInadmissibleTrialWithoutACutback)
{
    // r(u) = atan(u - 4 lambda) in one increment: the full Newton step from u = 0
    // (x = -4) lands at u = 22.5, and every state with |u| > 8 is reported
    // inadmissible (as an inverted element would be). The line search must back off
    // inside the iteration; the increment converges without a cutback.
    constexpr double s = 4.0, admissible_radius = 8.0;
    int inadmissible = 0;
    NonlinearSystem arctan = moving_arctan(s);
    NonlinearSystem system;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        if (std::abs(u(0)) > admissible_radius) {
            ++inadmissible;
            out.ok = false;
            out.message = "inadmissible deformation";
            return;
        }
        arctan.evaluate(u, lambda, need_tangent, out);
    };
    NewtonSettings newton;
    SteppingSettings stepping;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_EQ(result.total_cutbacks, 0);
    EXPECT_EQ(result.increments.size(), 1u);
    EXPECT_GT(inadmissible, 0) << "no trial was inadmissible: the test no longer exercises the back-off";
    EXPECT_EQ(result.increments[0].report.inadmissible_trials, inadmissible);
    EXPECT_TRUE(test::near(u(0), s, solution_tolerance));
}

TEST(LoadStepping, StopRequestEndsTheRunAfterTheCurrentIncrement)
{
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 5;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
    int n_tangents = 0, n_residuals = 0;
    NonlinearSystem system;
    system.linear = true;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        ++(need_tangent ? n_tangents : n_residuals);
        out.residual = Vector::Constant(1, 2.0 * u(0) - lambda);
        out.force_scale = lambda;
        out.tangent = scalar_matrix(2.0);
    };
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 3;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(system, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_EQ(result.increments.size(), 3u);
    EXPECT_EQ(n_tangents, 3);
    EXPECT_EQ(n_residuals, 3);  // each solution's, which checks the solve
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
    EXPECT_NE(failed.message.find("linear solve"), std::string::npos) << failed.message;
}

TEST(LoadStepping, LogsOneLinePerConvergedIncrement)
{
    std::vector<std::string> lines;
    RunContext context([&](Verbosity, const std::string& line) { lines.push_back(line); }, Verbosity::normal);
    NewtonSettings newton;
    SteppingSettings stepping;
    stepping.count = 3;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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

namespace iga::solver {
namespace {

// One spring against a wall, augmented Lagrangian by hand: dof u = penetration,
// spring stiffness k, load lambda F pushing into the wall, contact pressure
// p = <m + eps u> with the multiplier m held here:
//   r(u) = k u - lambda F + p(u).
// The outer callback is the Uzawa step m <- <m + eps u>; at lambda = 1 the solve
// gives u_n = (F - m_n)/(k + eps), so m_n = F (1 - rho^n), rho = k/(k + eps).
struct OneSpring {
    double k = 1.0, F = 2.0, eps = 3.0;  // rho = 1/4
    double m = 0.0, committed = 0.0;
    double tolerance = 1e-3;  // accept when u <= tolerance
    int max_updates = 100;
    int updates = 0;

    NonlinearSystem system()
    {
        NonlinearSystem s;
        s.evaluate = [this](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
            const double trial = m + eps * u(0);
            out.residual = Vector::Constant(1, k * u(0) - lambda * F + std::max(trial, 0.0));
            out.force_scale = F;
            if (need_tangent)
                out.tangent = scalar_matrix(k + (trial > 0.0 ? eps : 0.0));
        };
        return s;
    }
    SteppingCallbacks callbacks()
    {
        SteppingCallbacks c;
        c.commit = [this] { committed = m; updates = 0; };
        c.rollback = [this] { m = committed; updates = 0; };
        c.outer = [this](const Vector& u, double) {
            OuterDecision d;
            if (u(0) <= tolerance)
                return d;
            if (updates == max_updates) {
                d.action = OuterDecision::Action::reject;
                d.message = "penetration above tolerance";
                return d;
            }
            m = std::max(m + eps * u(0), 0.0);
            ++updates;
            d.action = OuterDecision::Action::resolve;
            return d;
        };
        return c;
    }
};

TEST(LoadStepping, OuterUpdatesFollowTheOneSpringClosedForm)
{
    OneSpring spring;
    // u_n = F rho^n / (k + eps) = 0.5 / 4^n: 0.5, 0.125, 0.031, 0.0078, 0.00195, 0.00049:
    // the first u_n <= 1e-3 is n = 5.
    constexpr int expected_updates = 5;
    const double rho = spring.k / (spring.k + spring.eps);
    SteppingSettings stepping;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks = spring.callbacks();
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(spring.system(), u, stepping, NewtonSettings{}, solver, callbacks,
                                                 nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    ASSERT_EQ(result.increments.size(), 1u);
    EXPECT_EQ(result.increments[0].outer_updates, expected_updates);
    EXPECT_EQ(result.increments[0].cutbacks, 0);
    // Newton stops at 1e-10 relative residual, so u and m carry ~1e-10 F.
    constexpr double closed_form_tolerance = 1e-9;
    EXPECT_TRUE(test::near(spring.committed, spring.F * (1.0 - std::pow(rho, expected_updates)),
                           closed_form_tolerance * spring.F))
        << "m after 5 updates";
    EXPECT_TRUE(test::near(u(0), spring.F * std::pow(rho, expected_updates) / (spring.k + spring.eps),
                           closed_form_tolerance))
        << "u after 5 updates";
    // The increment's report sums every solve: one residual history entry per iteration.
    EXPECT_EQ(result.increments[0].report.iterations, result.total_iterations);
    EXPECT_EQ(static_cast<int>(result.increments[0].report.residual_history.size()),
              result.increments[0].report.iterations + expected_updates + 1);
}

// A rejection counts as a failed attempt: the multiplier is rolled back to the
// committed value and the increment is cut back; with the rejection persisting
// the run ends with the callback's reason in the message.
TEST(LoadStepping, RejectedOuterLoopIsCutBackAndRolledBack)
{
    OneSpring spring;
    spring.max_updates = 1;  // never enough for u <= 1e-3 from m = 0 at any load factor >= 1/256
    SteppingSettings stepping;
    stepping.max_cutbacks = 2;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks = spring.callbacks();
    int rollbacks = 0;
    auto rollback = callbacks.rollback;
    callbacks.rollback = [&] {
        rollback();
        ++rollbacks;
        EXPECT_EQ(spring.m, 0.0) << "rolled back to the committed multiplier";
    };
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(spring.system(), u, stepping, NewtonSettings{}, solver, callbacks,
                                                 nullptr);
    EXPECT_FALSE(result.completed);
    EXPECT_EQ(rollbacks, 3);
    EXPECT_EQ(result.total_cutbacks, 2);
    EXPECT_NE(result.message.find("the outer loop rejected the solution after 2 cutbacks"), std::string::npos)
        << result.message;
    EXPECT_NE(result.message.find("penetration above tolerance"), std::string::npos) << result.message;
    EXPECT_EQ(u(0), 0.0) << "the last converged state (the start)";
}

}  // namespace
}  // namespace iga::solver
