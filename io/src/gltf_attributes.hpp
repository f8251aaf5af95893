#pragma once
// Internal: the per-vertex attributes of glTF triangle primitives -- colours,
// normals, application-specific scalars -- read alongside the positions, one
// row per vertex MeshAssembler appends.
//
//  - Colours: the glTF base colour, baseColorFactor x baseColorTexture
//    (sampled at its TEXCOORD_n) x COLOR_0, each 1 when absent, multiplied in
//    linear space and stored sRGB-encoded (VertexAttributes' convention).
//    Read when any primitive has one of the three (a factor counts when it is
//    not 1, 1, 1, 1); every vertex then gets its primitive's product. An
//    alpha column is kept only when some vertex's alpha is below 1.
//  - Normals: NORMAL, turned by the inverse transpose of the node transform's
//    linear part and renormalised; read only when every primitive has NORMAL.
//  - Scalars: SCALAR attributes named "_NAME", stored as NAME; each read only
//    when every primitive has it.
//  - The textures, kept whole for baking (LoadedMesh::texture): where every
//    primitive's base colour is an image alone, sampled at its TEXCOORD_n
//    (no COLOR_0, a white factor), those images, each vertex's coordinates
//    and each face's image.
// Accessors are checked when planned; values are decoded (and textures
// decoded) only while the output is written, vertex block by vertex block.

#include "geodual/mesh/texture_image.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "gltf_accessor.hpp"
#include "gltf_json.hpp"
#include "gltf_scene_graph.hpp"
#include "gltf_texture.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

/// What one triangle primitive stores per vertex, checked but not yet read.
struct PrimitiveAttributes {
  std::optional<AccessorView> color;  ///< COLOR_0
  std::array<double, 4> base_color_factor{1, 1, 1, 1};
  std::optional<TextureStore::Texture> texture;  ///< baseColorTexture with a readable image
  bool texture_transformed = false;              ///< with KHR_texture_transform (not applied)
  std::optional<AccessorView> texcoord;          ///< the texture's TEXCOORD_n
  std::size_t texcoord_set = 0;
  std::optional<AccessorView> normal;
  std::map<std::string, AccessorView> scalars;  ///< by name without the leading '_'
  /// Where the above come from: accessor index by attribute name, and
  /// "material" -> material index (for comparing primitives that share POSITION).
  std::map<std::string, std::size_t> sources;
};

class AttributeReader {
 public:
  /// The references must outlive the reader. `allow_quantized`: KHR_mesh_quantization's integer normals are allowed.
  AttributeReader(const Json& root, BufferStore& buffers, TextureStore& textures, bool allow_quantized,
                  std::string where);

  /// Checks the attributes (and the material) of a triangle primitive whose
  /// POSITION accessor has `vertex_count` elements.
  PrimitiveAttributes plan(const Json& primitive, const Json& attributes, std::size_t vertex_count,
                           const std::string& where);

  /// Chooses which attributes the output has, once every primitive that will
  /// be read was planned (each counted once, however often it is instanced),
  /// and reserves room for `total_vertices` rows.
  void choose(const std::vector<const PrimitiveAttributes*>& primitives, std::size_t total_vertices);

  /// Appends the rows of `count` vertices (a POSITION accessor) of `primitive` under `instance`'s transform.
  void append(const PrimitiveAttributes& primitive, std::size_t count, const MeshInstance& instance);

  /// The rows appended, moved out (attributes with non-finite values dropped, with a note).
  VertexAttributes take();

  /// Which of the textures kept whole `primitive`'s base colour is (-1: none kept).
  std::int32_t kept_image(const PrimitiveAttributes& primitive) const;

  /// The base colour textures, where every primitive's is an image alone
  /// (sampled with REPEAT, untransformed), with their coordinates at the
  /// corners of `faces` (the triangles on the vertices appended) and
  /// `face_image` (kept_image of each face's primitive); empty otherwise.
  SurfaceTexture take_texture(const FaceMatrix& faces, std::vector<std::int32_t> face_image);

  /// What was read, dropped or ignored, for ReadInfo::notes (complete after take()).
  std::vector<std::string> notes() const;

 private:
  struct OutputScalar {
    std::string name;
    ValueType type = ValueType::float32;
    std::vector<double> values;
    bool finite = true;
  };

  AccessorView view_attribute(std::size_t accessor, std::initializer_list<AccessorShape> shapes,
                              std::size_t vertex_count, const std::string& where);
  void plan_material(const Json& primitive, const Json& attributes, std::size_t vertex_count, PrimitiveAttributes& plan,
                     const std::string& where);
  void append_colors(const PrimitiveAttributes& primitive, std::size_t count);
  void append_normals(const PrimitiveAttributes& primitive, std::size_t count, const MeshInstance& instance);

  const Json& root_;
  BufferStore& buffers_;
  TextureStore& textures_;
  bool allow_quantized_;
  std::string where_;

  bool read_colors_ = false;
  ValueType color_type_ = ValueType::float32;
  bool read_normals_ = false;
  std::vector<float> colors_;    // linear products, then sRGB-encoded: r, g, b, a per vertex
  std::vector<double> normals_;  // x, y, z per vertex
  bool normals_finite_ = true;
  std::vector<OutputScalar> scalars_;
  std::vector<std::size_t> kept_images_;  // the images kept whole, if any (glTF image indices)
  std::vector<double> texcoords_;         // u, v per vertex, with kept_images_

  std::vector<std::string> notes_;
  std::set<std::string> seen_attributes_;  // every attribute name of every primitive planned
  std::set<std::string> used_attributes_;
  std::set<std::size_t> textures_without_source_;
  std::set<std::size_t> transformed_texture_materials_;
  std::size_t primitives_without_texcoord_ = 0;
};

}  // namespace geodual::io::detail::gltf
