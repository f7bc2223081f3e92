// The table of linear backends (solver/backends.hpp), and how each row's solver is
// made and configured from the policy.
//
// SuiteSparse (one process):
//   - Cholesky (CHOLMOD) when every tangent is symmetric, else LU (UMFPACK):
//     Cholesky reads one triangle and would silently solve the wrong system;
//   - semi-definite tangents (small strain against rigid planes): a matrix Cholesky
//     refuses is singular, and the LU that would only say so again is skipped;
//   - nested dissection (METIS) in 3D, where it fills far less than AMD;
//   - Woodbury updates where tangents change in a few rows (small strain + contact).
// PETSc (any number of ranks): see solver/petsc_solver.hpp for its defaults.

#include "solver/backends.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "solver/linear.hpp"
#include "solver/suitesparse_solver.hpp"

#ifdef IGACONTACT_HAVE_PETSC
#include "solver/petsc_solver.hpp"
#endif

#include <algorithm>
#include <array>

namespace iga::solver {

namespace {

std::unique_ptr<LinearSolver> make_suitesparse(const LinearSolverPolicy& policy, const Communicator&)
{
    auto solver = std::make_unique<SuiteSparseSolver>(policy.symmetric ? SuiteSparseSolver::Kind::cholesky
                                                                       : SuiteSparseSolver::Kind::lu);
    if (policy.dim == 3)
        solver->set_ordering(SuiteSparseSolver::Ordering::nested_dissection);
    solver->set_semidefinite(policy.symmetric && policy.semidefinite);
    if (policy.updates)
        solver->set_updates(true);
    return solver;
}

#ifdef IGACONTACT_HAVE_PETSC
std::unique_ptr<LinearSolver> make_petsc(const LinearSolverPolicy& policy, const Communicator& comm)
{
    return std::make_unique<PetscSolver>(policy, comm);
}
constexpr auto petsc_maker = &make_petsc;
#else
constexpr std::unique_ptr<LinearSolver> (*petsc_maker)(const LinearSolverPolicy&, const Communicator&) = nullptr;
#endif

constexpr std::string_view petsc_hint = "PETSc was not found at build time; scripts/setup.sh installs it";

// clang-format off
//  backend               method             deck name      method name         symmetric distributed updates shifted  make               hint
const std::array<LinearMethod, 6> table{{
    {Backend::suitesparse, Method::direct,    "suitesparse", "CHOLMOD Cholesky", true,     false,      true,   true,    &make_suitesparse, {}},
    {Backend::suitesparse, Method::direct,    "suitesparse", "UMFPACK LU",       false,    false,      true,   true,    &make_suitesparse, {}},
    {Backend::petsc,       Method::direct,    "petsc",       "MUMPS Cholesky",   true,     true,       false,  true,    petsc_maker,       petsc_hint},
    {Backend::petsc,       Method::direct,    "petsc",       "MUMPS LU",         false,    true,       false,  true,    petsc_maker,       petsc_hint},
    {Backend::petsc,       Method::iterative, "petsc",       "CG + AMG",         true,     true,       false,  true,    petsc_maker,       petsc_hint},
    {Backend::petsc,       Method::iterative, "petsc",       "GMRES + AMG / LU", false,    true,       false,  true,    petsc_maker,       petsc_hint},
}};
// clang-format on

}  // namespace

std::span<const LinearMethod> linear_methods()
{
    return table;
}

const LinearMethod* find_linear_method(Backend backend, Method method, bool symmetric)
{
    for (const LinearMethod& m : table)
        if (m.backend == backend && m.method == method && m.symmetric_only == symmetric)
            return &m;
    return nullptr;
}

std::optional<Backend> backend_named(std::string_view name)
{
    for (const LinearMethod& m : table)
        if (m.backend_name == name)
            return m.backend;
    return std::nullopt;
}

std::string_view backend_name(Backend backend)
{
    for (const LinearMethod& m : table)
        if (m.backend == backend)
            return m.backend_name;
    return "?";
}

bool backend_available(Backend backend)
{
    return std::any_of(table.begin(), table.end(),
                       [&](const LinearMethod& m) { return m.backend == backend && m.available(); });
}

bool backend_distributed(Backend backend)
{
    return std::any_of(table.begin(), table.end(),
                       [&](const LinearMethod& m) { return m.backend == backend && m.distributed; });
}

Backend distributed_backend()
{
    const auto m = std::find_if(table.begin(), table.end(), [](const LinearMethod& m) { return m.distributed; });
    IGA_CHECK(m != table.end(), "distributed_backend: the table has no distributed backend");
    return m->backend;
}

std::string available_backends()
{
    std::string text;
    for (std::size_t k = 0; k < table.size(); ++k) {
        const LinearMethod& m = table[k];
        const bool first_of_backend = k == 0 || table[k - 1].backend != m.backend;
        if (first_of_backend && backend_available(m.backend))
            text += (text.empty() ? "" : ", ") + std::string(m.backend_name);
    }
    return text;
}

}  // namespace iga::solver
