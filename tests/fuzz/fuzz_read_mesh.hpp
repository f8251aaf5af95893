#pragma once
// The body every reader's libFuzzer target shares: read the bytes as one
// format. A geodual::Error is a correct answer to bad input; anything else --
// a crash, a sanitizer report, another exception type, a leak, a hang, a huge
// allocation -- is a bug the fuzzer reports.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace geodual::fuzz {

inline int read_mesh_bytes(const std::uint8_t* data, std::size_t size, io::MeshFormat format, const char* name) {
  try {
    io::read_mesh_from_memory(std::as_bytes(std::span(data, size)), format, name);
  } catch (const Error&) {
    // Rejected with a message: the expected outcome for most inputs.
  }
  return 0;
}

}  // namespace geodual::fuzz
