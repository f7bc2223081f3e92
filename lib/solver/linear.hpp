#pragma once
// LinearSolver: a sparse direct solver for K x = b, wrapping SuiteSparse through
// Eigen's support modules: UMFPACK (general LU, for the non-symmetric tangent of
// two-half-pass contact, physics.md §7.10) and CHOLMOD (supernodal LL^T, for a
// tangent known to be symmetric positive definite).
//
// Kind::cholesky means "expected symmetric positive definite": a matrix CHOLMOD
// refuses (an indefinite finite-strain tangent, a rigid-body mode before first
// touch) is factorized by UMFPACK instead. If UMFPACK finds it indefinite but
// regular, Cholesky is tried again only after 1, 2, 4, ... (at most 32) further
// factorizations, so a run whose tangent becomes definite (contact closes) returns
// to the factorization that costs a fraction of an LU, while a tangent that stays
// indefinite wastes few Cholesky attempts. If UMFPACK finds it singular, the next
// factorization (the caller's Levenberg-Marquardt shift K + mu D, definite when K
// was semi-definite) tries Cholesky at once.
//
// Invariants: the symbolic analysis (fill-reducing ordering, elimination tree) of
// each backend is done again only when the sparsity pattern (the outer and inner
// index arrays of the compressed matrix) changes; each factorize() does a numeric
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
    /// pattern changed since the backend's last one. K need not be compressed.
    /// Returns `singular` for an exactly singular LU (also the fallback LU of
    /// Kind::cholesky), `failed` for a non-finite K or an input the backend rejects.
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
    /// The condensed dofs (sorted), empty when not condensing.
    const std::vector<int>& condensed_dofs() const;

    /// Fill-reducing ordering of the symbolic analyses: approximate minimum degree
    /// (the backends' default) or METIS nested dissection, which fills far less in
    /// 3D (measured on the 3D Hertz sphere, 32k dofs: Cholesky 1.6x faster; on 2D
    /// decks AMD is ~7 % faster).
    enum class Ordering { minimum_degree, nested_dissection };
    void set_ordering(Ordering ordering);

    /// Declares every matrix positive semi-definite (e.g. small-strain elasticity
    /// with penalty contact against rigid planes): a matrix Cholesky refuses is then
    /// singular, reported as `singular` without the LU attempt (the caller's
    /// Levenberg-Marquardt shift makes it definite). Only with Kind::cholesky.
    void set_semidefinite(bool semidefinite) { semidefinite_ = semidefinite; }

    /// Switches the backend (each keeps its own symbolic analysis).
    void set_kind(Kind kind);

    Kind kind() const { return kind_; }
    /// The backend of the last successful factorization (lu after a Cholesky fallback).
    Kind factorized_kind() const { return factorized_kind_; }
    int n_cholesky_fallbacks() const { return n_fallbacks_; }  ///< matrices Cholesky refused so far
    int n_symbolic() const { return n_symbolic_; }  ///< symbolic analyses done so far
    int n_numeric() const { return n_numeric_; }    ///< numeric factorizations done so far
    Index size() const { return K_.rows(); }

private:
    struct Backend;  // the Eigen/SuiteSparse objects, kept out of this header
    std::unique_ptr<Condensation> condensation_;

    bool same_pattern(const SparseMatrix& K) const;
    LinearStatus factorize_with(Kind kind);  // K_ by one backend, after its analysis if needed

    Kind kind_;
    Kind factorized_kind_;
    std::unique_ptr<Backend> backend_;
    SparseMatrix K_;              // the factorized matrix (compressed), read by solve()
    bool analysed_ = false;       // K_'s pattern is the one the analyses below were made for
    bool analysed_lu_ = false;    // UMFPACK's symbolic analysis matches K_'s pattern
    bool analysed_llt_ = false;   // CHOLMOD's symbolic analysis matches K_'s pattern
    bool factorized_ = false;     // the last numeric factorization succeeded
    bool semidefinite_ = false;   // set_semidefinite()
    int cholesky_skips_ = 0;      // factorizations left before Cholesky is tried again
    int cholesky_backoff_ = 1;    // skips after the next refusal (doubles, at most 32)
    int n_fallbacks_ = 0;
    int n_symbolic_ = 0;
    int n_numeric_ = 0;
};

const char* kind_name(LinearSolver::Kind kind);

}  // namespace iga::solver
