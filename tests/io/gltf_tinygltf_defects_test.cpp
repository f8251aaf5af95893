// Defects of Debian's tinygltf 2.7 (libtinygltf-dev 2.7.0) that keep geodual's
// glTF reader on its own parser (io/src/gltf_reader.cpp). Each test passes
// while the defect is there: when one fails, tinygltf was fixed and the
// reader may hand that part to it.

#include "../../io/src/format_readers.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/mesh/error.hpp"
#include "gltf_test_bytes.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace geodual::io {
namespace {

std::vector<std::byte> triangle_glb() {
  GltfScene scene;
  scene.triangle_meshes.push_back(
      {.name = "t",
       .mesh = {.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, .faces = FaceMatrix{{0, 1, 2}}}});
  return encode_gltf(scene, GltfContainer::glb);
}

bool no_image_decoding(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                       void*) {
  return true;
}

TEST(GltfTinygltfDefects, BinChunkMayRunEightBytesPastTheData) {
  // The BIN chunk's length is raised by 8: its data now ends 8 bytes after the
  // file. tinygltf compares the chunk's length with what remains without its
  // 8-byte header, so it accepts the file and keeps a BIN span reaching past
  // the end of its input. The bytes sit inside a larger vector here so that
  // the over-read stays in memory this test owns.
  std::vector<std::byte> glb = triangle_glb();
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const std::size_t bin_header = 20 + json_length;
  std::uint32_t bin_length = 0;
  std::memcpy(&bin_length, glb.data() + bin_header, 4);
  bin_length += 8;
  std::memcpy(glb.data() + bin_header, &bin_length, 4);
  const std::size_t file_size = glb.size();
  glb.resize(file_size + 64);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(no_image_decoding, nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  const bool accepted = loader.LoadBinaryFromMemory(
      &model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()), static_cast<unsigned int>(file_size));
  EXPECT_TRUE(accepted) << err;

  // geodual's reader refuses it.
  EXPECT_THROW(detail::read_gltf(std::span(glb).first(file_size), true, "long.glb"), Error);
}

TEST(GltfTinygltfDefectsDeathTest, DeeplyNestedExtrasOverflowTheStack) {
  // Valid JSON: tinygltf converts extras to its Value type recursively, one
  // stack frame per level, and crashes; geodual's reader returns.
  const std::string deep =
      R"({"asset":{"version":"2.0"},"extras":)" + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_DEATH(
      {
        tinygltf::TinyGLTF loader;
        tinygltf::Model model;
        std::string err;
        std::string warn;
        loader.LoadASCIIFromString(&model, &err, &warn, deep.data(), static_cast<unsigned int>(deep.size()), "");
      },
      "");
  EXPECT_NO_THROW(detail::read_gltf(gltf_test::as_span(deep), false, "deep.gltf"));
}

}  // namespace
}  // namespace geodual::io
