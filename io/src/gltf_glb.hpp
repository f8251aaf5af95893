#pragma once
// Internal: reading the GLB container (glTF 2.0 binary): a 12-byte header, a JSON
// chunk, an optional BIN chunk, and possibly chunks of unknown types, which
// readers must skip.

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace geodual::io::detail {

struct GlbChunks {
  std::span<const std::byte> json;
  std::optional<std::span<const std::byte>> bin;  ///< absent when the file has no BIN chunk
};

/// Splits a GLB file into its chunks; the spans point into `data`. Any
/// structural problem throws geodual::Error("<where>: ...").
GlbChunks parse_glb(std::span<const std::byte> data, std::string_view where);

}  // namespace geodual::io::detail
