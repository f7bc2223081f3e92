#pragma once
// Dirichlet data of a scene: the deck's constraint items turned into prescribed
// dofs, and the groups of dofs whose reactions are reported per side.
//
// Every control point of a constrained side gets the item's prescribed
// components (fixed at zero, or given a value at load factor 1). Items may
// overlap (two sides share a corner, `fix` and `displacement` on one side):
// a component prescribed twice with the same value is fine; with different
// values it is a located DeckError naming both items, the side and the point.
//
// Reaction groups: one per `body.side` that carries a constraint, in deck order
// of first appearance; a group holds every dof any of its items prescribes. A
// dof on two constrained sides (a shared corner) belongs to both groups, so each
// side's reaction is the full force its constraint exerts (results.md).

#include "analysis/scene.hpp"
#include "assembly/dof_map.hpp"
#include "io/deck.hpp"

#include <vector>

namespace iga::analysis {

struct DirichletData {
    std::vector<assembly::PrescribedDof> prescribed;  ///< each dof once
    std::vector<ReactionGroup> reactions;
};

/// bodies: the scene's deformable bodies (patches refined); node_offset: first
/// node of each body in the dof numbering.
DirichletData dirichlet_data(const io::Deck& deck, const std::vector<BodyModel>& bodies,
                             const std::vector<int>& body_of_deck, const std::vector<int>& node_offset);

}  // namespace iga::analysis
