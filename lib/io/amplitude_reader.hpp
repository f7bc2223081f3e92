#pragma once
// Reading an `amplitude:` key (docs/deck.md, "Load paths"): a list of at least
// two points [time, value] of finite numbers, times strictly increasing from 0.
// Every broken rule is recorded at the point or number that breaks it, so the
// message names the key path down to it (`loads.0.amplitude.2.0`).
//
// Part of the deck reader; internal to io/. Whether the item may carry an
// amplitude at all (it must have something to scale) is the caller's check.

#include "core/amplitude.hpp"
#include "io/yaml_cursor.hpp"

#include <optional>

namespace iga::io {

/// The amplitude at `c` (which exists); nullopt after recording the issues.
std::optional<Amplitude> read_amplitude(const Cursor& c);

}  // namespace iga::io
