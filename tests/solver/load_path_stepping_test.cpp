// Tests for solver/load_stepping.hpp along a load path (core/amplitude.hpp):
// count increments spread over [0, T], every breakpoint hit exactly, increments
// never straddling a kink, cutbacks resuming from the last converged pseudo-time.

#include "core/amplitude.hpp"
#include "solver/load_stepping.hpp"
#include "solver/suitesparse_solver.hpp"
#include "support/tolerance.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace iga::solver {
namespace {

// Sums of a few increments of size O(1): a few ulps.
constexpr double time_round_off = 1e-14;
// Newton's tolerance 1e-10 on an O(1) scalar problem with unit tangent.
constexpr double solution_tolerance = 1e-9;

SparseMatrix unit_matrix()
{
    SparseMatrix K(1, 1);
    K.insert(0, 0) = 1.0;
    K.makeCompressed();
    return K;
}

// r(u; t) = u - a(t): the solution follows the amplitude, u = a(t).
NonlinearSystem following(const Amplitude& a)
{
    NonlinearSystem system;
    system.evaluate = [a](const Vector& u, double t, bool need_tangent, Evaluation& out) {
        out.residual = Vector::Constant(1, u(0) - a(t));
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = unit_matrix();
    };
    return system;
}

std::vector<double> times_of(const SteppingResult& result)
{
    std::vector<double> t;
    for (const IncrementRecord& r : result.increments)
        t.push_back(r.load_factor);
    return t;
}

TEST(LoadPathStepping, CountIncrementsSpreadOverThePathLandOnEveryBreakpoint)
{
    // T = 2, count 4: increments of 0.5, each one that would pass 0.3 or 1 shortened to end there.
    const Amplitude a({{0.0, 0.0}, {0.3, 1.0}, {1.0, -1.0}, {2.0, 0.5}});
    for (bool adaptive : {false, true}) {
        SCOPED_TRACE(adaptive ? "adaptive" : "fixed");
        SteppingSettings stepping;
        stepping.path = load_path({a});
        stepping.count = 4;
        stepping.adaptive = adaptive;
        NewtonSettings newton;
        SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
        SteppingCallbacks callbacks;
        Vector u = Vector::Zero(1);
        const SteppingResult result = run_load_steps(following(a), u, stepping, newton, solver, callbacks, nullptr);
        ASSERT_TRUE(result.completed) << result.message;
        const std::vector<double> t = times_of(result);
        ASSERT_EQ(t.size(), 5u);
        // Breakpoints exactly, the others up to the round-off of their sums.
        EXPECT_EQ(t[0], 0.3);
        EXPECT_TRUE(test::near(t[1], 0.8, time_round_off));
        EXPECT_EQ(t[2], 1.0);
        EXPECT_TRUE(test::near(t[3], 1.5, time_round_off));
        EXPECT_EQ(t[4], 2.0);
        EXPECT_TRUE(test::near(u(0), 0.5, solution_tolerance));
    }
}

TEST(LoadPathStepping, TwentyStepsOverTwoHitTheKinkWithoutASliver)
{
    // 10 sums of 0.1 miss 1 by an ulp: the increment must snap onto the kink, not
    // leave a 1e-16 increment before it.
    const Amplitude press({{0.0, 0.0}, {1.0, 1.0}, {2.0, 1.0}});
    SteppingSettings stepping;
    stepping.path = load_path({press, Amplitude({{0.0, 0.0}, {1.0, 0.0}, {2.0, 1.0}})});
    stepping.count = 20;
    stepping.adaptive = false;
    NewtonSettings newton;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(following(press), u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    const std::vector<double> t = times_of(result);
    ASSERT_EQ(t.size(), 20u);
    EXPECT_EQ(t[9], 1.0);
    EXPECT_EQ(t[19], 2.0);
    for (std::size_t k = 1; k < t.size(); ++k)
        EXPECT_TRUE(test::near(t[k] - t[k - 1], 0.1, time_round_off)) << "increment " << k + 1;
}

TEST(LoadPathStepping, ACutBackIncrementResumesFromTheLastConvergedTime)
{
    // The first attempt to reach t = 1.5 fails (as a diverging Newton would); the
    // increment 1 -> 1.5 is halved and retried from t = 1, and the path goes on to
    // T = 2 with the same solution u = a(t) as without the cutback.
    const Amplitude a({{0.0, 0.0}, {1.0, 1.0}, {2.0, 0.0}});
    const NonlinearSystem plain = following(a);
    bool failed_once = false;
    NonlinearSystem failing = plain;
    failing.evaluate = [&](const Vector& u, double t, bool need_tangent, Evaluation& out) {
        if (t == 1.5 && !failed_once) {
            failed_once = true;
            out.ok = false;
            out.message = "diverged";
            return;
        }
        plain.evaluate(u, t, need_tangent, out);
    };
    SteppingSettings stepping;
    stepping.path = load_path({a});
    stepping.count = 4;
    NewtonSettings newton;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    std::vector<double> converged;
    SteppingCallbacks callbacks;
    callbacks.converged = [&](const IncrementRecord& r, const Vector& u) {
        converged.push_back(r.load_factor);
        EXPECT_TRUE(test::near(u(0), a(r.load_factor), solution_tolerance)) << "t = " << r.load_factor;
    };
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(failing, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_EQ(result.total_cutbacks, 1);
    ASSERT_GE(converged.size(), 3u);
    EXPECT_EQ(converged[0], 0.5);
    EXPECT_EQ(converged[1], 1.0);
    EXPECT_EQ(converged[2], 1.25) << "the cut increment starts again at t = 1";
    EXPECT_EQ(converged.back(), 2.0);
    EXPECT_TRUE(failed_once);
    EXPECT_TRUE(test::near(u(0), 0.0, solution_tolerance));
}

TEST(LoadPathStepping, AHalvedIncrementEndingOnABreakpointIsHalvedFromItsTrueLength)
{
    // The planned increment is 0.5 but the one tried ends on the breakpoint 0.2 (length
    // 0.2): its cutback tries 0.1, not 0.25, which would end on 0.2 again.
    const Amplitude a({{0.0, 0.0}, {0.2, 1.0}, {1.0, 1.0}});
    const NonlinearSystem plain = following(a);
    bool failed_once = false;
    NonlinearSystem failing = plain;
    failing.evaluate = [&](const Vector& u, double t, bool need_tangent, Evaluation& out) {
        if (t == 0.2 && !failed_once) {
            failed_once = true;
            out.ok = false;
            out.message = "diverged";
            return;
        }
        plain.evaluate(u, t, need_tangent, out);
    };
    SteppingSettings stepping;
    stepping.path = load_path({a});
    stepping.count = 2;
    NewtonSettings newton;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    SteppingCallbacks callbacks;
    Vector u = Vector::Zero(1);
    const SteppingResult result = run_load_steps(failing, u, stepping, newton, solver, callbacks, nullptr);
    ASSERT_TRUE(result.completed) << result.message;
    EXPECT_EQ(result.total_cutbacks, 1);
    const std::vector<double> t = times_of(result);
    ASSERT_GE(t.size(), 3u);
    EXPECT_EQ(t[0], 0.1);
    EXPECT_EQ(t[1], 0.2);
    EXPECT_EQ(t.back(), 1.0);
}

}  // namespace
}  // namespace iga::solver
