#pragma once
// PetscSolver: the PETSc backend of LinearSolver (solver/linear.hpp), on the MPI
// ranks of the run (one rank without mpirun).
//
// Matrix: a distributed AIJ matrix; rank r owns the contiguous rows
// Communicator::block_range(n). Each rank hands over its summand (solver/linear.hpp)
// in Eigen's compressed columns; the entries, wherever their rows live, go through
// PETSc's COO assembly (MatSetPreallocationCOO once per sparsity pattern — exact
// preallocation, extended when a contact coupling extends the pattern — then
// MatSetValuesCOO per factorization, which sums the ranks' entries). Every owned
// diagonal entry is in the pattern, so the Levenberg-Marquardt shift needs no new one.
// CG's products use a second matrix, the upper triangle in symmetric blocks (SBAIJ):
// half the memory traffic of AIJ, which the multigrid set-up still needs.
//
// Methods (policy.method), defaults chosen for penalty and augmented-Lagrangian
// contact (docs/parallel.md):
//   direct:    MUMPS; Cholesky (LDL^T, so also indefinite) for symmetric tangents,
//              else LU.
//   iterative: CG for symmetric tangents, else GMRES(100) with right
//              preconditioning, both on the true residual, rtol 1e-8 (or what
//              solve_to asks, down to 1e-10); smoothed
//              aggregation (GAMG) with the rigid-body modes as near-null space, or,
//              when a contact penalty is stiff against its elements (eps h / E' >
//              1e2, where aggregation fails), hypre BoomerAMG. A non-symmetric
//              tangent of two deformable bodies in contact (policy.two_body_contact):
//              GMRES with a MUMPS LU, as no multigrid fits it. The
//              preconditioner is reused across Newton iterations while the Krylov
//              iterations stay within twice those of its first solve; a solve that
//              fails with a reused one is repeated with a fresh one. A solve that,
//              at the pace of its last 100 iterations, would miss its tolerance at
//              the cap of 1000 stops there as stalled.
// The options database comes last and wins: the deck's `solver.options`, then the
// PETSC_OPTIONS environment variable (e.g. "-pc_type gamg -ksp_monitor"). Both are
// checked before PETSc starts (core/petsc_options.hpp): a refused option throws
// PetscOptionsError on every rank alike, as does an option whose value PETSc rejects
// when it makes or sets up the solver or solves (-mg_levels_pc_type bogus): bad input,
// never a singular tangent. PETSc reads no options file, and what it prints (monitors,
// views) goes to standard error. warnings() names the options no solver read.
//
// Statuses: a zero pivot in the factorization or a preconditioner that cannot be
// built: `singular`; a solution whose true residual exceeds its bound (1e-6 ||b||, or
// 10 times the Krylov tolerance where that is more): `singular` from MUMPS, `not_converged` from
// a Krylov method, as is one that stops short (Newton shifts on either,
// solver/newton.hpp); a non-finite entry on any rank: `failed`.

#include "core/parallel.hpp"
#include "core/petsc_options.hpp"
#include "solver/linear.hpp"

#include <memory>
#include <vector>

namespace iga::solver {

class PetscSolver final : public LinearSolver {
public:
    PetscSolver(const LinearSolverPolicy& policy, const Communicator& comm);
    ~PetscSolver() override;
    PetscSolver(const PetscSolver&) = delete;
    PetscSolver& operator=(const PetscSolver&) = delete;

    LinearStatus factorize(const SparseMatrix& K) override;
    LinearStatus factorize_taking(SparseMatrix& K) override;
    LinearStatus factorize_shifted(double mu) override;
    /// K's values into the matrix, then factorize_shifted(mu): no factorization (or
    /// preconditioner) of a K known to be singular. K is left empty.
    LinearStatus factorize_shifted_taking(SparseMatrix& K, double mu) override;
    LinearStatus solve(const Vector& b, Vector& x) override;
    /// A Krylov method stops at max(accuracy, 1e-10) relative residual, unless the
    /// options database sets -ksp_rtol.
    LinearStatus solve_to(const Vector& b, Vector& x, double accuracy) override;
    LinearStatistics statistics() const override { return statistics_; }
    std::string describe() const override;
    std::string failure_detail() const override { return failure_detail_; }
    /// The options of the deck and of PETSC_OPTIONS that no PETSc object read
    /// (misspelt, or not taken by this method and preconditioner), once the
    /// preconditioner was set up.
    std::vector<std::string> warnings() const override;
    /// "cg + gamg": the Krylov method and preconditioner, for messages.
    std::string describe_method() const;

private:
    struct State;  // the PETSc objects, kept out of this header

    LinearStatus load(const SparseMatrix& K);  // K's values into the matrix (its pattern made when new); failed: not finite
    LinearStatus prepare();  // after load(): the preconditioner kept, or set up anew
    LinearStatus set_up_preconditioner();
    LinearStatus solve_with(const Vector& b, Vector& x, double rtol);  // rtol <= 0: the KSP's own
    void new_ksp();  // the policy's KSP, then the options database applied (a rejected option throws)
    // After a PETSc error on some rank (collective): throws PetscOptionsError on every
    // rank when on any rank it came from an option.
    void throw_if_options_error(bool failed_here) const;

    LinearSolverPolicy policy_;
    Communicator comm_;
    std::unique_ptr<State> state_;
    LinearStatistics statistics_;
    std::string failure_detail_;  // of the last factorize/solve that did not return ok
    std::vector<PetscOption> deck_options_, environment_options_;  // as checked: for messages, warnings()
};

}  // namespace iga::solver
