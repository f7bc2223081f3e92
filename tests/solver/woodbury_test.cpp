#include "solver/woodbury.hpp"
#include "solver/shift.hpp"
#include "solver/suitesparse_solver.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

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

// Adds a non-symmetric dense coupling among the dofs c (like a two-half-pass
// contact tangent), every (a, b) in c x c stored.
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

// A 3D grid Laplacian (7-point stencil, q^3 dofs) plus a small diagonal shift:
// sparse, SPD, and, like a 3D elastic stiffness, far costlier to factorize than
// to solve with, so that updates pay.
SparseMatrix grid_matrix(int q)
{
    const int n = q * q * q;
    auto id = [q](int i, int j, int k) { return i + q * (j + q * k); };
    std::vector<Triplet> t;
    for (int k = 0; k < q; ++k)
        for (int j = 0; j < q; ++j)
            for (int i = 0; i < q; ++i) {
                const int a = id(i, j, k);
                t.emplace_back(a, a, 0.01);
                const int neighbours[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
                for (const auto& nb : neighbours) {
                    if (nb[0] >= q || nb[1] >= q || nb[2] >= q)
                        continue;
                    const int b = id(nb[0], nb[1], nb[2]);
                    t.emplace_back(a, a, 1.0);
                    t.emplace_back(b, b, 1.0);
                    t.emplace_back(a, b, -1.0);
                    t.emplace_back(b, a, -1.0);
                }
            }
    SparseMatrix K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    return K;
}

Vector random_vector(Index n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal;
    Vector b(n);
    for (Index i = 0; i < n; ++i)
        b(i) = normal(rng);
    return b;
}

// Both sides are backward-stable solves of well-conditioned systems (condition
// numbers below 1e4 here): they agree far below this.
constexpr double agreement = 1e-10;

}  // namespace

TEST(WoodburyUpdate, SolvesTheUpdatedMatrixAndComputesOnlyNewColumns)
{
    constexpr int n = 40;
    const SparseMatrix K_ref = chain_matrix(n, 1);
    const Eigen::PartialPivLU<Matrix> reference{Matrix(K_ref)};
    Index columns_solved = 0;
    const WoodburyUpdate::ReferenceSolve solve_reference = [&](const Matrix& B) {
        columns_solved += B.cols();
        return Matrix(reference.solve(B));
    };
    WoodburyUpdate update;
    update.reset(n);
    // A growing set of contact dofs with a non-symmetric coupling (two-half-pass).
    const std::vector<std::vector<int>> supports{{3, 4, 5}, {3, 4, 5, 20, 21}, {4, 5, 20, 21, 39}};
    for (std::size_t k = 0; k < supports.size(); ++k) {
        const std::vector<int>& dofs = supports[k];
        const SparseMatrix K = with_contact(K_ref, dofs, 100 + static_cast<unsigned>(k));
        Matrix D = Matrix(K - K_ref)(dofs, dofs);
        ASSERT_TRUE(update.set_up(dofs, D, solve_reference));
        const Vector b = random_vector(n, 7 + static_cast<unsigned>(k));
        Vector x = reference.solve(b);
        update.correct(x);
        const Vector direct = Matrix(K).partialPivLu().solve(b);
        EXPECT_TRUE(test::at_most((x - direct).norm() / direct.norm(), agreement)) << "support " << k;
    }
    EXPECT_EQ(columns_solved, 6) << "3 + 2 new + 1 new columns: a column is solved once per reference";
    EXPECT_EQ(update.stored_columns(), 6);
}

TEST(WoodburyUpdate, ASingularUpdatedMatrixIsRefused)
{
    // A free chain held by one spring at dof 0: removing the spring leaves a
    // rigid mode, and the capacitance I + G D is singular.
    constexpr int n = 10;
    std::vector<Triplet> t{{0, 0, 1.0}};
    for (int i = 0; i + 1 < n; ++i) {
        t.emplace_back(i, i, 1.0);
        t.emplace_back(i + 1, i + 1, 1.0);
        t.emplace_back(i, i + 1, -1.0);
        t.emplace_back(i + 1, i, -1.0);
    }
    SparseMatrix K_ref(n, n);
    K_ref.setFromTriplets(t.begin(), t.end());
    const Eigen::PartialPivLU<Matrix> reference(Matrix{K_ref});
    WoodburyUpdate update;
    update.reset(n);
    EXPECT_FALSE(update.set_up({0}, Matrix::Constant(1, 1, -1.0),
                               [&](const Matrix& B) { return Matrix(reference.solve(B)); }));
}

TEST(SuiteSparseSolver, UpdatesServeTangentsThatChangeInAFewDofs)
{
    // Newton iterations of small-strain contact: the elastic part stays, the
    // contact block on a growing set of dofs changes; one factorization serves all.
    const SparseMatrix K0 = grid_matrix(14);
    const Index n = K0.rows();
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SuiteSparseSolver solver(kind);
        solver.set_updates(true);
        const std::vector<std::vector<int>> supports{
            {100, 101, 102}, {100, 101, 102, 115, 116}, {101, 102, 115, 116, 117}};
        for (std::size_t k = 0; k < supports.size(); ++k) {
            SparseMatrix K = K0;  // a symmetric positive semi-definite contact stiffness on the support
            for (int a : supports[k])
                for (int b : supports[k])
                    K.coeffRef(a, b) += (a == b ? 2.0 : 1.0) * (1.0 + 0.1 * static_cast<double>(k));
            ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
            const Vector b = random_vector(n, 11 + static_cast<unsigned>(k));
            Vector x;
            ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
            Eigen::SimplicialLDLT<SparseMatrix> direct(K);
            const Vector expected = direct.solve(b);
            EXPECT_TRUE(test::at_most((x - expected).norm() / expected.norm(), agreement))
                << kind_name(kind) << ", iteration " << k;
            EXPECT_EQ(solver.updated(), k > 0) << kind_name(kind) << ", iteration " << k;
        }
        EXPECT_EQ(solver.n_numeric(), 1) << kind_name(kind);
        EXPECT_EQ(solver.n_updates(), 2) << kind_name(kind);

        // A change everywhere (finite kinematics, a Levenberg-Marquardt shift) is
        // factorized and becomes the new reference.
        SparseMatrix shifted = K0;
        for (Index i = 0; i < n; ++i)
            shifted.coeffRef(i, i) += 1e-3;
        ASSERT_EQ(solver.factorize(shifted), LinearStatus::ok);
        EXPECT_FALSE(solver.updated());
        EXPECT_EQ(solver.n_numeric(), 2) << kind_name(kind);
        Vector x;
        ASSERT_EQ(solver.solve(Vector::Ones(n), x), LinearStatus::ok);
        EXPECT_TRUE(
            test::at_most((shifted * x - Vector::Ones(n)).norm() / std::sqrt(static_cast<double>(n)), agreement));

        // A non-finite entry is never taken into an update.
        SparseMatrix broken = shifted;
        broken.coeffRef(100, 100) = std::numeric_limits<double>::quiet_NaN();
        EXPECT_EQ(solver.factorize(broken), LinearStatus::failed) << kind_name(kind);
    }
}

TEST(SuiteSparseSolver, ASingularUpdateIsFactorizedAndReportedSingular)
{
    // K0 held only by the "contact" springs on dofs 0 and 1 (a body held by contact
    // alone): when the contact opens, the updated matrix is singular. The update
    // refuses it, and the factorization reports it like any singular tangent.
    const SparseMatrix grid = grid_matrix(6);
    const Index n = grid.rows();
    SparseMatrix free_body = grid;
    for (Index i = 0; i < n; ++i)
        free_body.coeffRef(i, i) -= 0.01;  // no shift: the constant vector is a null mode
    free_body.prune(0.0);
    SparseMatrix held = free_body;
    held.coeffRef(0, 0) += 1.0;
    held.coeffRef(1, 1) += 1.0;
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::cholesky);
    solver.set_updates(true);
    solver.set_semidefinite(true);
    ASSERT_EQ(solver.factorize(held), LinearStatus::ok);
    SparseMatrix opened = held;
    opened.coeffRef(0, 0) = free_body.coeff(0, 0);
    opened.coeffRef(1, 1) = free_body.coeff(1, 1);
    EXPECT_EQ(solver.factorize(opened), LinearStatus::singular);
    EXPECT_FALSE(solver.updated());
}

}  // namespace iga::solver

namespace iga::solver {

TEST(SuiteSparseSolver, TheSameMatrixAgainKeepsItsFactorization)
{
    // A linear scene refactorizes nothing from its second increment on.
    const SparseMatrix K = with_contact(chain_matrix(20, 6), {2, 3}, 7);
    SuiteSparseSolver solver(SuiteSparseSolver::Kind::lu);
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
// the plain and the updating solver must notice (a new symbolic analysis, or an
// update whose difference spans the new entries) and solve the new matrix.
TEST(SuiteSparseSolver, AGrownPatternIsAnalysedAgain)
{
    constexpr int n = 50;
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

    SuiteSparseSolver plain(SuiteSparseSolver::Kind::lu), updating(SuiteSparseSolver::Kind::lu);
    updating.set_updates(true);
    for (SuiteSparseSolver* solver : {&plain, &updating}) {
        ASSERT_EQ(solver->factorize(K1), LinearStatus::ok);
        ASSERT_EQ(solver->factorize(K2), LinearStatus::ok);
        Vector x;
        ASSERT_EQ(solver->solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most((x - reference).norm() / reference.norm(), agreement))
            << (solver == &updating ? "updating" : "plain");
    }
    EXPECT_EQ(plain.n_symbolic(), 2) << "one analysis per pattern";
}

TEST(SuiteSparseSolver, AShiftAfterAnUpdateShiftsTheUpdatedMatrix)
{
    // Newton shifts the K of its last factorize() (K + mu D, D = |diag K|). When that
    // factorize() was served by an update, K is K_ref + P^T D P, which the solver
    // keeps only as the reference and the update: the shift must be of that K, not
    // of the reference (whose contact block is another one).
    const SparseMatrix K0 = grid_matrix(8);
    const Index n = K0.rows();
    SparseMatrix K = K0;
    for (int a : {40, 41, 48})
        for (int b : {40, 41, 48})
            K.coeffRef(a, b) += a == b ? 30.0 : 10.0;  // diagonal entries change too: D is K's, not K0's
    constexpr double mu = 1e-2;  // large enough that shifting the wrong matrix shows
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SuiteSparseSolver solver(kind);
        solver.set_updates(true);
        ASSERT_EQ(solver.factorize(K0), LinearStatus::ok);
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
        ASSERT_TRUE(solver.updated()) << kind_name(kind);
        ASSERT_EQ(solver.factorize_shifted(mu), LinearStatus::ok);
        const Vector b = random_vector(n, 21);
        Vector x;
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        SparseMatrix expected = K;
        const Vector D = shift_scale(Vector(K.diagonal()));
        for (Index i = 0; i < n; ++i)
            expected.coeffRef(i, i) += mu * D(i);
        const Vector r = expected * x - b;
        EXPECT_TRUE(test::at_most(r.norm() / b.norm(), agreement)) << kind_name(kind);
    }
}

TEST(SuiteSparseSolver, FactorizeTakingSolvesAsFactorizeAndLeavesKEmpty)
{
    // Newton hands its tangent over (factorize_taking) so that a 3D tangent is not held
    // twice: the solves are those of factorize(), whether the call factorized, was an
    // update or kept the factorization, and the caller's matrix is freed every time.
    const SparseMatrix K0 = grid_matrix(8);
    const Index n = K0.rows();
    SparseMatrix K1 = K0;
    for (int a : {40, 41})
        for (int b : {40, 41})
            K1.coeffRef(a, b) += a == b ? 2.0 : 1.0;
    const Vector b = random_vector(n, 5);
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SuiteSparseSolver copying(kind), taking(kind);
        copying.set_updates(true);
        taking.set_updates(true);
        for (const SparseMatrix* K : std::vector<const SparseMatrix*>{&K0, &K0, &K1}) {  // a factorization, the same matrix again, an update
            SparseMatrix handed = *K;
            ASSERT_EQ(copying.factorize(*K), LinearStatus::ok);
            ASSERT_EQ(taking.factorize_taking(handed), LinearStatus::ok);
            EXPECT_EQ(handed.nonZeros(), 0);
            EXPECT_EQ(handed.data().allocatedSize(), 0) << kind_name(kind) << ": the storage is freed, not kept";
            EXPECT_EQ(taking.updated(), copying.updated());
            Vector x_copying, x_taking;
            ASSERT_EQ(copying.solve(b, x_copying), LinearStatus::ok);
            ASSERT_EQ(taking.solve(b, x_taking), LinearStatus::ok);
            EXPECT_TRUE(test::at_most((*K * x_taking - b).norm() / b.norm(), agreement)) << kind_name(kind);
            EXPECT_TRUE(test::at_most((x_taking - x_copying).norm() / x_copying.norm(), agreement));
        }
        EXPECT_EQ(taking.n_numeric(), 1) << kind_name(kind);
        EXPECT_EQ(taking.n_updates(), 1) << kind_name(kind);
    }
}

}  // namespace iga::solver

namespace iga::solver {

namespace {

// A body that only contact holds (docs/solver.md "The first touch"): the 3D grid
// Laplacian without its diagonal shift, the constant vector its null mode.
SparseMatrix free_body(int q)
{
    SparseMatrix K = grid_matrix(q);
    for (Index i = 0; i < K.rows(); ++i)
        K.coeffRef(i, i) -= 0.01;
    K.prune(0.0);
    return K;
}

// K0 plus penalty springs k at the dofs of the contact zone.
SparseMatrix held(const SparseMatrix& K0, const std::vector<int>& dofs, double k)
{
    SparseMatrix K = K0;
    for (int a : dofs)
        K.coeffRef(a, a) += k;
    return K;
}

double backward_error(const SparseMatrix& K, const Vector& x, const Vector& b)
{
    return (K * x - b).norm() / b.norm();
}

// K + mu D, D = shift_scale(diag K): what factorize_shifted(mu) solves.
SparseMatrix shifted(const SparseMatrix& K, double mu)
{
    SparseMatrix S = K;
    const Vector D = shift_scale(Vector(K.diagonal()));
    for (Index i = 0; i < S.rows(); ++i)
        S.coeffRef(i, i) += mu * D(i);
    return S;
}

constexpr double first_touch_mu = 1e-8;  // Newton's first shift of a tangent known singular

}  // namespace

TEST(SuiteSparseSolver, AShiftedReferenceServesTheNextTangentsByUpdates)
{
    // Newton at a first touch: the singular K0 is shifted (K0 + mu D), then the
    // tangents K0 + contact differ from the UNSHIFTED reference in the contact dofs
    // only. They are Woodbury updates of the shifted factorization, refined against K
    // itself: no second factorization, and the solves are those of K.
    const SparseMatrix K0 = free_body(8);
    const Index n = K0.rows();
    const std::vector<std::vector<int>> zones{{0, 1}, {0, 1, 8, 9}, {0, 1, 8, 9, 64}};
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SuiteSparseSolver solver(kind);
        solver.set_updates(true);
        solver.set_semidefinite(kind == SuiteSparseSolver::Kind::cholesky);
        SparseMatrix handed = K0;
        ASSERT_EQ(solver.factorize_shifted_taking(handed, first_touch_mu), LinearStatus::ok) << kind_name(kind);
        EXPECT_EQ(handed.nonZeros(), 0) << "taken, not copied";
        EXPECT_EQ(solver.n_numeric(), 1) << kind_name(kind) << ": K0 itself is not factorized";
        Vector x;
        ASSERT_EQ(solver.solve(random_vector(n, 3), x), LinearStatus::ok);
        for (std::size_t k = 0; k < zones.size(); ++k) {
            const SparseMatrix K = held(K0, zones[k], 1.0 + static_cast<double>(k));
            ASSERT_EQ(solver.factorize(K), LinearStatus::ok) << kind_name(kind);
            EXPECT_TRUE(solver.updated()) << kind_name(kind) << ", zone " << k;
            const Vector b = random_vector(n, 30 + static_cast<unsigned>(k));
            ASSERT_EQ(solver.solve(b, x), LinearStatus::ok) << kind_name(kind) << ", zone " << k;
            Eigen::SimplicialLDLT<SparseMatrix> direct(K);
            const Vector expected = direct.solve(b);
            EXPECT_TRUE(test::at_most((x - expected).norm() / expected.norm(), agreement))
                << kind_name(kind) << ", zone " << k;
            EXPECT_TRUE(test::at_most(backward_error(K, x, b), 1e-12)) << kind_name(kind) << ", zone " << k;
        }
        EXPECT_EQ(solver.n_numeric(), 1) << kind_name(kind);
        EXPECT_EQ(solver.n_updates(), 3) << kind_name(kind);
    }
}

TEST(SuiteSparseSolver, AShiftThatCannotBeRefinedAwayFactorizesKAndSaysSoTruthfully)
{
    const SparseMatrix K0 = free_body(6);
    const Index n = K0.rows();
    const Vector b = random_vector(n, 41);  // with a component along the constant null mode
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SCOPED_TRACE(kind_name(kind));
        const bool cholesky = kind == SuiteSparseSolver::Kind::cholesky;
        {
            // Still free (a spring inside the body, no contact): K is singular, the
            // refinement cannot converge, and K's own factorization is tried and
            // reported singular. Then the shift is of that K.
            SparseMatrix K = K0;
            for (int a : {3, 4})
                for (int c : {3, 4})
                    K.coeffRef(a, c) += a == c ? 2.0 : -2.0;
            SuiteSparseSolver solver(kind);
            solver.set_updates(true);
            solver.set_semidefinite(cholesky);
            SparseMatrix handed = K0;
            ASSERT_EQ(solver.factorize_shifted_taking(handed, first_touch_mu), LinearStatus::ok);
            ASSERT_EQ(solver.factorize(K), LinearStatus::ok);  // an update: its solve finds out
            Vector x;
            EXPECT_EQ(solver.solve(b, x), LinearStatus::singular);
            EXPECT_FALSE(solver.updated());
            EXPECT_EQ(solver.n_updates(), 0) << "a call whose solve fell back is a factorization";
            EXPECT_EQ(solver.n_numeric(), 2);
            constexpr double mu = 1e-6;
            ASSERT_EQ(solver.factorize_shifted(mu), LinearStatus::ok);
            ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
            EXPECT_TRUE(test::at_most(backward_error(shifted(K, mu), x, b), 1e-10));
        }
        {
            // Held, but so weakly that a large shift dominates (a contraction ~1 per
            // step): K is factorized, becomes the reference, and is solved exactly.
            const SparseMatrix K = held(K0, {0}, 1e-4);
            SuiteSparseSolver solver(kind);
            solver.set_updates(true);
            solver.set_semidefinite(cholesky);
            SparseMatrix handed = K0;
            ASSERT_EQ(solver.factorize_shifted_taking(handed, 1e-2), LinearStatus::ok);
            ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
            Vector x;
            ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
            EXPECT_TRUE(test::at_most(backward_error(K, x, b), 1e-10));
            EXPECT_FALSE(solver.updated());
            EXPECT_EQ(solver.n_updates(), 0);
            EXPECT_EQ(solver.n_numeric(), 2);
            // The factorized K is the reference now, unshifted: the next tangent is a plain update.
            const SparseMatrix K2 = held(K, {1, 2}, 1.0);
            ASSERT_EQ(solver.factorize(K2), LinearStatus::ok);
            EXPECT_TRUE(solver.updated());
            ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
            EXPECT_TRUE(test::at_most(backward_error(K2, x, b), 1e-10));
            EXPECT_EQ(solver.n_numeric(), 2);
        }
    }
}

TEST(SuiteSparseSolver, AShiftAfterAnUpdateOfAShiftedReferenceShiftsTheUpdatedMatrix)
{
    // Newton regularizes a tangent served by an update of a shifted reference: the
    // shift is of that tangent, K_u + P^T D P with its own D, not of the reference
    // (shifted by another mu, with another contact block).
    const SparseMatrix K0 = free_body(6);
    const Index n = K0.rows();
    const SparseMatrix K = held(K0, {0, 1, 6}, 30.0);
    const Vector b = random_vector(n, 51);
    constexpr double mu = 1e-2;  // large enough that shifting the wrong matrix shows
    for (SuiteSparseSolver::Kind kind : {SuiteSparseSolver::Kind::cholesky, SuiteSparseSolver::Kind::lu}) {
        SuiteSparseSolver solver(kind);
        solver.set_updates(true);
        SparseMatrix handed = K0;
        ASSERT_EQ(solver.factorize_shifted_taking(handed, first_touch_mu), LinearStatus::ok);
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
        ASSERT_TRUE(solver.updated()) << kind_name(kind);
        ASSERT_EQ(solver.factorize_shifted(mu), LinearStatus::ok);
        Vector x;
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(backward_error(shifted(K, mu), x, b), agreement)) << kind_name(kind);
        // And the plain K again: an update of that shifted reference, solved as K.
        ASSERT_EQ(solver.factorize(K), LinearStatus::ok);
        ASSERT_EQ(solver.solve(b, x), LinearStatus::ok);
        EXPECT_TRUE(test::at_most(backward_error(K, x, b), 1e-12)) << kind_name(kind);
        // (An update, or, if mu = 1e-2 is too strong to refine off, a factorization:
        // every factorize*() call counts once, as one or the other.)
        EXPECT_EQ(solver.n_numeric() + solver.n_updates(), 4) << kind_name(kind);
    }
}

}  // namespace iga::solver
