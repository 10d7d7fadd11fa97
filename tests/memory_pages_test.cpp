// populate_pages (core/memory_pages.h): fresh pages mapped before they are written.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <vector>

#include "core/memory_pages.h"

namespace tessera {
namespace {

// Resident pages of this process (/proc/self/statm, second field).
long resident_pages() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident;
}

TEST(MemoryPages, PopulatedPagesAreResidentBeforeTheyAreWritten) {
  const size_t bytes = size_t(64) << 20;
  std::vector<uint8_t> v;
  v.reserve(bytes);  // fresh memory from mmap (far over glibc's threshold), not yet touched
  const long before = resident_pages();
  if (!populate_pages(v.data(), bytes)) GTEST_SKIP() << "the kernel lacks MADV_POPULATE_WRITE";
  const long page = ::sysconf(_SC_PAGESIZE);
  // All but the partial pages at either end; other threads (Vulkan's, GoogleTest's) can only add.
  EXPECT_GE((resident_pages() - before) * page, long(bytes) - 2 * page);
  // The pages hold what is written to them, as any others.
  v.resize(bytes, 7);
  EXPECT_EQ(v[0], 7);
  EXPECT_EQ(v[bytes - 1], 7);
}

TEST(MemoryPages, SmallRangesAreLeftAlone) {
  std::vector<uint8_t> v(4096);
  EXPECT_FALSE(populate_pages(v.data(), v.size()));
  EXPECT_FALSE(populate_pages(nullptr, 0));
}

}  // namespace
}  // namespace tessera
