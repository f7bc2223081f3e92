#pragma once
// A contact side must face its partner. The contact kernels only act where a
// Gauss point penetrates the partner from in front of it, so a side named the
// wrong way round (a block's top face against the floor below it, an arc that
// faces up under a die) feels nothing until the whole body has passed through:
// the run ends at exit 0 with the body inside its partner and the forces of the
// correct run (docs/deck.md, "Contact pairs").
//
// The check, at the start (reference configuration, both sides sampled at 3
// points per element and direction, with their outward normals):
//  - each sample of a deformable side finds the partner's nearest sample (a rigid
//    obstacle: its foot point), and how much the two face each other,
//    facing = -n_side . n_partner (1: opposite normals, -1: both point the same way);
//  - the samples that matter are those nearest the partner (within a tenth of the
//    smaller side's size of the nearest one): where the bodies meet first;
//  - if the best facing among them is below facing_away, no part of the side that
//    the partner can reach turns towards it: an error, located at the pair's
//    `between`, naming the sides of the body that do face the partner;
//  - if it is below turned_across, the side meets the partner edge-on (a block's
//    vertical side against the floor): a warning.
// Discrete nearest samples are enough: the test reads normals, not gaps.

#include "analysis/scene.hpp"
#include "io/deck.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// Best facing below this: the side turns its back on the partner (more than 120°).
constexpr double facing_away = -0.5;
/// Best facing below this: the side meets the partner edge-on (within about 84° of it).
constexpr double turned_across = 0.1;

/// Throws a located DeckError when a deformable side of `model` turns its back on
/// its partner where they are nearest; returns the warnings for sides that meet it
/// edge-on (see above).
std::vector<std::string> check_sides_face(const io::Deck& deck, const Scene& scene, const io::ContactPair& pair,
                                          const PairModel& model);

}  // namespace iga::analysis
