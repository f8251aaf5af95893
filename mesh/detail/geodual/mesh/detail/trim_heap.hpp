#pragma once
// Giving freed heap memory back to the operating system between stages, so
// that a stage's temporaries do not stay resident beside the next stage's
// data (peak memory is what users of large scans run out of).
//
// glibc's malloc serves arrays below its (adaptive, up to 32 MB) mmap
// threshold from the heap, and keeps what they free there: a stage's
// temporaries then stay resident while the next stage maps new memory (the
// window pages) beside them. malloc_trim releases every whole free page of
// the heap, wherever it lies. Pages given back cost a page fault each when
// the heap grows again, so a heap with little free memory is left as it is:
// on small meshes the next stage reuses it (and see
// pipeline::keep_freed_memory_in_heap).

#include <cstddef>

// <malloc.h> first: it defines __GLIBC__ (through <features.h>) whatever was
// included before this header.
#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace geodual {

/// Free heap memory below this stays with the allocator (trim_heap).
inline constexpr std::size_t kHeapKeptBytes = std::size_t{32} << 20;

/// Returns the heap's free pages to the system (glibc) once they add up to
/// kHeapKeptBytes or more; elsewhere nothing.
inline void trim_heap() {
#if defined(__GLIBC__)
  if (mallinfo2().fordblks >= kHeapKeptBytes) malloc_trim(0);
#endif
}

}  // namespace geodual
