#pragma once
// Human-readable description of a deck's bodies for `igacontact check`: the
// analysed patch (degrees, spans, control points) and the name and meaning of
// each side (collapsed sides are flagged: they have zero length).

#include "io/deck.hpp"

#include <string>

namespace iga::analysis {

/// A YAML comment block, one body per paragraph. Builds each patch (so broken
/// geometry is reported here, as a DeckError naming the body).
std::string describe_bodies(const io::Deck& deck);

}  // namespace iga::analysis
