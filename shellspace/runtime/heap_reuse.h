// The C library's heap kept for reuse by a process that solves repeatedly.
// A Newton iteration allocates the same large buffers every time (per-slice
// Hessian blocks of a few MB, CHOLMOD's factor workspace); glibc serves
// every block above its mmap threshold (128 KB at first) with fresh pages
// and returns them on free, so each iteration faults them in and clears
// them again: on the cactus 10-ring problem (5k vertices, K = 8) a quarter
// of the CPU time went to page faults and memset. Raising the threshold to
// 32 MB (glibc's ceiling) and the trim threshold to 2 GB keeps blocks up to
// 32 MB in the heap once freed; larger ones (the x16 meshes' blocks) are
// still mapped and returned, so the peak of a large solve is unchanged.
#ifndef SHELLSPACE_RUNTIME_HEAP_REUSE_H_
#define SHELLSPACE_RUNTIME_HEAP_REUSE_H_

namespace shellspace {

// Sets the process's glibc malloc thresholds as above (a process-wide
// choice: the CLI's and the benchmarks' mains call it; a library caller,
// e.g. the Python module, leaves its host's allocator alone). Does nothing
// where the user set them (GLIBC_TUNABLES or MALLOC_MMAP_THRESHOLD_ /
// MALLOC_TRIM_THRESHOLD_ in the environment) or on another C library.
// Changes only memory reuse, never a result.
void KeepFreedHeapForReuse();

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_HEAP_REUSE_H_
