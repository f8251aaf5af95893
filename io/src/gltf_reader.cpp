// glTF 2.0 reading (.gltf and .glb) into one TriangleMesh: the container
// (GLB or JSON, decided by the content), the asset and extension checks, then
// the scene (gltf_scene_graph.hpp) and its triangles (gltf_mesh_assembler.hpp):
// every triangle primitive of every mesh the chosen scene shows, with its
// node's world transform applied; a mesh shown by two nodes appears twice.
//
// The JSON is parsed here with nlohmann::json rather than by tinygltf, which
// writes geodual's glTF: Debian's tinygltf 2.7 lets a GLB BIN chunk run 8 bytes
// past the end of its input and overflows the stack on deeply nested extras
// (both shown by tests/io/gltf_tinygltf_defects_test.cpp); it also looks for
// external files in the current directory, requires an external buffer to be
// exactly byteLength long, decodes every image, and names no element in its
// errors. This reader loads nothing but the buffers that the triangle
// primitives use (see gltf_buffers.hpp) and decodes only the images that
// give their vertices colour (gltf_texture.hpp).
//
// Besides positions and triangles it reads the vertices' colours (the base
// colour: factor x texture x COLOR_0), normals and "_NAME" scalars into
// LoadedMesh::attributes (gltf_attributes.hpp).

#include "format_readers.hpp"

#include "geodual/mesh/error.hpp"
#include "gltf_buffers.hpp"
#include "gltf_glb.hpp"
#include "gltf_json.hpp"
#include "gltf_mesh_assembler.hpp"
#include "gltf_scene_graph.hpp"
#include "gltf_texture.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <utility>

namespace geodual::io::detail {
namespace {

using gltf::fail;
using gltf::Json;

constexpr std::string_view memory_name = "<memory>";

constexpr std::string_view utf8_bom = "\xEF\xBB\xBF";

bool starts_with_glb_magic(std::span<const std::byte> data) {
  return data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
}

// Whether the first character after an optional byte order mark and white space is '{'.
bool looks_like_json(std::span<const std::byte> data) {
  std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  if (text.starts_with(utf8_bom)) text.remove_prefix(utf8_bom.size());
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && text[first] == '{';
}

Json parse_json(std::span<const std::byte> text, const std::string& where) {
  const char* begin = reinterpret_cast<const char*>(text.data());
  const char* end = begin + text.size();
  if (std::string_view(begin, text.size()).starts_with(utf8_bom)) begin += utf8_bom.size();
  try {
    return Json::parse(begin, end);
  } catch (const Json::parse_error& e) {
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix.
    std::string detail = e.what();
    if (const std::size_t close = detail.find("] ");
        !detail.empty() && detail[0] == '[' && close != std::string::npos) {
      detail.erase(0, close + 2);
    }
    constexpr std::size_t max_detail = 200;  // "last read" can quote a long token
    if (detail.size() > max_detail) detail = detail.substr(0, max_detail) + "...";
    fail(where, "not a glTF file: invalid JSON: " + detail);
  }
}

void check_asset(const Json& root, const std::string& where) {
  if (!root.is_object()) fail(where, "not a glTF file: the JSON is not an object");
  const Json* asset = gltf::optional_object(root, "asset", where);
  if (asset == nullptr) fail(where, "not a glTF file: the JSON has no 'asset' object");
  const std::optional<std::string> version = gltf::optional_string(*asset, "version", where + ": asset");
  if (!version) fail(where, "not a glTF file: 'asset' has no 'version'");
  if (!version->starts_with("2.")) {
    fail(where, "glTF version '" + version->substr(0, 16) + "' is not supported (only 2.x is read)");
  }
  const std::optional<std::string> min_version = gltf::optional_string(*asset, "minVersion", where + ": asset");
  if (min_version && *min_version != "2.0") {
    fail(where, "the file needs a glTF reader of at least version '" + min_version->substr(0, 16) +
                    "'; geodual reads glTF 2.0");
  }
}

bool names_string(const Json& list, std::string_view name) {
  return std::any_of(list.begin(), list.end(),
                     [&](const Json& v) { return v.is_string() && v.get_ref<const std::string&>() == name; });
}

// Refuses files that require an extension which changes geometry; returns
// whether KHR_mesh_quantization (integer positions) is in use.
bool check_extensions(const Json& root, const std::string& where, std::vector<std::string>& notes) {
  const Json& used = gltf::array_member(root, "extensionsUsed", where);
  const Json& required = gltf::array_member(root, "extensionsRequired", where);
  constexpr std::array<std::string_view, 8> harmless_prefixes = {
      "KHR_materials_", "KHR_texture_", "EXT_texture_", "MSFT_texture_",
      "KHR_lights_",    "EXT_lights_",  "KHR_xmp",      "KHR_mesh_quantization"};
  for (const Json& value : required) {
    if (!value.is_string()) fail(where, "'extensionsRequired' must list strings");
    const std::string& name = value.get_ref<const std::string&>();
    const bool harmless = std::any_of(harmless_prefixes.begin(), harmless_prefixes.end(),
                                      [&](std::string_view prefix) { return name.starts_with(prefix); });
    if (!harmless) {
      fail(where, "requires the glTF extension '" + name.substr(0, 64) +
                      "', which geodual cannot read (for compressed meshes, decompress first, "
                      "e.g. with gltf-transform or gltfpack)");
    }
  }
  if (names_string(used, "EXT_mesh_gpu_instancing")) {
    notes.push_back("EXT_mesh_gpu_instancing ignored: each node contributes its mesh once");
  }
  return names_string(used, "KHR_mesh_quantization") || names_string(required, "KHR_mesh_quantization");
}

LoadedMesh read_gltf_document(std::span<const std::byte> data, bool binary, const std::filesystem::path& name,
                              const std::string& where) {
  LoadedMesh result;
  ReadInfo& info = result.info;
  info.file_bytes = data.size();

  // The content decides, whatever the extension says: GLBs named .gltf are common.
  const bool is_glb = starts_with_glb_magic(data) || (binary && !looks_like_json(data));
  if (is_glb != binary) {
    info.notes.push_back(std::string("the file holds ") + (is_glb ? "binary GLB" : "JSON glTF") +
                         " despite its name; read it as such");
  }
  info.format = is_glb ? MeshFormat::glb : MeshFormat::gltf;
  info.encoding = is_glb ? "glTF 2.0 binary (GLB)" : "glTF 2.0 JSON";

  std::optional<std::span<const std::byte>> bin;
  std::span<const std::byte> json_text = data;
  if (is_glb) {
    const GlbChunks chunks = parse_glb(data, where);
    json_text = chunks.json;
    bin = chunks.bin;
  }
  const Json root = parse_json(json_text, where);
  check_asset(root, where);
  const bool allow_quantized = check_extensions(root, where, info.notes);

  gltf::BufferStore buffers(root, bin, name, where);
  const std::vector<gltf::MeshInstance> instances = gltf::collect_mesh_instances(root, where, info.notes);
  gltf::TextureStore textures(root, buffers, name, where);
  gltf::MeshAssembler assembler(root, buffers, textures, allow_quantized, where);
  result.mesh = assembler.assemble(instances);
  result.attributes = assembler.take_attributes();
  result.texture = assembler.take_texture(result.mesh.faces);
  for (std::string& note : assembler.notes()) info.notes.push_back(std::move(note));
  return result;
}

}  // namespace

LoadedMesh read_gltf(std::span<const std::byte> data, bool binary, const std::filesystem::path& name) {
  const std::string where = name.empty() ? std::string(memory_name) : name.string();
  try {
    return read_gltf_document(data, binary, name, where);
  } catch (const Json::exception& e) {
    // The helpers check types before reading values; this is a safety net.
    throw Error(where + ": malformed glTF JSON: " + e.what());
  }
}

}  // namespace geodual::io::detail
