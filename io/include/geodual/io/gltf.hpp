#pragma once
// glTF 2.0 output: a small scene description -- triangle meshes with optional
// per-vertex colours and scalar fields, line sets, point sets, and free-form
// metadata in asset.extras -- and writers for .glb and .gltf.
//
// What the files hold:
//  - one node and one mesh (with one primitive) per entry, in the order
//    triangle meshes, line sets, point sets; all nodes in one default scene;
//  - coordinates, colours and scalars as float32: a double that is not a
//    float32 value is rounded to the nearest one;
//  - triangle meshes: POSITION, NORMAL (area-weighted vertex normals, unit
//    length; (0, 0, 1) where the surrounding area is zero), optional COLOR_0,
//    TEXCOORD_0, TANGENT and scalar attributes, and uint16 indices when every
//    vertex index fits below 65535 (the primitive restart value), uint32
//    otherwise; with textures, a material holding them (embedded images);
//  - .glb: one GLB file. .gltf: one JSON file with the binary data embedded as
//    a base64 data URI (one file, so the atomic rename covers all of it);
//  - with GltfScene::compression, the triangle meshes compressed for the web
//    (GltfCompression); line and point sets are written as above.
// The output passes the Khronos glTF-Validator without errors or warnings,
// and the same scene always gives the same bytes.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io {

/// Per-vertex colours (vertex_attributes.hpp); in a glTF scene they are linear, as COLOR_0 is.
using geodual::ColorMatrix;

/// K x 2 point indices, one row per line segment.
using SegmentMatrix = Eigen::Matrix<Index, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// One float per vertex, written as an application-specific vertex attribute
/// (SCALAR float accessor). glTF requires such names to start with an
/// underscore, e.g. "_DISTANCE"; values must be finite.
struct GltfVertexScalar {
  std::string name{};
  std::vector<float> values{};
};

/// An image embedded in the file: the bytes of a PNG or JPEG file
/// (encode_image) and its MIME type, "image/png" or "image/jpeg".
struct GltfImage {
  std::vector<std::byte> bytes{};
  std::string mime_type{};
  bool empty() const { return bytes.empty(); }
};

/// Texture coordinates (u, v) per vertex, as TEXCOORD_0 holds them.
using TexcoordMatrix = Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor>;
/// Tangents (x, y, z, w) per vertex, as TANGENT holds them.
using TangentMatrix = Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// A triangle mesh (a TRIANGLES primitive).
struct GltfTriangleMesh {
  std::string name{};    ///< node and mesh name; empty: none
  TriangleMesh mesh{};   ///< at least one triangle
  ColorMatrix colors{};  ///< COLOR_0: empty, or one row per vertex
  /// NORMAL: empty for area-weighted normals, or one row per vertex
  /// (normalised; a zero or non-finite row gets the area-weighted normal).
  VertexMatrix normals{};
  std::vector<GltfVertexScalar> scalars{};  ///< one value per vertex each
  /// TEXCOORD_0: empty, or one finite row per vertex.
  TexcoordMatrix texcoords{};
  /// TANGENT: empty, or one row per vertex: xyz of unit length, w = +1 or -1
  /// (bitangent = cross(normal, tangent) w).
  TangentMatrix tangents{};
  /// The material's baseColorTexture and normalTexture (both address
  /// TEXCOORD_0, so they need texcoords): empty, or an embedded image. With
  /// either, the material is non-metallic and fully rough (a scan's look).
  GltfImage base_color_texture{};
  GltfImage normal_texture{};
};

/// A triangle mesh entry carrying `attributes` as glTF has them: colours
/// (sRGB-encoded) converted to linear COLOR_0, normals as NORMAL, each scalar
/// as the float attribute `_NAME`.
GltfTriangleMesh gltf_triangle_mesh(std::string name, TriangleMesh mesh, const VertexAttributes& attributes);

/// Line segments between points (a LINES primitive), e.g. polylines such as
/// Voronoi cell boundaries: consecutive points joined by segments (i, i + 1).
struct GltfLineSet {
  std::string name{};
  VertexMatrix points{};     ///< at least one row
  SegmentMatrix segments{};  ///< at least one row; indices into points
  ColorMatrix colors{};      ///< COLOR_0 per point: empty, or one row per point
};

/// Points (a POINTS primitive), e.g. sites or Voronoi vertices.
struct GltfPointSet {
  std::string name{};
  VertexMatrix points{};  ///< at least one row
  ColorMatrix colors{};   ///< COLOR_0 per point: empty, or one row per point
};

/// How triangle meshes are stored (docs/formats.md). Both compressed forms
/// mark their extensions required: a viewer without them cannot show the file.
enum class GltfCompression {
  none,  ///< float32 attributes, uint16/uint32 indices, as above
  /// EXT_meshopt_compression over KHR_mesh_quantization: triangles reordered
  /// for the vertex cache, then vertices for fetch (meshoptimizer); positions
  /// as uint16 on a 14-bit grid over the largest bounding-box side,
  /// dequantised by the node's translation and uniform scale; normals as
  /// normalised int8 through the 8-bit octahedral filter; colours as
  /// normalised uint16; scalars as float32.
  meshopt,
  /// KHR_draco_mesh_compression (Draco edgebreaker): positions quantised to
  /// 14 bits, normals to 10 (octahedral), colours to 16; scalars exact. Draco
  /// orders the vertices and triangles, and drops unused vertices and
  /// triangles with a repeated corner.
  draco,
};

/// "none", "meshopt" or "draco".
std::string_view gltf_compression_name(GltfCompression compression);

/// Everything one file holds. Needs at least one entry. Every member has a
/// default, so designated initializers may leave any of them out.
struct GltfScene {
  std::vector<GltfTriangleMesh> triangle_meshes{};
  std::vector<GltfLineSet> line_sets{};
  std::vector<GltfPointSet> point_sets{};
  /// asset.extras: the text of a JSON object (e.g. statistics, options), or empty for none.
  std::string extras_json{};
  /// asset.generator: the program that wrote the file, with its version.
  std::string generator = "geodual";
  /// How the triangle meshes are stored.
  GltfCompression compression = GltfCompression::none;
};

enum class GltfContainer {
  glb,            ///< binary .glb
  gltf_embedded,  ///< JSON .gltf with the buffer as a base64 data URI
};

/// The bytes of a .glb or .gltf file for `scene`. Throws geodual::Error,
/// naming the entry and element, for invalid input: out-of-range indices,
/// non-finite or beyond-float32 coordinates, colours outside [0, 1], wrong
/// row counts, scalar names without the leading underscore or used twice,
/// extras that are not a JSON object, empty entries, an empty scene.
std::vector<std::byte> encode_gltf(const GltfScene& scene, GltfContainer container);

/// Writes `scene` atomically to `path`: .glb or .gltf by the extension
/// (case-insensitive). Errors (as encode_gltf, plus I/O) name the path.
void write_gltf(const std::filesystem::path& path, const GltfScene& scene);

/// Writes one triangle mesh (positions, normals, indices) and its attributes
/// (gltf_triangle_mesh) to `path`, as above, stored as `compression` says.
void write_gltf(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes = {},
                GltfCompression compression = GltfCompression::none);

}  // namespace geodual::io
