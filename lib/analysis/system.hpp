#pragma once
// The residual and tangent of a scene at pseudo-time t, as the sum of its terms
// (analysis/term.hpp: elastic bodies, weak springs, dead loads, follower pressures,
// one contact term per pair, in that order):
//   r(u) = f_int(u) - sum_k a_k(t) f_k - sum_j a_j(t) f_follower,j(u) + sum_pairs r_c(u),
//   K = dr/du,
// on the free dofs (solver/newton.hpp's NonlinearSystem, whose load factor is t),
// each load scaled by its amplitude (Scene::dead_loads, FollowerPressure); the
// prescribed displacements and obstacle motions enter through u_full and r_c at t.
// Without amplitudes every a(t) = t = lambda, the classic load factor.
//
// Finite kinematics: elements are evaluated on n_threads() threads
// (analysis/elastic_term.hpp); contact pairs serially, first (their prepare()): a
// coupling not registered yet extends the pattern before the tangent matrix is made.
// Small kinematics: the element stiffness is constant, assembled once and reused
// (f_int = K u): no geometric terms are ever computed.
//
// force_scale (the scale of the relative residual) = max(||external forces||,
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
// its round-off; |f_e| per element for finite kinematics; |a_k(t)| |f_k|; |r_c|),
// plus the round-off of the contact pressures from their gaps (eps_mach eps |x| W
// per active Gauss point: a gap is a difference of coordinates). docs/theory.md,
// "When Newton has converged".
//
// Stopping: Newton's evaluations (context given) poll the context's stop request
// per contact pair and per element block and throw Interrupted (core/stop.hpp).
// On several ranks a stop must be taken by all ranks at the same point (one rank
// alone leaving would leave the others waiting in a sum): the request is then
// polled once per evaluation, inside the sum over the ranks.
//
// Parallel runs (core/parallel.hpp): a rank assembles the element blocks, follower
// sides and contact couplings of scene.partition into its tangent (its summand);
// dead loads, weak springs and the contact residual are added by rank 0 only (the
// contact evaluation itself runs on every rank, each for all Gauss points: the
// surfaces are O(N^(2/3)) of the model); then r, the round-off magnitudes and the
// norms are summed over the ranks, so every rank holds the same residual.

#include "analysis/contact_term.hpp"
#include "analysis/elastic_term.hpp"
#include "analysis/free_modes.hpp"
#include "analysis/load_terms.hpp"
#include "analysis/scene.hpp"
#include "analysis/term.hpp"
#include "core/run_context.hpp"
#include "solver/newton.hpp"

#include <memory>
#include <vector>

namespace iga::analysis {

class SceneSystem {
public:
    /// requested_threads: >= 1 exactly that many for the element loop, 0 automatic.
    /// comm: the ranks of a parallel run (core/parallel.hpp); each assembles the
    /// blocks of scene.partition, and every residual is summed over the ranks.
    SceneSystem(Scene& scene, RunContext& context, int requested_threads = 0,
                const Communicator& comm = Communicator());

    /// Threads of the element loop (1 for small kinematics, whose loop is serial).
    int n_threads() const { return elastic_->n_threads(); }
    /// Threads worth giving the linear solver's BLAS (the automatic choice for the
    /// tangent's size, or --threads), also where the assembly stays serial.
    int library_threads() const { return elastic_->library_threads(); }

    /// The NonlinearSystem view for the solver (captures this object).
    solver::NonlinearSystem nonlinear_system();

    void evaluate(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out);

    /// The residual on ALL dofs (n_full) at a state, without tangent, timers or
    /// counters. At equilibrium f_int = f_ext(t) - r_c + R on every dof, so the
    /// constrained entries of r = f_int - f_ext(t) + r_c are the reactions R (the
    /// force each constraint exerts on the body).
    Vector full_residual(const Vector& u_free, double load_factor);
    /// Every term's part of the results step at a converged state, right after its
    /// full_residual (analysis/term.hpp, Term::report).
    void report(const Vector& u_free, double load_factor, int samples_per_span, io::StepData& step) const;
    /// What the converged state `step` says is wrong with each term (Term::warnings).
    std::vector<std::string> warnings(const io::StepData& step) const;

    /// Contact evaluation of every pair at a converged state (no tangent, not counted
    /// in the contact timers): for output.
    std::vector<contact::PairEvaluation> contact_state(const Vector& u_free, double load_factor);

    /// Holds the listed contact points (solver::Evaluation::contact_active indices) open
    /// (solver::NonlinearSystem::hold_open); counted in /counters contact_points_held_open.
    /// How many it held.
    int hold_open(const std::vector<int>& points);
    /// At a converged state: frees held points that now press too deep to be left
    /// without force (solver::NonlinearSystem::release_deep_holds). How many.
    int release_deep_holds();
    /// After a converged increment: every term's state becomes the committed one.
    void commit();
    /// After a failed attempt: every term back to its committed state.
    void rollback();

    /// n_cp x d displacements of the control points of body b from a full vector.
    RowMatrix body_displacement(const Vector& u_full, int b) const;
    /// n_cp_side x d displacements of surface k of pair p (empty for a rigid surface).
    RowMatrix side_displacement(const Vector& u_full, int p, int k) const;

    int last_active() const { return last_active_; }

    /// Small kinematics: assembles the constant elastic stiffness K0 now (otherwise at
    /// the first evaluation); afterwards the elements' quadrature data are no longer
    /// read (release_element_geometry). No effect under finite kinematics.
    void assemble_constant_stiffness(const StopRequest& stop = {}) { elastic_->assemble_constant_stiffness(stop); }

    /// Per rank (one entry each, the same on every rank): the element blocks and the
    /// contact couplings it assembles. Collective.
    std::vector<double> elements_per_rank() const;
    std::vector<double> couplings_per_rank() const;

    /// Weak springs on free rigid-body modes, a term of every later evaluation.
    void set_weak_springs(std::vector<NodeSpring> springs);
    /// The tangent is singular while no contact point carries (singular_without_contact,
    /// analysis/free_modes.hpp): such an evaluation says so (Evaluation::singular_tangent).
    void set_singular_without_contact(bool singular) { singular_without_contact_ = singular; }

    const Communicator& communicator() const { return comm_; }
    /// On several ranks: the stop request, polled by all ranks together once per
    /// evaluation (see the header); the run clears the context's own.
    void set_collective_stop(StopRequest stop) { collective_stop_ = stop; }
    /// 1/2 sum_a u_a^T S_a u_a over the weak springs at a state.
    double spring_energy(const Vector& u_free, double load_factor) const;
    /// 1/2 u . f_int(u) over all dofs: the strain energy under small kinematics, its
    /// secant estimate under finite kinematics (the scale the spring energy is judged by).
    double strain_energy(const Vector& u_free, double load_factor);

private:
    void evaluate_into(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out,
                       RunContext* context, Vector* r_full_out);
    /// Gives the tangent the pattern (keeping its storage) or releases it.
    void shape_tangent(bool need_tangent, SparseMatrix& tangent) const;
    /// Sums the ranks' parts of an evaluation (no-op on one process) and makes
    /// failures and stop requests collective.
    void sum_over_ranks(ModelAssembly& a, RunContext* context) const;
    /// r, the force scale and the round-off floor of a summed evaluation into `out`.
    void finish(ModelAssembly& a, solver::Evaluation& out) const;

    Scene& scene_;
    RunContext& context_;
    Communicator comm_;
    std::vector<std::unique_ptr<Term>> terms_;  // in the order of the sums (analysis/term.hpp)
    ElasticTerm* elastic_ = nullptr;            // terms_[0]
    WeakSpringTerm* springs_ = nullptr;         // after it, when set
    std::vector<ContactTerm*> contact_;         // one per pair, last
    int last_active_ = 0;
    bool singular_without_contact_ = false;
    StopRequest collective_stop_;
};

}  // namespace iga::analysis
