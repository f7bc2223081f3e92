#pragma once
// The BLAS kernels the CPU allows, when OpenBLAS cannot tell.
//
// OpenBLAS (Debian's is built for every x86-64 CPU and picks its kernels at load
// time) chooses by the CPU model. A model it does not know, a newer Xeon or a
// virtual machine's CPUID (this project's machine reports family 6, model 207, to
// OpenBLAS 0.3.21), gets its oldest x86-64 kernels, Prescott (SSE3). The sparse
// Cholesky factorizations are dense matrix products underneath: on the 3D sphere
// octant the Prescott kernels made the linear solve 1.7x slower than the AVX-512
// ones (docs/performance.md, "BLAS kernels").
//
// OpenBLAS's documented remedy is the environment variable OPENBLAS_CORETYPE, read
// when the library loads, so before main(). use_cpu_blas_kernels() therefore starts
// the program again (execv of its own file, same arguments, same process) with
// OPENBLAS_CORETYPE set to the kernels the CPU's features allow: SkylakeX for
// AVX-512 (F, BW, DQ, VL), Haswell for AVX2 with FMA. It does nothing when the
// user set OPENBLAS_CORETYPE (also to keep OpenBLAS's choice: any value), when the
// BLAS is not OpenBLAS, or when OpenBLAS chose anything but its Prescott fallback.

#include <string>

namespace iga {

/// Call first thing in main(), before MPI starts; returns only when the program
/// keeps running as it is (nothing to do, or the restart failed).
void use_cpu_blas_kernels(char** argv);

/// OpenBLAS's kernel family ("SkylakeX", "Prescott", ...), or empty when the BLAS
/// is not OpenBLAS.
std::string blas_kernels();

}  // namespace iga
