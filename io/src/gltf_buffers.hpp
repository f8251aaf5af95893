#pragma once
// Internal: the buffers of a glTF file, loaded on first use so that buffers no
// triangle primitive needs (animations, images) are never read.
//
// A buffer comes from exactly one of:
//  - the GLB BIN chunk (buffer 0 of a GLB, without "uri");
//  - a base64 data URI ("data:<media type>;base64,<data>");
//  - an external file named by a relative URI, resolved against the folder of
//    the .gltf/.glb file. Absolute paths, URIs with a scheme (file:, http:),
//    and paths that leave that folder through ".." or, once resolved, through
//    a symbolic link are refused, so a file can only make geodual read files
//    inside its own folder (or below it). Data
//    read from memory without a file name may not have external buffers.
// Each buffer must hold at least its declared byteLength bytes; exactly
// byteLength bytes are kept.

#include "gltf_json.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

class BufferStore {
 public:
  /// `root` must outlive the store. `glb_bin` is the GLB BIN chunk, if any.
  /// `file` is the glTF file's path (empty: read from memory without a name).
  BufferStore(const Json& root, std::optional<std::span<const std::byte>> glb_bin, std::filesystem::path file,
              std::string where);

  std::size_t size() const { return loaded_.size(); }

  /// The byteLength bytes of buffer `index` (< size()).
  std::span<const std::byte> bytes(std::size_t index);

 private:
  std::span<const std::byte> load(std::size_t index);

  const Json& buffers_;
  std::optional<std::span<const std::byte>> glb_bin_;
  std::filesystem::path file_;
  std::string where_;
  std::vector<std::optional<std::span<const std::byte>>> loaded_;
  // Decoded data URIs and external files. The spans in loaded_ point into these
  // vectors' heap storage, which moving the vectors (on growth) keeps in place.
  std::vector<std::vector<std::byte>> owned_;
};

/// The file an external buffer URI names: percent-decoded and resolved against
/// the folder of `file`, symbolic links resolved; throws when the URI is
/// absolute, has a scheme or leads out of that folder.
std::filesystem::path resolve_relative_uri(std::string_view uri, const std::filesystem::path& file,
                                           std::string_view where);

/// Whether `uri` starts with "data:" (in any case).
bool is_data_uri(std::string_view uri);

/// The bytes of a base64 data URI ("data:<media type>;base64,<data>"); throws when it is not one.
std::vector<std::byte> decode_data_uri(std::string_view uri, std::string_view where);

/// The whole content of an external file (e.g. an image) that resolve_relative_uri
/// found; `what` names it in messages, e.g. "external image 'a.png'".
std::vector<std::byte> read_external_file(const std::filesystem::path& path, std::string_view what,
                                          std::string_view where);

}  // namespace geodual::io::detail::gltf
