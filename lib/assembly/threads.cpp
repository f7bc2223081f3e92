#include "assembly/threads.hpp"

#include <algorithm>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace iga::assembly {

int choose_threads(int requested, std::int64_t work, int hardware_threads)
{
    if (requested >= 1)
        return requested;
    if (work < parallel_work_threshold)
        return 1;
    return std::clamp(hardware_threads, 1, max_automatic_threads);
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

}  // namespace iga::assembly
