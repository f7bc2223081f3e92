#pragma once
// The key tables of docs/deck.md, generated from the deck schema (io/deck_schema.hpp).
// A generated table sits between two HTML comments that name a map of the schema:
//
//   <!-- keys: contact.* -->
//   | key | type | default | meaning |
//   ...
//   <!-- /keys -->
//
// `top-level` names the top level of the deck, `contact.*` the items of the list
// `contact`. The table lists the map's keys and, under a map or list that has no
// table of its own in the document, its keys too (`friction.coefficient`). A group
// of the schema (`nurbs`, `refine`, `transform`) counts as having a table when one
// of its places has one. The prose around the tables stays hand-written.
// scripts/update_deck_tables.py rewrites the tables (`igacontact keys --markdown`);
// tests/io/deck_schema_test.cpp fails when one differs from what the schema generates.

#include <string>
#include <string_view>
#include <vector>

namespace iga::io {

struct KeyTables {
    std::string markdown;                   ///< the document with every marked table generated
    std::vector<std::string> tables;        ///< the maps that have a table, in document order
    std::vector<std::string> undocumented;  ///< keys that no table shows (one path per row of the schema)
};

/// `markdown` with every marked table generated anew. Throws std::invalid_argument
/// (naming the line) for a marker that names no map of the schema, or a table
/// without its closing marker.
KeyTables generate_key_tables(std::string_view markdown);

}  // namespace iga::io
