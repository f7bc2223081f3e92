// Assembly kernels: does the precomputed-position scatter pay against triplets,
// and does the colored threaded loop pay against the serial one?
//
// Scene: a 2D grid of 64 x 64 quadratic spans (66 x 66 control points, 8712
// dofs, 4096 blocks of 18 dofs), left column fixed. "Element" kernel: a
// B^T D B sum over 9 Gauss points (~10k flops per span, like a small-strain
// element without the basis evaluation); "scatter" kernels add precomputed
// local matrices only.
// Run: bin/assembly_benchmark ("Parallel" = a ThreadTeam of 2).
//
// Measured on the project machine (2 cores, Release, GCC 12) while other builds
// kept the load average at 8-11, so wall times are ~2.5x the CPU times and only
// the CPU times compare the serial kernels (medians, per full assembly):
//                                            wall      CPU (main thread)
//   element + triplets + setFromTriplets     98 ms     38.5 ms
//   element + indexed add, natural order     59 ms     23.1 ms
//   element + indexed add, colored serial    65 ms     25.5 ms
//   element + colored, 2 threads            115 ms     22.5 ms  (OMP_WAIT_POLICY=passive: 62 ms, 12.2 ms)
//   scatter only, colored serial             7.0 ms     2.8 ms
//   scatter only, colored, 2 threads        39 ms       9.5 ms  (passive: 6.7 ms, 1.3 ms)
//   build the pattern (once per run)         66 ms     26 ms
// Findings: the indexed add is 1.7x cheaper than triplets; coloring costs ~10%
// in the serial loop (less cache reuse). The colored loop splits the work
// evenly (main-thread CPU halves with passive waiting), but on this
// oversubscribed machine the spin-waiting at the ~10 color barriers costs more
// than it saves: 2 threads were slower in wall time by default and only tied
// with OMP_WAIT_POLICY=passive. A speed-up on idle cores could not be measured
// here. (Those figures are for the former OpenMP loop; the ThreadTeam loop that
// replaced it waits passively and never for an absent helper: docs/solver.md "Threads".)

#include "assembly/dof_map.hpp"
#include "assembly/sparse_pattern.hpp"
#include "assembly/thread_team.hpp"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace iga;
using namespace iga::assembly;

constexpr int n_spans = 64;

struct Grid {
    DofMap dofs;
    std::vector<std::vector<int>> blocks;
    std::vector<Matrix> B;  // 9 Gauss points, 3 x 18 strain-displacement stand-ins
    Matrix D;

    static std::vector<PrescribedDof> left_column()
    {
        std::vector<PrescribedDof> c;
        for (int j = 0; j < n_spans + 2; ++j)
            for (int comp = 0; comp < 2; ++comp)
                c.push_back({2 * j * (n_spans + 2) + comp, 0.0, Amplitude()});
        return c;
    }

    Grid() : dofs(2, {(n_spans + 2) * (n_spans + 2)}, left_column())
    {
        const int row = n_spans + 2;
        for (int ey = 0; ey < n_spans; ++ey)
            for (int ex = 0; ex < n_spans; ++ex) {
                std::vector<int> block;
                for (int b = 0; b < 3; ++b)
                    for (int a = 0; a < 3; ++a)
                        for (int comp = 0; comp < 2; ++comp)
                            block.push_back(dofs.dof((ey + b) * row + ex + a, comp));
                blocks.push_back(block);
            }
        for (int q = 0; q < 9; ++q) {
            Matrix b(3, 18);
            for (int j = 0; j < 18; ++j)
                for (int i = 0; i < 3; ++i)
                    b(i, j) = 0.01 * ((q * 7 + i * 5 + j * 3) % 11) - 0.05;
            B.push_back(b);
        }
        D = Matrix::Identity(3, 3) * 2.0;
        D(0, 1) = D(1, 0) = 1.0;
    }

    void element(int block, Matrix& K_local) const
    {
        K_local.setZero(18, 18);
        const double scale = 1.0 + 1e-3 * block;
        for (const Matrix& b : B)
            K_local.noalias() += (scale * b.transpose()) * (D * b);
    }
};

void BM_ElementTriplets(benchmark::State& state)
{
    const Grid g;
    std::vector<Triplet> triplets;
    Matrix K_local;
    for (auto _ : state) {
        triplets.clear();
        for (int b = 0; b < static_cast<int>(g.blocks.size()); ++b) {
            g.element(b, K_local);
            const auto& block = g.blocks[b];
            for (int j = 0; j < 18; ++j) {
                const int col = g.dofs.free_index(block[j]);
                if (col < 0)
                    continue;
                for (int i = 0; i < 18; ++i) {
                    const int row = g.dofs.free_index(block[i]);
                    if (row >= 0)
                        triplets.emplace_back(row, col, K_local(i, j));
                }
            }
        }
        SparseMatrix K(g.dofs.n_free(), g.dofs.n_free());
        K.setFromTriplets(triplets.begin(), triplets.end());
        benchmark::DoNotOptimize(K.valuePtr());
    }
}
BENCHMARK(BM_ElementTriplets)->Unit(benchmark::kMillisecond);

void BM_ElementIndexedNaturalOrder(benchmark::State& state)
{
    const Grid g;
    const SparsePattern pattern(g.dofs, g.blocks);
    SparseMatrix K = pattern.make_matrix();
    Matrix K_local;
    for (auto _ : state) {
        K.coeffs().setZero();
        for (int b = 0; b < pattern.n_blocks(); ++b) {
            g.element(b, K_local);
            pattern.add(b, K_local, K);
        }
        benchmark::DoNotOptimize(K.valuePtr());
    }
}
BENCHMARK(BM_ElementIndexedNaturalOrder)->Unit(benchmark::kMillisecond);

void element_colored(benchmark::State& state, const Execution& execution)
{
    const Grid g;
    const SparsePattern pattern(g.dofs, g.blocks);
    SparseMatrix K = pattern.make_matrix();
    for (auto _ : state) {
        K.coeffs().setZero();
        pattern.for_each_block(
            [&](int b) {
                thread_local Matrix K_local;
                g.element(b, K_local);
                pattern.add(b, K_local, K);
            },
            execution);
        benchmark::DoNotOptimize(K.valuePtr());
    }
}
ThreadTeam two_threads(2);  // benchmark-wide team
void BM_ElementIndexedColoredSerial(benchmark::State& state) { element_colored(state, Execution::serial()); }
void BM_ElementIndexedColoredParallel(benchmark::State& state) { element_colored(state, Execution{&two_threads}); }
BENCHMARK(BM_ElementIndexedColoredSerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ElementIndexedColoredParallel)->Unit(benchmark::kMillisecond)->UseRealTime();

void scatter_only(benchmark::State& state, const Execution& execution)
{
    const Grid g;
    const SparsePattern pattern(g.dofs, g.blocks);
    std::vector<Matrix> locals(g.blocks.size());
    for (int b = 0; b < pattern.n_blocks(); ++b)
        g.element(b, locals[b]);
    SparseMatrix K = pattern.make_matrix();
    for (auto _ : state) {
        K.coeffs().setZero();
        pattern.for_each_block([&](int b) { pattern.add(b, locals[b], K); }, execution);
        benchmark::DoNotOptimize(K.valuePtr());
    }
}
void BM_ScatterOnlySerial(benchmark::State& state) { scatter_only(state, Execution::serial()); }
void BM_ScatterOnlyParallel(benchmark::State& state) { scatter_only(state, Execution{&two_threads}); }
BENCHMARK(BM_ScatterOnlySerial)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScatterOnlyParallel)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BuildPattern(benchmark::State& state)
{
    const Grid g;
    for (auto _ : state) {
        const SparsePattern pattern(g.dofs, g.blocks);
        benchmark::DoNotOptimize(pattern.n_nonzeros());
    }
}
BENCHMARK(BM_BuildPattern)->Unit(benchmark::kMillisecond);

}  // namespace
