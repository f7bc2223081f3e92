#pragma once
// LinearSolver: K x = b for Newton's steps, behind one interface (the shape of
// polysolve's linear::Solver and MFEM's PETSc wrappers). Two backends,
// SuiteSparseSolver (solver/suitesparse_solver.hpp, the default) and PetscSolver
// (solver/petsc_solver.hpp, on the MPI ranks of the run, core/parallel.hpp).
// What each backend and method can do is one table (solver/backends.hpp); which one
// solves, and how it is configured (symmetric or not, semi-definite or not, updates,
// ordering, the options of an iterative method), is decided from LinearSolverPolicy
// by make_linear_solver() (solver/linear_policy.cpp) and the table's rows
// (solver/backends.cpp).
//
// The matrix a rank passes to factorize() is its summand: on one process the whole
// tangent, on several ranks the terms of the elements and contact couplings that
// rank assembled; the operator is their sum. b and x are whole vectors, the same on
// every rank (the parallel model of core/parallel.hpp).
//
// Statuses, not exceptions, for numerical failures; `ok` never comes with a
// non-finite x. Shapes: K is n x n (n free dofs), b and x have n entries.

#include "core/types.hpp"
#include "solver/backends.hpp"

#include <memory>
#include <string>
#include <vector>

namespace iga {
class Communicator;
}

namespace iga::solver {

enum class LinearStatus {
    ok,
    singular,       ///< singular (a zero pivot), or the solution fails the backward-error check
    failed,         ///< Cholesky on a matrix that is not positive definite, or an input the backend rejects
    not_converged   ///< an iterative method stopped short of its tolerance (iteration cap, breakdown,
                    ///< an indefinite preconditioner): the matrix may be singular or merely hard for it
};

const char* status_name(LinearStatus status);

/// What a backend did so far (counters of the results file).
struct LinearStatistics {
    int symbolic = 0;            ///< symbolic analyses (fill-reducing orderings)
    int numeric = 0;             ///< numeric factorizations (direct) or preconditioner set-ups (iterative)
    int updates = 0;             ///< factorize() calls served by a (Woodbury) update of an earlier factorization
    int cholesky_fallbacks = 0;  ///< matrices Cholesky refused (then factorized by LU)
    long long iterations = 0;    ///< Krylov iterations over all solves (iterative backends)
};

class LinearSolver {
public:
    virtual ~LinearSolver() = default;

    /// Prepares solves with K (this rank's summand, square): a factorization, an
    /// update of an earlier one, or a preconditioner. `singular` for an exactly
    /// singular K, `failed` for a non-finite K or one the backend rejects.
    virtual LinearStatus factorize(const SparseMatrix& K) = 0;
    /// factorize(K) for a caller that no longer needs K: the backend may take its
    /// storage, and K is left empty either way. A 3D tangent is ~100 MB at 30k dofs,
    /// and a backend that copies K would otherwise hold it twice while it factorizes.
    virtual LinearStatus factorize_taking(SparseMatrix& K)
    {
        const LinearStatus status = factorize(K);
        release(K);
        return status;
    }

    /// Prepares solves with K + mu D, K the matrix of the last factorize() and
    /// D = diag(|K_ii|) of the summed K, a zero entry replaced by the mean nonzero
    /// |K_ii| (1 when all are zero): Newton's Levenberg-Marquardt shift for a
    /// singular tangent (solver/newton.hpp). Precondition: factorize() was called.
    virtual LinearStatus factorize_shifted(double mu) = 0;
    /// factorize_taking(K) then factorize_shifted(mu), for a K the caller knows to be
    /// singular (Newton at a first touch, solver/newton.hpp): a backend may skip the
    /// factorization of K, which could only fail. Later factorize_shifted() calls shift
    /// this K. K is left empty.
    virtual LinearStatus factorize_shifted_taking(SparseMatrix& K, double mu)
    {
        factorize_taking(K);  // its status does not matter: the shifted one does
        return factorize_shifted(mu);
    }

    /// Solves with what the last factorize*() prepared. `singular` when x is not
    /// finite or ||K x - b|| > 1e-6 ||b||; x is then unspecified.
    virtual LinearStatus solve(const Vector& b, Vector& x) = 0;
    /// solve() for a caller that needs no more than ||K x - b|| <= accuracy ||b||
    /// (Newton's linear path knows what its tolerance asks of the step): an iterative
    /// backend may stop there instead of at its own tolerance, and its backward-error
    /// bound becomes max(1e-6, 10 accuracy). A direct backend solves to round-off anyway.
    virtual LinearStatus solve_to(const Vector& b, Vector& x, double accuracy)
    {
        (void)accuracy;
        return solve(b, x);
    }

    virtual LinearStatistics statistics() const = 0;
    /// One line for the log: the backend and method, e.g. "CHOLMOD Cholesky, METIS".
    virtual std::string describe() const = 0;
    /// Whether the last factorize() was an update of an earlier factorization.
    virtual bool updated() const { return false; }
    /// What the last solve that did not return `ok` showed, in a clause for a message
    /// (e.g. "cg + gamg stopped after 1000 iterations: DIVERGED_ITS"); may be empty.
    virtual std::string failure_detail() const { return {}; }
    /// Lines for the run's warnings at its end (PETSc: options no solver read).
    virtual std::vector<std::string> warnings() const { return {}; }
};

/// Everything that decides which backend and how it runs: from the deck
/// (backend, method, options) and from the scene (the rest).
struct LinearSolverPolicy {
    Backend backend = Backend::suitesparse;
    Method method = Method::direct;
    std::string options;        ///< PETSc options database text (petsc only)
    bool symmetric = true;      ///< every tangent symmetric: Cholesky / CG may be used
    bool semidefinite = false;  ///< every tangent positive semi-definite (small strain, rigid planes)
    bool updates = false;       ///< tangents change in a few rows between calls: Woodbury updates pay
    int dim = 2;                ///< space dimension: 3D orders by nested dissection, blocks of 3
    /// The stiffest contact penalty against the elements it acts on, max eps h / E'
    /// over the pairs (0 without contact): algebraic multigrid by aggregation loses
    /// its way past ~1e2 (petsc_solver.hpp).
    double penalty_ratio = 0.0;
    /// A contact pair couples two deformable bodies. With a non-symmetric tangent
    /// (two-half-pass) no algebraic multigrid fits it: GMRES is then preconditioned by
    /// a MUMPS LU (solver/petsc_solver.hpp).
    bool two_body_contact = false;
    /// The rigid-body modes on the free dofs (n_free x 3 in 2D, x 6 in 3D), the
    /// near-null space of an algebraic multigrid preconditioner; may be empty.
    Matrix rigid_body_modes;
    /// The free dofs come in consecutive blocks of this many, the components of one
    /// control point (every point all free or all fixed), or 1: smoothed aggregation
    /// then aggregates points, not single components (fewer, better aggregates).
    int block_size = 1;
};

/// The solver of the table's row (solver/backends.hpp) the policy asks for. Throws
/// Error when the backend is not built in (petsc without PETSc), when a backend that
/// is not distributed is asked for on several ranks (the caller maps that to the
/// distributed one first, analysis/solver_choice.cpp), or when the backend has no
/// such method (suitesparse has no iterative one).
std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverPolicy& policy, const Communicator& comm);

}  // namespace iga::solver
