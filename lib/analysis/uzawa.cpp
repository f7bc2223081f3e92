#include "analysis/uzawa.hpp"

#include "analysis/contact_penalty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace iga::analysis {

UzawaLoop::UzawaLoop(Scene& scene, SceneSystem& system, RunContext& context)
    : scene_(scene), system_(system), context_(context)
{
    for (const PairModel& p : scene_.pairs)
        active_ = active_ || p.augmented;
    last_penetration_.assign(scene_.pairs.size(), -1.0);
}

void UzawaLoop::begin_attempt()
{
    updates_ = 0;
    std::fill(last_penetration_.begin(), last_penetration_.end(), -1.0);
}

double held_open_fraction(const contact::PairEvaluation& state, double tolerance)
{
    double held = 0.0, total = 0.0;
    for (const contact::CarrierResult& carrier : state.carriers)
        for (Index g = 0; g < carrier.pressure.size() && g < carrier.gap.size(); ++g) {
            const double force = carrier.weight(g) * carrier.pressure(g);
            total += force;
            if (-carrier.gap(g) > tolerance)
                held += force;
        }
    return total > 0.0 ? held / total : 0.0;
}

bool stalls(double rate, double penetration, double tolerance, int updates_left)
{
    // At rate rho the penetration after the updates left is penetration rho^updates_left.
    return !(rate < 1.0) || penetration * std::pow(rate, updates_left) > tolerance;
}

solver::OuterDecision UzawaLoop::after_solve(const Vector& u_free, double load_factor)
{
    solver::OuterDecision decision;
    if (!active_)
        return decision;
    const std::vector<contact::PairEvaluation> states = system_.contact_state(u_free, load_factor);

    // Which pairs still penetrate more than their tolerance.
    std::string over;  // the first such pair, in words
    int max_updates = 0;
    for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
        PairModel& model = scene_.pairs[p];
        if (!model.augmented)
            continue;
        if (!states[p].ok) {  // cannot happen at a converged state; reject rather than update from it
            decision.action = solver::OuterDecision::Action::reject;
            decision.message = fmt::format("contact pair '{}': {}", model.name, states[p].message);
            return decision;
        }
        const double penetration = states[p].max_penetration;
        double max_pressure = 0.0;
        for (const contact::CarrierResult& carrier : states[p].carriers)
            if (carrier.pressure.size() > 0)
                max_pressure = std::max(max_pressure, carrier.pressure.maxCoeff());
        const double tolerance =
            model.gap_tolerance > 0.0 ? model.gap_tolerance
                                      : auto_gap_tolerance(model.rule.element_size, model.rule.modulus, max_pressure);
        model.gap_tolerance_used = tolerance;
        const double held = held_open_fraction(states[p], tolerance);
        // With friction: how far pressed points still slide against the tangential penalty.
        const double elastic_slip = states[p].max_elastic_slip;
        if (penetration > tolerance || held > held_open_tolerance || elastic_slip > tolerance) {
            if (over.empty())
                over = penetration > tolerance
                           ? fmt::format("contact pair '{}': max penetration {:.3g} above gap_tolerance {:.3g}",
                                         model.name, penetration, tolerance)
                       : held > held_open_tolerance
                           ? fmt::format("contact pair '{}': {:.3g} of its force acts across gaps open wider "
                                         "than gap_tolerance {:.3g} (multipliers of a contact that is opening)",
                                         model.name, held, tolerance)
                           : fmt::format("contact pair '{}': max elastic slip {:.3g} above gap_tolerance {:.3g} "
                                         "(friction: tangential multipliers not yet converged)",
                                         model.name, elastic_slip, tolerance);
            max_updates = std::max(max_updates, model.max_updates);
        }
    }
    if (over.empty())
        return decision;  // accept
    if (updates_ >= max_updates) {
        decision.action = solver::OuterDecision::Action::reject;
        decision.message = fmt::format("{} after {} Uzawa updates (augmented_lagrangian.max_updates); allow more "
                                       "updates or a larger gap_tolerance",
                                       over, updates_);
        return decision;
    }

    for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
        PairModel& model = scene_.pairs[p];
        if (!model.augmented)
            continue;
        model.pair.update_multipliers(states[p]);
        const double penetration = states[p].max_penetration;
        const double last = last_penetration_[p];
        last_penetration_[p] = penetration;
        if (!(last > 0.0) || !(penetration > model.gap_tolerance_used) ||
            !stalls(penetration / last, penetration, model.gap_tolerance_used, model.max_updates - updates_))
            continue;
        const double penalty = model.pair.settings().law.stiffness();
        if (penalty * uzawa_raise_factor > uzawa_max_raise * model.initial_penalty * (1.0 + 1e-12))
            continue;  // at the bound: Uzawa goes on at this penalty
        model.pair.set_penalty(penalty * uzawa_raise_factor);
        const std::string note = fmt::format(
            "contact pair '{}': the augmented Lagrangian raised the penalty to {:.3g} ({:.3g} x the initial {:.3g}): "
            "the penetration stalled ({:.3g} -> {:.3g} at load factor {:.4g})",
            model.name, model.pair.settings().law.stiffness(),
            model.pair.settings().law.stiffness() / model.initial_penalty,
            model.initial_penalty, last, penetration, load_factor);
        context_.log(Verbosity::normal, note);
        notes_.push_back(note);
    }
    ++updates_;
    context_.log(Verbosity::verbose, fmt::format("  Uzawa update {} at load factor {:.4g}: {}", updates_,
                                                 load_factor, over));
    decision.action = solver::OuterDecision::Action::resolve;
    return decision;
}

}  // namespace iga::analysis
