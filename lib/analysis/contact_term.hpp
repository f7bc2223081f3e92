#pragma once
// One contact pair as a model term (analysis/term.hpp): its residual r_c and tangent
// (contact/contact_pair.hpp, Kopacka et al. eqs. 5-7) and its per-point history.
//
// prepare() evaluates the pair at the current displacements (search, projection, the
// contact law per Gauss point) and registers the couplings the pattern lacks (a
// Gauss point slid onto a master element not met before): the pattern is extended
// before the tangent is shaped, so every block of an evaluation has its place.
// add_to() adds the pair's residual (root rank: the contact evaluation runs on every
// rank, for all Gauss points) and each coupling's block on the rank that owns it.
// commit() and rollback() keep or drop the pair's trial state (foot points,
// multipliers, friction history).
//
// Round-off: the gap of an active Gauss point is a difference of coordinates of size
// |x|, so its pressure carries an error of about eps_mach (|lambda| + eps |x|), and W
// times that lands on the point's dofs; with friction a sticking traction, eps_T times
// such a difference, adds eps_mach eps_T |x|. Independent errors add in quadrature
// (ModelAssembly::gap_round_off).

#include "analysis/term.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace iga::analysis {

/// Points Newton finds cycling are held open only while the normal force they would
/// carry free is at most this share of their side's (ContactTerm::hold_open): a contact
/// edge's point, not the zone. The dragged block's trailing corner point, held, is left
/// with up to 1.4 % of its side's force (a penetration a fifth of the deepest); the three
/// edge points a coarse frictionless roller cycled on would leave out 30 %.
inline constexpr double max_held_force = 0.05;

class ContactTerm final : public Term {
public:
    ContactTerm(Scene& scene, int pair);

    void prepare(ModelAssembly& a) override;
    void add_to(ModelAssembly& a) override;
    void commit() override;
    void rollback() override;
    /// The pair's part of the step: its sides' Gauss points, recovered pressure, forces.
    void report(const ModelAssembly& a, int samples_per_span, io::StepData& step) const override;
    /// Penetration too deep for the penalty, two half passes that disagree.
    std::vector<std::string> warnings(const io::StepData& step) const override;

    /// The evaluation of the last prepare().
    const contact::PairEvaluation& evaluation() const { return evaluation_; }
    /// Appends, per Gauss point of the carrying sides in order, 1 where it presses in
    /// the last evaluation and 0 elsewhere (solver::Evaluation::contact_active).
    void append_activity(std::vector<std::uint8_t>& out) const;
    /// Gauss points over the carrying sides (the length append_activity() appends).
    int n_points() const;
    /// Holds point `index` (append_activity() order) open, unless its side's held points
    /// would then leave out more than max_held_force of the side's normal force in the
    /// last evaluation. Whether it was held.
    bool hold_open(int index);
    /// Frees the held points of each side whose held points now leave out more than
    /// max_held_force of its normal force (the last evaluation, a converged state). How many.
    int release_deep_holds();
    /// Frees every held point.
    void release_holds() { model_.pair.release_holds(); }

private:
    /// The normal force carrier c's held points would carry free, over that and the
    /// force its points carry, in the last evaluation.
    double withheld_share(int c) const;
    /// Extends the pattern by the couplings of the last evaluation that it lacks.
    void register_couplings(RunContext* context);

    Scene& scene_;
    int index_;  ///< the pair's index in the scene (and in a step's contact results)
    PairModel& model_;
    contact::PairEvaluation evaluation_;
};

/// n_cp_side x d displacements of surface k of a pair from the full vector (empty for a rigid surface).
RowMatrix side_displacement(const Scene& scene, const PairModel& pair, const Vector& u_full, int k);

}  // namespace iga::analysis
