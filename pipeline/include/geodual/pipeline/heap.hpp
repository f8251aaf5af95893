#pragma once
// How a program whose work is geodual's can let the allocator keep what
// each geodesic diagram frees, for the next (docs/library.md#memory).

namespace geodual::pipeline {

/// Sets glibc's malloc (process-wide; elsewhere nothing) to keep freed
/// blocks of up to 256 MB in the heap, instead of mapping each such array
/// anew and trimming the heap's free top at once: each geodesic diagram
/// allocates and frees arrays of tens of MB, whose pages would otherwise
/// fault in again for the next (docs/library.md#memory). The library still
/// hands a free heap of 32 MB or more back between stages.
/// The command line tool calls it at its start; the library never does.
void keep_freed_memory_in_heap();

}  // namespace geodual::pipeline
