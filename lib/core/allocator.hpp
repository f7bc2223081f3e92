#pragma once
// The C allocator as glibc sets it up, whatever a linked library changed.
//
// Debian's SuperLU_dist (linked through PETSc) turns off mmap in malloc and
// trimming of the heap from its load-time constructor (mallopt(M_MMAP_MAX, 0),
// mallopt(M_TRIM_THRESHOLD, -1)). Every tangent, factor and copy of a 3D model then
// comes from the brk heap and is never returned, so memory freed between Newton
// iterations stays resident and fragments: the 3D sphere octant (31.7k dofs)
// peaked at 1.21 GB of RSS for 1.02 GB of live heap. Measured and explained in
// docs/performance.md, "Memory in 3D".

namespace iga {

/// Large blocks (>= 4 MiB: matrices, factors, vectors past 500k dofs) from mmap,
/// so that freeing one returns it to the system; the heap trimmed again. Call first
/// thing in main(). A no-op where the C library is not glibc.
void restore_allocator_defaults();

}  // namespace iga
