// make_linear_solver: the one place that decides which backend solves Newton's
// systems (solver/linear.hpp), by the table of what each one can do
// (solver/backends.hpp); how each is configured is its row's (solver/backends.cpp).

#include "solver/linear.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

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

namespace {

/// A row of the backend's, for what the table says of the backend as a whole.
const LinearMethod& any_row(Backend backend)
{
    for (const LinearMethod& m : linear_methods())
        if (m.backend == backend)
            return m;
    throw Error("make_linear_solver: a backend without a row in solver/backends.cpp");
}

/// The first backend that has the method.
std::string backend_with(Method method)
{
    for (const LinearMethod& m : linear_methods())
        if (m.method == method)
            return std::string(m.backend_name);
    return "?";
}

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverPolicy& policy, const Communicator& comm)
{
    const std::string backend(backend_name(policy.backend));
    if (!backend_available(policy.backend))
        throw Error("the " + backend + " backend is not built into this igacontact (" +
                    std::string(any_row(policy.backend).build_hint) + ")");
    if (comm.parallel() && !backend_distributed(policy.backend))
        throw Error("the " + backend + " backend runs on one process; use the " +
                    std::string(backend_name(distributed_backend())) + " backend on several ranks");
    const LinearMethod* method = find_linear_method(policy.backend, policy.method, policy.symmetric);
    if (!method)
        throw Error("the " + backend + " backend is " +
                    (policy.method == Method::iterative ? "direct only; an iterative method"
                                                        : "iterative only; a direct method") +
                    " needs the " + backend_with(policy.method) + " backend");
    return method->make(policy, comm);
}

}  // namespace iga::solver
