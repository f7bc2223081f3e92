#pragma once
// The deck schema: one table of every key of the deck format (docs/deck.md), each
// with its kind, type, range, default and a one-line meaning; the table itself is
// lib/io/deck_schema.cpp. It is the only place that lists the keys; everything else
// that knows them derives from it:
//  - the reader accepts exactly the keys listed for each map, and reads the simple
//    values with the type and range given here (Cursor::check_keys, Cursor::read);
//  - `--set` walks these paths (io/overrides.hpp);
//  - the key tables of docs/deck.md are generated from it (io/deck_key_tables.hpp);
//  - tests hold the resolved-deck writer and the reader to it
//    (tests/io/deck_schema_test.cpp).
//
// A path is dotted, with `*` standing for any item of a list:
// `contact.*.friction.coefficient`. Maps that appear in several places (`nurbs`,
// `refine`, `transform`) are declared once, as a group, and included where they appear.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace iga::io {

/// What a key holds: a map of keys, a list of items (maps, addressed by `name` or
/// index), or a value (a scalar, or a list of numbers or words read as one value).
enum class KeyKind { map, list, value };

/// The type of a value, as far as the generic reader checks it. `choice` is one word
/// of a fixed list (an enum of io/deck.hpp); `other` values are read by hand.
enum class ValueType { none, integer, number, number_or_auto, boolean, string, choice, integers, numbers, other };

/// Bounds on a number, or on each entry of a list of numbers.
struct Range {
    enum class Kind { none, above, at_least, open_interval };
    Kind kind = Kind::none;
    double low = 0.0;
    double high = 0.0;
    std::string_view why;  ///< said after the failure: "must be > 0 (why)"

    bool admits(double x) const;
    /// "> 0", ">= 1", "in (-1, 0.5)"; "" without bounds.
    std::string text() const;
    /// "must be > 0", "must lie in (-1, 0.5)", with the reason if there is one.
    std::string failure() const;
};

/// Whether a key must be given.
enum class Presence {
    optional,     ///< has a default
    required,     ///< the reader reports "missing required key" when it is absent
    conditional,  ///< required in some cases only, which the reader checks by hand
};

/// One key of the deck format.
struct DeckKey {
    std::string path;  ///< "contact.*.friction.coefficient"
    KeyKind kind = KeyKind::value;
    ValueType type = ValueType::none;
    Range range;
    std::vector<std::string> words;  ///< choice: the spellings (io/deck_names.hpp)
    std::string type_text;           ///< the type as docs/deck.md names it: "integer ≥ 1", "`small` or `finite`"
    Presence presence = Presence::optional;
    std::string default_text;  ///< as the user reads it: "`25`", "none", "— (gravity)"; "—" when required
    std::string meaning;       ///< one line, markdown
    /// The shared group this map or list takes its keys from ("nurbs"), or "".
    std::string group;
    /// The row of the table that declares the key: the rows of a group declare a key
    /// at each place the group is included.
    std::size_t row = 0;
};

/// Every key of the deck format, in table order (a map before its keys).
const std::vector<DeckKey>& deck_keys();
/// The key at `path` (list items written `*`), or nullptr.
const DeckKey* find_deck_key(std::string_view path);
/// The keys of the map at `path` ("" for the top level, "contact.*" for an item), in table order.
const std::vector<std::string>& map_keys(std::string_view path);
/// Every key path, in table order: what `--set` accepts, with list items written `*`.
std::vector<std::string> deck_key_paths();

}  // namespace iga::io
