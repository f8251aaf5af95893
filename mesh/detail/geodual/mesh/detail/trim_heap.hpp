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
// on small meshes the next stage reuses it.

#include <cstddef>

#if defined(__GLIBC__)
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

/// For a program whose work is geodual's (the command line tool, the
/// benchmarks), at its start: glibc's malloc keeps freed arrays of up to
/// 256 MB in the heap, instead of mapping each anew (above its adaptive mmap
/// threshold) and trimming the heap's free top at once. Each geodesic
/// diagram allocates and frees such arrays, whose pages would otherwise
/// fault in again for the next. Process-wide, so the library never calls it;
/// trim_heap still gives a large free heap back between stages.
inline void keep_freed_memory_in_heap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace geodual
