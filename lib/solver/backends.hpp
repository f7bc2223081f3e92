#pragma once
// What each linear backend can do, stated once: one row per backend and method, and
// for each which matrices it takes, whether it runs on several MPI ranks, whether it
// is direct, whether it serves a changed tangent by a low-rank (Woodbury) update,
// whether it factorizes K + mu D, and whether this build has it. Everything else asks
// this table: make_linear_solver (solver/linear_policy.cpp) checks a policy against it
// and makes the row's solver, the app's --version lists its backends, the deck's solver.backend
// and solver.type are these enums themselves (core/model_options.hpp), and
// tests/solver/linear_backends_test.cpp runs one contract over every row this build
// has. The deck reader (io/deck_reader.cpp) may not link solver/: that test checks its
// spellings and its rule "iterative needs petsc" against this table.

#include "core/model_options.hpp"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace iga {
class Communicator;
}

namespace iga::solver {

class LinearSolver;
struct LinearSolverPolicy;

/// The backends a deck can choose and their methods (core/model_options.hpp).
using Backend = iga::SolverBackend;
using Method = iga::SolverType;

/// One method of one backend (a row of the table).
struct LinearMethod {
    Backend backend;
    Method method;
    std::string_view backend_name;  ///< the deck's spelling of `solver.backend`
    std::string_view name;          ///< the factorization or Krylov method, e.g. "CHOLMOD Cholesky"
    /// Chosen for symmetric tangents, and solves only those (it reads one triangle, or
    /// its method needs symmetry); else any square matrix.
    bool symmetric_only;
    bool distributed;       ///< runs on several MPI ranks (the ranks' summands of K)
    bool woodbury_updates;  ///< a tangent that changed in a few rows may be a low-rank update
    bool shifted;           ///< factorize_shifted(mu): K + mu D (Newton's Levenberg-Marquardt step)
    /// Makes the solver for a policy; null when this build does not have the backend.
    std::unique_ptr<LinearSolver> (*make)(const LinearSolverPolicy& policy, const Communicator& comm);
    /// What is missing when `make` is null: how to build it in.
    std::string_view build_hint;

    bool available() const { return make != nullptr; }
    bool direct() const { return method == Method::direct; }
};

/// Every row, available in this build or not, suitesparse first (the default).
std::span<const LinearMethod> linear_methods();

/// The row that solves a policy's (backend, method, symmetric); nullopt when the
/// backend has no such method (suitesparse has no iterative one).
const LinearMethod* find_linear_method(Backend backend, Method method, bool symmetric);

/// The backend of that deck spelling ("suitesparse", "petsc"); nullopt for another word.
std::optional<Backend> backend_named(std::string_view name);
std::string_view backend_name(Backend backend);

/// Any method of the backend is built in / runs on several ranks.
bool backend_available(Backend backend);
bool backend_distributed(Backend backend);
/// The backend that runs on several ranks (a run under mpirun -np N > 1 takes it).
Backend distributed_backend();

/// The backends this build has, in the table's order: "suitesparse, petsc".
std::string available_backends();

/// Whether this build has the PETSc backend.
inline bool petsc_available() { return backend_available(Backend::petsc); }

}  // namespace iga::solver
