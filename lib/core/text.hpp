#pragma once
// Numbers in messages: one spelling of a point for every message that names one.

#include "core/types.hpp"

#include <string>

namespace iga {

/// "(x, y[, z])" with `significant` significant digits per coordinate (printf's %g).
std::string point_text(const VecN& x, int significant = 6);
/// Row `row` of an n x d array of points, as point_text.
std::string point_text(const RowMatrix& points, Index row, int significant = 6);

}  // namespace iga
