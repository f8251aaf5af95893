// pipeline::keep_freed_memory_in_heap: a large array freed and allocated
// again reuses the heap's pages instead of faulting fresh ones in.

#include "geodual/pipeline/heap.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <memory>

#include <sys/resource.h>

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace geodual {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

/// The page faults of allocating `bytes`, writing every byte, and freeing them.
long faults_of_a_written_array(std::size_t bytes) {
  const long before = minor_faults();
  {
    const std::unique_ptr<char[]> array(new char[bytes]);
    std::memset(array.get(), 1, bytes);
    // The compiler may not drop the writes: read one back.
    EXPECT_EQ(array[bytes / 2], 1);
  }
  return minor_faults() - before;
}

#if defined(M_MMAP_THRESHOLD)  // glibc's malloc
TEST(KeepFreedMemoryInHeap, AnArrayAllocatedAgainReusesThePagesOfTheFreedOne) {
  constexpr std::size_t kBytes = std::size_t{96} << 20;  // above glibc's largest adaptive mmap threshold
  constexpr long kPages = static_cast<long>(kBytes / 4096);
  // By default such an array is mapped and unmapped: every page faults in each time.
  EXPECT_GT(faults_of_a_written_array(kBytes), kPages / 2);
  EXPECT_GT(faults_of_a_written_array(kBytes), kPages / 2);
  pipeline::keep_freed_memory_in_heap();
  faults_of_a_written_array(kBytes);  // the heap grows once
  EXPECT_LT(faults_of_a_written_array(kBytes), kPages / 20);
}
#endif

}  // namespace
}  // namespace geodual
