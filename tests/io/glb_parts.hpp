#pragma once
// A GLB file split into its JSON document and binary chunk, checking the
// container's rules on the way: shared by the glTF writing tests.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace geodual::io::gltf_test {

/// The little-endian uint32 at `offset` of `data`.
inline std::uint32_t u32_at(const std::vector<std::byte>& data, std::size_t offset) {
  std::uint32_t value = 0;
  std::memcpy(&value, data.data() + offset, sizeof value);
  return value;
}

struct Glb {
  nlohmann::json document;
  std::vector<std::byte> bin;
};

// Splits a GLB as a reader would, checking the container rules on the way.
inline Glb split_glb(const std::vector<std::byte>& glb) {
  Glb out;
  EXPECT_GE(glb.size(), 28u);
  EXPECT_EQ(std::memcmp(glb.data(), "glTF", 4), 0);
  EXPECT_EQ(u32_at(glb, 4), 2u);
  EXPECT_EQ(u32_at(glb, 8), glb.size());
  const std::uint32_t json_length = u32_at(glb, 12);
  EXPECT_EQ(u32_at(glb, 16), 0x4E4F534Au);  // "JSON"
  EXPECT_EQ(json_length % 4, 0u);
  const auto* text = reinterpret_cast<const char*>(glb.data() + 20);
  out.document = nlohmann::json::parse(text, text + json_length);  // trailing padding spaces are JSON whitespace
  const std::size_t bin_header = 20 + json_length;
  EXPECT_EQ(bin_header % 4, 0u);
  const std::uint32_t bin_length = u32_at(glb, bin_header);
  EXPECT_EQ(u32_at(glb, bin_header + 4), 0x004E4942u);  // "BIN\0"
  EXPECT_EQ(bin_length % 4, 0u);
  EXPECT_EQ(bin_header + 8 + bin_length, glb.size());
  out.bin.assign(glb.begin() + static_cast<std::ptrdiff_t>(bin_header + 8), glb.end());
  return out;
}

}  // namespace geodual::io::gltf_test
