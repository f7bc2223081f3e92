#include "analysis/failure_advice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace iga::analysis {

namespace {

/// A penalty above 1e6 E makes the tangent's condition number, and so the amplified
/// round-off, the likely reason (docs/performance.md "penalty: auto": 1e2-1e3 E/h is plenty).
constexpr double stiff_penalty_ratio = 1e6;

std::string penalty_facts(const FailureContext& c)
{
    std::string text = fmt::format("the penalty is {:.3g} times E", c.penalty_over_modulus);
    if (c.penalty_raised > 1)
        text += fmt::format(" (the augmented Lagrangian raised it {:.3g}-fold)", c.penalty_raised);
    return text;
}

/// A friction force within this fraction of mu N has reached the Coulomb limit (the
/// last converged increment of a load that exceeds it sits on the limit to round-off,
/// or just below it when the increment before the failure was cut).
constexpr double friction_limit_fraction = 0.99;

/// A displacement component with more than this share of the friction force's direction
/// holds a body along the contact.
constexpr double along_share = 0.01;

/// The body of a results side "body.side".
std::string body_of(const std::string& side_name)
{
    return side_name.substr(0, side_name.find('.'));
}

/// True when deformable body `name` has no prescribed displacement along `direction` (a
/// component that has a share of it) and touches nothing but `pair`: then only that pair's
/// friction holds it along the contact against its loads.
bool held_only_by(const Scene& scene, const io::StepData& last, const std::string& name, const std::string& pair,
                  const std::vector<double>& direction)
{
    const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                   [&](const BodyModel& b) { return b.name == name; });
    if (body == scene.bodies.end() || !scene.dofs)
        return false;
    const int b = static_cast<int>(body - scene.bodies.begin());
    const assembly::DofMap& dofs = *scene.dofs;
    double length = 0.0;
    for (const double t : direction)
        length += t * t;
    length = std::sqrt(length);
    for (int i = 0; i < dofs.dimension() && i < static_cast<int>(direction.size()); ++i) {
        if (std::abs(direction[static_cast<std::size_t>(i)]) <= along_share * length)
            continue;  // a component across the slide may be held (a pressed top)
        for (int node = dofs.node_offset(b); node < dofs.node_offset(b) + dofs.n_nodes(b); ++node)
            if (dofs.is_constrained(dofs.dof(node, i)))
                return false;
    }
    for (const io::ContactPairResult& other : last.contact)
        if (other.name != pair)
            for (const io::ContactSideResult& side : other.sides)
                if (body_of(side.side_name) == name)
                    return false;
    return true;
}

/// The first frictional side at its Coulomb limit at `last`, in words ("... block.v0 in
/// contact pair 'p' ...: friction force 1.5 against mu N = 1.5"), and a body of its pair
/// that only that contact holds (held_only_by); empty if none.
std::pair<std::string, std::string> saturated_friction(const Scene& scene, const io::StepData& last)
{
    for (const io::ContactPairResult& pair : last.contact) {
        const auto model = std::find_if(scene.pairs.begin(), scene.pairs.end(),
                                        [&](const PairModel& p) { return p.name == pair.name; });
        if (model == scene.pairs.end() || !model->pair.settings().friction.active())
            continue;
        const double mu = model->pair.settings().friction.coefficient;
        for (const io::ContactSideResult& side : pair.sides) {
            double tangential = 0.0;
            for (double f : side.friction_force)
                tangential += f * f;
            tangential = std::sqrt(tangential);
            const double limit = mu * std::abs(side.normal_force);
            if (!(limit > 0.0) || tangential < friction_limit_fraction * limit)
                continue;
            std::string free_body;
            for (const io::ContactSideResult& s : pair.sides)
                if (free_body.empty() && held_only_by(scene, last, body_of(s.side_name), pair.name, side.friction_force))
                    free_body = body_of(s.side_name);
            return {fmt::format("in the last converged increment (load factor {:.4g}) the friction on {} in contact "
                                "pair '{}' had reached its limit: friction force {:.4g} against mu N = {:.4g} "
                                "(mu = {:g})",
                                last.load_factor, side.side_name, pair.name, tangential, limit, mu),
                    free_body};
        }
    }
    return {};
}

}  // namespace

FailureContext failure_context(const Scene& scene, const io::StepData* last)
{
    FailureContext c;
    c.has_contact = scene.has_contact();
    if (!c.has_contact)
        return c;
    if (last)
        std::tie(c.saturated_friction, c.held_by_friction) = saturated_friction(scene, *last);
    double E_min = std::numeric_limits<double>::infinity(), penalty_max = 0;
    for (const BodyModel& b : scene.bodies)
        E_min = std::min(E_min, b.material.E);
    for (const PairModel& p : scene.pairs) {
        penalty_max = std::max(penalty_max, p.pair.settings().law.stiffness());
        if (p.initial_penalty > 0)
            c.penalty_raised = std::max(c.penalty_raised, p.pair.settings().law.stiffness() / p.initial_penalty);
    }
    c.penalty_over_modulus = penalty_max / E_min;
    return c;
}

namespace {

/// Where Newton failed beside a frictional side at its Coulomb limit, for any cause: a
/// body pushed along the contact by a force has no equilibrium beyond that load, which
/// no step size or penalty changes. A prescribed slide is at the limit too, and fails for
/// other reasons: the note says which case it is about.
std::string friction_limit_note(const FailureContext& c)
{
    if (c.saturated_friction.empty())
        return {};
    std::string fact = c.saturated_friction;
    fact.front() = static_cast<char>(std::toupper(static_cast<unsigned char>(fact.front())));
    const std::string remedy = "lower that load, raise friction.coefficient, or drive the body by a displacement";
    if (!c.held_by_friction.empty())
        return ". " + fact + ". Body " + c.held_by_friction +
               " has no prescribed displacement along the contact and no other contact: only this friction holds "
               "it there, so no equilibrium exists beyond this load, whatever the steps; " + remedy;
    return ". " + fact +
           ": if a force, not a prescribed displacement, pushes that body along the contact, no equilibrium "
           "exists beyond this load, whatever the steps; " + remedy;
}

std::string advice_for_cause(solver::FailureCause cause, const FailureContext& c)
{
    const std::string smaller_steps = "smaller increments (a larger steps.count)";
    const std::string smaller_penalty = "a smaller penalty (about 1e2-1e3 E/h is plenty; penalty: auto)";
    switch (cause) {
    case solver::FailureCause::none: return {};
    case solver::FailureCause::linear_solver:
        return ". The iterative linear solver did not converge: the tangent may be singular (a body held by "
               "nothing, or only by contact that is not yet closed) or hard for its preconditioner (a nearly "
               "incompressible material, nu near 0.5, is hard for algebraic multigrid). "
               "solver.type: direct tells the two apart; solver.options (PETSc options) changes the method";
    case solver::FailureCause::free_mode:
        if (!c.saturated_friction.empty())
            return ". Singular tangent: " + c.saturated_friction +
                   ". A tangential load beyond what friction can hold (mu N) has nothing left to hold the body: "
                   "lower that load, raise friction.coefficient, or drive the body by a prescribed displacement "
                   "if it is meant to slide";
        return ". Singular tangent: a body may be unconstrained (held by nothing, or only by frictionless "
               "contact that is not yet closed). Constrain every rigid-body motion the loads can excite";
    case solver::FailureCause::inadmissible:
        return ". A trial state could not be evaluated (an inverted element, det F <= 0, or a failed contact "
               "projection). Use " + smaller_steps;
    case solver::FailureCause::growth:
        return ". Newton diverged: use " + smaller_steps +
               (c.has_contact ? ", or " + smaller_penalty + "; " + penalty_facts(c) : std::string());
    case solver::FailureCause::round_off_floor:
        if (c.has_contact && c.penalty_over_modulus > stiff_penalty_ratio)
            return ". The residual is at its round-off floor and " + penalty_facts(c) +
                   ": the stiff tangent turns that round-off into corrections that do not settle. Use " +
                   smaller_penalty + " or a looser newton.tolerance";
        return ". The residual is at its round-off floor but the corrections do not settle (an "
               "ill-conditioned tangent" +
               (c.has_contact ? "; " + penalty_facts(c) : std::string()) +
               "). Use a looser newton.tolerance, or reduce the stiffness contrast";
    case solver::FailureCause::cycle:
        return ". The Newton residual cycles between two states: an active-set (or projection) flip-flop, "
               "Gauss points entering and leaving contact (or switching the segment they project onto) on "
               "alternate iterations. Use " + smaller_steps + " or " + smaller_penalty;
    case solver::FailureCause::stagnation:
        return ". The residual stagnates above its round-off floor: the tangent does not fit the residual "
               "(e.g. an active set that changes under the step). Use " + smaller_steps;
    case solver::FailureCause::wandering:
        return ". Newton did not settle: the tangent does not predict where its steps go" +
               (c.has_contact ? std::string(" (with contact, typically points that press, stick or slip in turn)")
                              : std::string()) +
               ", and more iterations are not likely to help. Use " + smaller_steps +
               (c.has_contact ? " or " + smaller_penalty : std::string());
    case solver::FailureCause::slow:
        return ". Newton was still converging: raise newton.max_iterations or use " + smaller_steps;
    }
    return {};
}

}  // namespace

std::string failure_advice(solver::FailureCause cause, const FailureContext& c)
{
    std::string advice = advice_for_cause(cause, c);
    switch (cause) {
    case solver::FailureCause::growth:
    case solver::FailureCause::cycle:
    case solver::FailureCause::stagnation:
    case solver::FailureCause::wandering:
    case solver::FailureCause::slow: advice += friction_limit_note(c); break;
    default: break;  // free_mode says it itself; the others have another cause
    }
    return advice;
}

}  // namespace iga::analysis
