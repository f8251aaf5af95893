#include "gltf_meshopt_views.hpp"

#include "geodual/mesh/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>

namespace geodual::io::detail::gltf {
namespace {

using Json = nlohmann::json;  // sorted members, as tinygltf writes them

constexpr std::uint32_t json_chunk = 0x4E4F534A;  // "JSON"
constexpr std::size_t header_bytes = 12;
constexpr std::size_t chunk_header_bytes = 8;

std::uint32_t read_u32(const std::string& file, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, file.data() + at, 4);
  return value;
}

void put_u32(std::string& out, std::size_t value) {
  const auto v = static_cast<std::uint32_t>(value);
  out.append(reinterpret_cast<const char*>(&v), 4);
}

std::size_t padded(std::size_t n) { return (n + 3) / 4 * 4; }

void add_extensions(Json& root, std::span<const MeshoptView> views) {
  Json& buffer_views = root.at("bufferViews");
  const std::size_t fallback_buffer = root.at("buffers").size();
  std::size_t fallback_bytes = 0;
  for (const MeshoptView& entry : views) {
    Json& view = buffer_views.at(static_cast<std::size_t>(entry.view));
    Json extension = {{"buffer", view.at("buffer")},
                      {"byteLength", view.at("byteLength")},
                      {"byteOffset", view.value("byteOffset", std::uint64_t{0})},
                      {"byteStride", entry.byte_stride},
                      {"count", entry.count},
                      {"mode", entry.triangles ? "TRIANGLES" : "ATTRIBUTES"}};
    if (entry.filter != "NONE") extension["filter"] = entry.filter;
    view["extensions"]["EXT_meshopt_compression"] = std::move(extension);
    view["buffer"] = fallback_buffer;
    view["byteLength"] = entry.byte_stride * entry.count;
    if (fallback_bytes > 0) {
      view["byteOffset"] = fallback_bytes;
    } else {
      view.erase("byteOffset");
    }
    fallback_bytes = padded(fallback_bytes + entry.byte_stride * entry.count);
  }
  if (fallback_bytes == 0) return;
  root["buffers"].push_back(
      {{"byteLength", fallback_bytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
}

std::string dump(const Json& root) { return root.dump(-1, ' ', false, Json::error_handler_t::replace); }

}  // namespace

void add_meshopt_views(std::string& file, bool glb, std::span<const MeshoptView> views) {
  if (!glb) {
    Json root = Json::parse(file);
    add_extensions(root, views);
    file = dump(root);
    return;
  }
  // tinygltf's GLB: header, JSON chunk, BIN chunk (kept byte for byte).
  if (file.size() < header_bytes + chunk_header_bytes || read_u32(file, header_bytes + 4) != json_chunk) {
    throw Error("glTF output: tinygltf wrote an unexpected GLB layout");
  }
  const std::size_t json_length = read_u32(file, header_bytes);
  const std::size_t rest = header_bytes + chunk_header_bytes + json_length;
  Json root = Json::parse(file.substr(header_bytes + chunk_header_bytes, json_length));
  add_extensions(root, views);
  std::string text = dump(root);
  text.resize(padded(text.size()), ' ');
  std::string out = file.substr(0, 8);
  put_u32(out, header_bytes + chunk_header_bytes + text.size() + (file.size() - rest));
  put_u32(out, text.size());
  put_u32(out, json_chunk);
  out += text;
  out.append(file, rest, std::string::npos);
  file = std::move(out);
}

}  // namespace geodual::io::detail::gltf
