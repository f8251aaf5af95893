#pragma once
// Giving freed heap memory back to the operating system between stages, so
// that a stage's temporaries do not stay resident beside the next stage's
// data (peak memory is what users of large scans run out of).
//
// glibc's malloc serves arrays below its (adaptive, up to 32 MB) mmap
// threshold from the heap, and keeps what they free there: a stage's
// temporaries then stay resident while the next stage maps new memory (the
// window pages) beside them. malloc_trim releases every whole free page of
// the heap, wherever it lies.

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace geodual {

/// Returns the heap's free pages to the system (glibc); elsewhere nothing.
inline void trim_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace geodual
