#include "gltf_model_builder.hpp"

#include "geodual/mesh/error.hpp"
#include "gltf_draco.hpp"
#include "gltf_meshopt.hpp"
#include "gltf_vertex_normals.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace geodual::io::detail::gltf {
namespace {

// uint16 indices may use 0..65534: 65535 is the primitive restart value, which glTF forbids.
constexpr Index max_vertices_for_uint16 = 65535;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw Error(where + ": " + what); }

std::string entry_name(std::string_view kind, std::size_t index, std::string_view name) {
  std::string text = std::string(kind) + " " + std::to_string(index);
  if (!name.empty()) text += " '" + std::string(name) + "'";
  return text;
}

// tinygltf's JSON writer throws on invalid UTF-8: such bytes become U+FFFD instead.
std::string valid_utf8(std::string_view text) {
  using Json = nlohmann::json;
  const std::string quoted = Json(std::string(text)).dump(-1, ' ', false, Json::error_handler_t::replace);
  return Json::parse(quoted).get<std::string>();
}

void check_indices(std::span<const Index> indices, Index vertex_count, std::string_view element,
                   std::size_t corners_per_element, const std::string& where) {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < 0 || indices[i] >= vertex_count) {
      fail(where, std::string(element) + " " + std::to_string(i / corners_per_element) + " refers to vertex " +
                      std::to_string(indices[i]) + ", but there are " + std::to_string(vertex_count) + " vertices");
    }
  }
}

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

int accessor_type(int components) {
  switch (components) {
    case 1: return TINYGLTF_TYPE_SCALAR;
    case 2: return TINYGLTF_TYPE_VEC2;
    case 3: return TINYGLTF_TYPE_VEC3;
    default: return TINYGLTF_TYPE_VEC4;
  }
}

// x, y, z per vertex as float32; throws where a coordinate is not a finite float32 value.
std::vector<float> float_positions(const VertexMatrix& points, const std::string& where) {
  if (points.rows() == 0) fail(where, "has no vertices");
  if (points.rows() > std::numeric_limits<Index>::max()) fail(where, "has too many vertices");
  std::vector<float> xyz(static_cast<std::size_t>(points.size()));
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double coordinate = points(v, k);
      // Checked before the cast: converting a double beyond the float range is undefined.
      if (!std::isfinite(coordinate) || std::abs(coordinate) > std::numeric_limits<float>::max()) {
        fail(where, "vertex " + std::to_string(v) + " has coordinate " + std::to_string(coordinate) +
                        ", which is not a finite float32 value");
      }
      xyz[static_cast<std::size_t>(3 * v + k)] = static_cast<float>(coordinate);
    }
  }
  return xyz;
}

// The NORMAL values: `normals` where a row is finite and not zero (normalised), area-weighted otherwise.
std::vector<float> unit_normals(const TriangleMesh& mesh, const VertexMatrix& normals, const std::string& where) {
  std::vector<float> unit = area_weighted_vertex_normals(mesh.vertices, mesh.faces);
  if (normals.rows() == 0) return unit;
  if (normals.rows() != mesh.vertices.rows()) {
    fail(where, "has " + std::to_string(normals.rows()) + " normals for " + std::to_string(mesh.vertices.rows()) +
                    " vertices");
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v) {
    const double length = normals.row(v).norm();
    if (!std::isfinite(length) || length == 0) continue;  // the area-weighted one stays
    for (Eigen::Index k = 0; k < 3; ++k) {
      unit[static_cast<std::size_t>(3 * v + k)] = static_cast<float>(normals(v, k) / length);
    }
  }
  return unit;
}

void check_colors(const ColorMatrix& colors, Eigen::Index rows, const std::string& where) {
  if (colors.rows() != rows || (colors.cols() != 3 && colors.cols() != 4)) {
    fail(where, "colours are " + std::to_string(colors.rows()) + " x " + std::to_string(colors.cols()) + "; expected " +
                    std::to_string(rows) + " x 3 (RGB) or x 4 (RGBA)");
  }
  for (Eigen::Index v = 0; v < colors.rows(); ++v) {
    for (Eigen::Index k = 0; k < colors.cols(); ++k) {
      const float c = colors(v, k);
      if (!(c >= 0.0F && c <= 1.0F)) {
        fail(where,
             "colour of vertex " + std::to_string(v) + " has component " + std::to_string(c) + ", outside [0, 1]");
      }
    }
  }
}

void check_scalar(const GltfVertexScalar& scalar, std::set<std::string, std::less<>>& names, Index vertex_count,
                  const std::string& where) {
  const std::string scalar_where = where + ": scalar attribute '" + scalar.name + "'";
  if (scalar.name.size() < 2 || scalar.name[0] != '_') {
    fail(scalar_where, "name must start with '_' (glTF's rule for application-specific attributes), e.g. '_DISTANCE'");
  }
  if (!names.insert(scalar.name).second) fail(scalar_where, "is given twice");
  if (scalar.values.size() != static_cast<std::size_t>(vertex_count)) {
    fail(scalar_where,
         "has " + std::to_string(scalar.values.size()) + " values for " + std::to_string(vertex_count) + " vertices");
  }
  for (std::size_t v = 0; v < scalar.values.size(); ++v) {
    if (!std::isfinite(scalar.values[v])) {
      fail(scalar_where, "value of vertex " + std::to_string(v) + " is not finite; glTF allows no NaN or infinity");
    }
  }
}

// TEXCOORD_0's values: finite, one row per vertex (empty: none).
std::vector<float> checked_texcoords(const TexcoordMatrix& texcoords, Index vertex_count, const std::string& where) {
  if (texcoords.rows() == 0) return {};
  if (texcoords.rows() != vertex_count) {
    fail(where, "has " + std::to_string(texcoords.rows()) + " texture coordinates for " + std::to_string(vertex_count) +
                    " vertices");
  }
  for (Eigen::Index v = 0; v < texcoords.rows(); ++v) {
    if (!texcoords.row(v).allFinite()) {
      fail(where, "texture coordinates of vertex " + std::to_string(v) + " are not finite");
    }
  }
  return {texcoords.data(), texcoords.data() + texcoords.size()};
}

// TANGENT's values: xyz normalised, w the sign of the row's w (empty: none).
std::vector<float> checked_tangents(const TangentMatrix& tangents, Index vertex_count, const std::string& where) {
  if (tangents.rows() == 0) return {};
  if (tangents.rows() != vertex_count) {
    fail(where,
         "has " + std::to_string(tangents.rows()) + " tangents for " + std::to_string(vertex_count) + " vertices");
  }
  std::vector<float> values(static_cast<std::size_t>(tangents.size()));
  for (Eigen::Index v = 0; v < tangents.rows(); ++v) {
    const double length = tangents.row(v).head<3>().cast<double>().norm();
    const float w = tangents(v, 3);
    if (!std::isfinite(length) || !(length > 0) || !(w == 1.0F || w == -1.0F)) {
      fail(where, "tangent of vertex " + std::to_string(v) + " is not a direction with w = +1 or -1 (glTF's TANGENT)");
    }
    for (Eigen::Index k = 0; k < 3; ++k) {
      values[static_cast<std::size_t>(4 * v + k)] = static_cast<float>(tangents(v, k) / length);
    }
    values[static_cast<std::size_t>(4 * v + 3)] = w;
  }
  return values;
}

}  // namespace

ModelBuilder::ModelBuilder(std::string where, GltfCompression compression)
    : where_(std::move(where)), compression_(compression) {
  model_.asset.version = "2.0";
  model_.asset.generator = "geodual";
  model_.buffers.emplace_back();
}

void ModelBuilder::add_triangles(std::string_view name, const TriangleMesh& mesh, const GltfTriangleMesh& entry) {
  const std::string where = where_ + ": " + entry_name("triangle mesh", triangle_meshes_++, name);
  if (mesh.num_faces() == 0) fail(where, "has no triangles");
  const std::span<const Index> corners(mesh.faces.data(), static_cast<std::size_t>(mesh.faces.size()));
  check_indices(corners, mesh.num_vertices(), "face", 3, where);
  std::vector<float> texcoords = checked_texcoords(entry.texcoords, mesh.num_vertices(), where);
  std::vector<float> tangents = checked_tangents(entry.tangents, mesh.num_vertices(), where);
  const std::optional<int> material = add_material(entry, where);

  if (compression_ != GltfCompression::none) {
    TriangleStreams streams;
    streams.vertex_count = static_cast<std::size_t>(mesh.num_vertices());
    streams.positions = float_positions(mesh.vertices, where);
    streams.normals = unit_normals(mesh, entry.normals, where);
    if (entry.colors.size() > 0) {
      check_colors(entry.colors, mesh.vertices.rows(), where);
      streams.color_channels = static_cast<int>(entry.colors.cols());
      streams.colors.assign(entry.colors.data(), entry.colors.data() + entry.colors.size());
    }
    std::set<std::string, std::less<>> names;
    for (const GltfVertexScalar& scalar : entry.scalars) {
      check_scalar(scalar, names, mesh.num_vertices(), where);
      streams.scalars.push_back({valid_utf8(scalar.name), scalar.values});
    }
    streams.texcoords = std::move(texcoords);
    streams.tangents = std::move(tangents);
    streams.indices.assign(corners.begin(), corners.end());
    if (compression_ == GltfCompression::meshopt) {
      add_meshopt_triangles(name, streams);
    } else {
      add_draco_triangles(name, streams, where);
    }
    if (material) model_.meshes.back().primitives.back().material = *material;
    return;
  }

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = add_positions(mesh.vertices, where);
  const std::vector<float> normal_values = unit_normals(mesh, entry.normals, where);
  primitive.attributes["NORMAL"] =
      add_accessor(bytes_of(normal_values), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normal_values.size() / 3,
                   TINYGLTF_TARGET_ARRAY_BUFFER);
  if (const auto color = add_colors(entry.colors, mesh.vertices.rows(), where)) {
    primitive.attributes["COLOR_0"] = *color;
  }
  if (!texcoords.empty()) {
    primitive.attributes["TEXCOORD_0"] =
        add_accessor(bytes_of(texcoords), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, texcoords.size() / 2,
                     TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  if (!tangents.empty()) {
    primitive.attributes["TANGENT"] =
        add_accessor(bytes_of(tangents), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, tangents.size() / 4,
                     TINYGLTF_TARGET_ARRAY_BUFFER);
  }

  std::set<std::string, std::less<>> names;
  for (const GltfVertexScalar& scalar : entry.scalars) {
    check_scalar(scalar, names, mesh.num_vertices(), where);
    primitive.attributes[valid_utf8(scalar.name)] =
        add_accessor(bytes_of(scalar.values), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, scalar.values.size(),
                     TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  primitive.indices = add_indices(corners, mesh.num_vertices());
  if (material) primitive.material = *material;
  add_node(name, std::move(primitive));
}

std::optional<int> ModelBuilder::add_material(const GltfTriangleMesh& entry, const std::string& where) {
  if (entry.base_color_texture.empty() && entry.normal_texture.empty()) return std::nullopt;
  if (entry.texcoords.rows() == 0) fail(where, "has textures but no texture coordinates (TEXCOORD_0)");
  tinygltf::Material material;
  material.pbrMetallicRoughness.metallicFactor = 0;  // a scan's surface: a dielectric, fully rough
  material.pbrMetallicRoughness.roughnessFactor = 1;
  if (!entry.base_color_texture.empty()) {
    material.pbrMetallicRoughness.baseColorTexture.index =
        add_texture(entry.base_color_texture, "base colour texture", where);
  }
  if (!entry.normal_texture.empty()) {
    material.normalTexture.index = add_texture(entry.normal_texture, "normal texture", where);
  }
  model_.materials.push_back(std::move(material));
  return static_cast<int>(model_.materials.size() - 1);
}

int ModelBuilder::add_texture(const GltfImage& image, std::string_view what, const std::string& where) {
  if (image.mime_type != "image/png" && image.mime_type != "image/jpeg") {
    fail(where, std::string(what) + " has MIME type '" + image.mime_type + "'; glTF embeds image/png or image/jpeg");
  }
  if (model_.samplers.empty()) {  // one sampler for every texture: trilinear, repeated
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    model_.samplers.push_back(std::move(sampler));
  }
  tinygltf::Image stored;
  stored.bufferView = add_view(image.bytes, /*target=*/0);
  stored.mimeType = image.mime_type;
  model_.images.push_back(std::move(stored));
  tinygltf::Texture texture;
  texture.sampler = 0;
  texture.source = static_cast<int>(model_.images.size() - 1);
  model_.textures.push_back(std::move(texture));
  return static_cast<int>(model_.textures.size() - 1);
}

void ModelBuilder::add_meshopt_triangles(std::string_view name, const TriangleStreams& streams) {
  const MeshoptPrimitive encoded = encode_meshopt(streams);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  for (const MeshoptStream& stream : encoded.streams) {
    const bool indices = stream.attribute.empty();
    const int view =
        add_view(stream.encoded, indices ? TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER : TINYGLTF_TARGET_ARRAY_BUFFER);
    if (!indices) model_.bufferViews.back().byteStride = stream.byte_stride;
    meshopt_views_.push_back({.view = view,
                              .byte_stride = stream.byte_stride,
                              .count = stream.count,
                              .triangles = indices,
                              .filter = stream.filter});
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = static_cast<int>(stream.component_type);
    accessor.type = accessor_type(stream.components);
    accessor.count = stream.count;
    accessor.normalized = stream.normalized;
    accessor.minValues = stream.min;
    accessor.maxValues = stream.max;
    model_.accessors.push_back(std::move(accessor));
    const int index = static_cast<int>(model_.accessors.size() - 1);
    if (indices) {
      primitive.indices = index;
    } else {
      primitive.attributes[stream.attribute] = index;
    }
  }
  tinygltf::Node& node = add_node(name, std::move(primitive));
  node.translation.assign(encoded.translation.begin(), encoded.translation.end());
  node.scale.assign(3, encoded.scale);
  use_extension("EXT_meshopt_compression");
  use_extension("KHR_mesh_quantization");
}

void ModelBuilder::add_draco_triangles(std::string_view name, const TriangleStreams& streams,
                                       const std::string& where) {
  const DracoPrimitive encoded = encode_draco(streams, where);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Value::Object ids;
  for (const auto& [attribute, id] : encoded.attribute_ids) {
    tinygltf::Accessor accessor;  // no bufferView: the data is in the Draco bitstream
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = attribute == "POSITION" || attribute == "NORMAL" ? TINYGLTF_TYPE_VEC3
                    : attribute == "COLOR_0"                         ? accessor_type(streams.color_channels)
                    : attribute == "TEXCOORD_0"                      ? TINYGLTF_TYPE_VEC2
                    : attribute == "TANGENT"                         ? TINYGLTF_TYPE_VEC4
                                                                     : TINYGLTF_TYPE_SCALAR;
    accessor.count = encoded.decoded_vertices;
    if (attribute == "POSITION") {
      accessor.minValues = encoded.position_min;
      accessor.maxValues = encoded.position_max;
    }
    model_.accessors.push_back(std::move(accessor));
    primitive.attributes[attribute] = static_cast<int>(model_.accessors.size() - 1);
    ids.emplace(attribute, tinygltf::Value(static_cast<int>(id)));
  }
  tinygltf::Accessor indices;
  indices.componentType = encoded.decoded_vertices <= static_cast<std::size_t>(max_vertices_for_uint16)
                              ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                              : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.type = TINYGLTF_TYPE_SCALAR;
  indices.count = encoded.decoded_indices;
  model_.accessors.push_back(std::move(indices));
  primitive.indices = static_cast<int>(model_.accessors.size() - 1);
  tinygltf::Value::Object extension;
  extension.emplace("bufferView", tinygltf::Value(add_view(encoded.encoded, /*target=*/0)));
  extension.emplace("attributes", tinygltf::Value(std::move(ids)));
  primitive.extensions.emplace("KHR_draco_mesh_compression", tinygltf::Value(std::move(extension)));
  add_node(name, std::move(primitive));
  use_extension("KHR_draco_mesh_compression");
}

void ModelBuilder::use_extension(const std::string& name) {
  for (std::vector<std::string>* list : {&model_.extensionsUsed, &model_.extensionsRequired}) {
    if (std::find(list->begin(), list->end(), name) == list->end()) list->push_back(name);
  }
}

void ModelBuilder::add_lines(const GltfLineSet& lines) {
  const std::string where = where_ + ": " + entry_name("line set", line_sets_++, lines.name);
  if (lines.segments.rows() == 0) fail(where, "has no segments");
  const auto point_count = static_cast<Index>(lines.points.rows());
  const std::span<const Index> ends(lines.segments.data(), static_cast<std::size_t>(lines.segments.size()));
  check_indices(ends, point_count, "segment", 2, where);

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_LINE;
  primitive.attributes["POSITION"] = add_positions(lines.points, where);
  if (const auto color = add_colors(lines.colors, lines.points.rows(), where)) primitive.attributes["COLOR_0"] = *color;
  primitive.indices = add_indices(ends, point_count);
  add_node(lines.name, std::move(primitive));
}

void ModelBuilder::add_points(const GltfPointSet& points) {
  const std::string where = where_ + ": " + entry_name("point set", point_sets_++, points.name);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_POINTS;
  primitive.attributes["POSITION"] = add_positions(points.points, where);
  if (const auto color = add_colors(points.colors, points.points.rows(), where))
    primitive.attributes["COLOR_0"] = *color;
  add_node(points.name, std::move(primitive));
}

int ModelBuilder::add_positions(const VertexMatrix& points, const std::string& where) {
  const std::vector<float> xyz = float_positions(points, where);
  std::vector<double> low(3, std::numeric_limits<double>::infinity());
  std::vector<double> high(3, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    low[i % 3] = std::min(low[i % 3], static_cast<double>(xyz[i]));
    high[i % 3] = std::max(high[i % 3], static_cast<double>(xyz[i]));
  }
  const int accessor = add_accessor(bytes_of(xyz), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                    static_cast<std::size_t>(points.rows()), TINYGLTF_TARGET_ARRAY_BUFFER);
  // The spec requires min and max for POSITION; they are the float32 values themselves.
  model_.accessors.back().minValues = std::move(low);
  model_.accessors.back().maxValues = std::move(high);
  return accessor;
}

std::optional<int> ModelBuilder::add_colors(const ColorMatrix& colors, Eigen::Index rows, const std::string& where) {
  if (colors.size() == 0) return std::nullopt;
  check_colors(colors, rows, where);
  const std::span<const float> values(colors.data(), static_cast<std::size_t>(colors.size()));
  return add_accessor(std::as_bytes(values), TINYGLTF_COMPONENT_TYPE_FLOAT,
                      colors.cols() == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, static_cast<std::size_t>(rows),
                      TINYGLTF_TARGET_ARRAY_BUFFER);
}

int ModelBuilder::add_indices(std::span<const Index> indices, Index vertex_count) {
  if (vertex_count <= max_vertices_for_uint16) {
    const std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
    return add_accessor(bytes_of(narrow), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, indices.size(),
                        TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  }
  const std::vector<std::uint32_t> wide(indices.begin(), indices.end());
  return add_accessor(bytes_of(wide), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size(),
                      TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

int ModelBuilder::add_view(std::span<const std::byte> data, int target) {
  std::vector<unsigned char>& bin = model_.buffers[0].data;
  bin.resize((bin.size() + 3) / 4 * 4, 0);  // every view starts on a 4-byte boundary
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin.size();
  view.byteLength = data.size();
  view.target = target;
  const auto* first = reinterpret_cast<const unsigned char*>(data.data());
  bin.insert(bin.end(), first, first + data.size());
  model_.bufferViews.push_back(std::move(view));
  return static_cast<int>(model_.bufferViews.size() - 1);
}

int ModelBuilder::add_accessor(std::span<const std::byte> data, int component_type, int type, std::size_t count,
                               int target) {
  tinygltf::Accessor accessor;
  accessor.bufferView = add_view(data, target);
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model_.accessors.push_back(std::move(accessor));
  return static_cast<int>(model_.accessors.size() - 1);
}

tinygltf::Node& ModelBuilder::add_node(std::string_view name, tinygltf::Primitive primitive) {
  tinygltf::Mesh mesh;
  tinygltf::Node node;
  mesh.name = node.name = valid_utf8(name);
  mesh.primitives.push_back(std::move(primitive));
  model_.meshes.push_back(std::move(mesh));
  node.mesh = static_cast<int>(model_.meshes.size() - 1);
  model_.nodes.push_back(std::move(node));
  return model_.nodes.back();
}

tinygltf::Model ModelBuilder::finish() {
  if (model_.nodes.empty()) fail(where_, "nothing to write: the scene has no meshes, lines or points");
  tinygltf::Scene scene;
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) scene.nodes.push_back(static_cast<int>(n));
  model_.scenes.push_back(std::move(scene));
  model_.defaultScene = 0;
  return std::move(model_);
}

}  // namespace geodual::io::detail::gltf
