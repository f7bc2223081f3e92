// Tests for solver/newton.hpp on small algebraic systems with exact tangents:
// quadratic convergence, line search, trust-radius cap, singular tangents at
// first contact, linear systems, failure statuses and the restored state.

#include "solver/failure_cause.hpp"
#include "solver/newton.hpp"
#include "solver/suitesparse_solver.hpp"
#include "core/parallel.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

SparseMatrix sparse(const Matrix& dense)
{
    return dense.sparseView();
}

// The smallest convergence target the default tolerance 1e-10 guarantees is
// ||u - u*|| <= ||K^-1|| * 1e-10 * scale; for the O(1) problems below that is
// <= 1e-9, and Newton's last quadratic step usually lands far below it.
constexpr double solution_tolerance = 1e-8;

// ---------------------------------------------------------------------------
// r(u) = A u + c u.^3 - lambda f, A = tridiag(-1, 4, -1) (SPD, lambda_min >= 2),
// with f chosen so that u* is the exact solution at lambda = 1.
struct CubicSystem {
    Matrix A;
    double c = 1.0;
    Vector u_star;
    Vector f;
    double tangent_factor = 1.0;  // != 1: a deliberately wrong tangent
    std::vector<Vector> evaluated;

    CubicSystem()
    {
        const int n = 4;
        A = Matrix::Zero(n, n);
        for (int i = 0; i < n; ++i) {
            A(i, i) = 4.0;
            if (i + 1 < n)
                A(i, i + 1) = A(i + 1, i) = -1.0;
        }
        u_star.resize(n);
        u_star << 1.0, -0.5, 2.0, 0.3;
        f = A * u_star + c * u_star.array().cube().matrix();
    }

    NonlinearSystem system()
    {
        NonlinearSystem s;
        s.evaluate = [this](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
            evaluated.push_back(u);
            out.residual = A * u + c * u.array().cube().matrix() - lambda * f;
            out.force_scale = lambda * f.norm();
            if (need_tangent) {
                Matrix K = A;
                K.diagonal() += 3.0 * c * u.array().square().matrix();
                out.tangent = sparse(tangent_factor * K);
            }
        };
        return s;
    }
};

// Exact Taylor expansion of the cubic: e_{k+1} = K(u_k)^-1 [3c u_k e_k^2 + c e_k^3]
// componentwise, with ||K^-1||_2 <= 1/lambda_min(A) (3c u^2 >= 0 only adds), so
// ||e_{k+1}|| <= C_k ||e_k||^2 with C_k = (3c ||u_k||_inf + c ||e_k||_inf) / lambda_min(A):
// a bound, not a fit.
double quadratic_bound(const CubicSystem& cubic, const Vector& u_k)
{
    constexpr double lambda_min_A = 2.0;  // Gershgorin for tridiag(-1, 4, -1): >= 4 - 2
    const Vector e = u_k - cubic.u_star;
    return (3.0 * cubic.c * u_k.lpNorm<Eigen::Infinity>() + cubic.c * e.lpNorm<Eigen::Infinity>()) / lambda_min_A;
}

// Below 1e-12 the error is round-off, no longer Newton's.
constexpr double round_off_floor = 1e-12;

TEST(Newton, ConvergesQuadraticallyWithExactTangent)
{
    CubicSystem cubic;
    NonlinearSystem system = cubic.system();
    NewtonSettings settings;
    settings.line_search = false;  // every evaluation is then a Newton iterate
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, settings, solver, nullptr);

    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_TRUE(test::at_most((u - cubic.u_star).norm(), solution_tolerance));
    ASSERT_EQ(static_cast<int>(report.residual_history.size()), report.iterations + 1);
    ASSERT_EQ(cubic.evaluated.size(), report.residual_history.size());

    // The bound holds exactly up to the rounding of the iterates.
    constexpr double bound_slack = 1.0 + 1e-9;
    // "Asymptotic regime": errors this small, where only the quadratic term matters.
    constexpr double asymptotic_error = 1e-2;
    int checked = 0, asymptotic = 0;
    for (std::size_t k = 0; k + 1 < cubic.evaluated.size(); ++k) {
        const double e = (cubic.evaluated[k] - cubic.u_star).norm();
        const double e_next = (cubic.evaluated[k + 1] - cubic.u_star).norm();
        if (e_next < round_off_floor)
            break;
        EXPECT_TRUE(test::at_most(e_next / (e * e), bound_slack * quadratic_bound(cubic, cubic.evaluated[k])))
            << "iteration " << k;
        ++checked;
        if (e < asymptotic_error)
            ++asymptotic;
    }
    EXPECT_GE(checked, 3);
    EXPECT_GE(asymptotic, 1) << "the test must reach the asymptotic regime above round-off";
}

TEST(Newton, WrongTangentIsCaughtByTheQuadraticBound)
{
    // Control for the test above: a tangent scaled by 1.3 converges only
    // linearly (rate ~0.23), which must violate e_{k+1} <= C e_k^2 once e_k is small.
    CubicSystem cubic;
    cubic.tangent_factor = 1.3;
    NonlinearSystem system = cubic.system();
    NewtonSettings settings;
    settings.line_search = false;
    settings.max_iterations = 60;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, settings, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    bool violated = false;
    for (std::size_t k = 0; k + 1 < cubic.evaluated.size(); ++k) {
        const double e = (cubic.evaluated[k] - cubic.u_star).norm();
        const double e_next = (cubic.evaluated[k + 1] - cubic.u_star).norm();
        if (e_next > round_off_floor && e_next > quadratic_bound(cubic, cubic.evaluated[k]) * e * e)
            violated = true;
    }
    EXPECT_TRUE(violated);
}

TEST(Newton, AlreadyConvergedStartTakesNoIteration)
{
    CubicSystem cubic;
    NonlinearSystem system = cubic.system();
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = cubic.u_star;
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    EXPECT_EQ(report.status, NewtonStatus::converged);
    EXPECT_EQ(report.iterations, 0);
    EXPECT_EQ(cubic.evaluated.size(), 1u);
    EXPECT_EQ(solver.n_numeric(), 0);
}

TEST(Newton, RecordsTimersAndIterationCount)
{
    CubicSystem cubic;
    NonlinearSystem system = cubic.system();
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    RunContext context;
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, &context);
    ASSERT_EQ(report.status, NewtonStatus::converged);
    EXPECT_EQ(context.count("newton_iterations"), report.iterations);
    EXPECT_EQ(context.timers().count("assembly"), 1u);
    EXPECT_EQ(context.timers().count("linear_solve"), 1u);
    EXPECT_EQ(solver.n_symbolic(), 1) << "the tangent pattern never changes here";
    EXPECT_EQ(solver.n_numeric(), report.iterations);
}

// ---------------------------------------------------------------------------
// r(u) = atan(u - shift): plain Newton diverges when started more than ~1.39 from the root.
NonlinearSystem arctan_system(double shift, std::vector<double>* evaluated = nullptr,
                              double fail_below = -std::numeric_limits<double>::infinity())
{
    NonlinearSystem system;
    system.evaluate = [=](const Vector& u, double, bool need_tangent, Evaluation& out) {
        if (evaluated)
            evaluated->push_back(u(0));
        if (u(0) < fail_below) {
            out.ok = false;
            out.message = "projection left the patch";
            return;
        }
        out.residual = Vector::Constant(1, std::atan(u(0) - shift));
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = sparse(Matrix::Constant(1, 1, 1.0 / (1.0 + (u(0) - shift) * (u(0) - shift))));
    };
    return system;
}

TEST(Newton, LineSearchRescuesOvershootingStep)
{
    const double shift = 1.0;
    const Vector start = Vector::Constant(1, shift + 4.0);
    NewtonSettings settings;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);

    Vector u = start;
    settings.line_search = false;
    const NewtonReport plain = solve_newton(arctan_system(shift), 1.0, u, settings, solver, nullptr);
    EXPECT_NE(plain.status, NewtonStatus::converged);
    EXPECT_EQ(u(0), start(0)) << "a failed solve restores u";

    settings.line_search = true;
    const NewtonReport searched = solve_newton(arctan_system(shift), 1.0, u, settings, solver, nullptr);
    ASSERT_EQ(searched.status, NewtonStatus::converged) << searched.message;
    EXPECT_GT(searched.line_search_cuts, 0);
    EXPECT_TRUE(test::near(u(0), shift, solution_tolerance));
    // Armijo backtracking on ||r||: the residual decreases monotonically.
    for (std::size_t k = 1; k < searched.residual_history.size(); ++k)
        EXPECT_LT(searched.residual_history[k], searched.residual_history[k - 1]) << "iteration " << k;
}

TEST(Newton, FailedEvaluationAtATrialPointIsBacktracked)
{
    // From u = 3 the full step lands at -9.5, where evaluate() fails (think: the
    // projection leaves the patch); the line search must treat it as rejected.
    Vector u = Vector::Constant(1, 3.0);
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    NewtonSettings settings;
    const NewtonReport report = solve_newton(arctan_system(0.0, nullptr, -5.0), 1.0, u, settings, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_TRUE(test::near(u(0), 0.0, solution_tolerance));

    settings.line_search = false;
    u(0) = 3.0;
    const NewtonReport plain = solve_newton(arctan_system(0.0, nullptr, -5.0), 1.0, u, settings, solver, nullptr);
    EXPECT_EQ(plain.status, NewtonStatus::evaluation_failed);
    EXPECT_NE(plain.message.find("projection left the patch"), std::string::npos) << plain.message;
    EXPECT_EQ(u(0), 3.0);
}

TEST(Newton, EvaluationFailureAtStartIsReported)
{
    Vector u = Vector::Constant(1, -10.0);
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    const NewtonReport report =
        solve_newton(arctan_system(0.0, nullptr, -5.0), 1.0, u, NewtonSettings{}, solver, nullptr);
    EXPECT_EQ(report.status, NewtonStatus::evaluation_failed);
    EXPECT_NE(report.message.find("projection left the patch"), std::string::npos) << report.message;
    EXPECT_EQ(u(0), -10.0);
}

TEST(Newton, NonFiniteResidualNeverEntersTheState)
{
    // r(u) = log(u) - 1: the full step from u = 10 lands at u < 0, where r is NaN.
    NonlinearSystem system;
    system.evaluate = [](const Vector& u, double, bool need_tangent, Evaluation& out) {
        out.residual = Vector::Constant(1, std::log(u(0)) - 1.0);
        out.force_scale = 1.0;
        if (need_tangent)
            out.tangent = sparse(Matrix::Constant(1, 1, 1.0 / u(0)));
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    NewtonSettings settings;
    Vector u = Vector::Constant(1, 10.0);
    const NewtonReport searched = solve_newton(system, 1.0, u, settings, solver, nullptr);
    ASSERT_EQ(searched.status, NewtonStatus::converged) << searched.message;
    EXPECT_TRUE(test::near(u(0), std::exp(1.0), solution_tolerance));

    settings.line_search = false;
    u(0) = 10.0;
    const NewtonReport plain = solve_newton(system, 1.0, u, settings, solver, nullptr);
    EXPECT_EQ(plain.status, NewtonStatus::diverged);
    EXPECT_EQ(u(0), 10.0);
}

/// Newton without a line search on r(u) = u - target (affine, solved as nonlinear) from
/// u = 0 with the trust radius 1; `evaluated` records every state it evaluates.
NewtonReport solve_capped_shift(double target, std::vector<double>& evaluated, Vector& u)
{
    NonlinearSystem system;
    system.max_step = 1.0;
    system.evaluate = [&evaluated, target](const Vector& v, double, bool need_tangent, Evaluation& out) {
        evaluated.push_back(v(0));
        out.residual = Vector::Constant(1, v(0) - target);
        out.force_scale = target;
        if (need_tangent)
            out.tangent = sparse(Matrix::Identity(1, 1));
    };
    NewtonSettings settings;
    settings.line_search = false;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    u = Vector::Zero(1);
    return solve_newton(system, 1.0, u, settings, solver, nullptr);
}

TEST(Newton, MaxStepCapsTheUpdate)
{
    // r(u) = u - 10: with a trust radius of 1 and no line search, the iterates are
    // exactly 1, 2, ..., 10 (each step removes at least 10 % of ||r||: the radius keeps).
    std::vector<double> evaluated;
    Vector u;
    const NewtonReport report = solve_capped_shift(10.0, evaluated, u);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_EQ(report.iterations, 10);
    ASSERT_EQ(evaluated.size(), 11u);
    for (int k = 0; k <= 10; ++k)
        EXPECT_EQ(evaluated[k], static_cast<double>(k));
}

TEST(Newton, ATrustRadiusThatStallsNewtonGrows)
{
    // r(u) = u - 1000 with a trust radius of 1: each capped step removes a thousandth of
    // ||r||, so at the radius Newton would need 1000 iterations. A capped full step that
    // leaves ||r|| above 0.9 of the last doubles the radius: the first step is still 1
    // (the cap holds where it was set), then the radius grows until the steps make
    // progress, and Newton converges well within its 25 iterations. (MaxStepCapsTheUpdate
    // is the other side: steps that reduce ||r|| by 10 % or more keep the radius.)
    std::vector<double> evaluated;
    Vector u;
    const NewtonReport report = solve_capped_shift(1000.0, evaluated, u);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    ASSERT_GE(evaluated.size(), 3u);
    EXPECT_EQ(evaluated[1], 1.0);
    EXPECT_EQ(evaluated[2], 3.0);  // the radius doubled once
    // Doubling from 1 to the ~100 at which a step removes 10 % takes 7 iterations.
    EXPECT_GE(report.iterations, 7);
    EXPECT_LE(report.iterations, 20);
    EXPECT_TRUE(test::near(u(0), 1000.0, solution_tolerance * 1000.0));
}

// ---------------------------------------------------------------------------
// First touch: one dof, r(u) = k <u - gap>_+ - lambda f. The tangent k H(u - gap)
// is exactly zero until contact, so the first factorizations are singular.
TEST(Newton, FirstTouchWithZeroTangentConvergesViaRegularization)
{
    const double k = 100.0, gap = 1.0, f = 1.0;
    std::vector<double> evaluated;
    NonlinearSystem system;
    system.max_step = 0.4;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        evaluated.push_back(u(0));
        const double penetration = std::max(u(0) - gap, 0.0);
        out.residual = Vector::Constant(1, k * penetration - lambda * f);
        out.force_scale = lambda * f + k * penetration;
        if (need_tangent)
            out.tangent = sparse(Matrix::Constant(1, 1, u(0) > gap ? k : 0.0));
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_GE(report.regularized_iterations, 1);
    // The first (regularized, huge) step is capped at the radius 0.4; across the open gap
    // the residual is flat, a capped step makes no progress and the radius doubles, so the
    // gap of 1 takes two steps (0.4, then 0.8) where a fixed radius took three.
    ASSERT_GE(evaluated.size(), 2u);
    EXPECT_EQ(evaluated[1], 0.4);
    EXPECT_GE(report.iterations, 2);
    EXPECT_TRUE(test::near(u(0), gap + f / k, solution_tolerance));
}

// A soft spring k pushed by f onto a stiff Hertz-like contact C <u - g>^(3/2) at
// a small gap g (the force of a growing contact zone, as for a sphere): the Newton
// step of the contact-free start, du = f / k, overshoots the root of the
// directional residual s(alpha) = du r(alpha du) nearly a thousandfold, and s
// climbs from -1 to +1e6 along the step. Regula falsi (even Illinois) creeps from
// the left end and runs out of its 12 evaluations; with the bisection safeguard the
// first step lands where the forces balance along du (|s| <= 0.1 |s(0)|, the
// search's acceptance) instead of backtracking on ||r||.
TEST(Newton, DirectionalSearchFindsTheRootOfAStronglyCurvedSlope)
{
    const double k = 1.0, f = 1.0, g = 1e-3, C = 1e6;
    NonlinearSystem system;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        const double penetration = std::max(u(0) - g, 0.0);
        const double contact = C * penetration * std::sqrt(penetration);
        out.residual = Vector::Constant(1, k * u(0) + contact - lambda * f);
        out.force_scale = lambda * f + contact;
        if (need_tangent)
            out.tangent = sparse(Matrix::Constant(1, 1, k + 1.5 * C * std::sqrt(penetration)));
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    ASSERT_GE(report.residual_history.size(), 2u);
    constexpr double acceptance = 0.1;  // the search accepts |s(alpha)| <= 0.1 |s(0)| (one dof: s = du r)
    EXPECT_TRUE(test::at_most(report.residual_history[1], acceptance * report.residual_history[0]))
        << "first step: relative residual " << report.residual_history[1];
    // The contact-free tangent is exact up to the gap: u solves k u + C (u - g)^1.5 = f.
    const double pen = u(0) - g;
    EXPECT_TRUE(test::near(k * u(0) + C * pen * std::sqrt(pen), f, solution_tolerance));
}

// Two nodes joined by a spring kb, pushed by f toward a wall at distance gap that
// acts on node 2 through a penalty spring kc. Until contact the tangent has the rigid
// translation [1, 1] as null vector; tell_singular: the evaluation says so.
constexpr double wall_kb = 1e3, wall_kc = 1e4, wall_gap = 0.1, wall_f = 5.0;
NonlinearSystem floating_body_against_a_wall(bool tell_singular)
{
    NonlinearSystem system;
    system.max_step = 0.05;
    system.evaluate = [tell_singular](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        const double kb = wall_kb, kc = wall_kc, gap = wall_gap;
        const double penetration = std::max(u(1) - gap, 0.0);
        out.residual.resize(2);
        out.residual << kb * (u(0) - u(1)) - lambda * wall_f, kb * (u(1) - u(0)) + kc * penetration;
        out.force_scale = lambda * wall_f + kc * penetration;
        if (need_tangent) {
            Matrix K(2, 2);
            K << kb, -kb, -kb, kb + (u(1) > gap ? kc : 0.0);
            out.tangent = sparse(K);
            out.singular_tangent = tell_singular && !(u(1) > gap);
        }
    };
    return system;
}

/// Converged, through a regularized first touch, to node 2 pressed f/kc into the wall
/// and node 1 f/kb behind it.
void expect_wall_equilibrium(const NewtonReport& report, const Vector& u)
{
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_GE(report.regularized_iterations, 1);
    const double u2 = wall_gap + wall_f / wall_kc;
    EXPECT_TRUE(test::near(u(1), u2, solution_tolerance));
    EXPECT_TRUE(test::near(u(0), u2 + wall_f / wall_kb, solution_tolerance));
}

TEST(Newton, FloatingBodyHeldOnlyByContactConverges)
{
    const NonlinearSystem system = floating_body_against_a_wall(false);
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(2);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    expect_wall_equilibrium(report, u);
}

// The calls Newton makes to its linear solver, recorded around a SuiteSparseSolver.
class RecordingSolver final : public LinearSolver {
public:
    RecordingSolver() : inner_(SuiteSparseSolver::Kind::cholesky)
    {
        inner_.set_semidefinite(true);
        inner_.set_updates(true);
    }
    LinearStatus factorize(const SparseMatrix& K) override
    {
        calls.push_back("factorize");
        return inner_.factorize(K);
    }
    LinearStatus factorize_taking(SparseMatrix& K) override
    {
        calls.push_back("factorize");
        return inner_.factorize_taking(K);
    }
    LinearStatus factorize_shifted(double mu) override
    {
        calls.push_back("shift " + text(mu));
        return inner_.factorize_shifted(mu);
    }
    LinearStatus factorize_shifted_taking(SparseMatrix& K, double mu) override
    {
        calls.push_back("shift at once " + text(mu));
        return inner_.factorize_shifted_taking(K, mu);
    }
    LinearStatus solve(const Vector& b, Vector& x) override { return inner_.solve(b, x); }
    LinearStatistics statistics() const override { return inner_.statistics(); }
    std::string describe() const override { return inner_.describe(); }
    bool updated() const override { return inner_.updated(); }

    std::vector<std::string> calls;

private:
    static std::string text(double mu)
    {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%g", mu);
        return buffer;
    }
    SuiteSparseSolver inner_;
};

// The floating body above, whose system knows that its tangent is singular until the
// contact carries (Evaluation::singular_tangent, as analysis/system.hpp sets it at a
// first touch): Newton shifts that tangent at once, from mu = 1e-8, and never has it
// factorized; the shifted factorization then serves the later tangents by updates.
TEST(Newton, AKnownSingularTangentIsShiftedAtOnce)
{
    for (bool known : {true, false}) {
        SCOPED_TRACE(known ? "known singular" : "not told");
        const NonlinearSystem system = floating_body_against_a_wall(known);
        RecordingSolver solver;
        Vector u = Vector::Zero(2);
        const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
        expect_wall_equilibrium(report, u);
        ASSERT_FALSE(solver.calls.empty());
        if (known) {
            EXPECT_EQ(solver.calls.front(), "shift at once 1e-08");
            EXPECT_EQ(std::count(solver.calls.begin(), solver.calls.end(), "shift 1e-10"), 0);
        } else {
            EXPECT_EQ(solver.calls.front(), "factorize") << "without the hint Newton tries K first, as before";
        }
    }
}

// ---------------------------------------------------------------------------
TEST(Newton, LinearSystemIsOneSolve)
{
    CubicSystem cubic;
    int n_tangents = 0, n_residuals = 0;
    NonlinearSystem system;
    system.linear = true;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        ++(need_tangent ? n_tangents : n_residuals);
        out.residual = cubic.A * u - lambda * cubic.f;
        out.force_scale = lambda * cubic.f.norm();
        if (need_tangent)
            out.tangent = sparse(cubic.A);
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Ones(4);  // any start: the affine system is solved exactly
    const NewtonReport report = solve_newton(system, 0.5, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_EQ(report.iterations, 1);
    EXPECT_EQ(n_tangents, 1);
    // The solution's residual checks the solve: r(u + du) = r(u) + K du, no tangent kept.
    EXPECT_EQ(n_residuals, 1);
    EXPECT_EQ(solver.n_numeric(), 1);
    ASSERT_EQ(report.residual_history.size(), 2u);
    EXPECT_TRUE(test::at_most(report.residual_norm, NewtonSettings{}.tolerance));
    const Vector reference = cubic.A.ldlt().solve(0.5 * cubic.f);
    EXPECT_TRUE(test::at_most((u - reference).norm(), solution_tolerance));
}

// r(u) = A u - lambda f, the cubic system's linear part, with force scale
// force_factor * lambda ||f||.
NonlinearSystem affine_system(const CubicSystem& cubic, double force_factor)
{
    NonlinearSystem system;
    system.linear = true;
    system.evaluate = [&cubic, force_factor](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        out.residual = cubic.A * u - lambda * cubic.f;
        out.force_scale = force_factor * lambda * cubic.f.norm();
        if (need_tangent)
            out.tangent = sparse(cubic.A);
    };
    return system;
}

// A solver that solves only as far as it is asked: its solution leaves exactly the
// relative residual `accuracy` (an iterative backend's stopping test, at its limit).
class InexactSolver final : public LinearSolver {
public:
    LinearStatus factorize(const SparseMatrix& K) override
    {
        K_ = Matrix(K);
        return LinearStatus::ok;
    }
    LinearStatus factorize_shifted(double) override { return LinearStatus::failed; }
    LinearStatus solve(const Vector& b, Vector& x) override { return solve_to(b, x, 1e-8); }
    LinearStatus solve_to(const Vector& b, Vector& x, double accuracy) override
    {
        accuracies.push_back(accuracy);
        const Vector e = Vector::LinSpaced(b.size(), 1.0, 2.0);
        x = K_.ldlt().solve(b + accuracy * b.norm() / e.norm() * e);  // K x - b = accuracy ||b|| e / ||e||
        return LinearStatus::ok;
    }
    LinearStatistics statistics() const override { return {}; }
    std::string describe() const override { return "inexact"; }

    std::vector<double> accuracies;

private:
    Matrix K_;
};

// The linear path asks its solver for the residual its tolerance needs (half of it),
// in one solve; asked for less, a Krylov method would stop at its own 1e-8 and need a
// refinement solve, which restarts it.
TEST(Newton, ALinearSystemAsksItsSolverForWhatTheToleranceNeeds)
{
    const CubicSystem cubic;
    const NonlinearSystem system = affine_system(cubic, 2.0);
    InexactSolver solver;
    Vector u = Vector::Zero(4);
    const NewtonSettings settings;
    const NewtonReport report = solve_newton(system, 0.5, u, settings, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    // ||r(0)|| = 0.5 ||f|| = force_scale / 2, so the relative residual asked for is
    // 0.5 * tolerance * force_scale / ||r(0)|| = tolerance.
    ASSERT_EQ(solver.accuracies.size(), 1u) << "one solve, no refinement";
    EXPECT_TRUE(test::near_rel(solver.accuracies[0], settings.tolerance, 1e-12));
    EXPECT_TRUE(test::at_most(report.residual_norm, 0.5 * settings.tolerance * (1 + 1e-6)));
}

// A Krylov method that stops short, shifted or not: Newton says so once, with what the
// solver saw, and does not call the tangent singular (both paths: linear and not).
class StoppingSolver final : public LinearSolver {
public:
    LinearStatus factorize(const SparseMatrix&) override { return LinearStatus::ok; }
    LinearStatus factorize_shifted(double) override { return LinearStatus::ok; }
    LinearStatus solve(const Vector&, Vector&) override { return LinearStatus::not_converged; }
    LinearStatistics statistics() const override { return {}; }
    std::string describe() const override { return "stopping"; }
    std::string failure_detail() const override { return "cg + gamg stopped after 2 iterations: DIVERGED_ITS"; }
};

TEST(Newton, AKrylovSolverThatStopsShortIsReportedAsSuch)
{
    for (bool linear : {true, false}) {
        SCOPED_TRACE(linear ? "linear" : "nonlinear");
        CubicSystem cubic;
        NonlinearSystem system = cubic.system();
        system.linear = linear;
        StoppingSolver solver;
        Vector u = Vector::Zero(4);
        const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
        EXPECT_EQ(report.status, NewtonStatus::linear_solver_not_converged);
        EXPECT_STREQ(status_name(report.status), "linear_solver_not_converged");
        EXPECT_NE(report.message.find("the linear solver did not converge (cg + gamg stopped after 2 iterations"),
                  std::string::npos)
            << report.message;
        EXPECT_EQ(report.message.find("not converged"), std::string::npos) << "said once: " << report.message;
        EXPECT_TRUE(u.isZero(0.0)) << "a failed solve restores u";
    }
}

// A Krylov method that stops short on K and on small shifts but converges on K + 1e-2 I
// (nearly incompressible elasticity under CG + GAMG): refinement with so perturbed a
// matrix cannot reach the tolerance, and the report says that the linear solver
// stopped, not that K is singular or Newton slow.
class ShiftOnlySolver final : public LinearSolver {
public:
    LinearStatus factorize(const SparseMatrix& K) override
    {
        K_ = Matrix(K);
        shifted_ = false;
        return LinearStatus::ok;
    }
    LinearStatus factorize_shifted(double mu) override
    {
        shifted_ = true;
        mu_ = mu;
        return LinearStatus::ok;
    }
    LinearStatus solve(const Vector& b, Vector& x) override
    {
        if (!shifted_ || mu_ < 1e-2)  // the small shifts do not help it either
            return LinearStatus::not_converged;
        const Matrix I = Matrix::Identity(K_.rows(), K_.cols());
        x = (K_ + mu_ * I).ldlt().solve(b);
        return LinearStatus::ok;
    }
    LinearStatistics statistics() const override { return {}; }
    std::string describe() const override { return "shift only"; }
    std::string failure_detail() const override
    {
        return "cg + gamg stopped after 1000 iterations: DIVERGED_ITS";
    }

private:
    Matrix K_;
    bool shifted_ = false;
    double mu_ = 0;
};

TEST(Newton, ALinearSystemSolvedOnlyWithAShiftSaysTheSolverStopped)
{
    const CubicSystem cubic;
    const NonlinearSystem system = affine_system(cubic, 1.0);
    ShiftOnlySolver solver;
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    EXPECT_EQ(report.status, NewtonStatus::linear_solver_not_converged);
    EXPECT_TRUE(report.last_step_regularized);
    EXPECT_TRUE(report.krylov_stopped);
    EXPECT_EQ(failure_cause(report), FailureCause::linear_solver) << "not a free mode: K is regular";
    EXPECT_NE(report.message.find("did not converge (cg + gamg stopped after 1000 iterations"), std::string::npos)
        << report.message;
    EXPECT_NE(report.message.find("on the tangent shifted by mu = "), std::string::npos) << report.message;
}

// A preconditioner that does not fit the tangents (GMRES + GAMG on two cylinders in
// contact, issue 31): Newton stops at the second Krylov solve in a row that stops short
// on the unshifted tangent, instead of crawling on shifted steps; the first such solve
// is a warning that reaches a -q run (Verbosity::quiet) and names what to set.
TEST(Newton, AKrylovSolverThatStopsShortTwiceInARowEndsNewtonWithAWarning)
{
    CubicSystem cubic;
    const NonlinearSystem system = cubic.system();
    ShiftOnlySolver solver;
    std::vector<std::string> lines;
    RunContext context([&](Verbosity, const std::string& line) { lines.push_back(line); }, Verbosity::quiet);
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, &context);
    EXPECT_EQ(report.status, NewtonStatus::linear_solver_not_converged) << report.message;
    EXPECT_NE(report.message.find("iteration 2: the linear solver did not converge on 2 tangents in a row (cg + gamg"),
              std::string::npos)
        << report.message;
    EXPECT_EQ(failure_cause(report), FailureCause::linear_solver);
    ASSERT_EQ(lines.size(), 1u) << "one warning, however many solves stop";
    EXPECT_EQ(lines[0].rfind("warning: the iterative linear solver did not converge (cg + gamg", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find("solver.type: direct"), std::string::npos) << lines[0];
    EXPECT_EQ(context.count("krylov_stops"), 2);
}

TEST(Newton, InconsistentSingularLinearSystemFails)
{
    // Floating spring pushed along its rigid mode: no solution exists.
    NonlinearSystem system;
    system.linear = true;
    system.evaluate = [](const Vector& u, double lambda, bool, Evaluation& out) {
        Matrix K(2, 2);
        K << 1, -1, -1, 1;
        out.residual = K * u - lambda * Vector::Ones(2);
        out.force_scale = lambda * std::sqrt(2.0);
        out.tangent = sparse(K);
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    Vector u = Vector::Zero(2);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    EXPECT_NE(report.status, NewtonStatus::converged);
    EXPECT_TRUE(u.isZero(0.0)) << "a failed solve restores u";
    EXPECT_FALSE(report.message.empty());
}

TEST(Newton, NonSymmetricSystemGetsLuFromThePolicy)
{
    Matrix K(2, 2);
    K << 2, 1, 0, 3;
    const Vector f(Vector::Ones(2));
    NonlinearSystem system;
    system.symmetric = false;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        out.residual = K * u - lambda * f;
        out.force_scale = lambda * f.norm();
        if (need_tangent)
            out.tangent = sparse(K);
    };
    // The choice lives in one place (the table, solver/backends.cpp): Cholesky reads one
    // triangle and would solve another system.
    LinearSolverPolicy policy;
    policy.symmetric = system.symmetric;
    const std::unique_ptr<LinearSolver> solver = make_linear_solver(policy, Communicator());
    EXPECT_NE(solver->describe().find("UMFPACK LU"), std::string::npos) << solver->describe();
    Vector u = Vector::Zero(2);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, *solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_TRUE(test::at_most((u - K.partialPivLu().solve(f)).norm(), solution_tolerance));
}

TEST(Newton, IndefiniteTangentIsFactorizedByLu)
{
    Matrix K(2, 2);
    K << 1, 0, 0, -2;  // symmetric, indefinite
    const Vector f(Vector::Ones(2));
    NonlinearSystem system;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        out.residual = K * u - lambda * f;
        out.force_scale = lambda * f.norm();
        if (need_tangent)
            out.tangent = sparse(K);
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(2);
    const NewtonReport report = solve_newton(system, 1.0, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::lu);
    EXPECT_GE(solver.n_cholesky_fallbacks(), 1);
    EXPECT_EQ(report.regularized_iterations, 0);
    EXPECT_TRUE(test::near(u(1), -0.5, solution_tolerance));
}

TEST(Newton, MaxIterationsReportsTheLastResidual)
{
    CubicSystem cubic;
    NonlinearSystem system = cubic.system();
    NewtonSettings settings;
    settings.max_iterations = 2;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(4);
    const NewtonReport report = solve_newton(system, 1.0, u, settings, solver, nullptr);
    EXPECT_EQ(report.status, NewtonStatus::max_iterations);
    EXPECT_EQ(report.iterations, 2);
    EXPECT_TRUE(u.isZero(0.0));
    EXPECT_NE(report.message.find("tolerance 1e-10"), std::string::npos) << report.message;
}

// A stress-free rigid motion imposed by Dirichlet values (a block slid along a
// plane at gap 0, verification/hard/grazing_plane.yaml): a free chain of springs
// whose node 0 is moved by lambda d. The solution is the rigid translation and
// every force, the reaction included, is round-off of K u: the force scale falls
// with the residual and the relative residual stays O(1). Newton must recognise
// the zero-force state (it used to fail with max_iterations).
TEST(Newton, ZeroForceSolutionConvergesAtRoundOff)
{
    // Spring stiffnesses chosen so that the row sums of K are not exactly 0 in
    // floating point (0.1 + 0.7 - 0.1 - 0.7 = -1.1e-16): round-off, as in assembly.
    const std::vector<double> k = {100.0, 700.0, 1000.0 / 3.0, 2900.0, 0.1};
    const int n_nodes = static_cast<int>(k.size()) + 1;
    Matrix K_full = Matrix::Zero(n_nodes, n_nodes);
    for (int e = 0; e + 1 < n_nodes; ++e) {
        K_full(e, e) += k[e];
        K_full(e + 1, e + 1) += k[e];
        K_full(e, e + 1) -= k[e];
        K_full(e + 1, e) -= k[e];
    }
    const double d = 0.3;  // prescribed displacement of node 0 at lambda = 1
    NonlinearSystem system;
    system.evaluate = [&](const Vector& u, double lambda, bool need_tangent, Evaluation& out) {
        Vector u_full(n_nodes);
        u_full << lambda * d, u;
        const Vector f_full = K_full * u_full;        // internal forces, reaction at node 0
        out.residual = f_full.tail(n_nodes - 1);
        out.force_scale = f_full.norm();              // no external load: only f_int and the reaction
        // Its round-off: eps_mach |K| |u| on the free rows (the system's contract).
        out.residual_floor =
            std::numeric_limits<double>::epsilon() * (K_full.cwiseAbs() * u_full.cwiseAbs()).tail(n_nodes - 1).norm();
        if (need_tangent)
            out.tangent = sparse(K_full.bottomRightCorner(n_nodes - 1, n_nodes - 1));
    };
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(n_nodes - 1);
    const double lambda = 0.37;
    const NewtonReport report = solve_newton(system, lambda, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    for (int i = 0; i < n_nodes - 1; ++i)
        EXPECT_TRUE(test::near(u(i), lambda * d, solution_tolerance)) << i;
}

// ---------------------------------------------------------------------------
// The round-off floor. One spring, r(u) = k (u - u*), whose residual can only be
// computed to a resolution q, the way a sum with round-off q can: the value is
// rounded to the middle of its q-wide bin, so |r| >= q/2 whatever u, and no
// Newton step can reduce it further. The system reports `reported_floor` as its
// round-off estimate. Force scale 1.
struct QuantizedSpring {
    double k = 1.0;
    double u_star = 1.0;
    double q = 0.0;
    double reported_floor = 0.0;

    NonlinearSystem system()
    {
        NonlinearSystem s;
        s.evaluate = [this](const Vector& u, double, bool need_tangent, Evaluation& out) {
            const double exact = k * (u(0) - u_star);
            out.residual = Vector::Constant(1, q * (std::floor(exact / q) + 0.5));
            out.force_scale = 1.0;
            out.residual_floor = reported_floor;
            if (need_tangent)
                out.tangent = sparse(Matrix::Constant(1, 1, k));
        };
        return s;
    }
};

// Resolution 1e-10 of the force: the relative residual cannot fall below 5e-11, above
// the tolerance 1e-14 by more than the factor 1e3 the previous round-off rule allowed.
// Told that floor, Newton converges once the correction (q/2k = 5e-11 of u) settles.
TEST(Newton, ResidualAtItsRoundOffFloorConverges)
{
    QuantizedSpring spring;
    spring.q = 1e-10;
    spring.reported_floor = spring.q;
    NonlinearSystem system = spring.system();
    NewtonSettings settings;
    settings.tolerance = 1e-14;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(system, 1.0, u, settings, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_NE(report.message.find("round-off floor"), std::string::npos) << report.message;
    // The state is the solution to the resolution over the stiffness, q / k.
    EXPECT_TRUE(test::near(u(0), spring.u_star, spring.q / spring.k)) << u(0) - spring.u_star;
}

// The same spring, but the system says its round-off is 1e6 times smaller: the
// residual 5e-11 is then an unconverged state, however small the Newton step, and
// is not accepted (the previous rule, 1e3 x tolerance with a small step, took it).
TEST(Newton, LargeResidualWithSmallStepIsNotAccepted)
{
    QuantizedSpring spring;
    spring.q = 1e-10;
    spring.reported_floor = 1e-6 * spring.q;
    NonlinearSystem system = spring.system();
    NewtonSettings settings;
    settings.tolerance = 1e-12;
    settings.max_iterations = 8;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(system, 1.0, u, settings, solver, nullptr);
    EXPECT_EQ(report.status, NewtonStatus::max_iterations) << report.message;
    EXPECT_TRUE(u.isZero(0.0)) << "a failed solve restores u";
}

// ---------------------------------------------------------------------------
// A contact point with no equilibrium in either of its states (docs/solver.md, "A
// point held open"): its gap u (penetration > 0) obeys r(u) = u - g_free + kappa <u>
// with kappa = -2, as the reduced equation of a frictional point whose own friction
// drives it in. Pressed (u > 0) the root of that branch, g_free / (1 + kappa) < 0, is
// open; open, the root g_free > 0 is pressed: Newton alternates between the two.
// Held open, r = u - g_free has its root at the penetration g_free, without force.
struct PointWithoutEquilibrium {
    double g_free = 1e-3;
    double kappa = -2.0;
    bool held = false;
    int hold_requests = 0;

    NonlinearSystem system(bool can_hold)
    {
        NonlinearSystem s;
        s.evaluate = [this](const Vector& u, double, bool need_tangent, Evaluation& out) {
            const bool pressed = !held && u(0) > 0.0;
            out.residual = Vector::Constant(1, u(0) - g_free + (pressed ? kappa * u(0) : 0.0));
            out.force_scale = 1.0;
            out.contact_active = {static_cast<std::uint8_t>(pressed ? 1 : 0)};
            if (need_tangent)
                out.tangent = sparse(Matrix::Constant(1, 1, 1.0 + (pressed ? kappa : 0.0)));
        };
        s.symmetric = false;
        if (can_hold)
            s.hold_open = [this](const std::vector<int>& points) {
                ++hold_requests;
                EXPECT_EQ(points, std::vector<int>{0});
                held = true;
                return 1;
            };
        return s;
    }
};

TEST(Newton, APointThatPressesAndOpensInTurnCyclesUnlessHeld)
{
    PointWithoutEquilibrium point;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(point.system(false), 1.0, u, NewtonSettings{}, solver, nullptr);
    EXPECT_NE(report.status, NewtonStatus::converged);
    EXPECT_EQ(report.held_open, 0);
}

TEST(Newton, APointThatPressesAndOpensInTurnIsHeldOpenAndNewtonConverges)
{
    PointWithoutEquilibrium point;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    Vector u = Vector::Zero(1);
    const NewtonReport report = solve_newton(point.system(true), 1.0, u, NewtonSettings{}, solver, nullptr);
    ASSERT_EQ(report.status, NewtonStatus::converged) << report.message;
    EXPECT_EQ(point.hold_requests, 1);
    EXPECT_EQ(report.held_open, 1);
    // Asked after the first A, B, A, B of four accepted states, then one linear step.
    EXPECT_LE(report.iterations, 6);
    EXPECT_NEAR(u(0), point.g_free, 1e-12);  // the penetration the held point is left with
}

}  // namespace
}  // namespace iga::solver
