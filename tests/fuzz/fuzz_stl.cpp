// libFuzzer target for the STL reader (see fuzz_read_mesh.hpp and the README).

#include "fuzz_read_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return geodual::fuzz::read_mesh_bytes(data, size, geodual::io::MeshFormat::stl, "fuzz.stl");
}
