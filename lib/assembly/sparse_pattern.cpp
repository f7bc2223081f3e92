#include "assembly/sparse_pattern.hpp"

#include "assembly/thread_team.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

namespace iga::assembly {

namespace {

// Greedy coloring: each block takes the smallest color that no block sharing
// one of its free dofs has taken. Structured IGA meshes of degree p need about
// (p+1)^d colors; a dense contact block conflicts with its neighbours only.
std::vector<std::vector<int>> color_blocks(const std::vector<std::vector<int>>& block_free, int n_free)
{
    std::vector<std::vector<int>> colors_at_dof(n_free);
    std::vector<int> forbidden_by;  // color -> last block that saw it taken
    std::vector<std::vector<int>> colors;
    for (int b = 0; b < static_cast<int>(block_free.size()); ++b) {
        for (int f : block_free[b])
            if (f >= 0)
                for (int c : colors_at_dof[f])
                    forbidden_by[c] = b;
        int color = 0;
        while (color < static_cast<int>(colors.size()) && forbidden_by[color] == b)
            ++color;
        if (color == static_cast<int>(colors.size())) {
            colors.emplace_back();
            forbidden_by.push_back(-1);
        }
        colors[color].push_back(b);
        for (int f : block_free[b])
            if (f >= 0 && (colors_at_dof[f].empty() || colors_at_dof[f].back() != color))
                colors_at_dof[f].push_back(color);
    }
    return colors;
}

}  // namespace

SparsePattern::SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, int n_searched)
    : SparsePattern(dofs, std::move(blocks), std::vector<char>{}, std::max(n_searched, 0))
{
}

SparsePattern::SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, std::vector<char> searched)
    : SparsePattern(dofs, std::move(blocks), std::move(searched), -1)
{
}

SparsePattern::SparsePattern(const DofMap& dofs, std::vector<std::vector<int>> blocks, std::vector<char> searched,
                             int n_searched)
    : n_free_(dofs.n_free()), free_of_full_(dofs.free_of_full()), blocks_(std::move(blocks)),
      searched_(std::move(searched))
{
    if (n_searched >= 0) {  // the first n_searched blocks
        searched_.assign(blocks_.size(), 0);
        std::fill_n(searched_.begin(), std::min(blocks_.size(), static_cast<std::size_t>(n_searched)), 1);
    }
    IGA_CHECK(searched_.size() == blocks_.size(), "SparsePattern: one searched flag per block");
    const int n_full = static_cast<int>(free_of_full_.size());
    block_free_.resize(blocks_.size());
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
        block_free_[b].reserve(blocks_[b].size());
        for (int full : blocks_[b]) {
            IGA_CHECK(full >= 0 && full < n_full, "SparsePattern: block " + std::to_string(b) + " has dof " +
                                                      std::to_string(full) + " outside [0, " +
                                                      std::to_string(n_full) + ")");
            block_free_[b].push_back(free_of_full_[full]);
        }
    }

    // Rows of each column: the union of the blocks' dense couplings, plus the
    // diagonal, one column at a time from the blocks that hold it. (Collecting
    // every block's rows per column first held each row once per block: 27 times
    // in 3D at degree 2, twice the finished pattern.)
    std::vector<int> first_block_of(static_cast<std::size_t>(n_free_) + 1, 0);  // CSR: free dof -> blocks
    for (const std::vector<int>& f : block_free_)
        for (int col : f)
            if (col >= 0)
                ++first_block_of[static_cast<std::size_t>(col) + 1];
    for (int j = 0; j < n_free_; ++j)
        first_block_of[j + 1] += first_block_of[j];
    std::vector<int> blocks_of(static_cast<std::size_t>(first_block_of.back()));
    {
        std::vector<int> fill(first_block_of.begin(), first_block_of.end() - 1);
        for (std::size_t b = 0; b < block_free_.size(); ++b)
            for (int col : block_free_[b])
                if (col >= 0)
                    blocks_of[static_cast<std::size_t>(fill[col]++)] = static_cast<int>(b);
    }
    std::vector<int> seen_in(static_cast<std::size_t>(n_free_), -1);  // row -> last column that took it
    outer_.assign(n_free_ + 1, 0);
    for (int j = 0; j < n_free_; ++j) {
        const std::size_t start = inner_.size();
        seen_in[j] = j;
        inner_.push_back(j);
        for (int k = first_block_of[j]; k < first_block_of[j + 1]; ++k)
            for (int row : block_free_[static_cast<std::size_t>(blocks_of[static_cast<std::size_t>(k)])])
                if (row >= 0 && seen_in[row] != j) {
                    seen_in[row] = j;
                    inner_.push_back(row);
                }
        std::sort(inner_.begin() + static_cast<std::ptrdiff_t>(start), inner_.end());
        outer_[j + 1] = static_cast<int>(inner_.size());
    }
    inner_.shrink_to_fit();

    add_block_positions(0);

    colors_ = color_blocks(block_free_, n_free_);
}

int SparsePattern::search_position(int row, int column) const
{
    const int* first = inner_.data() + outer_[column];
    const int* last = inner_.data() + outer_[column + 1];
    return static_cast<int>(std::lower_bound(first, last, row) - inner_.data());
}

void SparsePattern::add_block_positions(std::size_t first_block)
{
    position_offset_.resize(blocks_.size() + 1);
    if (first_block == 0)
        position_offset_[0] = 0;
    for (std::size_t b = first_block; b < blocks_.size(); ++b)
        position_offset_[b + 1] =
            position_offset_[b] + (searched(static_cast<int>(b)) ? 0 : blocks_[b].size() * blocks_[b].size());
    positions_.resize(position_offset_.back(), -1);
    for (std::size_t b = first_block; b < blocks_.size(); ++b) {
        if (searched(static_cast<int>(b)))
            continue;
        const std::vector<int>& f = block_free_[b];
        const std::size_t n = f.size();
        int* pos = positions_.data() + position_offset_[b];
        for (std::size_t j = 0; j < n; ++j) {
            if (f[j] < 0)
                continue;
            for (std::size_t i = 0; i < n; ++i)
                if (f[i] >= 0)
                    pos[j * n + i] = search_position(f[i], f[j]);
        }
    }
}

int SparsePattern::extend(std::vector<std::vector<int>> blocks, bool* entries_added, bool searched)
{
    const std::size_t first_block = blocks_.size();
    searched_.resize(first_block + blocks.size(), searched ? 1 : 0);
    const int n_full = static_cast<int>(free_of_full_.size());
    for (std::vector<int>& block : blocks) {
        std::vector<int> f;
        f.reserve(block.size());
        for (int full : block) {
            IGA_CHECK(full >= 0 && full < n_full, "SparsePattern::extend: a block has dof " + std::to_string(full) +
                                                      " outside [0, " + std::to_string(n_full) + ")");
            f.push_back(free_of_full_[full]);
        }
        block_free_.push_back(std::move(f));
        blocks_.push_back(std::move(block));
    }

    // Couplings of the new blocks that the structure lacks, as (column, row), sorted.
    std::vector<std::pair<int, int>> missing;
    for (std::size_t b = first_block; b < blocks_.size(); ++b)
        for (int col : block_free_[b])
            if (col >= 0) {
                const int* first = inner_.data() + outer_[col];
                const int* last = inner_.data() + outer_[col + 1];
                for (int row : block_free_[b])
                    if (row >= 0 && !std::binary_search(first, last, row))
                        missing.emplace_back(col, row);
            }
    std::sort(missing.begin(), missing.end());
    missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
    if (entries_added)
        *entries_added = !missing.empty();

    if (!missing.empty()) {
        // Merge column by column; remap[k] is the new index of old entry k.
        std::vector<int> outer(static_cast<std::size_t>(n_free_) + 1, 0);
        std::vector<int> inner;
        inner.reserve(inner_.size() + missing.size());
        std::vector<int> remap(inner_.size());
        std::size_t m = 0;
        for (int j = 0; j < n_free_; ++j) {
            int k = outer_[j];
            const int k_end = outer_[j + 1];
            while (k < k_end || (m < missing.size() && missing[m].first == j)) {
                const bool take_old =
                    k < k_end && !(m < missing.size() && missing[m].first == j && missing[m].second < inner_[k]);
                if (take_old) {
                    remap[static_cast<std::size_t>(k)] = static_cast<int>(inner.size());
                    inner.push_back(inner_[k++]);
                } else {
                    inner.push_back(missing[m++].second);
                }
            }
            outer[static_cast<std::size_t>(j) + 1] = static_cast<int>(inner.size());
        }
        for (int& p : positions_)
            if (p >= 0)
                p = remap[static_cast<std::size_t>(p)];
        outer_ = std::move(outer);
        inner_ = std::move(inner);
    }
    add_block_positions(first_block);
    colors_ = color_blocks(block_free_, n_free_);  // greedy in block order: old blocks keep their colors
    return static_cast<int>(first_block);
}

SparseMatrix SparsePattern::make_matrix() const
{
    SparseMatrix K;
    shape(K);
    return K;
}

void SparsePattern::shape(SparseMatrix& K) const
{
    // Written in place: a 3D tangent is ~100 MB at 30k dofs, and a copy through a
    // temporary (or an Eigen assignment, which copies) would briefly double it.
    const auto nnz = static_cast<Index>(inner_.size());
    K.resize(n_free_, n_free_);
    K.resizeNonZeros(nnz);
    std::copy(outer_.begin(), outer_.end(), K.outerIndexPtr());
    std::copy(inner_.begin(), inner_.end(), K.innerIndexPtr());
    std::fill(K.valuePtr(), K.valuePtr() + nnz, 0.0);
}

bool SparsePattern::matches(const SparseMatrix& K) const
{
    return K.isCompressed() && K.rows() == n_free_ && K.cols() == n_free_ &&
           K.nonZeros() == static_cast<Index>(inner_.size()) &&
           std::equal(outer_.begin(), outer_.end(), K.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), K.innerIndexPtr());
}

void SparsePattern::add(int block, const Matrix& K_local, SparseMatrix& K) const
{
    const Index n = static_cast<Index>(blocks_[block].size());
    IGA_ASSERT(K_local.rows() == n && K_local.cols() == n, "SparsePattern::add: local matrix is not n x n");
    IGA_ASSERT(K.nonZeros() == n_nonzeros() && K.rows() == n_free_, "SparsePattern::add: K is not from make_matrix()");
    double* values = K.valuePtr();
    const double* local = K_local.data();
    if (searched(block)) {  // the same entries in the same order as the stored positions
        const std::vector<int>& f = block_free_[block];
        for (Index j = 0; j < n; ++j) {
            if (f[j] < 0)
                continue;
            const int* column = inner_.data();
            const int end = outer_[f[j] + 1];
            int position = -1, previous_row = -2;
            for (Index i = 0; i < n; ++i) {
                const int row = f[i];
                if (row < 0)
                    continue;
                // A control point's components, and the neighbours along a patch's first
                // direction, are consecutive rows: the next entry of the column, no search.
                if (row == previous_row + 1 && position + 1 < end && column[position + 1] == row)
                    ++position;
                else
                    position = search_position(row, f[j]);
                values[position] += local[j * n + i];
                previous_row = row;
            }
        }
        return;
    }
    const int* pos = positions_.data() + position_offset_[block];
    for (Index k = 0; k < n * n; ++k)  // column-major on both sides
        if (pos[k] >= 0)
            values[pos[k]] += local[k];
}

void SparsePattern::add(int block, std::span<const int> local, const Matrix& K_sub, SparseMatrix& K) const
{
    const std::size_t n = blocks_[block].size();
    const Index m = static_cast<Index>(local.size());
    IGA_ASSERT(K_sub.rows() == m && K_sub.cols() == m, "SparsePattern::add: sub-block matrix size differs");
    IGA_ASSERT(K.nonZeros() == n_nonzeros() && K.rows() == n_free_, "SparsePattern::add: K is not from make_matrix()");
    const std::vector<int>& f = block_free_[block];
    const int* pos = searched(block) ? nullptr : positions_.data() + position_offset_[block];
    double* values = K.valuePtr();
    for (Index b = 0; b < m; ++b) {
        IGA_ASSERT(local[b] >= 0 && static_cast<std::size_t>(local[b]) < n,
                   "SparsePattern::add: local index out of range");
        const int* column = pos ? pos + static_cast<std::size_t>(local[b]) * n : nullptr;
        for (Index a = 0; a < m; ++a) {
            if (!column) {
                const int row = f[static_cast<std::size_t>(local[a])], col = f[static_cast<std::size_t>(local[b])];
                if (row >= 0 && col >= 0)
                    values[search_position(row, col)] += K_sub(a, b);
                continue;
            }
            const int p = column[local[a]];
            if (p >= 0)
                values[p] += K_sub(a, b);
        }
    }
}

void SparsePattern::add_vector(int block, const Vector& r_local, Vector& r_free) const
{
    const std::vector<int>& f = block_free_[block];
    IGA_ASSERT(r_local.size() == static_cast<Index>(f.size()), "SparsePattern::add_vector: local vector size differs");
    IGA_ASSERT(r_free.size() == n_free_, "SparsePattern::add_vector: r_free is not n_free");
    for (std::size_t i = 0; i < f.size(); ++i)
        if (f[i] >= 0)
            r_free(f[i]) += r_local(static_cast<Index>(i));
}

void SparsePattern::add_vector(const std::vector<int>& full_dofs, const Vector& r_local, Vector& r_free) const
{
    IGA_ASSERT(r_local.size() == static_cast<Index>(full_dofs.size()), "SparsePattern::add_vector: sizes differ");
    IGA_ASSERT(r_free.size() == n_free_, "SparsePattern::add_vector: r_free is not n_free");
    for (std::size_t i = 0; i < full_dofs.size(); ++i) {
        const int f = free_of_full_[full_dofs[i]];
        if (f >= 0)
            r_free(f) += r_local(static_cast<Index>(i));
    }
}

std::vector<int> SparsePattern::local_indices(int block, std::span<const int> full_dofs) const
{
    const std::vector<int>& dofs = blocks_[block];
    std::vector<int> local;
    local.reserve(full_dofs.size());
    for (int full : full_dofs) {
        const auto it = std::find(dofs.begin(), dofs.end(), full);
        IGA_CHECK(it != dofs.end(), "SparsePattern::local_indices: dof " + std::to_string(full) +
                                        " is not in block " + std::to_string(block));
        local.push_back(static_cast<int>(it - dofs.begin()));
    }
    return local;
}

void SparsePattern::for_each_block(const std::function<void(int block)>& kernel, const Execution& execution) const
{
    if (execution.team == nullptr || execution.team->n_threads() == 1) {
        for (const std::vector<int>& blocks : colors_)
            for (int b : blocks)
                kernel(b);
        return;
    }

    // Small chunks: contact blocks cost far more than element blocks, and a helper
    // preempted while holding a chunk delays the color by that chunk only.
    constexpr int chunk = 4;
    const int n_colors = static_cast<int>(colors_.size());
    std::vector<std::atomic<int>> next(colors_.size());  // next unclaimed block of each color
    std::vector<std::atomic<int>> done(colors_.size());  // finished blocks of each color
    for (std::size_t c = 0; c < colors_.size(); ++c) {
        next[c].store(0, std::memory_order_relaxed);
        done[c].store(0, std::memory_order_relaxed);
    }
    std::atomic<int> open_color{0};  // colors below it may be worked on; n_colors + 1 when finished
    std::mutex error_mutex;
    std::exception_ptr error;

    // Claims and runs chunks of color c until none is left.
    auto work_on = [&](int c) {
        const std::vector<int>& blocks = colors_[static_cast<std::size_t>(c)];
        const int n = static_cast<int>(blocks.size());
        for (int first = next[c].fetch_add(chunk); first < n; first = next[c].fetch_add(chunk)) {
            const int last = std::min(n, first + chunk);
            for (int k = first; k < last; ++k) {
                try {
                    kernel(blocks[static_cast<std::size_t>(k)]);
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(error_mutex);
                    if (!error)
                        error = std::current_exception();
                }
            }
            if (done[c].fetch_add(last - first) + (last - first) == n)
                done[c].notify_all();
        }
    };
    // Helpers: follow the caller from color to color; leave when it has finished.
    auto helper = [&] {
        for (int c = 0; c < n_colors; ++c) {
            for (int open = open_color.load(); open <= c; open = open_color.load())
                open_color.wait(open);
            if (open_color.load() > n_colors)
                return;
            work_on(c);
        }
    };
    execution.team->run([&, caller = std::this_thread::get_id()] {
        if (std::this_thread::get_id() != caller) {
            helper();
            return;
        }
        for (int c = 0; c < n_colors; ++c) {
            open_color.store(c + 1);
            open_color.notify_all();
            work_on(c);
            const int n = static_cast<int>(colors_[static_cast<std::size_t>(c)].size());
            for (int d = done[c].load(); d < n; d = done[c].load())
                done[c].wait(d);  // chunks still running on helpers
        }
        open_color.store(n_colors + 1);
        open_color.notify_all();
    });
    if (error)
        std::rethrow_exception(error);
}

}  // namespace iga::assembly
