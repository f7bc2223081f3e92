#pragma once
// SuiteSparseSolver: the embedded backend of LinearSolver (solver/linear.hpp), a
// serial sparse direct solver for K x = b, wrapping SuiteSparse through
// Eigen's support modules: UMFPACK (general LU, for the non-symmetric tangent of
// two-half-pass contact, docs/solver.md "Linear solvers") and CHOLMOD (supernodal LL^T, for a
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
// Kind::cholesky keeps only K's upper triangle (K is symmetric, and CHOLMOD reads no
// more): half the memory of the reference, 57 MB at 32k dofs in 3D; a refused K is
// made whole again for UMFPACK while its LU is in use.
//
// Updates (set_updates(true); solver/woodbury.hpp): a factorization is kept as a
// reference, and a later K that differs from it only in the rows and columns of a
// few dofs is solved by a Woodbury update of the reference instead of being
// factorized, when that costs fewer flops than a factorization (the columns of
// K_ref^-1 the update still needs against the factorization's own flop count,
// both known from the backend's analysis), and its columns fit in the memory of
// the factor. Anything else (a dense change, a singular capacitance) takes the
// ordinary path, and the new factorization becomes the reference.
//
// A shifted reference (factorize_shifted: Newton's K_u + mu D for a singular K_u)
// is kept as the reference of later updates: a later K is compared with the
// unshifted K_u, so that a tangent which differs from it in the contact dofs only is
// a Woodbury update of K_u + mu D, i.e. solves (K + mu D) x = b, and solve() then
// refines x against K itself, x += (K + mu D)^-1 (b - K x) (the error contracts by
// ~||(K + mu D)^-1 mu D|| per step: far below 1 once the contact holds what the
// shift held). A solution that still misses the backward-error bound takes the
// ordinary path: K is factorized and becomes the (unshifted) reference.

#include "solver/linear.hpp"

#include <memory>
#include <vector>

namespace iga::solver {

class WoodburyUpdate;

class SuiteSparseSolver final : public LinearSolver {
public:
    enum class Kind {
        lu,       ///< UMFPACK: general, non-symmetric
        cholesky  ///< CHOLMOD: known symmetric positive definite (reads the upper triangle only)
    };

    explicit SuiteSparseSolver(Kind kind);
    ~SuiteSparseSolver() override;
    SuiteSparseSolver(SuiteSparseSolver&&) noexcept;
    SuiteSparseSolver& operator=(SuiteSparseSolver&&) noexcept;
    SuiteSparseSolver(const SuiteSparseSolver&) = delete;
    SuiteSparseSolver& operator=(const SuiteSparseSolver&) = delete;

    /// Numeric factorization of K (square), after a symbolic analysis if the
    /// pattern changed since the backend's last one. K need not be compressed.
    /// Returns `singular` for an exactly singular LU (also the fallback LU of
    /// Kind::cholesky), `failed` for a non-finite K or an input the backend rejects.
    LinearStatus factorize(const SparseMatrix& K) override;
    /// As factorize(K); K's storage becomes the reference's instead of a copy of it.
    LinearStatus factorize_taking(SparseMatrix& K) override;

    /// K + mu D of the last factorize()'s K (solver/linear.hpp); the diagonal is
    /// added to K's pattern once if it lacks entries, so the symbolic analysis of
    /// the shifted pattern serves every mu.
    LinearStatus factorize_shifted(double mu) override;
    /// K + mu D without factorizing K first; K's storage becomes the reference's.
    LinearStatus factorize_shifted_taking(SparseMatrix& K, double mu) override;

    /// Solves K x = b with the last successful factorization. Returns `singular`
    /// when x is not finite or the backward error ||K x - b|| > 1e-6 ||b||
    /// (a near-singular K that the pivoting did not flag); x is then unspecified.
    /// Precondition: the last factorize() returned ok.
    LinearStatus solve(const Vector& b, Vector& x) override;

    LinearStatistics statistics() const override;
    std::string describe() const override;

    /// Woodbury updates of a reference factorization (see above): for tangents that
    /// change in a few rows and columns between calls (contact under small
    /// kinematics). Off by default.
    void set_updates(bool on);
    /// Whether the last factorize() was an update of the reference (Woodbury, or the
    /// removal of the reference's shift by refinement, or both).
    bool updated() const override { return updated_; }

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

    /// UMFPACK's 64-bit version (umfpack_dl) from the next LU on. It is taken by itself
    /// when the 32-bit version reports a factor too large for its indices (as out of
    /// memory, however much the machine has); this asks for it from the start.
    void set_lu_64bit();
    /// The LU in use is UMFPACK's 64-bit version.
    bool lu_64bit() const;

    /// Switches the backend (each keeps its own symbolic analysis).
    void set_kind(Kind kind);

    Kind kind() const { return kind_; }
    /// The backend of the last successful factorization (lu after a Cholesky fallback).
    Kind factorized_kind() const { return factorized_kind_; }
    int n_cholesky_fallbacks() const { return n_fallbacks_; }  ///< matrices Cholesky refused so far
    int n_symbolic() const { return n_symbolic_; }  ///< symbolic analyses done so far
    int n_numeric() const { return n_numeric_; }    ///< numeric factorizations done so far
    /// factorize() calls served by an update of the reference (Woodbury, or an unshift
    /// by refinement); one whose solve fell back to a factorization is not counted.
    int n_updates() const { return n_updates_; }
    Index size() const { return reference_.rows(); }
    /// Entries of the reference as stored: one triangle of a symmetric K under Kind::cholesky.
    Index stored_entries() const { return reference_.nonZeros(); }

private:
    struct Backend;  // the Eigen/SuiteSparse objects, kept out of this header

    // factorize(); owned: K itself, handed over by factorize_taking() (swapped in, not copied)
    LinearStatus factorize_matrix(const SparseMatrix& K, SparseMatrix* owned);
    void take_reference(const SparseMatrix& K, SparseMatrix* owned);  // reference_ := K, unfactorized
    LinearStatus factorize_reference();  // reference_ as it stands, Cholesky or LU by the policy above
    // K x for the K of the last factorize*(): an update's K_u + P^T D P (K_u: reference_ unshifted)
    Vector apply(const Vector& x) const;
    void materialize();  // reference_ := the K of the last factorize() (unshifted, the update's difference added)
    LinearStatus refactorize_and_solve(const Vector& b, Vector& x);  // an update missed the bound: the ordinary path

    bool same_pattern(const SparseMatrix& K) const;  // as reference_
    LinearStatus factorize_with(Kind kind);  // reference_ by one backend, after its analysis if needed
    LinearStatus factorize_lu(const SparseMatrix& A, bool& analysed);
    LinearStatus factorize_cholesky(bool& analysed);
    const SparseMatrix& lu_source();         // reference_ as a whole matrix, for UMFPACK
    bool try_update(const SparseMatrix& K);  // K as a Woodbury update of reference_, if it pays
    Matrix solve_reference(const Matrix& B) const;  // reference_^-1 B

    Kind kind_;
    Kind factorized_kind_;
    std::unique_ptr<Backend> backend_;
    SparseMatrix reference_;      // the factorized matrix (compressed), read by solve(); upper_: its upper triangle
    bool upper_ = false;          // reference_ holds the upper triangle only (Kind::cholesky: K symmetric)
    SparseMatrix lu_matrix_;      // upper_ and an LU in use: the whole matrix UMFPACK factorized and refines with
    std::unique_ptr<WoodburyUpdate> update_;  // set_updates(true)
    bool updated_ = false;        // the last factorize() was an update: solve() corrects, refines and checks against K_u + P^T D P
    double factor_flops_ = 0;     // of reference_'s factorization (backend's count)
    double column_flops_ = 0;     // of one solve with it
    double factor_entries_ = 0;   // nonzeros of its factors
    bool analysed_ = false;       // reference_'s pattern is the one the analyses below were made for
    bool analysed_lu_ = false;    // UMFPACK's symbolic analysis matches reference_'s pattern
    bool analysed_llt_ = false;   // CHOLMOD's symbolic analysis matches reference_'s pattern
    bool factorized_ = false;     // the last numeric factorization succeeded
    bool semidefinite_ = false;   // set_semidefinite()
    int cholesky_skips_ = 0;      // factorizations left before Cholesky is tried again
    int cholesky_backoff_ = 1;    // skips after the next refusal (doubles, at most 32)
    int n_fallbacks_ = 0;
    int n_symbolic_ = 0;
    int n_numeric_ = 0;
    int n_updates_ = 0;
    Ordering ordering_ = Ordering::minimum_degree;
    // factorize_shifted(): reference_ holds K_u with its whole diagonal (made at the first
    // shift after a factorize()), shifted by shift_ D; K_u's diagonal values, D, and where
    // they sit. shift_base_valid_: K_u is the K of the last factorize() (no update since).
    std::vector<int> diagonal_position_;
    Vector base_diagonal_, shift_scale_;
    double shift_ = 0;            // mu of reference_'s shift, 0: reference_ is K_u itself
    bool shift_base_valid_ = false;
};

const char* kind_name(SuiteSparseSolver::Kind kind);

}  // namespace iga::solver
