#pragma once
// From a deck body to the analysed NURBS patch: the raw NURBS data or the
// built-in shape, then the refinement of the deck in its fixed order
// (elevate, uniform spans, inserted knots). Refinement preserves the geometry.

#include "io/deck.hpp"
#include "nurbs/patch.hpp"

namespace iga::analysis {

/// The refined patch of a deformable body. Precondition: !body.rigid.
nurbs::Patch build_patch(const io::Body& body, int dimension);

}  // namespace iga::analysis
