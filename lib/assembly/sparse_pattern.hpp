#pragma once
// SparsePattern: the sparsity pattern of the free x free tangent, built once
// and extended when new couplings appear, and the scatter of local (block)
// matrices and vectors into it.
//
// A "connectivity block" is a list of full dof indices that couple with each
// other: an element's (knot span's) dofs, or the dofs of one contact coupling (a
// slave side element and a master side element it may project onto; see
// analysis/scene.hpp). extend() adds blocks later (a Gauss point that slid onto a
// master element not registered yet): their new entries are merged into the
// compressed structure column by column and the stored positions of the existing
// blocks are remapped, O(nnz + new entries), with no rebuild from the blocks; the
// result is identical to a pattern built with all blocks from the start (same
// arrays, same colors). A matrix made before an extension that added entries no
// longer matches(): make a new one (and the linear solver then redoes its
// symbolic analysis, solver/suitesparse_solver.hpp). The pattern is the union of
// the blocks' dense couplings restricted to free dofs, plus the whole diagonal
// (so that a Levenberg-Marquardt shift K + mu D keeps the pattern; see
// solver/newton.hpp). For each block the position in K.valuePtr() of every local
// entry (i, j) is precomputed (-1 when the row or the column is constrained), so
// add() is an indexed add with no search. Prescribed values need no lifting: the
// driver evaluates the residual at the expanded full vector (DofMap::expand).
//
// Shapes: a block with n dofs takes an n x n local matrix and n-vector in the
// order of its dof list. Memory: 4 n^2 bytes of positions per block (18 dofs:
// 1.3 kB, a 2D quadratic span; 81 dofs: 26 kB, a 3D quadratic span: 210 MB for
// 8000 spans, more than the tangent itself). Blocks added once only (the element
// blocks under small kinematics, whose constant stiffness is assembled once) are
// better left without, and so are blocks too large to pay for theirs (a 3D contact
// coupling of two quadratic spans: 162 dofs, 105 kB; the candidate couplings of two
// crossed cylinders at 35k dofs held 919 MB of positions, more than the factor): a
// searched block keeps no positions, and add() finds each of its entries by a
// binary search in its column, the search that precomputing does, so the sums are
// the same, in the same order. The constructor's first n_searched blocks, or those
// flagged, are searched; extend() says for the blocks it adds.
//
// Parallel assembly: the blocks are greedily colored so that no two blocks of
// one color share a free dof; for_each_block runs the colors one after the
// other and the blocks of a color on the threads of a ThreadTeam
// (assembly/thread_team.hpp; the caller is one of them), so threads never write
// the same entry. Blocks are handed out in chunks from an atomic counter per
// color; the caller advances to the next color once every block of the current
// one is done, waiting (passively) only for chunks that a helper has claimed,
// never for a helper to show up. So a helper that another process holds off its
// core costs at most the chunk it holds, and the loop is never much slower than
// the serial one on a loaded machine (OpenMP's spin-waiting barriers were, up
// to 100x; docs/performance.md "Threads"). The serial path visits the blocks in the same
// color order, so both give bitwise identical results. Measured with
// benchmarks/assembly_benchmark.cpp (64 x 64 quadratic 2D spans, 18-dof blocks):
// the indexed add costs 0.6x the CPU time of triplets + setFromTriplets; coloring
// costs ~10% serially. Choosing the thread count: assembly/threads.hpp.

#include "assembly/dof_map.hpp"
#include "core/types.hpp"

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace iga::assembly {

class ThreadTeam;

/// How for_each_block runs: without a team (or a team of one) the plain serial loop.
struct Execution {
    ThreadTeam* team = nullptr;
    static Execution serial() { return {}; }
};

class SparsePattern {
public:
    /// blocks: full dof indices of each block (any order; a dof may repeat).
    /// Blocks [0, n_searched) keep no positions (see above).
    SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, int n_searched = 0);
    /// searched[b] != 0: block b keeps no positions (one flag per block).
    SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, std::vector<char> searched);

    int n_free() const { return n_free_; }
    int n_blocks() const { return static_cast<int>(blocks_.size()); }
    Index n_nonzeros() const { return static_cast<Index>(inner_.size()); }
    const std::vector<int>& block_dofs(int block) const { return blocks_[block]; }

    /// Adds blocks after construction (see above); returns the index of the first
    /// new block. True in *entries_added when the structure grew (then matrices
    /// from make_matrix() before the call no longer match()).
    /// `searched`: the new blocks keep no positions (see above).
    int extend(std::vector<std::vector<int>> blocks, bool* entries_added = nullptr, bool searched = false);

    /// n_free x n_free, compressed, every stored value zero.
    SparseMatrix make_matrix() const;
    /// K takes this pattern (compressed, every stored value zero), reusing its storage.
    void shape(SparseMatrix& K) const;
    /// True when K has exactly this pattern (the precondition of add()).
    bool matches(const SparseMatrix& K) const;

    /// K += K_local scattered by the block's dof list; constrained rows and
    /// columns are skipped. Precondition: K from make_matrix(), K_local n x n.
    void add(int block, const Matrix& K_local, SparseMatrix& K) const;
    /// Sub-block add: K_sub(a, b) goes to the block's local entry (local[a], local[b]),
    /// e.g. the dofs of one Gauss point's slave and master spans inside a contact
    /// pair's block (local indices from local_indices()).
    void add(int block, std::span<const int> local, const Matrix& K_sub, SparseMatrix& K) const;
    /// r_free += r_local by the block's dof list (constrained entries skipped).
    void add_vector(int block, const Vector& r_local, Vector& r_free) const;
    /// r_free += r_local by any full dof list (constrained entries skipped). In
    /// for_each_block, use only dofs of the block being visited.
    void add_vector(const std::vector<int>& full_dofs, const Vector& r_local, Vector& r_free) const;

    /// Positions of full_dofs in the block's dof list (first occurrence); a dof
    /// not in the block is an iga::Error. A linear search: precompute, don't call per entry.
    std::vector<int> local_indices(int block, std::span<const int> full_dofs) const;

    int n_colors() const { return static_cast<int>(colors_.size()); }
    /// Blocks of one color: no two share a free dof.
    const std::vector<int>& color(int c) const { return colors_[c]; }

    /// Calls kernel(block) once per block, color by color; with a team of n > 1
    /// threads the blocks of a color run on them (the calling thread included).
    /// The kernel may add() and add_vector() for its own block only. Colors
    /// separate free dofs only: writes indexed by constrained dofs (e.g. reactions
    /// in a full-length vector) may race and must be done outside. An exception
    /// thrown by the kernel is rethrown here, after all blocks ran (the first one caught).
    void for_each_block(const std::function<void(int block)>& kernel, const Execution& execution) const;

private:
    // searched: one flag per block, or (n_searched >= 0) the first n_searched blocks.
    SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, std::vector<char> searched,
                  int n_searched);
    void add_block_positions(std::size_t first_block);
    /// Position of (row, column) in K.valuePtr() (both free and in the pattern).
    int search_position(int row, int column) const;
    bool searched(int block) const { return searched_[static_cast<std::size_t>(block)] != 0; }

    int n_free_;
    std::vector<int> free_of_full_;            // copy of the DofMap table (n_full)
    std::vector<std::vector<int>> blocks_;     // full dofs per block
    std::vector<std::vector<int>> block_free_; // free index (or -1) per block entry
    std::vector<int> outer_;                   // n_free + 1, column starts
    std::vector<int> inner_;                   // row indices, sorted within each column
    std::vector<std::size_t> position_offset_; // n_blocks + 1, into positions_
    std::vector<int> positions_;               // per block, n x n column-major, -1 = skipped
    std::vector<char> searched_;               // per block: keeps no positions
    std::vector<std::vector<int>> colors_;
};

}  // namespace iga::assembly
