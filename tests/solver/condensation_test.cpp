#include "solver/condensation.hpp"
#include "solver/linear.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>

namespace iga::solver {

namespace {

// A random sparse SPD "elastic" matrix (a 1D chain with random springs plus a
// diagonal shift), n x n.
SparseMatrix chain_matrix(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> k(1.0, 2.0);
    std::vector<Triplet> t;
    for (int i = 0; i + 1 < n; ++i) {
        const double s = k(rng);
        t.emplace_back(i, i, s);
        t.emplace_back(i + 1, i + 1, s);
        t.emplace_back(i, i + 1, -s);
        t.emplace_back(i + 1, i, -s);
    }
    for (int i = 0; i < n; ++i)
        t.emplace_back(i, i, 0.1);
    SparseMatrix K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    return K;
}

// Adds a non-symmetric dense coupling among the condensed dofs (like a
// two-half-pass contact tangent) without changing the pattern's interior block.
SparseMatrix with_contact(const SparseMatrix& K0, const std::vector<int>& c, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> v(-0.5, 1.5);
    Matrix dense = Matrix(K0);
    for (int a : c)
        for (int b : c)
            dense(a, b) += v(rng);
    SparseMatrix K = dense.sparseView();
    // Keep the same pattern every time: store every (a, b) in c x c.
    std::vector<Triplet> t;
    for (Index j = 0; j < dense.cols(); ++j)
        for (Index i = 0; i < dense.rows(); ++i)
            if (dense(i, j) != 0.0 || (std::find(c.begin(), c.end(), i) != c.end() &&
                                       std::find(c.begin(), c.end(), j) != c.end()))
                t.emplace_back(static_cast<int>(i), static_cast<int>(j), dense(i, j));
    SparseMatrix out(K0.rows(), K0.cols());
    out.setFromTriplets(t.begin(), t.end());
    out.makeCompressed();
    return out;
}

}  // namespace

TEST(Condensation, SolvesLikeADenseLUAndFactorizesTheInteriorOnce)
{
    constexpr int n = 40;
    const std::vector<int> condensed{3, 4, 5, 20, 21, 39};
    const SparseMatrix K0 = chain_matrix(n, 1);
    Condensation condensation(condensed);
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    for (unsigned iteration = 0; iteration < 4; ++iteration) {
        const SparseMatrix K = with_contact(K0, condensed, 100 + iteration);
        ASSERT_EQ(condensation.factorize(K), LinearStatus::ok);
        Vector b(n);
        for (int i = 0; i < n; ++i)
            b(i) = normal(rng);
        Vector x;
        ASSERT_EQ(condensation.solve(b, x), LinearStatus::ok);
        const Vector reference = Matrix(K).partialPivLu().solve(b);
        // Both are backward-stable direct solves of a well-conditioned 40 x 40 system:
        // they agree to a few hundred eps relative.
        constexpr double agreement = 1e-12;
        EXPECT_TRUE(test::at_most((x - reference).norm() / reference.norm(), agreement));
    }
    // Only the condensed block changed between calls: one interior factorization.
    EXPECT_EQ(condensation.n_interior_factorizations(), 1);
}

TEST(Condensation, AChangedInteriorIsRefactorized)
{
    constexpr int n = 30;
    const std::vector<int> condensed{0, 1, 29};
    SparseMatrix K = with_contact(chain_matrix(n, 2), condensed, 3);
    Condensation condensation(condensed);
    ASSERT_EQ(condensation.factorize(K), LinearStatus::ok);
    K.coeffRef(10, 10) += 1.0;  // an interior value changes (finite kinematics, a shift)
    ASSERT_EQ(condensation.factorize(K), LinearStatus::ok);
    EXPECT_EQ(condensation.n_interior_factorizations(), 2);
    Vector b = Vector::Ones(n), x;
    ASSERT_EQ(condensation.solve(b, x), LinearStatus::ok);
    constexpr double backward = 1e-12;  // direct solve of a well-conditioned system
    EXPECT_TRUE(test::at_most((K * x - b).norm() / b.norm(), backward));
}

TEST(Condensation, ASingularSchurComplementIsReported)
{
    // A free chain (no diagonal shift) whose only support would be the condensed end:
    // with zero contact stiffness the whole matrix is singular.
    constexpr int n = 10;
    std::vector<Triplet> t;
    for (int i = 0; i + 1 < n; ++i) {
        t.emplace_back(i, i, 1.0);
        t.emplace_back(i + 1, i + 1, 1.0);
        t.emplace_back(i, i + 1, -1.0);
        t.emplace_back(i + 1, i, -1.0);
    }
    SparseMatrix K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    Condensation condensation({0});
    EXPECT_EQ(condensation.factorize(K), LinearStatus::singular);
}

TEST(LinearSolver, CondensedModeMatchesTheDirectSolve)
{
    constexpr int n = 50;
    const std::vector<int> condensed{10, 11, 12, 13};
    const SparseMatrix K = with_contact(chain_matrix(n, 4), condensed, 5);
    LinearSolver direct(LinearSolver::Kind::lu), condensed_solver(LinearSolver::Kind::lu);
    condensed_solver.set_condensed_dofs(condensed);
    ASSERT_EQ(direct.factorize(K), LinearStatus::ok);
    ASSERT_EQ(condensed_solver.factorize(K), LinearStatus::ok);
    const Vector b = Vector::LinSpaced(n, -1.0, 2.0);
    Vector x1, x2;
    ASSERT_EQ(direct.solve(b, x1), LinearStatus::ok);
    ASSERT_EQ(condensed_solver.solve(b, x2), LinearStatus::ok);
    constexpr double agreement = 1e-12;  // two direct solves of a well-conditioned system
    EXPECT_TRUE(test::at_most((x1 - x2).norm() / x1.norm(), agreement));
}

}  // namespace iga::solver

namespace iga::solver {

TEST(LinearSolver, TheSameMatrixAgainKeepsItsFactorization)
{
    // A linear scene refactorizes nothing from its second increment on.
    const SparseMatrix K = with_contact(chain_matrix(20, 6), {2, 3}, 7);
    LinearSolver solver(LinearSolver::Kind::lu);
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
    EXPECT_EQ(solver.n_numeric(), 1);
    SparseMatrix changed = K;
    changed.coeffRef(5, 5) += 1.0;
    ASSERT_EQ(solver.factorize(changed), LinearStatus::ok);
    EXPECT_EQ(solver.n_numeric(), 2);
    Vector x;
    ASSERT_EQ(solver.solve(Vector::Ones(20), x), LinearStatus::ok);
    constexpr double backward = 1e-12;  // direct solve of a well-conditioned 20 x 20 system
    EXPECT_TRUE(test::at_most((changed * x - Vector::Ones(20)).norm() / std::sqrt(20.0), backward));
}

}  // namespace iga::solver

namespace iga::solver {

// A contact coupling registered during a run grows the tangent's pattern: both
// the plain and the condensed solver must notice (new symbolic analysis / block
// maps) and solve the new matrix, not reuse the old structure.
TEST(LinearSolver, AGrownPatternIsAnalysedAgain)
{
    constexpr int n = 50;
    const std::vector<int> condensed{10, 11, 12, 13, 30, 31};
    const SparseMatrix K1 = with_contact(chain_matrix(n, 4), {10, 11, 12, 13}, 5);
    // The same values plus couplings between 10..13 and 30..31 (a new coupling block).
    Matrix dense = Matrix(with_contact(chain_matrix(n, 4), {10, 11, 12, 13}, 5));
    for (int i : {10, 11, 12, 13})
        for (int j : {30, 31}) {
            dense(i, j) += 0.25;
            dense(j, i) -= 0.125;
        }
    const SparseMatrix K2 = dense.sparseView();
    ASSERT_GT(K2.nonZeros(), K1.nonZeros());
    const Vector b = Vector::LinSpaced(n, -1.0, 2.0);
    const Vector reference = dense.lu().solve(b);
    constexpr double agreement = 1e-12;  // direct solves of a well-conditioned system

    LinearSolver plain(LinearSolver::Kind::lu), condensed_solver(LinearSolver::Kind::lu);
    condensed_solver.set_condensed_dofs(condensed);
    for (LinearSolver* solver : {&plain, &condensed_solver}) {
        ASSERT_EQ(solver->factorize(K1), LinearStatus::ok);
        ASSERT_EQ(solver->factorize(K2), LinearStatus::ok);
        Vector x;
        ASSERT_EQ(solver->solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most((x - reference).norm() / reference.norm(), agreement))
            << (solver->condensed() ? "condensed" : "plain");
    }
    EXPECT_EQ(plain.n_symbolic(), 2) << "one analysis per pattern";
}

}  // namespace iga::solver
