// Tests for solver/petsc_solver.hpp on one rank (the MPI runs are verification/mpi)
// beyond the contract every backend meets (linear_backends_test.cpp): what a Krylov
// method that stops short or stalls reports, the preconditioner of two-body contact,
// a K known to be singular shifted without its own factorization, a pattern that grows
// between factorizations, preconditioner reuse, Krylov solves to the accuracy a
// caller asks for, and its options (issue 32): refused in PETSC_OPTIONS before PETSc
// starts, rejected by PETSc at the set-up as bad input, unread ones as warnings.

#include "core/parallel.hpp"
#include "solver/petsc_solver.hpp"
#include "support/random_matrices.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

// Matrices are strictly diagonally dominant (cond ~ 10): a direct solve errs by
// ~cond * eps; a Krylov solve stops at a relative true residual of 1e-8, so its
// error is below cond * 1e-8.
constexpr double direct_tolerance = 1e-12;
constexpr double krylov_tolerance = 1e-6;
constexpr unsigned seed = 20261126;

using test::dominant_matrix;
using test::random_vector;
using test::relative_error;

LinearSolverPolicy petsc_policy(Method method, bool symmetric)
{
    LinearSolverPolicy policy;
    policy.backend = Backend::petsc;
    policy.method = method;
    policy.symmetric = symmetric;
    return policy;
}

struct Case {
    const char* name;
    Method method;
    bool symmetric;
    double tolerance;
};

const Case cases[] = {
    {"MUMPS Cholesky", Method::direct, true, direct_tolerance},
    {"MUMPS LU", Method::direct, false, direct_tolerance},
    {"CG + GAMG", Method::iterative, true, krylov_tolerance},
    {"GMRES + GAMG", Method::iterative, false, krylov_tolerance},
};

TEST(PetscSolver, AKrylovMethodThatStopsShortSaysWhatItSaw)
{
    // Two iterations cannot reach 1e-8 on a 300 x 300 system: the status says the method
    // stopped, not that K is singular, and the detail names the method and PETSc's reason.
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(300, true, rng);
    LinearSolverPolicy policy = petsc_policy(Method::iterative, true);
    policy.options = "-ksp_max_it 2";
    PetscSolver solver(policy, Communicator());
    PetscOptionsClearValue(nullptr, "-ksp_max_it");  // the options database is global: read by now
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    Vector x;
    EXPECT_EQ(solver.solve(random_vector(300, rng), x), LinearStatus::not_converged);
    const std::string detail = solver.failure_detail();
    EXPECT_NE(detail.find("cg + "), std::string::npos) << detail;
    EXPECT_NE(detail.find("after 2 iterations: DIVERGED_ITS"), std::string::npos) << detail;
}

// A K known to be singular (Newton at a first touch) is shifted without being
// factorized first: one factorization, of K + mu D, the same solution as
// factorize() followed by factorize_shifted(), and K is left empty.
TEST(PetscSolver, AKnownSingularMatrixIsShiftedWithoutItsOwnFactorization)
{
    Matrix dense(3, 3);
    dense << 1, -1, 0, -1, 2, -1, 0, -1, 1;
    const Vector b = (Vector(3) << 1, 0, -1).finished();
    const double mu = 1e-2;
    PetscSolver two_steps(petsc_policy(Method::direct, true), Communicator());
    two_steps.factorize(dense.sparseView());
    ASSERT_EQ(two_steps.factorize_shifted(mu), LinearStatus::ok);
    EXPECT_EQ(two_steps.statistics().numeric, 2);
    PetscSolver at_once(petsc_policy(Method::direct, true), Communicator());
    SparseMatrix K = dense.sparseView();
    ASSERT_EQ(at_once.factorize_shifted_taking(K, mu), LinearStatus::ok);
    EXPECT_EQ(at_once.statistics().numeric, 1);
    EXPECT_EQ(K.nonZeros(), 0);
    Vector x_reference, x;
    ASSERT_EQ(two_steps.solve(b, x_reference), LinearStatus::ok);
    ASSERT_EQ(at_once.solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, x_reference), direct_tolerance));
}

TEST(PetscSolver, AGrownPatternIsAssembledAgain)
{
    // A contact coupling extends the pattern between Newton iterations.
    std::mt19937 rng(seed);
    const SparseMatrix small = dominant_matrix(50, true, rng);
    SparseMatrix grown = small;
    grown.coeffRef(0, 49) += 0.5;
    grown.coeffRef(49, 0) += 0.5;
    grown.coeffRef(0, 0) += 1.0;
    grown.coeffRef(49, 49) += 1.0;
    grown.makeCompressed();
    const Vector b = random_vector(50, rng);
    PetscSolver solver(petsc_policy(Method::direct, true), Communicator());
    Vector x;
    for (const SparseMatrix* K : {&small, static_cast<const SparseMatrix*>(&grown), &small}) {
        ASSERT_EQ(solver.factorize(*K), LinearStatus::ok);
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(relative_error(x, Matrix(*K).partialPivLu().solve(b)), direct_tolerance));
    }
    EXPECT_EQ(solver.statistics().symbolic, 3) << "one COO preallocation per pattern change";
}

TEST(PetscSolver, APreconditionerIsReusedWhileItServes)
{
    // Newton's tangents change a little from one iteration to the next: the
    // preconditioner of the first serves the second, and the answer is still the
    // second system's.
    std::mt19937 rng(seed);
    const SparseMatrix K1 = dominant_matrix(400, true, rng);
    SparseMatrix K2 = K1;
    for (int i = 0; i < 400; i += 7)
        K2.coeffRef(i, i) *= 1.01;
    const Vector b = random_vector(400, rng);
    PetscSolver solver(petsc_policy(Method::iterative, true), Communicator());
    Vector x;
    ASSERT_EQ(solver.factorize(K1), LinearStatus::ok);
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    ASSERT_EQ(solver.factorize(K2), LinearStatus::ok);
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    EXPECT_EQ(solver.statistics().numeric, 1) << "the second tangent reuses the first preconditioner";
    EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K2).partialPivLu().solve(b)), krylov_tolerance));
}

// solve_to(): a Krylov method stops at the relative residual the caller asks for
// (Newton's linear path), down to 1e-10; a direct method solves to round-off.
TEST(PetscSolver, AKrylovSolveStopsWhereTheCallerAsks)
{
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        std::mt19937 rng(seed);
        const SparseMatrix K = dominant_matrix(300, c.symmetric, rng);
        const Vector b = random_vector(300, rng);
        PetscSolver solver(petsc_policy(c.method, c.symmetric), Communicator());
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
        auto residual = [&](const Vector& x) { return (K * x - b).norm() / b.norm(); };
        Vector x;
        long long before = solver.statistics().iterations;
        ASSERT_EQ(solver.solve_to(b, x, 1e-3), LinearStatus::ok);
        const long long loose = solver.statistics().iterations - before;
        EXPECT_TRUE(test::at_most(residual(x), c.method == Method::direct ? direct_tolerance : 1e-3));
        before = solver.statistics().iterations;
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        const long long own = solver.statistics().iterations - before;
        EXPECT_TRUE(test::at_most(residual(x), c.method == Method::direct ? direct_tolerance : 1e-8));
        ASSERT_EQ(solver.solve_to(b, x, 1e-14), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(residual(x), c.method == Method::direct ? direct_tolerance : 1e-10))
            << "the floor";
        if (c.method == Method::iterative) {
            EXPECT_LT(loose, own) << "1e-3 takes fewer iterations than the solver's own 1e-8";
        }
    }
}

// A user's -ksp_rtol looser than the backward-error bound 1e-6 is honoured: the solve is
// checked against ten times that tolerance, not rejected for missing 1e-6.
TEST(PetscSolver, AUserToleranceLooserThanTheBoundIsHonoured)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(300, true, rng);
    const Vector b = random_vector(300, rng);
    LinearSolverPolicy policy = petsc_policy(Method::iterative, true);
    policy.options = "-ksp_rtol 1e-4";
    PetscSolver solver(policy, Communicator());
    PetscOptionsClearValue(nullptr, "-ksp_rtol");  // the options database is global: read by now
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    Vector x;
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    const double residual = (K * x - b).norm() / b.norm();
    EXPECT_TRUE(test::at_most(residual, 1e-3)) << "the bound: ten times the tolerance";
    EXPECT_GT(residual, 1e-6) << "a solve that stopped at 1e-4, not one that went on to 1e-8: " << residual;
    ASSERT_EQ(solver.solve_to(b, x, 1e-10), LinearStatus::ok) << "the user's tolerance holds for every solve";
    EXPECT_GT((K * x - b).norm() / b.norm(), 1e-6) << (K * x - b).norm() / b.norm();
}

/// A tangent no multigrid fits: the non-symmetric dominant matrix with the sign of
/// every other diagonal entry flipped (indefinite, as two bodies pressed together by a
/// stiff two-half-pass penalty can make it).
SparseMatrix indefinite_matrix(int n, std::mt19937& rng)
{
    SparseMatrix K = dominant_matrix(n, false, rng);
    for (int i = 0; i < n; i += 2)
        K.coeffRef(i, i) = -K.coeff(i, i);
    K.makeCompressed();
    return K;
}

// Two deformable bodies in two-half-pass contact: GMRES is preconditioned by a MUMPS
// LU (GAMG stalls on such tangents, issue 31), so on one rank it takes one iteration,
// and the deck's options still choose another preconditioner.
TEST(PetscSolver, ATwoBodyContactTangentIsPreconditionedByLu)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = indefinite_matrix(300, rng);
    const Vector b = random_vector(300, rng);
    LinearSolverPolicy policy = petsc_policy(Method::iterative, false);
    policy.two_body_contact = true;
    PetscSolver solver(policy, Communicator());
    EXPECT_EQ(solver.describe_method(), "gmres + lu");
    EXPECT_NE(solver.describe().find("(mumps)"), std::string::npos) << solver.describe();
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    Vector x;
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    EXPECT_LE(solver.statistics().iterations, 2) << "an exact LU: GMRES converges at once";
    EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K).partialPivLu().solve(b)), krylov_tolerance));

    policy.options = "-pc_type jacobi";
    PetscSolver chosen(policy, Communicator());
    PetscOptionsClearValue(nullptr, "-pc_type");  // the options database is global: read by now
    EXPECT_EQ(chosen.describe_method(), "gmres + jacobi") << "the deck's options win";
    // Without two bodies in contact a non-symmetric tangent keeps the multigrid.
    EXPECT_EQ(PetscSolver(petsc_policy(Method::iterative, false), Communicator()).describe_method(), "gmres + gamg");
}

// A Krylov solve that cannot reach its tolerance within the iteration cap at its pace
// stops after about one restart cycle, not at the cap, and says it stalled: GMRES(100)
// without a preconditioner on a 1D Laplacian (cond ~ 1e6) gains little per cycle.
TEST(PetscSolver, AStalledKrylovSolveStopsEarlyAndSaysSo)
{
    const int n = 2000;
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
        entries.emplace_back(i, i, 2.0);
        if (i + 1 < n) {
            entries.emplace_back(i, i + 1, -1.0);
            entries.emplace_back(i + 1, i, -1.0);
        }
    }
    SparseMatrix K(n, n);
    K.setFromTriplets(entries.begin(), entries.end());
    std::mt19937 rng(seed);
    const Vector b = random_vector(n, rng);
    LinearSolverPolicy policy = petsc_policy(Method::iterative, false);
    policy.options = "-pc_type none";
    PetscSolver solver(policy, Communicator());
    PetscOptionsClearValue(nullptr, "-pc_type");
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    Vector x;
    EXPECT_EQ(solver.solve(b, x), LinearStatus::not_converged);
    // One cycle to measure the pace, a few more iterations at most to judge it.
    constexpr long long stall_iterations = 300;
    EXPECT_LE(solver.statistics().iterations, stall_iterations) << "stopped at the cap of 1000";
    const std::string detail = solver.failure_detail();
    EXPECT_NE(detail.find("gmres + none stalled: its residual fell to "), std::string::npos) << detail;
    EXPECT_NE(detail.find("too slowly to reach 1e-08 within 1000"), std::string::npos) << detail;
}

// PETSc and MPI are finalized once, after the last test.
class FinalizeParallel : public ::testing::Environment {
public:
    void TearDown() override { parallel::finalize(); }
};
const auto* const finalize_environment = ::testing::AddGlobalTestEnvironment(new FinalizeParallel);

// Issue 32: PETSC_OPTIONS is checked before PETSc reads it (at its start): an option
// that would make PETSc write a file is bad input of the environment's.
TEST(PetscSolver, ARefusedOptionInTheEnvironmentIsBadInputOfTheEnvironment)
{
    ASSERT_EQ(setenv("PETSC_OPTIONS", "-log_view :results.h5", 1), 0);
    try {
        PetscSolver solver(petsc_policy(Method::direct, true), Communicator());
        ADD_FAILURE() << "-log_view was taken";
    } catch (const PetscOptionsError& e) {
        EXPECT_EQ(e.source(), PetscOptionsSource::environment);
        EXPECT_EQ(e.variable(), "PETSC_OPTIONS");
        EXPECT_NE(std::string(e.what()).find("-log_view :results.h5: makes PETSc write a performance log"),
                  std::string::npos)
            << e.what();
    }
    unsetenv("PETSC_OPTIONS");
    // The deck's own options are checked as well (the deck reader did so first).
    LinearSolverPolicy policy = petsc_policy(Method::direct, true);
    policy.options = "-ksp_view ascii:deck.yaml";
    try {
        PetscSolver solver(policy, Communicator());
        ADD_FAILURE() << "-ksp_view ascii:deck.yaml was taken";
    } catch (const PetscOptionsError& e) {
        EXPECT_EQ(e.source(), PetscOptionsSource::deck);
        EXPECT_NE(std::string(e.what()).find("PETSc would write the file deck.yaml"), std::string::npos) << e.what();
    }
}

// Issue 32: a value PETSc rejects only when it sets up the preconditioner (the type of
// block Jacobi's inner solver) is bad input naming the option, not a singular matrix
// (it was `singular`, and Newton shifted it to the end of its cutbacks).
TEST(PetscSolver, AnOptionRejectedAtTheSetUpIsBadInputNotASingularMatrix)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(50, true, rng);
    LinearSolverPolicy policy = petsc_policy(Method::iterative, true);
    policy.options = "-pc_type bjacobi -sub_pc_type bogus";
    PetscSolver solver(policy, Communicator());
    try {
        const LinearStatus status = solver.factorize(K);
        ADD_FAILURE() << "factorize returned " << status_name(status);
    } catch (const PetscOptionsError& e) {
        EXPECT_EQ(e.source(), PetscOptionsSource::deck);
        EXPECT_NE(std::string(e.what()).find("-sub_pc_type bogus: PETSc rejected it"), std::string::npos) << e.what();
    }
    PetscOptionsClearValue(nullptr, "-pc_type");
    PetscOptionsClearValue(nullptr, "-sub_pc_type");
}

// An option no PETSc object read (misspelt, or not one of this method's) is named in
// the run's warnings once the preconditioner was set up; one that MUMPS read at its
// factorization is not.
TEST(PetscSolver, AnOptionNoSolverReadIsAWarning)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(50, true, rng);
    LinearSolverPolicy policy = petsc_policy(Method::direct, true);
    policy.options = "-ksp_nonexistent_option 3 -mat_mumps_icntl_14 50";
    PetscSolver solver(policy, Communicator());
    EXPECT_TRUE(solver.warnings().empty()) << "before the set-up, unread says nothing";
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    const std::vector<std::string> warnings = solver.warnings();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("-ksp_nonexistent_option (solver.options)"), std::string::npos) << warnings[0];
    EXPECT_EQ(warnings[0].find("icntl_14"), std::string::npos) << warnings[0];
    PetscOptionsClearValue(nullptr, "-ksp_nonexistent_option");
    PetscOptionsClearValue(nullptr, "-mat_mumps_icntl_14");
}

}  // namespace
}  // namespace iga::solver
