#pragma once
// The residual and tangent of a scene, as the sum of its terms:
//   r(u) = f_int(u) - lambda f_ext - lambda f_follower(u) + sum_pairs r_c(u),
//   K = dr/du,
// on the free dofs (solver/newton.hpp's NonlinearSystem). Finite kinematics:
// elements are evaluated on n_threads() threads (colored blocks; the count from
// assembly/threads.hpp: requested, or automatic from the element work); contact
// pairs serially, first: their tangent blocks (one per slave element x master
// element coupling) go into the pattern blocks of those couplings, and a coupling
// not registered yet extends the pattern before the tangent matrix is made.
// Small kinematics: the element stiffness is constant, assembled once and
// reused (f_int = K u): no geometric terms are ever computed.
//
// force_scale (the scale of the relative residual) = max(||lambda f_ext||,
// ||reactions||, ||contact forces||, ||f_int||): the forces in play, so that
// displacement-driven scenes converge relative to their reactions.
//
// Weak springs (analysis/free_modes.hpp), when set, add S_a u_a to the residual
// and S_a to the tangent at their nodes (free dofs only: a free mode does not
// move a prescribed dof); they are not counted in the force scale.
//
// residual_floor (the round-off of ||r||, solver/newton.hpp) = eps_mach times the
// norm over the free dofs of the sum of the absolute values of every term summed
// into r (|K0| |u| for small kinematics, where a rigid motion cancels K0 u but not
// its round-off; |f_e| per element for finite kinematics; |lambda f_ext|; |r_c|),
// plus the round-off of the contact pressures from their gaps (eps_mach eps |x| W
// per active Gauss point: a gap is a difference of coordinates). docs/theory.md,
// "When Newton has converged".
//
// Stopping: Newton's evaluations (context given) poll the context's stop request
// per contact pair and per element block and throw Interrupted (core/stop.hpp).

#include "analysis/free_modes.hpp"
#include "analysis/scene.hpp"
#include "assembly/sparse_pattern.hpp"
#include "assembly/thread_team.hpp"
#include "core/run_context.hpp"
#include "solver/newton.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace iga::analysis {

class SceneSystem {
public:
    /// requested_threads: >= 1 exactly that many for the element loop, 0 automatic.
    SceneSystem(Scene& scene, RunContext& context, int requested_threads = 0);

    /// Threads of the element loop (1 for small kinematics, whose loop is serial).
    int n_threads() const { return team_ ? team_->n_threads() : 1; }

    /// The NonlinearSystem view for the solver (captures this object).
    solver::NonlinearSystem nonlinear_system();

    void evaluate(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out);

    /// The residual on ALL dofs (n_full) at a state, without tangent, timers or
    /// counters. At equilibrium f_int = lambda f_ext - r_c + R on every dof, so the
    /// constrained entries of r = f_int - lambda f_ext + r_c are the reactions R (the
    /// force each constraint exerts on the body).
    /// `contact_out`, when given, receives the pairs' evaluations at that state (for output).
    Vector full_residual(const Vector& u_free, double load_factor,
                         std::vector<contact::PairEvaluation>* contact_out = nullptr);

    /// Contact evaluation of every pair at a converged state (no tangent, not counted
    /// in the contact timers): for output.
    std::vector<contact::PairEvaluation> contact_state(const Vector& u_free, double load_factor);

    /// n_cp x d displacements of the control points of body b from a full vector.
    RowMatrix body_displacement(const Vector& u_full, int b) const;
    /// n_cp_side x d displacements of surface k of pair p (empty for a rigid surface).
    RowMatrix side_displacement(const Vector& u_full, int p, int k) const;

    int last_active() const { return last_active_; }

    /// Weak springs on free rigid-body modes, added to every later evaluation.
    void set_weak_springs(std::vector<NodeSpring> springs) { springs_ = std::move(springs); }
    /// 1/2 sum_a u_a^T S_a u_a over the weak springs at a state.
    double spring_energy(const Vector& u_free, double load_factor) const;
    /// 1/2 u . f_int(u) over all dofs: the strain energy under small kinematics, its
    /// secant estimate under finite kinematics (the scale the spring energy is judged by).
    double strain_energy(const Vector& u_free, double load_factor);

private:
    void evaluate_into(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out,
                       RunContext* context, Vector* r_full_out,
                       std::vector<contact::PairEvaluation>* contact_out);
    /// Extends the pattern by the couplings of these evaluations that it lacks.
    void register_couplings(const std::vector<contact::PairEvaluation>& contact, RunContext* context);
    void assemble_elements(const Vector& u_full, bool need_tangent, Vector& r_full, SparseMatrix& K,
                           solver::Evaluation& out, Vector& magnitude,
                           const StopRequest& stop);

    Scene& scene_;
    RunContext& context_;
    std::unique_ptr<assembly::ThreadTeam> team_;  // null: serial element loop
    struct BlockOwner {
        int body;
        int element;
    };
    std::vector<BlockOwner> owner_;                // element block -> (body, element), blocks come first
    std::optional<SparseMatrix> full_stiffness_;   // small kinematics: elastic K over all (full) dofs
    std::vector<Vector> element_force_;            // finite kinematics: f_int per block (reused storage)
    int last_active_ = 0;
    std::vector<NodeSpring> springs_;
};

}  // namespace iga::analysis
