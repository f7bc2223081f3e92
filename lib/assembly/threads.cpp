#include "assembly/threads.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

// OpenBLAS's run-time control, present when the BLAS loaded is OpenBLAS (weak:
// null with another BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace iga::assembly {

int choose_threads(int requested, std::int64_t work, int hardware_threads, double load)
{
    if (requested >= 1)  // the user's call on a loaded machine, but never more than it has:
        return std::min(requested, std::max(1, hardware_threads));  // each thread costs memory, and the libraries' threads fail to start
    if (work < parallel_work_threshold)
        return 1;
    const int busy = load > 0.0 ? static_cast<int>(std::lround(std::min(load, 1e6))) : 0;  // !(NaN > 0)
    return std::clamp(hardware_threads - busy, 1, max_automatic_threads);
}

double system_load()
{
    double load[1] = {0.0};
    return getloadavg(load, 1) == 1 ? load[0] : 0.0;
}

int hardware_threads()
{
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void limit_library_threads()
{
#ifdef _OPENMP
    omp_set_num_threads(1);
    omp_set_dynamic(0);
#endif
}

bool set_blas_threads(int n)
{
    if (openblas_set_num_threads == nullptr)
        return false;
    openblas_set_num_threads(std::max(1, n));
    return true;
}

}  // namespace iga::assembly
