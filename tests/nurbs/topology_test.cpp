// Interface detection of nurbs::glue_patches (nurbs/topology.hpp) through its
// corner hash: a grid of squares given in shuffled order, with every corner
// moved by less than the tolerance so that coincident corners fall into
// different hash cells, is glued along exactly its interior sides, each pair
// once, with the sides and orientation geometry dictates; the nodes count the
// grid's distinct points. A requested stop interrupts the gluing.

#include "core/stop.hpp"
#include "nurbs/topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <random>
#include <tuple>

namespace iga::nurbs {
namespace {

constexpr double tolerance = 1e-6;
// Corners are moved by up to this fraction of the tolerance (per coordinate, so
// two copies of one corner stay within sqrt(2) * 2 * 0.3 = 0.85 tolerance): a cell
// of the hash is one tolerance wide, so such pairs straddle cell borders.
constexpr double jitter = 0.3;

/// Bilinear unit square with lower-left corner (i, j), corners moved by `shift`.
Patch square(int i, int j, std::mt19937& random)
{
    std::uniform_real_distribution<double> shift(-jitter * tolerance, jitter * tolerance);
    RowMatrix P(4, 2);
    for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a)
            P.row(a + 2 * b) << i + a + shift(random), j + b + shift(random);
    return Patch({KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, P, Vector::Ones(4));
}

struct Grid {
    std::vector<Patch> patches;
    std::vector<std::pair<int, int>> cell;  ///< (i, j) of each patch
};

Grid shuffled_grid(int nx, int ny)
{
    std::mt19937 random(7);
    std::vector<std::pair<int, int>> cells;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            cells.emplace_back(i, j);
    std::shuffle(cells.begin(), cells.end(), random);
    Grid g;
    for (const auto& [i, j] : cells) {
        g.patches.push_back(square(i, j, random));
        g.cell.emplace_back(i, j);
    }
    return g;
}

TEST(Topology, ShuffledGridIsGluedAlongExactlyItsInteriorSides)
{
    constexpr int nx = 13, ny = 11;
    Grid g = shuffled_grid(nx, ny);
    const Topology topo = glue_patches(g.patches, tolerance);

    EXPECT_EQ(topo.interfaces.size(), static_cast<std::size_t>((nx - 1) * ny + nx * (ny - 1)));
    std::map<std::tuple<int, int, int, int>, int> seen;  // (i, j, i', j') of the lower-left cell first
    for (const Interface& f : topo.interfaces) {
        ASSERT_LT(f.patch_a, f.patch_b);
        const auto [ia, ja] = g.cell[static_cast<std::size_t>(f.patch_a)];
        const auto [ib, jb] = g.cell[static_cast<std::size_t>(f.patch_b)];
        // Neighbours across x: a's u1 is b's u0 (or the other way); across y: v1 / v0.
        if (ja == jb && ib == ia + 1) {
            EXPECT_EQ(f.side_a, Side::u1);
            EXPECT_EQ(f.side_b, Side::u0);
        } else if (ja == jb && ib == ia - 1) {
            EXPECT_EQ(f.side_a, Side::u0);
            EXPECT_EQ(f.side_b, Side::u1);
        } else if (ia == ib && jb == ja + 1) {
            EXPECT_EQ(f.side_a, Side::v1);
            EXPECT_EQ(f.side_b, Side::v0);
        } else if (ia == ib && jb == ja - 1) {
            EXPECT_EQ(f.side_a, Side::v0);
            EXPECT_EQ(f.side_b, Side::v1);
        } else {
            ADD_FAILURE() << "patches at (" << ia << ", " << ja << ") and (" << ib << ", " << jb
                          << ") are not neighbours";
        }
        EXPECT_FALSE(f.orientation.flip[0]) << "both sides run along +x (or +y)";
        const auto key = std::min(std::tuple(ia, ja, ib, jb), std::tuple(ib, jb, ia, ja));
        EXPECT_EQ(++seen[key], 1) << "a pair of patches glued twice";
    }
    EXPECT_EQ(topo.n_nodes, (nx + 1) * (ny + 1));
}

TEST(Topology, StopRequestInterruptsTheGluing)
{
    Grid g = shuffled_grid(4, 3);
    std::atomic<bool> flag{true};
    EXPECT_THROW(glue_patches(g.patches, tolerance, StopRequest(&flag)), Interrupted);
    flag = false;
    EXPECT_NO_THROW(glue_patches(g.patches, tolerance, StopRequest(&flag)));
}

}  // namespace
}  // namespace iga::nurbs
