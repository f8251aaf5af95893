#include "geodual/pipeline/heap.hpp"

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace geodual::pipeline {

void keep_freed_memory_in_heap() {
#if defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)  // glibc's
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace geodual::pipeline
