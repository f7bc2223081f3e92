#pragma once
// Rigid obstacles of a deck as contact surfaces (plane, circle/sphere, with
// their motion), and the set-up check that a deformable body does not start
// entirely inside an obstacle: with the convex-hull property of NURBS, all of a
// body's control points inside a plane's half-space (or a ball) put the whole
// body there, which almost always means a flipped normal or a misplaced obstacle.

#include "analysis/scene.hpp"
#include "contact/rigid_obstacle.hpp"
#include "io/deck.hpp"

namespace iga::analysis {

contact::RigidObstacle rigid_obstacle(const io::Body& body);

/// Throws a located DeckError when the deformable body of `model` (a pair with a
/// rigid obstacle) lies entirely inside the obstacle at load factor 0.
void check_obstacle_side(const io::Deck& deck, const Scene& scene, const io::ContactPair& pair,
                         const PairModel& model);

}  // namespace iga::analysis
