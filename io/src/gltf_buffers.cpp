#include "gltf_buffers.hpp"

#include "gltf_base64.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>
#include <utility>

namespace geodual::io::detail::gltf {
namespace fs = std::filesystem;
namespace {

bool starts_with_ignoring_case(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(text[i]) != lower(prefix[i])) return false;
  }
  return true;
}

// RFC 3986 scheme: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
bool has_scheme(std::string_view uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  const auto is_alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!is_alpha(uri[0])) return false;
  for (const char c : uri.substr(1, colon - 1)) {
    if (!is_alpha(c) && !(c >= '0' && c <= '9') && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

std::optional<std::string> percent_decode(std::string_view text) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size() || hex(text[i + 1]) < 0 || hex(text[i + 2]) < 0) return std::nullopt;
    out += static_cast<char>(hex(text[i + 1]) * 16 + hex(text[i + 2]));
    i += 2;
  }
  return out;
}

std::string shortened(std::string_view uri) {
  constexpr std::size_t max_length = 80;
  return uri.size() <= max_length ? std::string(uri) : std::string(uri.substr(0, max_length)) + "...";
}

std::vector<std::byte> read_file_prefix(const fs::path& path, std::uint64_t length, std::string_view uri,
                                        std::string_view where) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    fail(where, "external buffer file '" + shortened(uri) + "' not found (looked for '" + path.string() + "')");
  }
  if (!fs::is_regular_file(status)) {
    fail(where, "external buffer '" + path.string() + "' is not a regular file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(where, "cannot read external buffer '" + path.string() + "': " + ec.message());
  if (size < length) {
    fail(where, "external buffer '" + path.string() + "' has " + std::to_string(size) +
                    " bytes, fewer than the declared byteLength " + std::to_string(length));
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<std::byte> data(static_cast<std::size_t>(length));
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(length));
  if (!in) fail(where, "cannot read external buffer '" + path.string() + "'");
  return data;
}

}  // namespace

bool is_data_uri(std::string_view uri) { return starts_with_ignoring_case(uri, "data:"); }

std::vector<std::byte> decode_data_uri(std::string_view uri, std::string_view where) {
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) fail(where, "data URI has no ',' before its data");
  const std::string_view header = uri.substr(0, comma);
  constexpr std::string_view base64_marker = ";base64";
  if (header.size() < base64_marker.size() ||
      !starts_with_ignoring_case(header.substr(header.size() - base64_marker.size()), base64_marker)) {
    fail(where, "data URI '" + shortened(header) + "' is not base64-encoded (expected ';base64,')");
  }
  std::optional<std::vector<std::byte>> data = decode_base64(uri.substr(comma + 1));
  if (!data) fail(where, "data URI holds invalid base64");
  return std::move(*data);
}

std::vector<std::byte> read_external_file(const fs::path& path, std::string_view what, std::string_view where) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(where, std::string(what) + " not found (looked for '" + path.string() + "')");
  if (!fs::is_regular_file(status)) fail(where, std::string(what) + " '" + path.string() + "' is not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(where, "cannot read " + std::string(what) + " '" + path.string() + "': " + ec.message());
  std::ifstream in(path, std::ios::binary);
  std::vector<std::byte> data(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(size));
  if (!in) fail(where, "cannot read " + std::string(what) + " '" + path.string() + "'");
  return data;
}

fs::path resolve_relative_uri(std::string_view uri, const fs::path& file, std::string_view where) {
  if (has_scheme(uri)) {
    fail(where,
         "URI '" + shortened(uri) + "' is not a relative file reference (only data: URIs and relative paths are read)");
  }
  const std::optional<std::string> decoded = percent_decode(uri);
  if (!decoded) fail(where, "URI '" + shortened(uri) + "' has an invalid %-escape");
  if (decoded->empty() || decoded->find('\0') != std::string::npos) {
    fail(where, "URI '" + shortened(uri) + "' does not name a file");
  }
  const fs::path relative = fs::path(*decoded).lexically_normal();
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory()) {
    fail(where, "URI '" + shortened(uri) + "' is an absolute path; glTF buffers must be relative to the glTF file");
  }
  if (!relative.empty() && *relative.begin() == "..") {
    fail(where, "URI '" + shortened(uri) + "' leaves the glTF file's folder; refusing to read it");
  }
  if (file.empty()) {
    fail(where, "external buffer '" + shortened(uri) +
                    "' cannot be resolved: the glTF data was read from memory without a file name");
  }
  // Symbolic links can still lead out: compare the resolved paths.
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(file.parent_path().empty() ? fs::path(".") : file.parent_path(), ec);
  const fs::path target = ec ? fs::path() : fs::weakly_canonical(folder / relative, ec);
  if (ec) fail(where, "cannot resolve URI '" + shortened(uri) + "': " + ec.message());
  const auto [folder_end, target_end] = std::mismatch(folder.begin(), folder.end(), target.begin(), target.end());
  if (folder_end != folder.end()) {
    fail(where, "URI '" + shortened(uri) + "' resolves through a symbolic link to '" + target.string() +
                    "', outside the glTF file's folder; refusing to read it");
  }
  return target;
}

BufferStore::BufferStore(const Json& root, std::optional<std::span<const std::byte>> glb_bin, fs::path file,
                         std::string where)
    : buffers_(array_member(root, "buffers", where)),
      glb_bin_(glb_bin),
      file_(std::move(file)),
      where_(std::move(where)),
      loaded_(buffers_.size()) {}

std::span<const std::byte> BufferStore::bytes(std::size_t index) {
  if (!loaded_.at(index)) loaded_[index] = load(index);
  return *loaded_[index];
}

std::span<const std::byte> BufferStore::load(std::size_t index) {
  const Json& buffer = buffers_[index];
  const std::string where = where_ + ": " + describe("buffer", index, buffer);
  if (!buffer.is_object()) fail(where, "must be a JSON object");
  const std::uint64_t length = required_uint(buffer, "byteLength", where);
  if (length == 0) fail(where, "'byteLength' must be at least 1");
  const std::optional<std::string> uri = optional_string(buffer, "uri", where);

  if (!uri) {
    if (index != 0 || !glb_bin_) {
      fail(where, glb_bin_ ? "has no 'uri'; only buffer 0 can refer to the GLB BIN chunk"
                           : "has no 'uri' and there is no GLB BIN chunk to refer to");
    }
    if (length > glb_bin_->size()) {
      fail(where, "'byteLength' " + std::to_string(length) + " exceeds the GLB BIN chunk (" +
                      std::to_string(glb_bin_->size()) + " bytes)");
    }
    return glb_bin_->first(static_cast<std::size_t>(length));
  }

  std::vector<std::byte> data;
  if (is_data_uri(*uri)) {
    data = decode_data_uri(*uri, where);
    if (data.size() < length) {
      fail(where, "data URI holds " + std::to_string(data.size()) + " bytes, fewer than the declared byteLength " +
                      std::to_string(length));
    }
    data.resize(static_cast<std::size_t>(length));
  } else {
    data = read_file_prefix(resolve_relative_uri(*uri, file_, where), length, *uri, where);
  }
  owned_.push_back(std::move(data));
  return owned_.back();
}

}  // namespace geodual::io::detail::gltf
