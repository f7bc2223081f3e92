#pragma once
// The resolved deck: an io::Deck written back as YAML, after --set overrides and
// with every default explicit (docs/deck.md). It is stored as /deck in
// the results file (docs/results.md) and printed by `igacontact check`.
//
// Invariants (tests/io/deck_reader_test.cpp): reading the text back with
// read_deck_text(text, label, "") gives an equal Deck (apart from source_file
// and resolved_yaml), and writing that again gives the same text. Numbers are
// written in their shortest exact form (always with a '.', so any YAML reader
// takes them for floats). output.file is written as resolved (relative to the
// working directory, or absolute), hence the empty deck_dir when reading back.
// A contact quadrature of 0 ("degree + 2 of each side", which depends on the
// side) is left out; empty refine entries are left out. A body from a geometry file
// whose patches carry a refine of their own (only `accuracy:` levels give them one; the
// file's patches take none) is written as inline patches, and reads back as such.

#include "io/deck.hpp"

#include <string>

namespace iga::io {

std::string write_resolved_yaml(const Deck& deck);

}  // namespace iga::io
