#pragma once
// Internal: assembles a glTF asset -- JSON plus one binary buffer -- entry by
// entry, checking each entry first. One node and one single-primitive mesh per
// entry; one buffer view per accessor, each starting on a 4-byte boundary,
// with ARRAY_BUFFER / ELEMENT_ARRAY_BUFFER targets.

#include "geodual/io/gltf.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail::gltf {

class Encoder {
 public:
  /// `where` starts every error message (the output path, or "glTF output").
  explicit Encoder(std::string where) : where_(std::move(where)) {}

  void add_triangles(std::string_view name, const TriangleMesh& mesh, const ColorMatrix& colors,
                     std::span<const GltfVertexScalar> scalars);
  void add_lines(const GltfLineSet& lines);
  void add_points(const GltfPointSet& points);

  /// The finished file. `extras_json`: empty, or the text of a JSON object for asset.extras.
  std::vector<std::byte> finish(GltfContainer container, std::string_view extras_json);

 private:
  using Json = nlohmann::ordered_json;

  std::size_t add_positions(const VertexMatrix& points, const std::string& where);
  std::optional<std::size_t> add_colors(const ColorMatrix& colors, Eigen::Index rows, const std::string& where);
  std::size_t add_indices(std::span<const Index> indices, Index vertex_count);
  std::size_t add_float_accessor(std::span<const float> values, std::string_view type, Json min = {}, Json max = {});
  std::size_t add_buffer_view(std::span<const std::byte> data, std::uint32_t target);
  void add_node(std::string_view name, Json primitive);
  std::string entry_name(std::string_view kind, std::size_t index, std::string_view name) const;

  std::string where_;
  Json nodes_ = Json::array();
  Json meshes_ = Json::array();
  Json accessors_ = Json::array();
  Json buffer_views_ = Json::array();
  std::vector<std::byte> bin_;
  std::size_t triangle_meshes_ = 0;
  std::size_t line_sets_ = 0;
  std::size_t point_sets_ = 0;
};

}  // namespace geodual::io::detail::gltf
