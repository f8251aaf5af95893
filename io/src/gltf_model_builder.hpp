#pragma once
// Internal: a GltfScene as a tinygltf::Model, entry by entry, each entry
// checked first. One node and one single-primitive mesh per entry; one buffer
// holding every accessor's data, one buffer view per accessor, each starting
// on a 4-byte boundary, with ARRAY_BUFFER / ELEMENT_ARRAY_BUFFER targets.

#include "geodual/io/gltf.hpp"
#include "gltf_meshopt_views.hpp"
#include "gltf_triangle_streams.hpp"

#include <tiny_gltf.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail::gltf {

class ModelBuilder {
 public:
  /// `where` starts every error message (the output path, or "glTF output").
  explicit ModelBuilder(std::string where, GltfCompression compression = GltfCompression::none);

  /// `mesh` with the attributes and textures of `entry` (whose own mesh is
  /// not read). Normals empty: area-weighted ones; otherwise normalised, with
  /// the area-weighted normal where a row is zero or not finite.
  void add_triangles(std::string_view name, const TriangleMesh& mesh, const GltfTriangleMesh& entry);
  void add_lines(const GltfLineSet& lines);
  void add_points(const GltfPointSet& points);

  /// The model with its default scene listing every node; throws when there is none.
  tinygltf::Model finish();

  /// The buffer views holding meshopt-encoded data (add_meshopt_views() writes their extension).
  const std::vector<MeshoptView>& meshopt_views() const { return meshopt_views_; }

 private:
  void add_meshopt_triangles(std::string_view name, const TriangleStreams& streams);
  void add_draco_triangles(std::string_view name, const TriangleStreams& streams, const std::string& where);
  void use_extension(const std::string& name);
  std::optional<int> add_material(const GltfTriangleMesh& entry, const std::string& where);
  int add_texture(const GltfImage& image, std::string_view what, const std::string& where);
  int add_positions(const VertexMatrix& points, const std::string& where);
  std::optional<int> add_colors(const ColorMatrix& colors, Eigen::Index rows, const std::string& where);
  int add_indices(std::span<const Index> indices, Index vertex_count);
  int add_accessor(std::span<const std::byte> data, int component_type, int type, std::size_t count, int target);
  int add_view(std::span<const std::byte> data, int target);
  tinygltf::Node& add_node(std::string_view name, tinygltf::Primitive primitive);

  std::string where_;
  GltfCompression compression_;
  std::vector<MeshoptView> meshopt_views_;
  tinygltf::Model model_;
  std::size_t triangle_meshes_ = 0;
  std::size_t line_sets_ = 0;
  std::size_t point_sets_ = 0;
};

}  // namespace geodual::io::detail::gltf
