#pragma once
// The elastic bodies as a model term: the internal forces f_int(u) and their
// tangent dK = df_int/du, per knot span of every patch (mechanics/element.hpp).
//
// Small kinematics: the element stiffness is constant, so the term assembles
// K0 over ALL dofs once (constrained rows give the reactions, constrained columns
// the prescribed displacements), keeps its upper triangle, and each evaluation is
// f_int = K0 u (one sparse product) with K0's free block as the tangent: no geometric
// term is ever computed. Finite kinematics: every evaluation evaluates the element
// blocks this rank owns on n_threads() threads (colored blocks; assembly/threads.hpp
// chooses the count: requested, or automatic from the element work) and scatters them.
//
// Round-off: per dof |K0| |u| (small kinematics, where a rigid motion cancels K0 u but
// not its round-off), or |f_e| + (a bound of |K_e| |u_e|) per element (finite: F = I +
// grad u loses eps |u| to the same cancellation where an element has travelled far, as a
// slid die has; ElementResponse::cancellation, formed without K_e, so that an evaluation
// without the tangent forms no K_e), goes into the magnitudes.
// A failed element evaluation (det F <= 0, a material that cannot be evaluated) is a
// numerical failure naming the body, the parameter and the point (the lowest failed
// block, so the message does not depend on the threads).

#include "analysis/term.hpp"
#include "assembly/thread_team.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace iga::analysis {

class ElasticTerm final : public Term {
public:
    /// requested_threads: >= 1 exactly that many, 0 automatic (from the element work).
    ElasticTerm(const Scene& scene, RunContext& context, int requested_threads);

    void add_to(ModelAssembly& a) override;

    /// f_int(u) over all dofs, this rank's blocks only (no tangent, no timers).
    Vector internal_forces(const Vector& u_full);
    /// Small kinematics: assembles K0 now (else at the first evaluation); afterwards the
    /// elements' quadrature data are no longer read. No effect under finite kinematics.
    void assemble_constant_stiffness(const StopRequest& stop = {});

    /// Threads of the element loop (1 for small kinematics, whose loop is serial).
    int n_threads() const { return team_ ? team_->n_threads() : 1; }
    /// Threads worth giving the linear solver's BLAS (the automatic choice for the
    /// tangent's size, or --threads).
    int library_threads() const { return library_threads_; }

private:
    /// f (zero on entry) += f_int, magnitude += |f_e|; the tangent when given.
    void assemble(const Vector& u_full, Vector& f, Vector& magnitude, SparseMatrix* tangent, ModelAssembly* failures,
                  const StopRequest& stop);
    void assemble_finite(const Vector& u_full, Vector& f, Vector& magnitude, SparseMatrix* tangent,
                         ModelAssembly* failures, const StopRequest& stop);
    const mechanics::ElementGeometry& element_of(int block) const;
    const BodyModel& body_of(int block) const;
    const std::vector<int>& dofs_of(int block) const;

    const Scene& scene_;
    struct BlockOwner {
        int body;
        int element;
    };
    std::vector<BlockOwner> owner_;               // element block -> (body, element)
    std::unique_ptr<assembly::ThreadTeam> team_;  // null: serial element loop
    int library_threads_ = 1;
    std::optional<SparseMatrix> full_stiffness_;  // small kinematics: K0 over all dofs, upper triangle
    std::vector<Vector> element_force_;           // finite kinematics: f_int per block (reused storage)
    std::vector<Vector> element_round_off_;       // finite kinematics: |f_e| + cancellation bound per block
};

}  // namespace iga::analysis
