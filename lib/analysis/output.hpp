#pragma once
// From the scene and a converged state to the plain structs of the results
// file (io/results_data.hpp): body geometry, one increment's displacements and
// contact data (Gauss points and Sauer's post-processed pressure), and the
// analytic Hertz reference with this run's errors against it.

#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "io/deck.hpp"
#include "io/results_data.hpp"

#include <vector>

namespace iga::analysis {

std::vector<io::BodyGeometry> body_geometry(const Scene& scene);

/// The reaction of every constrained side from the full residual at a converged
/// state (scene.reactions order).
std::vector<io::Reaction> reactions(const Scene& scene, const Vector& r_full);

/// Displacements, reactions and contact data of the state u_free at load_factor.
io::StepData step_data(const Scene& scene, SceneSystem& system, const Vector& u_free, double load_factor,
                       int samples_per_span);

/// Contact pair p's part of a step (its attributes and carrying sides) from its
/// evaluation `state` at the converged state u_full, load_factor (ContactTerm::report).
io::ContactPairResult pair_result(const Scene& scene, int p, const contact::PairEvaluation& state,
                                  const Vector& u_full, double load_factor, int samples_per_span);

/// The Hertz reference of the deck (if any), with the errors of `step` against it.
/// Errors are measured over reference coordinates (Hertz is a small-strain theory).
std::vector<io::ReferenceData> references(const Scene& scene, const io::StepData* step);

}  // namespace iga::analysis
