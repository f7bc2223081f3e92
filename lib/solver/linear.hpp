#pragma once
// LinearSolver: a sparse direct solver for K x = b, wrapping SuiteSparse through
// Eigen's support modules: UMFPACK (general LU, for the non-symmetric tangent of
// two-half-pass contact, physics.md §7.10) and CHOLMOD (supernodal LL^T, for a
// tangent known to be symmetric positive definite).
//
// Invariants: the symbolic analysis (fill-reducing ordering, elimination tree) is
// done again only when the sparsity pattern (the outer and inner index arrays of
// the compressed matrix) or the kind changes; each factorize() does a numeric
// factorization. Numerical failures are statuses, never exceptions, and a status
// `ok` never comes with a non-finite x. Shapes: K is n x n (column-major, int
// indices, see core/types.hpp), b and x have n entries.
// Ownership: factorize() copies K (O(nnz)), because UMFPACK reads the matrix
// again in solve() for iterative refinement; the caller's K may change afterwards.

#include "core/types.hpp"

#include <memory>
#include <vector>

namespace iga::solver {

enum class LinearStatus {
    ok,
    singular,  ///< exactly singular pivot (UMFPACK), or the solution fails the backward-error check
    failed     ///< Cholesky on a matrix that is not positive definite, or an input the backend rejects
};

const char* status_name(LinearStatus status);

class Condensation;

class LinearSolver {
public:
    enum class Kind {
        lu,       ///< UMFPACK: general, non-symmetric
        cholesky  ///< CHOLMOD: known symmetric positive definite (reads the lower triangle only)
    };

    explicit LinearSolver(Kind kind);
    ~LinearSolver();
    LinearSolver(LinearSolver&&) noexcept;
    LinearSolver& operator=(LinearSolver&&) noexcept;
    LinearSolver(const LinearSolver&) = delete;
    LinearSolver& operator=(const LinearSolver&) = delete;

    /// Numeric factorization of K (square), after a symbolic analysis if the
    /// pattern or the kind changed since the last call. K need not be compressed.
    /// Returns `failed` for Cholesky of a matrix that is not positive definite
    /// (the caller may switch to lu), `singular` for an exactly singular LU.
    LinearStatus factorize(const SparseMatrix& K);

    /// Solves K x = b with the last successful factorization. Returns `singular`
    /// when x is not finite or the backward error ||K x - b|| > 1e-6 ||b||
    /// (a near-singular K that the pivoting did not flag); x is then unspecified.
    /// Precondition: the last factorize() returned ok.
    LinearStatus solve(const Vector& b, Vector& x) const;

    /// Static condensation onto these dofs (solver/condensation.hpp): for tangents
    /// that change only in these rows/columns between calls (contact under small
    /// kinematics). Empty: off (the default).
    void set_condensed_dofs(std::vector<int> dofs);
    bool condensed() const { return condensation_ != nullptr; }

    /// Switches the backend; the next factorize() does a new symbolic analysis.
    void set_kind(Kind kind);

    Kind kind() const { return kind_; }
    int n_symbolic() const { return n_symbolic_; }  ///< symbolic analyses done so far
    int n_numeric() const { return n_numeric_; }    ///< numeric factorizations done so far
    Index size() const { return K_.rows(); }

private:
    struct Backend;  // the Eigen/SuiteSparse objects, kept out of this header
    std::unique_ptr<Condensation> condensation_;

    bool same_pattern(const SparseMatrix& K) const;

    Kind kind_;
    std::unique_ptr<Backend> backend_;
    SparseMatrix K_;              // the factorized matrix (compressed), read by solve()
    bool analysed_ = false;       // a symbolic analysis matches K_'s pattern and kind_
    bool factorized_ = false;     // the last numeric factorization succeeded
    int n_symbolic_ = 0;
    int n_numeric_ = 0;
};

const char* kind_name(LinearSolver::Kind kind);

}  // namespace iga::solver
