#include "shellspace/runtime/heap_reuse.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace shellspace {

namespace {

#if defined(__GLIBC__)
// Reserves the heap's next `bytes` of address space in one extension of
// the main arena (glibc's top pad: virtual only, no page is touched) and
// asks the kernel to back that range with transparent huge pages. The
// reservation stays (the trim threshold is at its maximum), so every later
// allocation from the main arena inside it gets huge pages. False if the
// heap did not grow (e.g. no room for it: glibc then maps its blocks, and
// nothing changes).
bool ReserveHugePageHeap(size_t bytes) {
  mallopt(M_TOP_PAD, static_cast<int>(bytes));
  char* const before = static_cast<char*>(sbrk(0));
  // Larger than any free block of the young heap, below the mmap threshold:
  // served by extending the heap, by itself plus the top pad.
  void* const probe = std::malloc(size_t{4} << 20);
  char* const after = static_cast<char*>(sbrk(0));
  std::free(probe);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default again
  std::uintptr_t from = 0, to = 0;
  if (probe == nullptr || after <= before ||
      !WholeHugePagesIn(reinterpret_cast<std::uintptr_t>(before),
                        static_cast<std::size_t>(after - before), &from, &to)) {
    return false;
  }
  return madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE) == 0;
}
#endif

}  // namespace

void KeepFreedHeapForReuse() {
#if defined(__GLIBC__)
  static std::atomic<bool> done{false};  // once per process
  if (done.exchange(true)) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if ((tunables != nullptr &&
       std::strstr(tunables, "glibc.malloc") != nullptr) ||
      std::getenv("MALLOC_MMAP_THRESHOLD_") != nullptr ||
      std::getenv("MALLOC_TRIM_THRESHOLD_") != nullptr ||
      std::getenv("MALLOC_TOP_PAD_") != nullptr) {
    return;
  }
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  // A quarter of the physical memory, at most 1 GB, at least 64 MB.
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const double physical =
      pages > 0 && page > 0 ? static_cast<double>(pages) * page : 0;
  const double reserve =
      std::min(double{1 << 30}, std::max(double{64 << 20}, physical / 4));
  ReserveHugePageHeap(static_cast<size_t>(reserve));
#endif
}

bool WholeHugePagesIn(std::uintptr_t address, std::size_t bytes,
                      std::uintptr_t* first, std::uintptr_t* last) {
  const std::uintptr_t huge = std::uintptr_t{2} << 20;
  if (address > UINTPTR_MAX - bytes) return false;  // wraps: not a block
  const std::uintptr_t end = address + bytes;
  if (address > UINTPTR_MAX - (huge - 1)) return false;
  const std::uintptr_t from = (address + huge - 1) & ~(huge - 1);
  const std::uintptr_t to = end & ~(huge - 1);
  if (to <= from) return false;
  *first = from;
  *last = to;
  return true;
}

void* MallocOnHugePages(std::size_t bytes) {
  void* const block = std::malloc(bytes);
#if defined(__GLIBC__)
  std::uintptr_t first = 0, last = 0;
  if (block != nullptr && bytes >= (std::size_t{32} << 20) &&
      WholeHugePagesIn(reinterpret_cast<std::uintptr_t>(block), bytes, &first,
                       &last)) {
    // Advice only: where the kernel declines, the block is ordinary memory.
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#endif
  return block;
}

}  // namespace shellspace
