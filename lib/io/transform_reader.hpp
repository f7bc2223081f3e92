#pragma once
// Reading a `transform:` list (docs/deck.md, "Placing geometry") of a built-in
// shape, a raw NURBS patch or a geometry file: translate, rotate, mirror, scale,
// one key per item, applied in list order. Part of the deck reader; internal to
// io/. Checks made here: one known step per item; vectors of the deck's
// dimension (a 2D rotation takes no axis, or [0, 0, a > 0]; a 3D one needs
// one); finite numbers; non-zero axis and normal; scale > 0.

#include "io/deck.hpp"
#include "io/yaml_cursor.hpp"

#include <vector>

namespace iga::io {

/// The steps of the list at `list` for a dim-D deck; issues are recorded at the
/// offending item or value, and the steps that were read correctly are returned.
std::vector<TransformStep> read_transform(const Cursor& list, int dim);

}  // namespace iga::io
