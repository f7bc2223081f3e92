// One contract over every linear backend and method this build has (the table of
// solver/backends.hpp; polysolve's `for (s : available_solvers())`): each row's solver,
// made by make_linear_solver as Newton gets it, solves an SPD system to its tolerance,
// a non-symmetric one where the method takes it, refactorizes after a change of values,
// reports a singular matrix by its status, factorizes K + mu D, and counts what it did.
// Backend-specific behaviour stays with its backend: linear_test.cpp (SuiteSparse),
// petsc_solver_test.cpp (PETSc), woodbury_test.cpp (updates).

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/deck_names.hpp"
#include "solver/backends.hpp"
#include "solver/linear.hpp"
#include "support/random_matrices.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <iterator>
#include <limits>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace iga::solver {
namespace {

// The test matrices (support/random_matrices.hpp) are diagonally dominant with
// cond ~ 10: a backward-stable direct solve errs by ~cond * eps ~ 1e-14.
constexpr double direct_tolerance = 1e-12;
// A Krylov method stops at a relative true residual of 1e-8 (petsc_solver.hpp), so
// its error is below cond * 1e-8 ~ 1e-7; 1e-6 leaves a factor 10 for the estimate.
constexpr double krylov_tolerance = 1e-6;
// K + mu D of the two-spring K below at mu = 1e-2: cond ~ 4e2 (eigenvalues 3 ... ~1e-2),
// so a direct solve errs by ~4e2 eps and a Krylov one by ~4e2 * 1e-8.
constexpr double shifted_direct_tolerance = 1e-12;
constexpr double shifted_krylov_tolerance = 1e-5;
constexpr unsigned seed = 20261127;
constexpr int n = 300;  // large enough that a Krylov method iterates, small for a dense reference

using test::dominant_matrix;
using test::random_vector;
using test::relative_error;

std::vector<LinearMethod> available_methods()
{
    std::vector<LinearMethod> rows;
    for (const LinearMethod& m : linear_methods())
        if (m.available())
            rows.push_back(m);
    return rows;
}

/// "MUMPS Cholesky" -> "MUMPS_Cholesky": a test name.
std::string test_name(const ::testing::TestParamInfo<LinearMethod>& info)
{
    std::string name;
    for (const char c : info.param.name)
        if (std::isalnum(static_cast<unsigned char>(c)))
            name += c;
        else if (!name.empty() && name.back() != '_')
            name += '_';
    return name;
}

class LinearBackend : public ::testing::TestWithParam<LinearMethod> {
protected:
    const LinearMethod& row() const { return GetParam(); }
    double tolerance() const { return row().direct() ? direct_tolerance : krylov_tolerance; }
    /// The solver of this row, as make_linear_solver makes it from a policy.
    std::unique_ptr<LinearSolver> make(bool symmetric) const
    {
        LinearSolverPolicy policy;
        policy.backend = row().backend;
        policy.method = row().method;
        policy.symmetric = symmetric;
        return make_linear_solver(policy, Communicator());
    }
    /// Solves K x = b with a fresh solver; returns ||x - x_dense|| / ||x_dense||.
    double solve_error(const SparseMatrix& K, const Vector& b, LinearSolver& solver) const
    {
        Vector x;
        EXPECT_EQ(solver.solve(b, x), LinearStatus::ok);
        return relative_error(x, Matrix(K).partialPivLu().solve(b));
    }
};

TEST_P(LinearBackend, SolvesAnSpdSystemToItsTolerance)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(n, true, rng);
    const Vector b = random_vector(n, rng);
    const auto solver = make(true);
    ASSERT_EQ(solver->factorize(K), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(solve_error(K, b, *solver), tolerance()));
}

TEST_P(LinearBackend, SolvesANonSymmetricSystemWhereTheMethodTakesOne)
{
    if (row().symmetric_only)
        GTEST_SKIP() << row().name << " solves symmetric matrices only (chosen for symmetric tangents)";
    std::mt19937 rng(seed + 1);
    const SparseMatrix K = dominant_matrix(n, false, rng);
    ASSERT_GT((Matrix(K) - Matrix(K).transpose()).norm(), 1.0) << "the test matrix should be non-symmetric";
    const Vector b = random_vector(n, rng);
    const auto solver = make(false);
    ASSERT_EQ(solver->factorize(K), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(solve_error(K, b, *solver), tolerance()));
}

TEST_P(LinearBackend, RefactorizesAfterAChangeOfValues)
{
    std::mt19937 rng(seed + 2);
    SparseMatrix K = dominant_matrix(n, row().symmetric_only, rng);
    const Vector b = random_vector(n, rng);
    const auto solver = make(row().symmetric_only);
    ASSERT_EQ(solver->factorize(K), LinearStatus::ok);
    Vector x;
    ASSERT_EQ(solver->solve(b, x), LinearStatus::ok);
    // New values on the same pattern, still dominant (and symmetric where it was).
    for (Index j = 0; j < K.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(K, j); it; ++it)
            it.valueRef() *= it.row() == it.col() ? 3.0 : 1.0 + 0.5 * ((it.row() + it.col()) % 3);
    ASSERT_EQ(solver->factorize(K), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(solve_error(K, b, *solver), tolerance())) << "the solve must use the new values";
}

TEST_P(LinearBackend, ReportsASingularMatrixByItsStatus)
{
    Matrix dense = Matrix::Identity(4, 4);
    dense(3, 3) = 0.0;  // a zero row and column: singular, the diagonal entry stored
    const SparseMatrix K = dense.sparseView(0.0, -1.0);
    const auto solver = make(row().symmetric_only);
    LinearStatus status = solver->factorize(K);
    Vector x;
    if (status == LinearStatus::ok)
        status = solver->solve(Vector::Ones(4), x);
    // A direct method knows; a Krylov method that stops short may only say that it did.
    if (row().direct()) {
        EXPECT_EQ(status, LinearStatus::singular) << status_name(status);
    } else {
        EXPECT_TRUE(status == LinearStatus::singular || status == LinearStatus::not_converged) << status_name(status);
    }
}

TEST_P(LinearBackend, ANonFiniteEntryFails)
{
    std::mt19937 rng(seed + 3);
    SparseMatrix K = dominant_matrix(20, row().symmetric_only, rng);
    K.coeffRef(3, 3) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(make(row().symmetric_only)->factorize(K), LinearStatus::failed);
}

// A semi-definite K (a free rigid mode of two springs) and its shift K + mu D,
// D = |diag K| (solver/shift.hpp), against the dense solution. The shift is of the last
// factorize()'s K, not of an earlier shifted one; and a K known to be singular may be
// shifted at once (factorize_shifted_taking), which leaves K empty. For CG, whose
// operator is the upper triangle in symmetric blocks beside the preconditioner's whole
// matrix, the shift must reach both, or CG would solve the singular K.
TEST_P(LinearBackend, FactorizesTheShiftedMatrix)
{
    if (!row().shifted)
        GTEST_SKIP() << row().name << " has no shifted factorization";
    Matrix dense(3, 3);
    dense << 1, -1, 0, -1, 2, -1, 0, -1, 1;
    const SparseMatrix K = dense.sparseView();
    const Vector b = (Vector(3) << 1, 0, -1).finished();
    const Matrix D = dense.diagonal().cwiseAbs().asDiagonal();
    const double bound = row().direct() ? shifted_direct_tolerance : shifted_krylov_tolerance;
    const auto solver = make(row().symmetric_only);
    // K is singular, but its status need not say so: a preconditioner may be built on it,
    // and MUMPS LU may meet no exactly zero pivot (b is in K's range, so a solve may even pass).
    solver->factorize(K);
    for (const double mu : {1e-2, 1e-1}) {
        SCOPED_TRACE("mu " + std::to_string(mu));
        ASSERT_EQ(solver->factorize_shifted(mu), LinearStatus::ok);
        Vector x;
        ASSERT_EQ(solver->solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(relative_error(x, (dense + mu * D).partialPivLu().solve(b)), bound));
    }
    SparseMatrix taken = K;
    const auto at_once = make(row().symmetric_only);
    ASSERT_EQ(at_once->factorize_shifted_taking(taken, 1e-2), LinearStatus::ok);
    EXPECT_EQ(taken.nonZeros(), 0) << "K is left empty";
    Vector x;
    ASSERT_EQ(at_once->solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, (dense + 1e-2 * D).partialPivLu().solve(b)), bound));
}

TEST_P(LinearBackend, CountsWhatItDid)
{
    std::mt19937 rng(seed + 4);
    const SparseMatrix K = dominant_matrix(n, row().symmetric_only, rng);
    const Vector b = random_vector(n, rng);
    const auto solver = make(row().symmetric_only);
    Vector x;
    for (const double scale : {1.0, 2.0}) {
        ASSERT_EQ(solver->factorize(SparseMatrix(scale * K)), LinearStatus::ok);
        ASSERT_EQ(solver->solve(b, x), LinearStatus::ok);
    }
    const LinearStatistics s = solver->statistics();
    EXPECT_EQ(s.symbolic, 1) << "one pattern, one analysis";
    if (row().direct()) {
        EXPECT_EQ(s.numeric, 2) << "one factorization per factorize()";
    } else {
        EXPECT_GE(s.numeric, 1) << "a preconditioner set up, perhaps reused";
        EXPECT_LE(s.numeric, 2);
        EXPECT_GT(s.iterations, 0) << "a Krylov method iterates";
    }
    EXPECT_EQ(s.updates, 0) << "no updates asked for";
    EXPECT_EQ(s.cholesky_fallbacks, 0) << "nothing refused";
    EXPECT_FALSE(solver->describe().empty());
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, LinearBackend, ::testing::ValuesIn(available_methods()), test_name);

// The deck reader (io/deck_reader.cpp) may not link solver/: its spellings of
// solver.backend and its rule "type iterative needs backend petsc" must agree with
// the table.
TEST(LinearBackendTable, TheDeckSpellsEveryBackendOfTheTable)
{
    for (const auto& entry : io::DeckNames<io::SolverBackend>::all)
        EXPECT_TRUE(backend_named(entry.name).has_value()) << entry.name;
    for (const LinearMethod& m : linear_methods()) {
        bool spelled = false;
        for (const auto& entry : io::DeckNames<io::SolverBackend>::all)
            spelled = spelled || entry.name == m.backend_name;
        EXPECT_TRUE(spelled) << m.backend_name << " has no deck spelling (io/deck_names.hpp)";
    }
    for (const bool symmetric : {true, false}) {
        EXPECT_EQ(find_linear_method(Backend::suitesparse, Method::iterative, symmetric), nullptr)
            << "the reader rejects type iterative with backend suitesparse";
        EXPECT_NE(find_linear_method(Backend::petsc, Method::iterative, symmetric), nullptr);
        for (const Backend backend : {Backend::suitesparse, Backend::petsc})
            EXPECT_NE(find_linear_method(backend, Method::direct, symmetric), nullptr);
    }
}

// docs/solver.md "Linear solvers" shows the table: one line per row, as written here.
TEST(LinearBackendTable, TheDocsShowTheTable)
{
    std::ifstream file(std::string(IGA_SOURCE_DIR) + "/docs/solver.md");
    ASSERT_TRUE(file.good());
    const std::string docs((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    for (const LinearMethod& m : linear_methods()) {
        const std::string line = "| `" + std::string(m.backend_name) + "` | `" +
                                 (m.direct() ? "direct" : "iterative") + "` | " + std::string(m.name) + " | " +
                                 (m.symmetric_only ? "symmetric" : "any") + " | " +
                                 (m.distributed ? "any number" : "one") + " | " +
                                 (m.woodbury_updates ? "yes" : "no") + " | " + (m.shifted ? "yes" : "no") + " |";
        EXPECT_NE(docs.find(line), std::string::npos) << "docs/solver.md lacks the row\n" << line;
    }
}

TEST(LinearBackendTable, TheDefaultBackendIsAlwaysBuiltAndOnlyPetscIsDistributed)
{
    EXPECT_EQ(linear_methods().front().backend, Backend::suitesparse);
    EXPECT_TRUE(backend_available(Backend::suitesparse));
    EXPECT_FALSE(backend_distributed(Backend::suitesparse));
    EXPECT_EQ(distributed_backend(), Backend::petsc);
#ifdef IGACONTACT_HAVE_PETSC
    EXPECT_EQ(available_backends(), "suitesparse, petsc");
#else
    EXPECT_EQ(available_backends(), "suitesparse");
#endif
}

TEST(LinearBackendTable, APolicyTheTableCannotServeIsAnError)
{
    LinearSolverPolicy policy;
    policy.method = Method::iterative;  // suitesparse has no iterative method
    EXPECT_THROW(make_linear_solver(policy, Communicator()), Error);
#ifndef IGACONTACT_HAVE_PETSC
    policy.backend = Backend::petsc;
    policy.method = Method::direct;
    EXPECT_THROW(make_linear_solver(policy, Communicator()), Error);
#endif
}

}  // namespace

/// A row in a test's name and messages: its method.
void PrintTo(const LinearMethod& m, std::ostream* os)
{
    *os << m.backend_name << " " << m.name;
}

}  // namespace iga::solver
