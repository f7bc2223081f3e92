#pragma once
// What to change after a Newton failure, by its cause (solver/failure_cause.hpp),
// in the words of the deck. The solver names the cause from the history; this
// adds only what the scene makes true (contact or not, the penalty against E, a
// penalty the augmented Lagrangian raised), never a cause the history does not show.

#include "analysis/scene.hpp"
#include "io/results_data.hpp"
#include "solver/failure_cause.hpp"

#include <string>

namespace iga::analysis {

/// The facts about a scene that the advice depends on.
struct FailureContext {
    bool has_contact = false;
    double penalty_over_modulus = 0;  ///< largest pair penalty / smallest E (0: no contact)
    double penalty_raised = 1;        ///< largest current / initial penalty (> 1: raised by the augmented Lagrangian)
    /// A frictional side whose friction force had reached mu N in the last converged
    /// increment, in words; empty if none.
    std::string saturated_friction;
    /// A body of that pair with no prescribed displacement along the friction force and no
    /// other contact, which only that friction holds along the contact; empty if none.
    std::string held_by_friction;
};

/// The scene's facts; `last` (the last converged state, if any) tells saturated friction.
FailureContext failure_context(const Scene& scene, const io::StepData* last = nullptr);

/// ". <cause in words>. <what to change>", to append to the failure message; empty for none.
std::string failure_advice(solver::FailureCause cause, const FailureContext& context);

}  // namespace iga::analysis
