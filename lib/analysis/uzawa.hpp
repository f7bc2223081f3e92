#pragma once
// The Uzawa outer loop of the augmented-Lagrangian contact pairs (enforcement:
// augmented_lagrangian; docs/theory.md "Augmented Lagrangian"), called by the load
// stepper after every converged Newton solve (solver::SteppingCallbacks::outer).
//
// At the converged state of a solve it measures each augmented pair's largest
// penetration g_max (over its Gauss points, both half passes), and the share of its
// force that acts across gaps open wider than gap_tolerance, which only multipliers
// can carry there (p = <lambda + eps g_N> > 0 at g_N < 0: multipliers left from a
// larger load, a contact being released; docs/deck.md "Load paths"):
//  - every pair has g_max <= gap_tolerance and that share <= held_open_tolerance, and
//    a frictional pair also its largest elastic slip |t_T - lambda_T| / eps_T over its
//    pressed points (contact::PairEvaluation::max_elastic_slip: at a sticking point the
//    slide the tangential penalty still turns into traction, at a slipping one the
//    change of its traction since the last update, over eps_T) <= gap_tolerance:
//    accept the increment;
//  - else, if max_updates updates were already made in this attempt: reject it (the
//    load stepper cuts the increment back; multipliers are rolled back with it);
//  - else update the multipliers of every augmented pair, lambda <- <lambda + eps g_N>
//    and, with friction, lambda_T <- t_T (contact::ContactPair::update_multipliers), and
//    solve again.
// Safeguard: when a pair's g_max falls from one solve to the next at a rate
// rho = g_max/g_max_previous that would not bring it within the tolerance in the
// updates left (rho >= 1, or g_max rho^left > gap_tolerance, stalls() below), its
// penalty is raised by raise_factor (the multipliers are kept), at most to max_raise
// times its initial value; each raise is logged (normal verbosity) and kept in
// notes() for the run's warnings. Raised penalties stay for the rest of the run.
// A run whose updates are on course keeps its penalty however slow the rate: a
// raise trades Uzawa updates for a stiffer Newton problem, which can fail.
//
// One UzawaLoop per run; attempt state (updates, last g_max) is reset by
// begin_attempt(), which the driver calls on commit and on rollback.

#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "core/run_context.hpp"
#include "solver/load_stepping.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// Uzawa stalls when the penetration, falling by `rate` per update (k/(k + eps) for
/// a contact stiffness k), would still exceed `tolerance` after `updates_left` more.
bool stalls(double rate, double penetration, double tolerance, int updates_left);
/// The share of a pair's normal force (sum of W p over its Gauss points) carried by
/// points whose gap is open wider than `tolerance`; 0 when the pair carries none.
double held_open_fraction(const contact::PairEvaluation& state, double tolerance);
/// Largest accepted share, 1 %: below the discretization error of the contact
/// pressure (~1 % of p0 on the Hertz decks), above what multipliers leave at the
/// open edge of a contact zone under a growing load (0.5 % on the two-cylinder deck
/// refined once), far below a released contact, whose multipliers carry all its force.
constexpr double held_open_tolerance = 1e-2;
/// Factor of one penalty raise.
constexpr double uzawa_raise_factor = 10.0;
/// Bound on the total raise of a pair's penalty over its initial value.
constexpr double uzawa_max_raise = 1e3;

class UzawaLoop {
public:
    UzawaLoop(Scene& scene, SceneSystem& system, RunContext& context);

    /// Some pair uses the augmented Lagrangian.
    bool active() const { return active_; }
    /// The decision after a converged solve at (u_free, load_factor); see the header.
    solver::OuterDecision after_solve(const Vector& u_free, double load_factor);
    /// A new attempt (after a commit or a rollback): no updates yet.
    void begin_attempt();
    /// Updates made in the current attempt.
    int updates() const { return updates_; }
    /// One line per penalty raise so far (for the run's warnings).
    const std::vector<std::string>& notes() const { return notes_; }

private:
    Scene& scene_;
    SceneSystem& system_;
    RunContext& context_;
    bool active_ = false;
    int updates_ = 0;
    std::vector<double> last_penetration_;  ///< per pair, g_max of the previous solve; < 0: none yet
    std::vector<std::string> notes_;
};

}  // namespace iga::analysis
