#pragma once
// Reading a deck: YAML text -> --set overrides -> validated io::Deck
// (docs/deck.md, format 1).
//
// Every problem becomes a located DeckIssue ("hertz.yaml:14:7: error:
// materials.steel.nu = 0.6: must lie in (-1, 0.5)"); all independent issues are
// collected and thrown together in one DeckError. A returned Deck satisfies the
// invariants listed in io/deck.hpp: references resolve, knot vectors are open,
// weights positive, vectors have d entries, the rigid plane normal is a unit
// vector, defaults are filled in, output.file is resolved against the deck's
// folder (relative to the working directory, or absolute), and resolved_yaml
// holds write_resolved_yaml(deck).

#include "io/deck.hpp"

#include <string>
#include <vector>

namespace iga::io {

/// Reads the deck file at `path` and applies `set_overrides` ("PATH=VALUE" each).
/// A missing or unreadable file is a DeckError naming `path`.
Deck read_deck(const std::string& path, const std::vector<std::string>& set_overrides = {});

/// Reads a deck held in memory. `file_label` names it in messages and in
/// Deck::source_file; `deck_dir` is the folder relative paths in the deck refer
/// to ("" = the working directory); the default output.file is
/// deck_dir/<file_label's file name with .h5>.
Deck read_deck_text(const std::string& yaml_text, const std::string& file_label, const std::string& deck_dir,
                    const std::vector<std::string>& set_overrides = {});

}  // namespace iga::io
