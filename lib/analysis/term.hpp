#pragma once
// The discrete model as a list of terms. Every part of it -- the elastic bodies,
// the dead loads, the follower pressures, the weak springs on free modes, one
// contact interaction per pair -- is a Term, and one evaluation of the model is a
// loop over them (analysis/system.hpp):
//
//   r(u) = sum_terms r_term(u, t),   K = sum_terms dr_term/du,
//
// in two passes: every term's prepare() (a contact term searches, projects and
// registers the couplings it met, which may extend the sparsity pattern), then, once
// the tangent has its pattern, every term's add_to() (residual, round-off magnitude
// and tangent blocks into the ModelAssembly). A term with history (contact: foot
// points, multipliers, stick/slip) keeps it itself: commit() after a converged
// increment, rollback() after a failed attempt. At a converged state a term adds what
// it has to show to the results step (report(): a contact pair its sides, pressures
// and forces) and names what the state says is wrong with it (warnings()).
//
// The order of the terms is the order of the sums (elastic bodies, weak springs,
// dead loads, follower pressures, contact pairs): it is fixed, so a run's round-off
// is reproducible.
//
// Parallel runs: which rank adds what is decided here, once. A tangent block goes
// to the rank that owns its pattern block (Partition::owns, via add_block); terms
// that are not split over the ranks (dead loads, the contact residual) are added by
// the root rank only (root()); the driver then sums r over the ranks.

#include "analysis/scene.hpp"
#include "core/run_context.hpp"
#include "core/stop.hpp"
#include "io/results_data.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// What one evaluation accumulates over the terms. Vectors are over ALL dofs
/// (n_full); the tangent is over the free dofs, in the scene's pattern.
struct ModelAssembly {
    /// An evaluation at u_full and t; `stop` polled per element block and pair.
    ModelAssembly(const Scene& scene_, const Vector& u_full_, double t_, bool need_tangent_ = false,
                  RunContext* context_ = nullptr, StopRequest stop_ = {}, bool root_ = true)
        : scene(scene_), u_full(u_full_), t(t_), need_tangent(need_tangent_), context(context_),
          stop(std::move(stop_)), root(root_)
    {
    }

    const Scene& scene;
    const Vector& u_full;  ///< displacements of all dofs at t (prescribed ones included)
    double t = 0.0;        ///< pseudo-time (the load factor without amplitudes)
    bool need_tangent = false;
    RunContext* context = nullptr;  ///< timers and counters of Newton's evaluations; null for output
    StopRequest stop;               ///< polled per element block and per pair (empty: never)
    bool root = true;               ///< this rank adds the terms that are not split over the ranks

    Vector r_full;     ///< the residual
    Vector magnitude;  ///< per dof, the sum of |each term summed into r|: its round-off scale
    Vector f_int;      ///< the internal forces alone (their constrained entries are the reactions)
    SparseMatrix* tangent = nullptr;  ///< null when need_tangent is false

    double external_norm = 0.0;  ///< ||dead loads|| + sum ||follower forces|| (this rank's part)
    double contact_norm = 0.0;   ///< sum over pairs of ||r_c||
    double gap_round_off = 0.0;  ///< round-off of the contact pressures, already times eps_mach
    int active = 0;              ///< Gauss points with positive pressure, all pairs

    bool ok = true;       ///< false: a numerical failure, named in `message`
    std::string message;

    /// Whether this rank assembles pattern block `block`.
    bool owns(int block) const { return scene.partition.owns(block); }
    /// K into the tangent at pattern block `block`, on the rank that owns it.
    void add_block(int block, const Matrix& K)
    {
        if (owns(block))
            scene.pattern->add(block, K, *tangent);
    }
    /// Records a numerical failure (the last one named wins, as the terms run in order).
    void fail(std::string why)
    {
        ok = false;
        message = std::move(why);
    }
};

/// The n x d displacements of the control points of a block from the full vector
/// (`dofs` in local a*d + i order).
Matrix local_displacement(const Vector& u_full, const std::vector<int>& dofs, int d);

/// One part of the discrete model (see the header).
class Term {
public:
    virtual ~Term() = default;
    /// Before the tangent is shaped: work that may extend the sparsity pattern.
    virtual void prepare(ModelAssembly&) {}
    /// Residual, magnitudes and (when asked) tangent blocks of this term.
    virtual void add_to(ModelAssembly& a) = 0;
    /// After a converged increment: its state becomes the committed one.
    virtual void commit() {}
    /// After a failed attempt: back to the committed state.
    virtual void rollback() {}
    /// At a converged state, after an evaluation of it (prepare() and add_to()): what
    /// this term adds to the results step. `samples_per_span`: output.samples_per_span.
    virtual void report(const ModelAssembly&, int /*samples_per_span*/, io::StepData&) const {}
    /// What the converged state `step` (reported by every term) says is wrong with this term.
    virtual std::vector<std::string> warnings(const io::StepData&) const { return {}; }
};

}  // namespace iga::analysis
