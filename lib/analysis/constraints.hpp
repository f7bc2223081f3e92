#pragma once
// Dirichlet data of a scene: the deck's constraint items turned into prescribed
// dofs, and the groups of dofs whose reactions are reported per side.
//
// Every control point of a constrained side gets the item's prescribed
// components (fixed at zero, or given a full value that the item's amplitude
// scales). Items may overlap (two sides share a corner, `fix` and `displacement`
// on one side): a component prescribed twice with the same value (and the same
// amplitude, unless the value is 0) is fine; otherwise it is a located DeckError
// naming both items, the side and the point.
//
// Reaction groups, three views of the same constrained dofs (results.md):
//  - `body.side`: one per side that carries a constraint, in deck order of first
//    appearance; a group holds every dof any of its items prescribes. A dof on two
//    constrained sides (a shared edge or corner) belongs to both groups, so each
//    side's reaction is the full force its constraint exerts, and the sides of a
//    body do not add up to its total;
//  - `total/<body>`: every constrained dof of the body once, so that reactions,
//    loads and contact forces of the body sum to zero;
//  - `items/<k>`: the dofs owned by constraint item k (0-based deck index), where a
//    dof prescribed by several items is owned by the first in deck order. The items
//    of a body partition its total.

#include "analysis/scene.hpp"
#include "assembly/dof_map.hpp"
#include "io/deck.hpp"

#include <vector>

namespace iga::analysis {

struct DirichletData {
    std::vector<assembly::PrescribedDof> prescribed;  ///< each dof once
    std::vector<ReactionGroup> reactions;  ///< sides, then totals, then items (see above)
    /// Constraints on a side collapsed to a point or a line: they hold that point or
    /// line only, rarely what a symmetry condition means (Scene::setup_warnings).
    std::vector<std::string> warnings;
};

/// bodies: the scene's deformable bodies (patches refined); node_offset: first
/// node of each body in the dof numbering.
DirichletData dirichlet_data(const io::Deck& deck, const std::vector<BodyModel>& bodies,
                             const std::vector<int>& body_of_deck, const std::vector<int>& node_offset);

}  // namespace iga::analysis
