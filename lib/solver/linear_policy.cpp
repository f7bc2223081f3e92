// make_linear_solver: the one place that decides which backend solves Newton's
// systems and how (solver/linear.hpp).
//
// SuiteSparse (one process):
//   - Cholesky (CHOLMOD) when every tangent is symmetric, else LU (UMFPACK):
//     Cholesky reads one triangle and would silently solve the wrong system;
//   - semi-definite tangents (small strain against rigid planes): a matrix Cholesky
//     refuses is singular, and the LU that would only say so again is skipped;
//   - nested dissection (METIS) in 3D, where it fills far less than AMD;
//   - Woodbury updates where tangents change in a few rows (small strain + contact).
// PETSc (any number of ranks): see solver/petsc_solver.hpp for its defaults.

#include "solver/linear.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "solver/suitesparse_solver.hpp"

#ifdef IGACONTACT_HAVE_PETSC
#include "solver/petsc_solver.hpp"
#endif

namespace iga::solver {

const char* status_name(LinearStatus status)
{
    switch (status) {
    case LinearStatus::ok: return "ok";
    case LinearStatus::singular: return "singular";
    case LinearStatus::failed: return "failed";
    case LinearStatus::not_converged: return "not converged";
    }
    return "unknown";
}

bool petsc_available()
{
#ifdef IGACONTACT_HAVE_PETSC
    return true;
#else
    return false;
#endif
}

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverPolicy& policy, const Communicator& comm)
{
    if (policy.backend == Backend::petsc) {
#ifdef IGACONTACT_HAVE_PETSC
        return std::make_unique<PetscSolver>(policy, comm);
#else
        throw Error("the petsc backend is not built into this igacontact (PETSc was not found at build time; "
                    "scripts/setup.sh installs it)");
#endif
    }
    if (comm.parallel())
        throw Error("the suitesparse backend runs on one process; use the petsc backend on several ranks");
    if (policy.method == Method::iterative)
        throw Error("the suitesparse backend is direct only; an iterative method needs the petsc backend");
    auto solver = std::make_unique<SuiteSparseSolver>(policy.symmetric ? SuiteSparseSolver::Kind::cholesky
                                                                       : SuiteSparseSolver::Kind::lu);
    if (policy.dim == 3)
        solver->set_ordering(SuiteSparseSolver::Ordering::nested_dissection);
    solver->set_semidefinite(policy.symmetric && policy.semidefinite);
    if (policy.updates)
        solver->set_updates(true);
    return solver;
}

}  // namespace iga::solver
