#include "core/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace iga {

void restore_allocator_defaults()
{
#if defined(__GLIBC__)
    // glibc's defaults (mallopt(3)): up to 65536 mmapped blocks, trim above 128 KiB.
    // The threshold is fixed at 4 MiB rather than left to glibc's dynamic rule, which
    // setting M_TRIM_THRESHOLD turns off (it would otherwise stay at 128 KiB, and every
    // small vector would cost an mmap).
    mallopt(M_MMAP_MAX, 65536);
    mallopt(M_TRIM_THRESHOLD, 128 * 1024);
    mallopt(M_MMAP_THRESHOLD, 4 * 1024 * 1024);
#endif
}

}  // namespace iga
