// The C library's heap kept for reuse, and backed by huge pages, in a
// process that solves repeatedly.
// A Newton iteration allocates the same large buffers every time (per-slice
// Hessian blocks of a few MB, the factorisation's buffers); glibc serves
// every block above its mmap threshold (128 KB at first) with fresh pages
// and returns them on free, so each iteration faults them in and clears
// them again: on the cactus 10-ring problem (5k vertices, K = 8) a quarter
// of the CPU time went to page faults and memset. Raising the threshold to
// 32 MB (glibc's ceiling) and the trim threshold to 2 GB keeps blocks up to
// 32 MB in the heap once freed; larger ones (the x16 meshes' blocks) are
// still mapped and returned, so the peak of a large solve is unchanged.
// The first touch of the heap's pages still costs a fault per 4 KB page
// (about 56,000 on that problem, the peak's worth; each costs microseconds
// in a virtual machine). Where the kernel gives transparent huge pages on
// request (/sys/kernel/mm/transparent_hugepage/enabled: madvise or always)
// the heap's next quarter of the physical memory (at most 1 GB, address
// space only) is reserved at once and marked for them (MADV_HUGEPAGE): a
// fault then brings 2 MB. On that problem, 1,600 faults instead of 56,000
// and 12 % less CPU time; the peak resident memory grows by at most one
// partly used 2 MB page per heap region.
#ifndef SHELLSPACE_RUNTIME_HEAP_REUSE_H_
#define SHELLSPACE_RUNTIME_HEAP_REUSE_H_

#include <cstddef>
#include <cstdint>

namespace shellspace {

// Sets the process's glibc malloc thresholds and reserves the huge-page
// heap as above (a process-wide choice: the CLI's and the benchmarks' mains
// call it first thing; a library caller, e.g. the Python module, leaves its
// host's allocator alone). Does nothing where the user set them
// (GLIBC_TUNABLES naming glibc.malloc, or MALLOC_MMAP_THRESHOLD_,
// MALLOC_TRIM_THRESHOLD_ or MALLOC_TOP_PAD_ in the environment) or on
// another C library, and on a second call. Changes only memory reuse,
// never a result.
void KeepFreedHeapForReuse();

// The whole 2 MB pages inside [address, address + bytes): [*first, *last)
// with *first the first 2 MB boundary at or after address and *last the
// last at or before its end; false (and nothing set) if there is none.
bool WholeHugePagesIn(std::uintptr_t address, std::size_t bytes,
                      std::uintptr_t* first, std::uintptr_t* last);

// std::malloc(bytes) (free it with std::free; std::realloc may resize it),
// with the whole 2 MB pages inside the block marked for transparent huge
// pages (MADV_HUGEPAGE) before anything touches them, for a block of 32 MB
// or more. Beyond the reserved heap of KeepFreedHeapForReuse (or without
// it) glibc maps such blocks afresh at every allocation, so each first
// touch faults: a supernodal factor's buffer (546 MB a slice on the cactus
// x16 problem, 84k vertices, K = 8) then costs 140,000 faults of 4 KB
// instead of 270 of 2 MB: on that problem 3.29M page faults become 1.76M,
// system time 31.7 s becomes 20.2 s and wall time 107 s becomes 91 s. On a
// kernel without transparent huge pages, or another C library, plain
// std::malloc. Never changes a result.
void* MallocOnHugePages(std::size_t bytes);

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_HEAP_REUSE_H_
