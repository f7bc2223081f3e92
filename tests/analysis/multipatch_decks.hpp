#pragma once
// Decks of the multi-patch tests: a block [0, 2] x [0, 1] x [0, 1] (z up) of
// degree (2, 2, 1), rational in u, either ONE patch with a double (C0) knot at
// x = 1 or TWO patches cut there (`left`, `right`), with a bottom that sags to
// its lowest near x = 1: z = 0.05 (x - 1)^2 + 0.01 (y - 0.5)^2 at the control
// polygon. block_deck_3d presses its top down by 0.01 onto the rigid plane z = 0.
// Control points are written u fastest, then v, then w (deck.md).
// The cut patches get part of their refinement through the interface: the left
// half is refined in v only, the right one in w only.

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace iga::test {

inline void write_text(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream out(path);
    out << text;
}

/// Control-point columns in x (the C0 knot sits at x = 1), rows in y, weights per column.
inline constexpr double block_xs[5] = {0.0, 0.5, 1.0, 1.5, 2.0};
inline constexpr double block_ys[3] = {0.0, 0.5, 1.0};
inline constexpr double block_ws[5] = {1.0, 0.9, 1.0, 0.8, 1.0};

/// Control points of columns first..last of the 3D block, as YAML list items.
inline std::string block_points_3d(int first, int last, const std::string& indent)
{
    std::string out;
    for (int l = 0; l < 2; ++l)
        for (int j = 0; j < 3; ++j)
            for (int i = first; i <= last; ++i) {
                const double x = block_xs[i], y = block_ys[j];
                const double z = l == 1 ? 1.0 : 0.05 * (x - 1.0) * (x - 1.0) + 0.01 * (y - 0.5) * (y - 0.5);
                out += fmt::format("{}- [{}, {}, {}, {}]\n", indent, x, y, z, block_ws[i]);
            }
    return out;
}

/// The uncut block: u knots 0.25, 0.5 (twice), 0.75 after refinement; v 0.5; w 0.5.
inline std::string block_3d_single()
{
    return "    nurbs:\n      degrees: [2, 2, 1]\n"
           "      knots: [[0, 0, 0, 0.5, 0.5, 1, 1, 1], [0, 0, 0, 1, 1, 1], [0, 0, 1, 1]]\n"
           "      control_points:\n" +
           block_points_3d(0, 4, "        ") + "    refine: {spans: [4, 2, 2]}\n";
}

/// The block cut at x = 1, with the named surfaces bottom and top across both patches.
inline std::string block_3d_split()
{
    return "    patches:\n"
           "      - name: left\n        nurbs:\n          degrees: [2, 2, 1]\n"
           "          knots: [[0, 0, 0, 0.5, 0.5, 0.5], [0, 0, 0, 1, 1, 1], [0, 0, 1, 1]]\n"
           "          control_points:\n" +
           block_points_3d(0, 2, "            ") +
           "        refine: {spans: [2, 2, 1]}\n"
           "      - name: right\n        nurbs:\n          degrees: [2, 2, 1]\n"
           "          knots: [[0.5, 0.5, 0.5, 1, 1, 1], [0, 0, 0, 1, 1, 1], [0, 0, 1, 1]]\n"
           "          control_points:\n" +
           block_points_3d(2, 4, "            ") +
           "        refine: {spans: [2, 1, 2]}\n"
           "    surfaces: {bottom: [left.w0, right.w0], top: [left.w1, right.w1]}\n";
}

/// The 3D block (`body`: one of the above) pressed on the plane z = 0 through
/// its side `bottom` (pair `touch`) by the displacement of its side `top`.
inline std::string block_deck_3d(const std::string& body, const std::string& bottom, const std::string& top)
{
    return fmt::format(R"(format: 1
analysis: {{dimension: 3, kinematics: small}}
materials:
  - {{name: m, model: linear_elastic, E: 1000.0, nu: 0.3}}
bodies:
  - name: block
    material: m
{}
  - name: floor
    rigid: {{plane: {{point: [0.0, 0.0, 0.0], normal: [0.0, 0.0, 1.0]}}}}
constraints:
  - {{body: block, side: {}, displacement: [0.0, 0.0, -0.01]}}
contact:
  - {{name: touch, between: [{}, floor], penalty: 1.0e5}}
output: {{samples_per_span: 3}}
)",
                       body, top, bottom);
}

}  // namespace iga::test
