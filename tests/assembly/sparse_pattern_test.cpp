// Tests for assembly/sparse_pattern.hpp: scatter against a dense reference
// built from triplets, constrained dofs, coloring, serial = parallel.

#include "assembly/sparse_pattern.hpp"
#include "assembly/thread_team.hpp"
#include "core/error.hpp"
#include "support/tolerance.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>


namespace iga::assembly {
namespace {

constexpr unsigned seed = 1234567;

// A 2D grid of nx x ny quadratic spans (control points (nx+2) x (ny+2)), one
// block per span with its 9 control points x 2 components = 18 dofs, plus one
// dense "contact" block coupling the top row of the grid with a second body of
// m control points. Left column of control points fixed (both components).
struct Scene {
    int nx = 6, ny = 5, m = 4;
    DofMap dofs;
    std::vector<std::vector<int>> blocks;

    static std::vector<PrescribedDof> left_column(int nx, int ny)
    {
        std::vector<PrescribedDof> c;
        for (int j = 0; j < ny + 2; ++j)
            for (int comp = 0; comp < 2; ++comp)
                c.push_back({2 * (j * (nx + 2)) + comp, 0.01 * j, Amplitude()});
        return c;
    }

    Scene() : dofs(2, {(nx + 2) * (ny + 2), m}, left_column(nx, ny))
    {
        const int row = nx + 2;
        for (int ey = 0; ey < ny; ++ey)
            for (int ex = 0; ex < nx; ++ex) {
                std::vector<int> block;
                for (int b = 0; b < 3; ++b)
                    for (int a = 0; a < 3; ++a)
                        for (int comp = 0; comp < 2; ++comp)
                            block.push_back(dofs.dof((ey + b) * row + ex + a, comp));
                blocks.push_back(block);
            }
        std::vector<int> contact;
        for (int a = 0; a < row; ++a)
            for (int comp = 0; comp < 2; ++comp)
                contact.push_back(dofs.dof((ny + 1) * row + a, comp));
        for (int a = 0; a < m; ++a)
            for (int comp = 0; comp < 2; ++comp)
                contact.push_back(dofs.dof(dofs.node_offset(1) + a, comp));
        blocks.push_back(contact);
    }
};

std::vector<Matrix> random_locals(const std::vector<std::vector<int>>& blocks, std::mt19937& rng)
{
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<Matrix> locals;
    for (const auto& block : blocks) {
        const int n = static_cast<int>(block.size());
        Matrix K(n, n);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                K(i, j) = value(rng);  // non-symmetric, as two-half-pass contact is
        locals.push_back(K);
    }
    return locals;
}

TEST(SparsePattern, AssembledMatrixEqualsTripletReference)
{
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    const std::vector<Matrix> locals = random_locals(scene.blocks, rng);

    SparseMatrix K = pattern.make_matrix();
    ASSERT_TRUE(pattern.matches(K));
    EXPECT_TRUE(Matrix(K).isZero(0.0));
    pattern.for_each_block([&](int b) { pattern.add(b, locals[b], K); }, Execution::serial());

    std::vector<Triplet> triplets;
    for (int b = 0; b < pattern.n_blocks(); ++b) {
        const auto& block = scene.blocks[b];
        for (std::size_t j = 0; j < block.size(); ++j)
            for (std::size_t i = 0; i < block.size(); ++i) {
                const int row = scene.dofs.free_index(block[i]);
                const int col = scene.dofs.free_index(block[j]);
                if (row >= 0 && col >= 0)
                    triplets.emplace_back(row, col, locals[b](i, j));
            }
    }
    SparseMatrix reference(scene.dofs.n_free(), scene.dofs.n_free());
    reference.setFromTriplets(triplets.begin(), triplets.end());

    // Each entry sums at most 4 element and 1 contact contributions of magnitude
    // <= 1, in a different order than the reference: <= ~5 ulps of 5.
    constexpr double summation_tolerance = 1e-14;
    EXPECT_TRUE(test::at_most((Matrix(K) - Matrix(reference)).cwiseAbs().maxCoeff(), summation_tolerance));
    EXPECT_EQ(K.rows(), scene.dofs.n_free());

    // The pattern is the reference pattern plus the diagonal, nothing else.
    const Matrix dense_reference = Matrix(reference);
    for (int j = 0; j < K.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
            const bool coupled = std::any_of(triplets.begin(), triplets.end(), [&](const Triplet& t) {
                return t.row() == it.row() && t.col() == it.col();
            });
            EXPECT_TRUE(coupled || it.row() == it.col()) << "entry (" << it.row() << ", " << it.col() << ")";
        }
    for (int i = 0; i < K.rows(); ++i)
        EXPECT_NE(std::find(K.innerIndexPtr() + K.outerIndexPtr()[i], K.innerIndexPtr() + K.outerIndexPtr()[i + 1], i),
                  K.innerIndexPtr() + K.outerIndexPtr()[i + 1])
            << "diagonal " << i << " missing";
}

TEST(SparsePattern, VectorAssemblySkipsConstrainedDofs)
{
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    Vector r = Vector::Zero(scene.dofs.n_free());
    Vector reference = Vector::Zero(scene.dofs.n_full());
    for (int b = 0; b < pattern.n_blocks(); ++b) {
        const auto& block = scene.blocks[b];
        Vector local(static_cast<Index>(block.size()));
        for (std::size_t i = 0; i < block.size(); ++i) {
            local(static_cast<Index>(i)) = 1.0 + b + 0.5 * static_cast<double>(i);
            reference(block[i]) += local(static_cast<Index>(i));
        }
        if (b % 2 == 0)
            pattern.add_vector(b, local, r);
        else
            pattern.add_vector(block, local, r);
    }
    // Sums of a few exactly representable numbers (multiples of 0.5 below 2^20): exact.
    EXPECT_EQ(r, scene.dofs.restrict(reference));
}

TEST(SparsePattern, SubBlockAddEqualsPaddedFullAdd)
{
    std::mt19937 rng(seed + 1);
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    const int contact = pattern.n_blocks() - 1;
    // One "Gauss point" couples two control points of the top row and one of body 2.
    const int row = scene.nx + 2;
    const int top = (scene.ny + 1) * row;
    const std::vector<int> gp_dofs = {scene.dofs.dof(top + 2, 0), scene.dofs.dof(top + 2, 1),
                                      scene.dofs.dof(top + 3, 0), scene.dofs.dof(top + 3, 1),
                                      scene.dofs.dof(scene.dofs.node_offset(1) + 1, 0),
                                      scene.dofs.dof(scene.dofs.node_offset(1) + 1, 1)};
    const std::vector<int> local = pattern.local_indices(contact, gp_dofs);
    const Matrix K_sub = random_locals({gp_dofs}, rng).front();

    SparseMatrix K = pattern.make_matrix();
    pattern.add(contact, local, K_sub, K);

    const int n = static_cast<int>(scene.blocks[contact].size());
    Matrix padded = Matrix::Zero(n, n);
    for (std::size_t b = 0; b < local.size(); ++b)
        for (std::size_t a = 0; a < local.size(); ++a)
            padded(local[a], local[b]) += K_sub(static_cast<Index>(a), static_cast<Index>(b));
    SparseMatrix K_padded = pattern.make_matrix();
    pattern.add(contact, padded, K_padded);
    EXPECT_EQ(Matrix(K), Matrix(K_padded));  // one addition per entry on both sides: exact

    EXPECT_THROW(pattern.local_indices(contact, std::vector<int>{scene.dofs.dof(0, 0) + 2}), iga::Error);
}

TEST(SparsePattern, ColorsNeverShareAFreeDof)
{
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    std::vector<int> seen(pattern.n_blocks(), 0);
    for (int c = 0; c < pattern.n_colors(); ++c) {
        std::set<int> used;
        for (int b : pattern.color(c)) {
            ++seen[b];
            for (int full : pattern.block_dofs(b)) {
                const int f = scene.dofs.free_index(full);
                if (f >= 0) {
                    EXPECT_TRUE(used.insert(f).second) << "color " << c << " block " << b << " dof " << f;
                }
            }
        }
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    // Quadratic spans overlap with up to 8 neighbours: a greedy coloring of the
    // grid needs 9 colors, plus one or two for the contact block.
    EXPECT_LE(pattern.n_colors(), 12);
}

TEST(SparsePattern, ParallelAndSerialAssemblyAreIdentical)
{
    std::mt19937 rng(seed + 2);
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    const std::vector<Matrix> locals = random_locals(scene.blocks, rng);

    auto assemble = [&](const Execution& execution, SparseMatrix& K, Vector& r) {
        K = pattern.make_matrix();
        r = Vector::Zero(scene.dofs.n_free());
        pattern.for_each_block(
            [&](int b) {
                pattern.add(b, locals[b], K);
                pattern.add_vector(b, locals[b].col(0), r);
            },
            execution);
    };
    SparseMatrix K_serial, K_parallel;
    Vector r_serial, r_parallel;
    assemble(Execution::serial(), K_serial, r_serial);
    for (int repeat = 0; repeat < 12; ++repeat) {  // races, if any, rarely show on the first run
        ThreadTeam team(2 + repeat % 3);
        assemble(Execution{&team}, K_parallel, r_parallel);
        // Bitwise: both visit the blocks in color order, one writer per entry per color.
        ASSERT_TRUE(std::equal(K_serial.valuePtr(), K_serial.valuePtr() + K_serial.nonZeros(),
                               K_parallel.valuePtr()));
        ASSERT_EQ(r_serial, r_parallel);
    }
}

TEST(SparsePattern, KernelExceptionIsRethrown)
{
    const Scene scene;
    const SparsePattern pattern(scene.dofs, scene.blocks);
    ThreadTeam team(3);
    for (const Execution execution : {Execution::serial(), Execution{&team}})
        EXPECT_THROW(pattern.for_each_block(
                         [](int b) {
                             if (b == 7)
                                 throw std::runtime_error("bad span");
                         },
                         execution),
                     std::runtime_error);
}

// A pattern built from the elements and then extended by the contact block (and
// by a block that adds no entry) is the pattern built with all of them at once:
// same compressed arrays, same colors, and bitwise the same assembled values.
TEST(SparsePattern, ExtendedPatternEqualsPatternBuiltAtOnce)
{
    const Scene scene;
    std::mt19937 rng(seed + 3);
    std::vector<std::vector<int>> all = scene.blocks;
    all.push_back(scene.blocks.front());  // a repeat: registers positions, adds no entry
    const std::vector<Matrix> locals = random_locals(all, rng);

    const SparsePattern at_once(scene.dofs, all);
    std::vector<std::vector<int>> elements(all.begin(), all.end() - 2);
    SparsePattern extended(scene.dofs, elements);
    const SparseMatrix before = extended.make_matrix();
    bool added = false;
    EXPECT_EQ(extended.extend({all[all.size() - 2]}, &added), static_cast<int>(all.size()) - 2);
    EXPECT_TRUE(added) << "the contact block couples the top row with the second body: new entries";
    EXPECT_FALSE(extended.matches(before));
    EXPECT_EQ(extended.extend({all.back()}, &added), static_cast<int>(all.size()) - 1);
    EXPECT_FALSE(added) << "a repeated element block adds no entry";

    ASSERT_EQ(extended.n_blocks(), at_once.n_blocks());
    ASSERT_EQ(extended.n_nonzeros(), at_once.n_nonzeros());
    EXPECT_TRUE(extended.matches(at_once.make_matrix()));
    ASSERT_EQ(extended.n_colors(), at_once.n_colors());
    for (int c = 0; c < at_once.n_colors(); ++c)
        EXPECT_EQ(extended.color(c), at_once.color(c)) << "color " << c;

    SparseMatrix K_once = at_once.make_matrix(), K_extended = extended.make_matrix();
    for (int b = 0; b < at_once.n_blocks(); ++b) {
        at_once.add(b, locals[static_cast<std::size_t>(b)], K_once);
        extended.add(b, locals[static_cast<std::size_t>(b)], K_extended);
    }
    // The same additions into the same slots in the same order: bitwise equal.
    for (Index k = 0; k < K_once.nonZeros(); ++k)
        ASSERT_EQ(K_once.valuePtr()[k], K_extended.valuePtr()[k]) << "entry " << k;
    EXPECT_GT(Matrix(K_once).cwiseAbs().maxCoeff(), 0.0);
}

TEST(SparsePattern, SearchedPositionsGiveTheStoredSums)
{
    const Scene scene;
    std::mt19937 rng(seed + 4);
    const std::vector<Matrix> locals = random_locals(scene.blocks, rng);
    const int n_elements = static_cast<int>(scene.blocks.size()) - 1;  // the contact block keeps its positions
    const SparsePattern stored(scene.dofs, scene.blocks);
    SparsePattern searched(scene.dofs, scene.blocks, n_elements);
    ASSERT_TRUE(searched.matches(stored.make_matrix()));

    SparseMatrix K_stored = stored.make_matrix(), K_searched = searched.make_matrix();
    for (int b = 0; b < stored.n_blocks(); ++b) {
        stored.add(b, locals[static_cast<std::size_t>(b)], K_stored);
        searched.add(b, locals[static_cast<std::size_t>(b)], K_searched);
    }
    // A sub-block add into a searched block (an element) and into a stored one (contact).
    const std::vector<int> gp = {0, 3, 4};
    const Matrix K_sub = random_locals({std::vector<int>(3)}, rng).front();
    for (int b : {0, n_elements}) {
        stored.add(b, gp, K_sub, K_stored);
        searched.add(b, gp, K_sub, K_searched);
    }
    for (Index k = 0; k < K_stored.nonZeros(); ++k)  // the same slots in the same order: bitwise
        ASSERT_EQ(K_stored.valuePtr()[k], K_searched.valuePtr()[k]) << "entry " << k;

    // Extending keeps the searched blocks searched and stores the new ones.
    searched.extend({scene.blocks.front()});
    SparseMatrix K_extended = searched.make_matrix();
    searched.add(searched.n_blocks() - 1, locals.front(), K_extended);
    searched.add(0, locals.front(), K_extended);
    SparseMatrix K_twice = stored.make_matrix();
    stored.add(0, locals.front(), K_twice);
    stored.add(0, locals.front(), K_twice);
    for (Index k = 0; k < K_twice.nonZeros(); ++k)
        ASSERT_EQ(K_twice.valuePtr()[k], K_extended.valuePtr()[k]) << "entry " << k;
}

TEST(SparsePattern, FlaggedSearchedBlocksGiveTheStoredSums)
{
    // The scene's choice (analysis/scene.hpp): elements stored (finite strain), the
    // contact couplings searched, also those that extend() adds later (3D).
    const Scene scene;
    std::mt19937 rng(seed + 5);
    const std::vector<Matrix> locals = random_locals(scene.blocks, rng);
    const std::size_t n_blocks = scene.blocks.size();
    ASSERT_GE(n_blocks, 2u);
    std::vector<char> flags(n_blocks, 0);
    flags[n_blocks - 1] = 1;  // the contact block
    const SparsePattern stored(scene.dofs, scene.blocks);
    SparsePattern searched(scene.dofs, scene.blocks, flags);
    ASSERT_TRUE(searched.matches(stored.make_matrix()));
    SparseMatrix K_stored = stored.make_matrix(), K_searched = searched.make_matrix();
    for (int b = 0; b < stored.n_blocks(); ++b) {
        stored.add(b, locals[static_cast<std::size_t>(b)], K_stored);
        searched.add(b, locals[static_cast<std::size_t>(b)], K_searched);
    }
    const std::vector<int> gp = {0, 3, 4};
    const Matrix K_sub = random_locals({std::vector<int>(3)}, rng).front();
    stored.add(static_cast<int>(n_blocks) - 1, gp, K_sub, K_stored);
    searched.add(static_cast<int>(n_blocks) - 1, gp, K_sub, K_searched);
    for (Index k = 0; k < K_stored.nonZeros(); ++k)
        ASSERT_EQ(K_stored.valuePtr()[k], K_searched.valuePtr()[k]) << "entry " << k;

    // A searched extension: the same sums as a stored one.
    SparsePattern stored_extended(scene.dofs, scene.blocks);
    stored_extended.extend({scene.blocks.back()});
    searched.extend({scene.blocks.back()}, nullptr, true);
    SparseMatrix A = stored_extended.make_matrix(), B = searched.make_matrix();
    stored_extended.add(stored_extended.n_blocks() - 1, locals.back(), A);
    searched.add(searched.n_blocks() - 1, locals.back(), B);
    ASSERT_EQ(A.nonZeros(), B.nonZeros());
    for (Index k = 0; k < A.nonZeros(); ++k)
        ASSERT_EQ(A.valuePtr()[k], B.valuePtr()[k]) << "entry " << k;

    EXPECT_THROW(SparsePattern(scene.dofs, scene.blocks, std::vector<char>(n_blocks + 1, 0)), iga::Error);
}

}  // namespace
}  // namespace iga::assembly
