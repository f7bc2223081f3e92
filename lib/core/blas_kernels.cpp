#include "core/blas_kernels.hpp"

#include <cstddef>
#include <cstdlib>

#include <unistd.h>

// OpenBLAS's run-time query, present when the BLAS loaded is OpenBLAS (weak: null
// with another BLAS).
extern "C" char* openblas_get_corename() __attribute__((weak));

namespace iga {

namespace {

/// The kernels the CPU's features allow, or null when Prescott is all it has.
const char* kernels_for_this_cpu()
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
        return "SkylakeX";
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return "Haswell";
#endif
    return nullptr;
}

}  // namespace

std::string blas_kernels()
{
    const char* name = openblas_get_corename ? openblas_get_corename() : nullptr;
    return name ? std::string(name) : std::string();
}

void use_cpu_blas_kernels(char** argv)
{
    if (std::getenv("OPENBLAS_CORETYPE") != nullptr || blas_kernels() != "Prescott")
        return;
    const char* kernels = kernels_for_this_cpu();
    if (kernels == nullptr)
        return;
    // The program's own file, not /proc/self/exe: the process is named after the file
    // it runs (ps, top, pkill igacontact).
    char path[4096];
    const ssize_t length = readlink("/proc/self/exe", path, sizeof(path) - 1);
    if (length <= 0 || static_cast<std::size_t>(length) >= sizeof(path) - 1)
        return;
    path[length] = '\0';
    // The variable stays set if the restart fails: then this process runs on as it is.
    if (setenv("OPENBLAS_CORETYPE", kernels, 1) != 0)
        return;
    execv(path, argv);
}

}  // namespace iga
