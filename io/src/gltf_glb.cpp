#include "gltf_glb.hpp"

#include "geodual/mesh/error.hpp"
#include "gltf_constants.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace geodual::io::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "GLB is little-endian; this code reads it in native order");

std::uint32_t load_u32(std::span<const std::byte> data, std::size_t offset) {
  std::uint32_t value = 0;
  std::memcpy(&value, data.data() + offset, sizeof value);
  return value;
}

std::string chunk_type_name(std::uint32_t type) {
  std::string name;
  for (int shift = 0; shift < 32; shift += 8) {
    const auto c = static_cast<unsigned char>((type >> shift) & 0xFF);
    name += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : '?';
  }
  return name;
}

[[noreturn]] void fail(std::string_view where, const std::string& what) {
  throw Error(std::string(where) + ": " + what);
}

}  // namespace

GlbChunks parse_glb(std::span<const std::byte> data, std::string_view where) {
  using namespace gltf;
  if (data.size() < glb_header_size) {
    fail(where, "truncated GLB: " + std::to_string(data.size()) + " bytes, shorter than the 12-byte header");
  }
  if (load_u32(data, 0) != glb_magic) {
    fail(where, "not a GLB file (the first 4 bytes are not 'glTF')");
  }
  if (const std::uint32_t version = load_u32(data, 4); version != glb_version) {
    fail(where, "unsupported GLB version " + std::to_string(version) + " (only glTF 2.0 is read)");
  }
  const std::uint32_t declared_length = load_u32(data, 8);
  if (declared_length > data.size()) {
    fail(where, "truncated GLB: the header declares " + std::to_string(declared_length) + " bytes but the data has " +
                    std::to_string(data.size()));
  }
  if (declared_length < data.size()) {
    fail(where, "GLB header declares " + std::to_string(declared_length) + " bytes but the data has " +
                    std::to_string(data.size()) + " (trailing bytes after the GLB)");
  }

  GlbChunks chunks;
  bool have_json = false;
  std::size_t offset = glb_header_size;
  for (int chunk = 0; offset < data.size(); ++chunk) {
    if (data.size() - offset < glb_chunk_header_size) {
      fail(where, "truncated GLB: chunk " + std::to_string(chunk) + " header at byte " + std::to_string(offset) +
                      " runs past the end");
    }
    const std::uint32_t length = load_u32(data, offset);
    const std::uint32_t type = load_u32(data, offset + 4);
    offset += glb_chunk_header_size;
    if (length > data.size() - offset) {
      fail(where, "truncated GLB: chunk " + std::to_string(chunk) + " ('" + chunk_type_name(type) + "') declares " +
                      std::to_string(length) + " bytes but only " + std::to_string(data.size() - offset) + " remain");
    }
    const std::span<const std::byte> payload = data.subspan(offset, length);
    offset += length;

    if (chunk == 0) {
      if (type != glb_chunk_json) {
        fail(where, "the first GLB chunk must be JSON, found '" + chunk_type_name(type) + "'");
      }
      chunks.json = payload;
      have_json = true;
    } else if (type == glb_chunk_json) {
      fail(where, "GLB has a second JSON chunk (chunk " + std::to_string(chunk) + ")");
    } else if (type == glb_chunk_bin) {
      if (chunk != 1) {
        fail(where, "the GLB BIN chunk must be the second chunk, found it as chunk " + std::to_string(chunk));
      }
      chunks.bin = payload;
    }
    // Chunks of other types are extensions' business: the spec says to skip them.
  }
  if (!have_json) fail(where, "GLB has no JSON chunk");
  return chunks;
}

}  // namespace geodual::io::detail
