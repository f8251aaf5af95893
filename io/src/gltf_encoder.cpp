#include "gltf_encoder.hpp"

#include "geodual/mesh/error.hpp"
#include "gltf_base64.hpp"
#include "gltf_constants.hpp"
#include "gltf_glb.hpp"
#include "gltf_vertex_normals.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>

namespace geodual::io::detail::gltf {
namespace {

// uint16 indices may use 0..65534: 65535 is the primitive restart value, which glTF forbids.
constexpr Index max_vertices_for_uint16 = 65535;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(where + ": " + what);
}

template <class T>
std::span<const std::byte> bytes_of(std::span<const T> values) {
  return std::as_bytes(values);
}

// nlohmann's dump() throws on invalid UTF-8 in strings (names, extras): replace it instead.
std::string dump(const nlohmann::ordered_json& json, int indent) {
  return json.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

void check_indices(std::span<const Index> indices, Index vertex_count, std::string_view element,
                   std::size_t corners_per_element, const std::string& where) {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < 0 || indices[i] >= vertex_count) {
      fail(where, std::string(element) + " " + std::to_string(i / corners_per_element) + " refers to vertex " +
                      std::to_string(indices[i]) + ", but there are " + std::to_string(vertex_count) +
                      " vertices");
    }
  }
}

}  // namespace

std::string Encoder::entry_name(std::string_view kind, std::size_t index, std::string_view name) const {
  std::string text = std::string(kind) + " " + std::to_string(index);
  if (!name.empty()) text += " '" + std::string(name) + "'";
  return text;
}

void Encoder::add_triangles(std::string_view name, const TriangleMesh& mesh, const ColorMatrix& colors,
                            std::span<const GltfVertexScalar> scalars) {
  const std::string where = where_ + ": " + entry_name("triangle mesh", triangle_meshes_++, name);
  if (mesh.num_faces() == 0) fail(where, "has no triangles");
  const std::span<const Index> corners(mesh.faces.data(), static_cast<std::size_t>(mesh.faces.size()));
  check_indices(corners, mesh.num_vertices(), "face", 3, where);

  Json attributes = Json::object();
  attributes["POSITION"] = add_positions(mesh.vertices, where);
  const std::vector<float> normals = area_weighted_vertex_normals(mesh.vertices, mesh.faces);
  attributes["NORMAL"] = add_float_accessor(normals, "VEC3");
  if (const auto color = add_colors(colors, mesh.vertices.rows(), where)) attributes["COLOR_0"] = *color;

  std::set<std::string, std::less<>> names;
  for (const GltfVertexScalar& scalar : scalars) {
    const std::string scalar_where = where + ": scalar attribute '" + scalar.name + "'";
    if (scalar.name.size() < 2 || scalar.name[0] != '_') {
      fail(scalar_where, "name must start with '_' (glTF's rule for application-specific attributes), e.g. '_DISTANCE'");
    }
    if (!names.insert(scalar.name).second) fail(scalar_where, "is given twice");
    if (scalar.values.size() != static_cast<std::size_t>(mesh.num_vertices())) {
      fail(scalar_where, "has " + std::to_string(scalar.values.size()) + " values for " +
                             std::to_string(mesh.num_vertices()) + " vertices");
    }
    for (std::size_t v = 0; v < scalar.values.size(); ++v) {
      if (!std::isfinite(scalar.values[v])) {
        fail(scalar_where, "value of vertex " + std::to_string(v) + " is not finite; glTF allows no NaN or infinity");
      }
    }
    attributes[scalar.name] = add_float_accessor(scalar.values, "SCALAR");
  }

  Json primitive = Json::object();
  primitive["attributes"] = std::move(attributes);
  primitive["indices"] = add_indices(corners, mesh.num_vertices());
  primitive["mode"] = static_cast<std::uint32_t>(PrimitiveMode::triangles);
  add_node(name, std::move(primitive));
}

void Encoder::add_lines(const GltfLineSet& lines) {
  const std::string where = where_ + ": " + entry_name("line set", line_sets_++, lines.name);
  if (lines.segments.rows() == 0) fail(where, "has no segments");
  const auto point_count = static_cast<Index>(lines.points.rows());
  const std::span<const Index> ends(lines.segments.data(), static_cast<std::size_t>(lines.segments.size()));
  check_indices(ends, point_count, "segment", 2, where);

  Json attributes = Json::object();
  attributes["POSITION"] = add_positions(lines.points, where);
  if (const auto color = add_colors(lines.colors, lines.points.rows(), where)) attributes["COLOR_0"] = *color;
  Json primitive = Json::object();
  primitive["attributes"] = std::move(attributes);
  primitive["indices"] = add_indices(ends, point_count);
  primitive["mode"] = static_cast<std::uint32_t>(PrimitiveMode::lines);
  add_node(lines.name, std::move(primitive));
}

void Encoder::add_points(const GltfPointSet& points) {
  const std::string where = where_ + ": " + entry_name("point set", point_sets_++, points.name);
  Json attributes = Json::object();
  attributes["POSITION"] = add_positions(points.points, where);
  if (const auto color = add_colors(points.colors, points.points.rows(), where)) attributes["COLOR_0"] = *color;
  Json primitive = Json::object();
  primitive["attributes"] = std::move(attributes);
  primitive["mode"] = static_cast<std::uint32_t>(PrimitiveMode::points);
  add_node(points.name, std::move(primitive));
}

std::size_t Encoder::add_positions(const VertexMatrix& points, const std::string& where) {
  if (points.rows() == 0) fail(where, "has no vertices");
  if (points.rows() > std::numeric_limits<Index>::max()) fail(where, "has too many vertices");
  std::vector<float> xyz(static_cast<std::size_t>(points.size()));
  std::array<float, 3> low;
  std::array<float, 3> high;
  low.fill(std::numeric_limits<float>::infinity());
  high.fill(-std::numeric_limits<float>::infinity());
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double coordinate = points(v, k);
      // Checked before the cast: converting a double beyond the float range is undefined.
      if (!std::isfinite(coordinate) || std::abs(coordinate) > std::numeric_limits<float>::max()) {
        fail(where, "vertex " + std::to_string(v) + " has coordinate " + std::to_string(coordinate) +
                        ", which is not a finite float32 value");
      }
      const auto value = static_cast<float>(coordinate);
      xyz[static_cast<std::size_t>(3 * v + k)] = value;
      low[static_cast<std::size_t>(k)] = std::min(low[static_cast<std::size_t>(k)], value);
      high[static_cast<std::size_t>(k)] = std::max(high[static_cast<std::size_t>(k)], value);
    }
  }
  // The spec requires min and max for POSITION; they are the float32 values themselves.
  return add_float_accessor(xyz, "VEC3", Json(low), Json(high));
}

std::optional<std::size_t> Encoder::add_colors(const ColorMatrix& colors, Eigen::Index rows,
                                               const std::string& where) {
  if (colors.size() == 0) return std::nullopt;
  if (colors.rows() != rows || (colors.cols() != 3 && colors.cols() != 4)) {
    fail(where, "colours are " + std::to_string(colors.rows()) + " x " + std::to_string(colors.cols()) +
                    "; expected " + std::to_string(rows) + " x 3 (RGB) or x 4 (RGBA)");
  }
  for (Eigen::Index v = 0; v < colors.rows(); ++v) {
    for (Eigen::Index k = 0; k < colors.cols(); ++k) {
      const float c = colors(v, k);
      if (!(c >= 0.0F && c <= 1.0F)) {
        fail(where, "colour of vertex " + std::to_string(v) + " has component " + std::to_string(c) +
                        ", outside [0, 1]");
      }
    }
  }
  return add_float_accessor(std::span<const float>(colors.data(), static_cast<std::size_t>(colors.size())),
                            colors.cols() == 3 ? "VEC3" : "VEC4");
}

std::size_t Encoder::add_indices(std::span<const Index> indices, Index vertex_count) {
  Json accessor = Json::object();
  if (vertex_count <= max_vertices_for_uint16) {
    std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
    accessor["bufferView"] = add_buffer_view(bytes_of<std::uint16_t>(narrow),
                                             static_cast<std::uint32_t>(BufferTarget::element_array_buffer));
    accessor["componentType"] = static_cast<std::uint32_t>(ComponentType::unsigned_short);
  } else {
    std::vector<std::uint32_t> wide(indices.begin(), indices.end());
    accessor["bufferView"] = add_buffer_view(bytes_of<std::uint32_t>(wide),
                                             static_cast<std::uint32_t>(BufferTarget::element_array_buffer));
    accessor["componentType"] = static_cast<std::uint32_t>(ComponentType::unsigned_int);
  }
  accessor["count"] = indices.size();
  accessor["type"] = "SCALAR";
  accessors_.push_back(std::move(accessor));
  return accessors_.size() - 1;
}

std::size_t Encoder::add_float_accessor(std::span<const float> values, std::string_view type, Json min,
                                        Json max) {
  const std::size_t components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
  Json accessor = Json::object();
  accessor["bufferView"] =
      add_buffer_view(bytes_of<float>(values), static_cast<std::uint32_t>(BufferTarget::array_buffer));
  accessor["componentType"] = static_cast<std::uint32_t>(ComponentType::float_);
  accessor["count"] = values.size() / components;
  accessor["type"] = type;
  if (!min.is_null()) accessor["min"] = std::move(min);
  if (!max.is_null()) accessor["max"] = std::move(max);
  accessors_.push_back(std::move(accessor));
  return accessors_.size() - 1;
}

std::size_t Encoder::add_buffer_view(std::span<const std::byte> data, std::uint32_t target) {
  bin_.resize((bin_.size() + 3) / 4 * 4, std::byte{0});  // every view starts on a 4-byte boundary
  Json view = Json::object();
  view["buffer"] = 0;
  view["byteOffset"] = bin_.size();
  view["byteLength"] = data.size();
  view["target"] = target;
  bin_.insert(bin_.end(), data.begin(), data.end());
  buffer_views_.push_back(std::move(view));
  return buffer_views_.size() - 1;
}

void Encoder::add_node(std::string_view name, Json primitive) {
  Json mesh = Json::object();
  Json node = Json::object();
  if (!name.empty()) {
    mesh["name"] = name;
    node["name"] = name;
  }
  mesh["primitives"] = Json::array({std::move(primitive)});
  meshes_.push_back(std::move(mesh));
  node["mesh"] = meshes_.size() - 1;
  nodes_.push_back(std::move(node));
}

std::vector<std::byte> Encoder::finish(GltfContainer container, std::string_view extras_json) {
  if (nodes_.empty()) fail(where_, "nothing to write: the scene has no meshes, lines or points");

  Json asset = Json::object();
  asset["version"] = "2.0";
  asset["generator"] = "geodual";
  if (!extras_json.empty()) {
    Json extras;
    try {
      extras = Json::parse(extras_json);
    } catch (const Json::parse_error& e) {
      fail(where_, std::string("asset extras are not valid JSON: ") + e.what());
    }
    if (!extras.is_object()) fail(where_, "asset extras must be a JSON object");
    asset["extras"] = std::move(extras);
  }

  Json scene_nodes = Json::array();
  for (std::size_t n = 0; n < nodes_.size(); ++n) scene_nodes.push_back(n);
  Json scene = Json::object();
  scene["nodes"] = std::move(scene_nodes);

  Json buffer = Json::object();
  buffer["byteLength"] = bin_.size();
  if (container == GltfContainer::gltf_embedded) {
    buffer["uri"] = "data:application/octet-stream;base64," + encode_base64(bin_);
  }

  Json root = Json::object();
  root["asset"] = std::move(asset);
  root["scene"] = 0;
  root["scenes"] = Json::array({std::move(scene)});
  root["nodes"] = std::move(nodes_);
  root["meshes"] = std::move(meshes_);
  root["accessors"] = std::move(accessors_);
  root["bufferViews"] = std::move(buffer_views_);
  root["buffers"] = Json::array({std::move(buffer)});

  if (container == GltfContainer::glb) return assemble_glb(dump(root, -1), bin_);
  const std::string text = dump(root, 1) + "\n";
  const auto* begin = reinterpret_cast<const std::byte*>(text.data());
  return {begin, begin + text.size()};
}

}  // namespace geodual::io::detail::gltf
