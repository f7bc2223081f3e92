#pragma once
// Names of the sides of a NURBS patch, as spelled in decks and results files.
//
// Side u0 is where the first parameter takes its smallest value, u1 its largest;
// v0/v1 for the second parameter, w0/w1 for the third (3D patches only).

#include <optional>
#include <string_view>

namespace iga {

enum class Side { u0, u1, v0, v1, w0, w1 };

/// Parametric direction fixed on the side: 0 for u0/u1, 1 for v0/v1, 2 for w0/w1.
constexpr int side_direction(Side s) { return static_cast<int>(s) / 2; }
/// True when the side lies at the end (largest value) of its direction.
constexpr bool side_at_end(Side s) { return static_cast<int>(s) % 2 == 1; }

constexpr std::string_view side_name(Side s)
{
    constexpr std::string_view names[] = {"u0", "u1", "v0", "v1", "w0", "w1"};
    return names[static_cast<int>(s)];
}

/// Parses "u0".."w1"; nullopt for anything else.
inline std::optional<Side> parse_side(std::string_view name)
{
    for (int i = 0; i < 6; ++i)
        if (side_name(static_cast<Side>(i)) == name)
            return static_cast<Side>(i);
    return std::nullopt;
}

}  // namespace iga
