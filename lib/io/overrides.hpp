#pragma once
// `--set PATH=VALUE` overrides (docs/deck.md "General rules"), applied to
// a deck's YAML tree before it is read, so that what gets validated, run and
// stored is the deck after overrides.
//
// PATH is a dotted key path. List items are named by their `name`, or by their
// index (always allowed, the only way for items without a name), and an index
// may also pick an entry of a list value (`bodies.b.nurbs.knots.0`). VALUE is
// parsed as YAML (a number, a word, a flow list or map; empty means null, which
// the reader takes as "not given").
// The path must exist in the deck format (io/deck_schema.hpp): a key the format
// knows may be set where the deck leaves it out, and maps missing on
// the way are created (`bodies.b.refine.spans=[8,8]` creates `refine`); list
// items are never created. Every node written is registered with the DeckSource,
// so a bad value in it is reported at "<command line>".
// Overrides apply in order; a later one may refine what an earlier one set.

#include "io/yaml_cursor.hpp"

#include <string>
#include <vector>

namespace iga::io {

/// Applies each "PATH=VALUE" of `set_overrides` to `root` (a null root becomes an
/// empty map). Bad overrides are recorded in `issues` and leave the tree unchanged.
void apply_overrides(YAML::Node& root, const std::vector<std::string>& set_overrides, DeckSource& source,
                     IssueList& issues);

}  // namespace iga::io
