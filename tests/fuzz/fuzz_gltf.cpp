// libFuzzer target for the glTF reader: every input is read as GLB, and
// inputs that start like JSON also as .gltf. A geodual::Error is the correct
// answer to bad input; anything else (a crash, a sanitizer report, another
// exception type, a huge allocation, a hang) is a bug.
//
// The name is empty, so external buffers are refused and no input makes the
// reader open files.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace {

void read_as(std::span<const std::byte> bytes, geodual::io::MeshFormat format) {
  try {
    geodual::io::read_mesh_from_memory(bytes, format, {});
  } catch (const geodual::Error&) {
    // Rejected with a message.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = std::as_bytes(std::span(data, size));
  read_as(bytes, geodual::io::MeshFormat::glb);
  if (size > 0 && data[0] == '{') read_as(bytes, geodual::io::MeshFormat::gltf);
  return 0;
}
