// KeepFreedHeapForReuse: blocks below the raised mmap threshold come from
// the heap, a freed one is handed out again, and where the kernel gives
// transparent huge pages on request they lie in a range advised for them
// (the "hg" flag of /proc/self/smaps).
#include "shellspace/runtime/heap_reuse.h"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace shellspace {
namespace {

// The name (e.g. "[heap]") and the VmFlags of the mapping that contains
// `address`, from /proc/self/smaps; empty strings if none does.
struct Mapping {
  std::string name, flags;
};
Mapping MappingOf(const void* address) {
  const uintptr_t a = reinterpret_cast<uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  Mapping found;
  while (std::getline(smaps, line)) {
    uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= a && a < end;
      if (inside) {
        std::string field;
        for (int i = 0; i < 4 && header >> field; ++i) {
        }  // permissions, offset, device, inode
        found.name.clear();
        header >> found.name;
      }
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      found.flags = line.substr(8);
      return found;
    }
  }
  return Mapping();
}

bool HasFlag(const Mapping& m, const std::string& flag) {
  std::istringstream flags(m.flags);
  std::string f;
  while (flags >> f) {
    if (f == flag) return true;
  }
  return false;
}

bool UserTunedMalloc() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return (tunables != nullptr &&
          std::string(tunables).find("glibc.malloc") != std::string::npos) ||
         std::getenv("MALLOC_MMAP_THRESHOLD_") != nullptr ||
         std::getenv("MALLOC_TRIM_THRESHOLD_") != nullptr ||
         std::getenv("MALLOC_TOP_PAD_") != nullptr;
}

bool KernelGivesHugePagesOnRequest() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(in, modes);
  return modes.find("[madvise]") != std::string::npos ||
         modes.find("[always]") != std::string::npos;
}

TEST(HeapReuseTest, LargeBlocksComeFromTheHeapAndAreReused) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "glibc only";
#endif
  if (UserTunedMalloc()) GTEST_SKIP() << "malloc tuned in the environment";
  KeepFreedHeapForReuse();
  // 8 MB: above glibc's default mmap threshold (128 KB), below the raised one.
  const size_t size = size_t{8} << 20;
  void* first = std::malloc(size);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(MappingOf(first).name, "[heap]");
  std::free(first);
  void* second = std::malloc(size);
  EXPECT_EQ(second, first);  // the freed block, not fresh pages
  std::free(second);
}

TEST(HeapReuseTest, HeapBlocksLieInAHugePageRange) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "glibc only";
#endif
  if (UserTunedMalloc()) GTEST_SKIP() << "malloc tuned in the environment";
  if (!KernelGivesHugePagesOnRequest()) {
    GTEST_SKIP() << "transparent huge pages off in this kernel";
  }
  KeepFreedHeapForReuse();
  // (The reserved range starts at the first 2 MB boundary above the heap's
  // end at the call, so a block may begin just below it: its middle is
  // inside.)
  const size_t size = size_t{8} << 20;
  char* block = static_cast<char*>(std::malloc(size));
  ASSERT_NE(block, nullptr);
  EXPECT_TRUE(HasFlag(MappingOf(block + size / 2), "hg"));
  std::free(block);
  // The twin: a mapping nobody advised has no "hg", and the same check
  // says so.
  void* plain = mmap(nullptr, size, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(plain, MAP_FAILED);
  const Mapping m = MappingOf(plain);
  EXPECT_FALSE(m.flags.empty());
  EXPECT_FALSE(HasFlag(m, "hg"));
  munmap(plain, size);
}

TEST(HeapReuseTest, WholeHugePagesInABlock) {
  const std::uintptr_t mb2 = std::uintptr_t{2} << 20;
  std::uintptr_t first = 0, last = 0;
  // [21, 28) MB: the whole pages [22, 28) MB; [21, 22) is partial.
  ASSERT_TRUE(
      WholeHugePagesIn(10 * mb2 + mb2 / 2, 7 * (mb2 / 2), &first, &last));
  EXPECT_EQ(first, 11 * mb2);
  EXPECT_EQ(last, 14 * mb2);
  // Aligned at both ends: all of it.
  ASSERT_TRUE(WholeHugePagesIn(4 * mb2, 3 * mb2, &first, &last));
  EXPECT_EQ(first, 4 * mb2);
  EXPECT_EQ(last, 7 * mb2);
  // [1, 4) MB holds one whole page, [2, 4); [1.5, 3.5) MB none.
  ASSERT_TRUE(WholeHugePagesIn(mb2 / 2, 3 * (mb2 / 2), &first, &last));
  EXPECT_EQ(first, mb2);
  EXPECT_EQ(last, 2 * mb2);
  first = last = 7;
  EXPECT_FALSE(WholeHugePagesIn(3 * (mb2 / 4), mb2, &first, &last));
  EXPECT_EQ(first, 7u);  // untouched
  EXPECT_FALSE(WholeHugePagesIn(UINTPTR_MAX - mb2, 2 * mb2, &first, &last));
}

TEST(HeapReuseTest, LargeBlocksAreAdvisedForHugePages) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "glibc only";
#endif
  if (!KernelGivesHugePagesOnRequest()) {
    GTEST_SKIP() << "transparent huge pages off in this kernel";
  }
  // 64 MB: above glibc's mmap threshold (a fresh mapping, or the huge-page
  // heap if an earlier test reserved it); either way its middle is advised.
  const size_t size = size_t{64} << 20;
  char* block = static_cast<char*>(MallocOnHugePages(size));
  ASSERT_NE(block, nullptr);
  EXPECT_TRUE(HasFlag(MappingOf(block + size / 2), "hg"));
  block[0] = block[size - 1] = 1;  // usable to its ends
  char* grown = static_cast<char*>(std::realloc(block, size / 2));
  ASSERT_NE(grown, nullptr);
  EXPECT_EQ(grown[0], 1);
  std::free(grown);
  // The twin: a fresh mapping of that size, as glibc makes for a block it
  // does not take from the heap, is not advised, and the same check says so.
  void* plain = mmap(nullptr, size, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(plain, MAP_FAILED);
  EXPECT_FALSE(HasFlag(MappingOf(static_cast<char*>(plain) + size / 2), "hg"));
  munmap(plain, size);
}

}  // namespace
}  // namespace shellspace
