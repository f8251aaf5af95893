// glTF 2.0 reading (.gltf and .glb) into one TriangleMesh.
//
// Every triangle primitive (TRIANGLES, and strips and fans converted to
// triangles) of every mesh that the chosen scene shows is appended, with its
// node's world transform applied; a mesh shown by two nodes appears twice.
// Each primitive's POSITION accessor contributes all its elements, in order
// (primitives of one mesh instance that share a POSITION accessor share those
// vertices). POINTS and LINES primitives are skipped and counted in the notes.
// Mirroring transforms (negative determinant) get their winding flipped so
// that triangles stay counter-clockwise seen from outside.
//
// The JSON is parsed here with nlohmann::json rather than by tinygltf: the
// Debian tinygltf 2.7 lets a GLB BIN chunk run 8 bytes past the end of its
// input, looks up external files in the current directory when they are not
// next to the glTF, and reads external images; this reader loads nothing but
// the buffers that the triangle primitives use (see gltf_buffers.hpp).

#include "format_readers.hpp"

#include "geodual/error.hpp"
#include "gltf_accessor.hpp"
#include "gltf_buffers.hpp"
#include "gltf_glb.hpp"
#include "gltf_json.hpp"
#include "gltf_scene_graph.hpp"
#include "gltf_triangulate.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <utility>

namespace geodual::io::detail {
namespace {

using gltf::Json;
using gltf::fail;

constexpr std::string_view memory_name = "<memory>";
constexpr auto max_elements = static_cast<std::size_t>(std::numeric_limits<Index>::max());

bool starts_with_glb_magic(std::span<const std::byte> data) {
  return data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
}

Json parse_json(std::span<const std::byte> text, const std::string& where) {
  const char* begin = reinterpret_cast<const char*>(text.data());
  const char* end = begin + text.size();
  constexpr std::string_view bom = "\xEF\xBB\xBF";
  if (text.size() >= bom.size() && std::string_view(begin, bom.size()) == bom) begin += bom.size();
  try {
    return Json::parse(begin, end);
  } catch (const Json::parse_error& e) {
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix.
    std::string detail = e.what();
    if (const std::size_t close = detail.find("] "); !detail.empty() && detail[0] == '[' && close != std::string::npos) {
      detail.erase(0, close + 2);
    }
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

class MeshAssembler {
 public:
  MeshAssembler(const Json& root, gltf::BufferStore& buffers, bool allow_quantized)
      : root_(root), buffers_(buffers), allow_quantized_(allow_quantized) {}

  void add(const gltf::MeshInstance& instance, const std::string& where);
  TriangleMesh take_mesh();
  void add_notes(std::vector<std::string>& notes) const;

 private:
  struct VertexRange {
    std::size_t first = 0;
    std::size_t count = 0;
  };

  void add_primitive(const Json& primitive, const gltf::MeshInstance& instance,
                     std::map<std::size_t, VertexRange>& instance_positions, const std::string& where);
  VertexRange add_positions(std::size_t accessor, const gltf::MeshInstance& instance, const std::string& where);

  const Json& root_;
  gltf::BufferStore& buffers_;
  bool allow_quantized_;
  std::vector<double> vertices_;  // x, y, z per vertex
  std::vector<Index> faces_;      // three per triangle

  std::size_t instances_ = 0;
  std::size_t transformed_instances_ = 0;
  std::size_t mirrored_instances_ = 0;
  std::map<std::string, std::size_t> skipped_by_mode_;
  std::size_t without_position_ = 0;
  std::size_t strips_and_fans_ = 0;
  std::size_t degenerate_dropped_ = 0;
  std::size_t trailing_ignored_ = 0;
};

void MeshAssembler::add(const gltf::MeshInstance& instance, const std::string& where) {
  const Json& meshes = gltf::array_member(root_, "meshes", where);
  const Json& mesh = meshes[instance.mesh];
  const std::string mesh_where = where + ": " + (instance.node.empty() ? "" : instance.node + ": ") +
                                 gltf::describe("mesh", instance.mesh, mesh);
  if (!mesh.is_object()) fail(mesh_where, "must be a JSON object");
  ++instances_;
  if (!instance.identity) ++transformed_instances_;
  if (instance.world.linear().determinant() < 0) ++mirrored_instances_;

  std::map<std::size_t, VertexRange> instance_positions;
  const Json& primitives = gltf::array_member(mesh, "primitives", mesh_where);
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    add_primitive(primitives[p], instance, instance_positions, mesh_where + " primitive " + std::to_string(p));
  }
}

void MeshAssembler::add_primitive(const Json& primitive, const gltf::MeshInstance& instance,
                                  std::map<std::size_t, VertexRange>& instance_positions,
                                  const std::string& where) {
  using gltf::PrimitiveMode;
  if (!primitive.is_object()) fail(where, "must be a JSON object");
  const std::uint64_t mode_code = gltf::optional_uint(primitive, "mode", where).value_or(4);
  if (mode_code > 6) fail(where, "invalid 'mode' " + std::to_string(mode_code));
  const auto mode = static_cast<PrimitiveMode>(mode_code);
  constexpr std::array<std::string_view, 4> non_triangle_modes = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
  if (mode_code < non_triangle_modes.size()) {
    ++skipped_by_mode_[std::string(non_triangle_modes[mode_code])];
    return;
  }

  const Json* attributes = gltf::optional_object(primitive, "attributes", where);
  if (attributes == nullptr) fail(where, "required 'attributes' is missing");
  const std::size_t accessor_count = gltf::array_member(root_, "accessors", where).size();
  const std::optional<std::size_t> position =
      gltf::optional_index(*attributes, "POSITION", accessor_count, "accessor", where + ": POSITION");
  if (!position) {
    ++without_position_;
    return;
  }
  auto cached = instance_positions.find(*position);
  if (cached == instance_positions.end()) {
    cached = instance_positions.emplace(*position, add_positions(*position, instance, where + ": POSITION")).first;
  }
  const VertexRange range = cached->second;

  std::vector<std::uint32_t> corners;
  if (const auto indices = gltf::optional_index(primitive, "indices", accessor_count, "accessor", where + ": indices")) {
    const gltf::AccessorView view =
        gltf::view_accessor(root_, buffers_, *indices, gltf::AccessorShape::scalar, where + ": indices");
    corners = gltf::read_indices(view);
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (corners[i] >= range.count) {
        fail(view.where, "element " + std::to_string(i) + " is vertex index " + std::to_string(corners[i]) +
                             ", but POSITION accessor " + std::to_string(*position) + " has only " +
                             std::to_string(range.count) + " vertices");
      }
    }
  } else {
    corners.resize(range.count);  // non-indexed: vertices are drawn in order
    std::iota(corners.begin(), corners.end(), std::uint32_t{0});
  }

  gltf::Triangulation triangles = gltf::triangulate(mode, std::move(corners));
  if (mode != PrimitiveMode::triangles) ++strips_and_fans_;
  degenerate_dropped_ += triangles.degenerate_dropped;
  trailing_ignored_ += triangles.trailing_ignored;
  if (faces_.size() / 3 + triangles.corners.size() / 3 > max_elements) {
    fail(where, "too many triangles in total (geodual meshes hold at most 2^31 - 1)");
  }
  const bool flip = instance.world.linear().determinant() < 0;
  const auto base = static_cast<Index>(range.first);
  faces_.reserve(faces_.size() + triangles.corners.size());
  for (std::size_t t = 0; t < triangles.corners.size(); t += 3) {
    const Index a = base + static_cast<Index>(triangles.corners[t]);
    const Index b = base + static_cast<Index>(triangles.corners[t + 1]);
    const Index c = base + static_cast<Index>(triangles.corners[t + 2]);
    faces_.insert(faces_.end(), {a, flip ? c : b, flip ? b : c});
  }
}

MeshAssembler::VertexRange MeshAssembler::add_positions(std::size_t accessor,
                                                        const gltf::MeshInstance& instance,
                                                        const std::string& where) {
  const gltf::AccessorView view =
      gltf::view_accessor(root_, buffers_, accessor, gltf::AccessorShape::vec3, where);
  const std::size_t first = vertices_.size() / 3;
  if (view.count > max_elements - first) {
    fail(view.where, "too many vertices in total (geodual meshes hold at most 2^31 - 1)");
  }
  gltf::append_positions(view, allow_quantized_, vertices_);
  if (!instance.identity) {
    for (std::size_t v = first; v < first + view.count; ++v) {
      Eigen::Map<Eigen::Vector3d> p(vertices_.data() + 3 * v);
      p = instance.world * p;
    }
  }
  return {.first = first, .count = view.count};
}

TriangleMesh MeshAssembler::take_mesh() {
  TriangleMesh mesh;
  const auto num_vertices = static_cast<Eigen::Index>(vertices_.size() / 3);
  const auto num_faces = static_cast<Eigen::Index>(faces_.size() / 3);
  mesh.vertices = Eigen::Map<const VertexMatrix>(vertices_.data(), num_vertices, 3);
  mesh.faces = Eigen::Map<const FaceMatrix>(faces_.data(), num_faces, 3);
  vertices_ = {};
  faces_ = {};
  return mesh;
}

void MeshAssembler::add_notes(std::vector<std::string>& notes) const {
  const auto count = [](std::size_t n, std::string_view one, std::string_view many) {
    return std::to_string(n) + " " + std::string(n == 1 ? one : many);
  };
  if (transformed_instances_ > 0) {
    notes.push_back("node transforms applied to " + count(transformed_instances_, "mesh instance", "mesh instances") +
                    " of " + std::to_string(instances_));
  }
  if (mirrored_instances_ > 0) {
    notes.push_back("triangle winding flipped in " +
                    count(mirrored_instances_, "mirrored mesh instance", "mirrored mesh instances"));
  }
  if (!skipped_by_mode_.empty()) {
    std::string text;
    std::size_t total = 0;
    for (const auto& [mode, n] : skipped_by_mode_) {
      text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + mode;
      total += n;
    }
    notes.push_back("skipped " + count(total, "non-triangle primitive", "non-triangle primitives") + " (" + text + ")");
  }
  if (without_position_ > 0) {
    notes.push_back("skipped " + count(without_position_, "primitive", "primitives") + " without POSITION");
  }
  if (strips_and_fans_ > 0) {
    notes.push_back("converted " + count(strips_and_fans_, "triangle strip or fan", "triangle strips and fans") +
                    " to triangles");
  }
  if (degenerate_dropped_ > 0) {
    notes.push_back("dropped " + count(degenerate_dropped_, "degenerate strip/fan triangle", "degenerate strip/fan triangles") +
                    " (repeated vertex)");
  }
  if (trailing_ignored_ > 0) {
    notes.push_back("ignored " + count(trailing_ignored_, "index", "indices") +
                    " after the last whole triangle of TRIANGLES primitives");
  }
}

LoadedMesh read_gltf_document(std::span<const std::byte> data, bool binary,
                              const std::filesystem::path& name, const std::string& where) {
  LoadedMesh result;
  ReadInfo& info = result.info;
  info.file_bytes = data.size();

  // The content decides, whatever the extension says: GLBs named .gltf are common.
  const bool is_glb = starts_with_glb_magic(data) || (binary && !(data.size() > 0 && data[0] == std::byte{'{'}));
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
  MeshAssembler assembler(root, buffers, allow_quantized);
  for (const gltf::MeshInstance& instance : instances) assembler.add(instance, where);
  assembler.add_notes(info.notes);
  result.mesh = assembler.take_mesh();
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
