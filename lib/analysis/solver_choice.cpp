#include "analysis/solver_choice.hpp"

#include "core/error.hpp"
#include "io/deck_names.hpp"

#include <algorithm>
#include <optional>

namespace iga::analysis {

Matrix rigid_body_modes(const Scene& scene)
{
    const assembly::DofMap& dofs = *scene.dofs;
    const int d = scene.dim;
    const int n_modes = d == 2 ? 3 : 6;
    Matrix modes = Matrix::Zero(dofs.n_free(), n_modes);
    // Rotations about the centroid keep the modes well conditioned against the translations.
    VecN centre = VecN::Zero(d);
    Index n_points = 0;
    for (const BodyModel& body : scene.bodies) {
        centre += body.node_points.colwise().sum().transpose();
        n_points += body.node_points.rows();
    }
    if (n_points > 0)
        centre /= static_cast<double>(n_points);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        const BodyModel& body = scene.bodies[b];
        for (int a = 0; a < body.n_nodes; ++a) {
            const VecN x = body.node_points.row(a).transpose() - centre;
            const int node = dofs.node_offset(static_cast<int>(b)) + a;
            auto set = [&](int component, int mode, double value) {
                const int free = dofs.free_index(dofs.dof(node, component));
                if (free >= 0)
                    modes(free, mode) = value;
            };
            for (int i = 0; i < d; ++i)
                set(i, i, 1.0);
            if (d == 2) {  // rotation about z: (-y, x)
                set(0, 2, -x(1));
                set(1, 2, x(0));
            } else {  // about x: (0, -z, y); about y: (z, 0, -x); about z: (-y, x, 0)
                set(1, 3, -x(2));
                set(2, 3, x(1));
                set(0, 4, x(2));
                set(2, 4, -x(0));
                set(0, 5, -x(1));
                set(1, 5, x(0));
            }
        }
    }
    return modes;
}

int point_block_size(const Scene& scene)
{
    // Free dofs are numbered in increasing full order, node by node (assembly/dof_map.hpp),
    // so they form blocks of d exactly when no node is partly constrained (a roller).
    const assembly::DofMap& dofs = *scene.dofs;
    const int d = scene.dim;
    for (int node = 0; node < dofs.n_full() / d; ++node) {
        int n_free = 0;
        for (int i = 0; i < d; ++i)
            n_free += dofs.free_index(dofs.dof(node, i)) >= 0 ? 1 : 0;
        if (n_free != 0 && n_free != d)
            return 1;
    }
    return d;
}

solver::LinearSolverPolicy linear_solver_policy(const Scene& scene,
                                                const solver::NonlinearSystem& system, const Communicator& comm)
{
    solver::LinearSolverPolicy policy;
    // The deck's backend by its spelling in the table (solver/backends.hpp); on several
    // ranks one that is not distributed gives way to the one that is.
    const solver::Backend named = scene.settings.solver.backend;
    policy.backend = comm.parallel() && !solver::backend_distributed(named) ? solver::distributed_backend() : named;
    policy.method = scene.settings.solver.type;
    policy.options = scene.settings.solver.options;
    policy.symmetric = system.symmetric;
    policy.dim = scene.dim;
    // Small-strain elasticity plus penalty contact against rigid planes (eps N N^T
    // (x) n n^T per Gauss point) is positive semi-definite: a tangent Cholesky
    // refuses is singular (a body held by contact alone before it touches), and the
    // LU that would only find that out again (several Cholesky costs in 3D) is
    // skipped. Curved obstacles (the turning normal adds -p/r (I - n n)) and finite
    // strain can be indefinite and keep the LU fallback.
    const bool only_planes = std::all_of(scene.pairs.begin(), scene.pairs.end(), [](const PairModel& p) {
        if (p.obstacle < 0)
            return false;
        const auto& obstacle = std::get<contact::RigidObstacle>(p.pair.surface(p.obstacle));
        return std::holds_alternative<contact::RigidPlane>(obstacle.shape);
    });
    policy.semidefinite = system.symmetric && scene.kinematics == mechanics::Kinematics::small &&
                          scene.followers.empty() && only_planes;
    // Small kinematics with contact: the tangent is the constant elastic stiffness
    // plus the contact stiffness of the active Gauss points, so one factorization
    // serves the following iterations and increments as a reference, and each new
    // tangent is a Woodbury update on the active contact dofs (solver/woodbury.hpp)
    // as long as that costs fewer flops than a factorization (the solver decides).
    policy.updates = scene.kinematics == mechanics::Kinematics::small && scene.has_contact();
    for (const PairModel& pair : scene.pairs)
        if (pair.rule.modulus > 0.0)
            policy.penalty_ratio = std::max(policy.penalty_ratio,
                                            pair.pair.settings().law.stiffness() * pair.rule.element_size /
                                                pair.rule.modulus);
    policy.two_body_contact =
        std::any_of(scene.pairs.begin(), scene.pairs.end(), [](const PairModel& p) { return p.obstacle < 0; });
    if (policy.method == solver::Method::iterative) {  // multigrid: the near-null space, point blocks
        policy.rigid_body_modes = rigid_body_modes(scene);
        policy.block_size = point_block_size(scene);
    }
    return policy;
}

}  // namespace iga::analysis
