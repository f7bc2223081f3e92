#pragma once
// How many threads the assembly uses, and keeping the libraries it calls to one.
//
// The only parallel loop is SparsePattern::for_each_block (the element kernels of
// finite kinematics). Threads pay only when a call has enough work to hide the
// cost of starting them and of the color barriers (~10 per call): below
// `parallel_work_threshold` (the sum over element blocks of n_local^2, i.e. the
// size of the element tangents) the automatic choice is serial. Above it, it is
// the number of idle cores (hardware threads minus the 1-minute load average,
// rounded), at least 1 and at most max_automatic_threads: on a machine that
// other jobs keep busy a second thread gains nothing and only adds jitter.
// Results do not depend on the thread count (bitwise; sparse_pattern.hpp), so
// a load-dependent choice costs no reproducibility. Numbers behind the
// threshold: docs/performance.md "Threads" (scripts/bench_threads.py).
//
// Library threads: CHOLMOD in the Debian build uses OpenMP (libgomp) for a few
// loops, and libgomp's idle threads spin by default (OMP_WAIT_POLICY is read at
// program start). limit_library_threads() sets the calling thread's OpenMP team
// size to one, so those loops run inline and nothing spins. BLAS carries the
// dense work of a supernodal factorization (CHOLMOD, MUMPS): with a threaded
// OpenBLAS (scripts/setup.sh installs libopenblas0-pthread) set_blas_threads()
// gives it the cores the assembly would use -- one per rank under MPI, where the
// ranks already fill the cores. Our own code is not compiled with OpenMP, so
// Eigen never starts threads either.

#include <cstdint>

namespace iga::assembly {

/// Element-tangent entries per assembly below which threads do not pay.
inline constexpr std::int64_t parallel_work_threshold = 200'000;
/// Upper bound of the automatic thread count (the loop stops scaling past a few).
inline constexpr int max_automatic_threads = 4;

/// Threads for a loop of `work` element-tangent entries: `requested` when >= 1
/// (at most hardware_threads: more only cost memory, per thread of OpenBLAS too), else (0 = automatic) 1 below parallel_work_threshold, else
/// clamp(hardware_threads - round(load), 1, max_automatic_threads).
/// hardware_threads <= 0 means unknown (1); a negative or NaN load counts as 0.
int choose_threads(int requested, std::int64_t work, int hardware_threads, double load);

/// std::thread::hardware_concurrency(), or 1 when unknown.
int hardware_threads();

/// The 1-minute load average (getloadavg), or 0 when unknown.
double system_load();

/// OpenMP team size one for the libraries called from this thread (CHOLMOD); a
/// no-op without OpenMP.
void limit_library_threads();

/// Threads for the BLAS behind the sparse factorizations (at least 1). Returns
/// false when the BLAS has no such control (not OpenBLAS): it then runs as built.
bool set_blas_threads(int n);

}  // namespace iga::assembly
