#pragma once
// From a deck body to the analysed NURBS patch: the raw NURBS data or the
// built-in shape, then the refinement of the deck in its fixed order
// (elevate, uniform spans, inserted knots). Refinement preserves the geometry.

#include "io/deck.hpp"
#include "nurbs/patch.hpp"

namespace iga::analysis {

/// A deck coordinate list as a small vector.
inline VecN to_vec(const std::vector<double>& v)
{
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Index>(v.size()));
}

/// The refined patch of a deformable body. Precondition: !body.rigid.
nurbs::Patch build_patch(const io::Body& body, int dimension);

}  // namespace iga::analysis
