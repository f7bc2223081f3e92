// Tests for solver/suitesparse_solver.hpp beyond the contract every backend meets
// (linear_backends_test.cpp): Cholesky's fallback to LU and its back-off, statuses on
// singular, non-finite and non-positive-definite input, one triangle kept, reuse of the
// symbolic analysis, orderings, semi-definite matrices.

#include "solver/suitesparse_solver.hpp"
#include "support/random_matrices.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace iga::solver {
namespace {

// Matrices below are strictly diagonally dominant by rows and columns with
// margin >= 2 and a few random entries per row, so cond(K) is O(10); a
// backward-stable solve errs by ~cond * eps ~ 1e-14.
constexpr double solve_tolerance = 1e-12;
constexpr unsigned seed = 20240611;

using test::dominant_matrix;
using test::random_vector;
using test::relative_error;

TEST(SuiteSparseSolver, SingularMatrixIsReportedNotSolved)
{
    // A floating two-node spring: rigid translation [1, 1] is a null vector.
    Matrix dense(3, 3);
    dense << 1, -1, 0, -1, 1, 0, 0, 0, 2;
    const SparseMatrix K = dense.sparseView();

    SuiteSparseSolver lu(SuiteSparseSolver::Kind::lu);
    EXPECT_EQ(lu.factorize(K), LinearStatus::singular);

    // Cholesky refuses it and falls back to LU, which finds it singular.
    SuiteSparseSolver cholesky(SuiteSparseSolver::Kind::cholesky);
    EXPECT_EQ(cholesky.factorize(K), LinearStatus::singular);
    EXPECT_EQ(cholesky.n_cholesky_fallbacks(), 1);
    // Singular, not indefinite: the shifted matrix a caller tries next gets Cholesky at once.
    const SparseMatrix shifted = SparseMatrix(K + SparseMatrix(Matrix::Identity(3, 3).sparseView()));
    ASSERT_EQ(cholesky.factorize(shifted), LinearStatus::ok);
    EXPECT_EQ(cholesky.factorized_kind(), SuiteSparseSolver::Kind::cholesky);

    // A structurally zero column.
    Matrix zero_column = Matrix::Identity(3, 3);
    zero_column(1, 1) = 0;
    SuiteSparseSolver lu2(SuiteSparseSolver::Kind::lu);
    EXPECT_EQ(lu2.factorize(zero_column.sparseView()), LinearStatus::singular);
}

TEST(SuiteSparseSolver, EmptyPatternIsSingularNotACrash)
{
    // A tangent with no stored entry at all: an open contact gap, nothing else.
    const SparseMatrix K(2, 2);
    SuiteSparseSolver lu(SuiteSparseSolver::Kind::lu);
    EXPECT_EQ(lu.factorize(K), LinearStatus::singular);
    SuiteSparseSolver cholesky(SuiteSparseSolver::Kind::cholesky);
    EXPECT_EQ(cholesky.factorize(K), LinearStatus::singular);
}

TEST(SuiteSparseSolver, NoUnknownsIsATrivialSolve)
{
    for (auto kind : {SuiteSparseSolver::Kind::lu, SuiteSparseSolver::Kind::cholesky}) {
        SuiteSparseSolver solver(kind);
        ASSERT_EQ(solver.factorize(SparseMatrix(0, 0)), LinearStatus::ok);
        Vector x = Vector::Ones(3);
        EXPECT_EQ(solver.solve(Vector(0), x), LinearStatus::ok);
        EXPECT_EQ(x.size(), 0);
    }
}

TEST(SuiteSparseSolver, IndefiniteMatrixIsFactorizedByLuAndCholeskyIsTriedAgainLater)
{
    Matrix indefinite(2, 2);
    indefinite << 1, 2, 2, 1;  // eigenvalues 3 and -1
    Matrix definite(2, 2);
    definite << 3, 1, 1, 3;    // eigenvalues 4 and 2 (same pattern)
    const SparseMatrix K_indefinite = indefinite.sparseView();
    const SparseMatrix K_definite = definite.sparseView();

    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(solver.factorize(K_indefinite), LinearStatus::ok) << "LU takes what Cholesky refuses";
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::lu);
    EXPECT_EQ(solver.n_cholesky_fallbacks(), 1);
    Vector x;
    ASSERT_EQ(solver.solve(Vector::Ones(2), x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most((x - Vector::Constant(2, 1.0 / 3.0)).norm(), solve_tolerance));

    // The back-off: the next factorization is LU without trying Cholesky, the one after is Cholesky again.
    ASSERT_EQ(solver.factorize(K_definite), LinearStatus::ok);
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::lu);
    ASSERT_EQ(solver.factorize(2.0 * K_definite), LinearStatus::ok);
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(solver.solve(Vector::Ones(2), x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most((x - Vector::Constant(2, 1.0 / 8.0)).norm(), solve_tolerance));
    EXPECT_EQ(solver.n_cholesky_fallbacks(), 1);
    EXPECT_EQ(solver.kind(), SuiteSparseSolver::Kind::cholesky);
    EXPECT_EQ(solver.n_symbolic(), 2) << "one analysis per backend for the one pattern";

    // Refusals in a row double the back-off: 1, then 2 LU-only factorizations.
    ASSERT_EQ(solver.factorize(K_indefinite), LinearStatus::ok);   // refused (back-off 1)
    ASSERT_EQ(solver.factorize(-K_indefinite), LinearStatus::ok);  // skipped
    ASSERT_EQ(solver.factorize(K_indefinite), LinearStatus::ok);   // refused again (back-off 2)
    EXPECT_EQ(solver.n_cholesky_fallbacks(), 3);
    ASSERT_EQ(solver.factorize(K_definite), LinearStatus::ok);
    ASSERT_EQ(solver.factorize(2.0 * K_definite), LinearStatus::ok);
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::lu) << "still inside the back-off of 2";
    ASSERT_EQ(solver.factorize(3.0 * K_definite), LinearStatus::ok);
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::cholesky);
}

TEST(SuiteSparseSolver, NonFiniteInputIsNeverOk)
{
    Matrix dense = Matrix::Identity(3, 3);
    dense(2, 2) = std::numeric_limits<double>::quiet_NaN();
    for (auto kind : {SuiteSparseSolver::Kind::lu, SuiteSparseSolver::Kind::cholesky}) {
        SuiteSparseSolver solver(kind);
        EXPECT_NE(solver.factorize(dense.sparseView()), LinearStatus::ok) << kind_name(kind);
    }

    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    ASSERT_EQ(solver.factorize(SparseMatrix(Matrix::Identity(3, 3).sparseView())), LinearStatus::ok);
    Vector b = Vector::Ones(3);
    b(1) = std::numeric_limits<double>::quiet_NaN();
    Vector x;
    EXPECT_NE(solver.solve(b, x), LinearStatus::ok);
}

TEST(SuiteSparseSolver, CholeskyOnNonSymmetricMatrixFailsTheBackwardErrorCheck)
{
    // CHOLMOD reads the upper triangle only; the backward-error check uses all of K
    // (a K that is not symmetric is kept whole).
    Matrix dense(2, 2);
    dense << 4, 3, 0, 4;  // read as symmetric from its upper triangle: [[4, 3], [3, 4]], SPD
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(solver.factorize(dense.sparseView()), LinearStatus::ok);
    Vector x;
    EXPECT_EQ(solver.solve(Vector::Ones(2), x), LinearStatus::singular);
}

// Kind::cholesky keeps one triangle of a symmetric K (the memory of the reference),
// and solves with it as with the whole K: directly, and through an LU where CHOLMOD
// refuses an indefinite K (Woodbury updates of the triangle: woodbury_test.cpp). LU,
// and a K that is not symmetric, are kept whole.
TEST(SuiteSparseSolver, CholeskyKeepsOneTriangleOfASymmetricMatrix)
{
    std::mt19937 rng(seed + 7);
    const Index n = 30;
    SparseMatrix K = dominant_matrix(n, true, rng);
    K = SparseMatrix(0.5 * (K + SparseMatrix(K.transpose())));
    K.makeCompressed();
    const Index upper_entries = (K.nonZeros() + n) / 2;  // the diagonal is stored
    const Vector b = random_vector(n, rng);
    Vector x;

    SuiteSparseSolver cholesky(SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(cholesky.factorize(K), LinearStatus::ok);
    EXPECT_EQ(cholesky.stored_entries(), upper_entries);
    ASSERT_EQ(cholesky.solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K).ldlt().solve(b)), solve_tolerance));

    // Indefinite: CHOLMOD refuses, UMFPACK factorizes the whole matrix made from the triangle.
    SparseMatrix indefinite = K;
    indefinite.coeffRef(5, 5) = -indefinite.coeffRef(5, 5);
    SuiteSparseSolver fallback(SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(fallback.factorize(indefinite), LinearStatus::ok);
    EXPECT_EQ(fallback.factorized_kind(), SuiteSparseSolver::Kind::lu);
    EXPECT_EQ(fallback.stored_entries(), upper_entries);
    ASSERT_EQ(fallback.solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, Matrix(indefinite).lu().solve(b)), solve_tolerance));

    SuiteSparseSolver lu(SuiteSparseSolver::Kind::lu);
    ASSERT_EQ(lu.factorize(K), LinearStatus::ok);
    EXPECT_EQ(lu.stored_entries(), K.nonZeros());
    SparseMatrix skew = K;
    skew.coeffRef(2, 9) += 1e-6 * std::abs(skew.coeffRef(2, 2));
    skew.makeCompressed();
    SuiteSparseSolver not_symmetric(SuiteSparseSolver::Kind::cholesky);
    ASSERT_EQ(not_symmetric.factorize(skew), LinearStatus::ok);
    EXPECT_EQ(not_symmetric.stored_entries(), skew.nonZeros());
}

TEST(SuiteSparseSolver, SymbolicAnalysisIsReusedWhileThePatternIsUnchanged)
{
    std::mt19937 rng(seed + 2);
    for (auto kind : {SuiteSparseSolver::Kind::lu, SuiteSparseSolver::Kind::cholesky}) {
        SCOPED_TRACE(kind_name(kind));
        SparseMatrix K = dominant_matrix(40, true, rng);
        const Vector b = random_vector(40, rng);
        SuiteSparseSolver solver(kind);
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);

        // New values, same pattern: numeric only, and the new values are used.
        for (Index k = 0; k < K.nonZeros(); ++k)
            K.valuePtr()[k] *= 1.0 + 0.1 * (k % 5);
        SparseMatrix K_symmetric = SparseMatrix(0.5 * (K + SparseMatrix(K.transpose())));
        ASSERT_EQ(solver.factorize(K_symmetric), LinearStatus::ok);
        Vector x;
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K_symmetric).ldlt().solve(b)), solve_tolerance));
        EXPECT_EQ(solver.n_symbolic(), 1);
        EXPECT_EQ(solver.n_numeric(), 2);

        // An uncompressed copy is the same matrix: the factorization is kept.
        SparseMatrix uncompressed = K_symmetric;
        uncompressed.uncompress();
        ASSERT_EQ(solver.factorize(uncompressed), LinearStatus::ok);
        EXPECT_EQ(solver.n_numeric(), 2);
        // With new values it is still the same pattern: numeric only.
        uncompressed *= 2.0;
        ASSERT_EQ(solver.factorize(uncompressed), LinearStatus::ok);
        EXPECT_EQ(solver.n_symbolic(), 1);
        EXPECT_EQ(solver.n_numeric(), 3);

        // A new entry changes the pattern: a new analysis.
        const Matrix dense = Matrix(K_symmetric);
        int gi = 0, gj = 1;
        while (dense(gi, gj) != 0.0) {  // first structural zero above the diagonal
            if (++gj == 40)
                gj = ++gi + 1;
        }
        SparseMatrix grown = K_symmetric;
        grown.coeffRef(gi, gj) += 0.01;
        grown.coeffRef(gj, gi) += 0.01;
        grown.makeCompressed();
        ASSERT_NE(grown.nonZeros(), K_symmetric.nonZeros()) << "the test needs an entry outside the pattern";
        ASSERT_EQ(solver.factorize(grown), LinearStatus::ok);
        EXPECT_EQ(solver.n_symbolic(), 2);
        EXPECT_EQ(solver.n_numeric(), 4);

        // Switching the kind needs the other backend's analysis.
        solver.set_kind(kind == SuiteSparseSolver::Kind::lu ? SuiteSparseSolver::Kind::cholesky : SuiteSparseSolver::Kind::lu);
        ASSERT_EQ(solver.factorize(grown), LinearStatus::ok);
        EXPECT_EQ(solver.n_symbolic(), 3);
    }
}

TEST(SuiteSparseSolver, CallerMayChangeTheMatrixBetweenFactorizeAndSolve)
{
    Matrix dense(2, 2);
    dense << 2, 1, 1, 3;
    SparseMatrix K = dense.sparseView();
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    K.coeffs().setConstant(std::numeric_limits<double>::quiet_NaN());  // the solver holds its own copy
    Vector x;
    ASSERT_EQ(solver.solve(Vector::Ones(2), x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most((x - dense.partialPivLu().solve(Vector::Ones(2))).norm(), solve_tolerance));
}

}  // namespace
}  // namespace iga::solver

namespace iga::solver {
namespace {

TEST(SuiteSparseSolver, NestedDissectionOrderingSolvesTheSameSystems)
{
    std::mt19937 rng(seed);
    const SparseMatrix K_spd = dominant_matrix(60, true, rng);
    const SparseMatrix K_general = dominant_matrix(60, false, rng);
    const Vector b = random_vector(60, rng);
    for (auto kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        const SparseMatrix& K = kind == SuiteSparseSolver::Kind::cholesky ? K_spd : K_general;
        SuiteSparseSolver solver(kind);
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
        solver.set_ordering(SuiteSparseSolver::Ordering::nested_dissection);
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok) << "a new ordering is a new analysis, not a stale factor";
        EXPECT_EQ(solver.n_symbolic(), 2);
        Vector x;
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K).partialPivLu().solve(b)), solve_tolerance))
            << kind_name(kind);
    }
}

// UMFPACK's 64-bit version is what a factor too large for the 32-bit one's indices gets
// (a 3D two-body tangent of 68k dofs); it must give the same solves, with a Woodbury
// update of its reference as well (the 32-bit limit itself is only reached by factors of
// gigabytes, so the switch is asked for here).
TEST(SuiteSparseSolver, The64BitLuSolvesWhatThe32BitOneSolves)
{
    std::mt19937 rng(seed);
    const SparseMatrix K = dominant_matrix(60, false, rng);
    const Vector b = random_vector(60, rng);
    const Vector expected = Matrix(K).partialPivLu().solve(b);
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
    solver.set_updates(true);
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    EXPECT_FALSE(solver.lu_64bit());
    solver.set_lu_64bit();
    ASSERT_TRUE(solver.lu_64bit());
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    EXPECT_EQ(solver.n_symbolic(), 2) << "the 64-bit version analyses the pattern itself";
    Vector x;
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, expected), solve_tolerance));
    // One entry changed: a Woodbury update of the 64-bit reference.
    SparseMatrix K2 = K;
    K2.coeffRef(7, 7) *= 1.5;
    ASSERT_EQ(solver.factorize(K2), LinearStatus::ok);
    EXPECT_TRUE(solver.updated());
    ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
    EXPECT_TRUE(test::at_most(relative_error(x, Matrix(K2).partialPivLu().solve(b)), solve_tolerance));
}

}  // namespace
}  // namespace iga::solver

namespace iga::solver {
namespace {

TEST(SuiteSparseSolver, SemidefiniteMatrixThatCholeskyRefusesIsSingularWithoutLu)
{
    // The floating two-node spring: positive semi-definite, rigid translation [1, 1, 0].
    Matrix dense(3, 3);
    dense << 1, -1, 0, -1, 1, 0, 0, 0, 2;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    solver.set_semidefinite(true);
    EXPECT_EQ(solver.factorize(dense.sparseView()), LinearStatus::singular);
    EXPECT_EQ(solver.n_cholesky_fallbacks(), 0) << "no LU attempt";
    EXPECT_EQ(solver.n_symbolic(), 1) << "CHOLMOD's analysis only";
    // The shifted matrix the caller tries next is definite: Cholesky.
    const SparseMatrix shifted = SparseMatrix((dense + 1e-8 * Matrix::Identity(3, 3)).sparseView());
    ASSERT_EQ(solver.factorize(shifted), LinearStatus::ok);
    EXPECT_EQ(solver.factorized_kind(), SuiteSparseSolver::Kind::cholesky);
}

}  // namespace
}  // namespace iga::solver
