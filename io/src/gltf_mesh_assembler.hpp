#pragma once
// Internal: turns the mesh instances of a glTF scene into one TriangleMesh.
//
// Two passes. The plan validates every triangle primitive of every mesh used
// (once per mesh, however often it is instanced: accessors, buffer views,
// bounds, modes) and totals the vertices and triangles the instances will
// produce; a total beyond 2^31 - 1 is refused before anything is allocated,
// and the output is then allocated once, at its final size. The read pass
// decodes, transforms and appends.
//
// Per instance: each triangle primitive's POSITION accessor is appended whole,
// in order (primitives of one instance that share a POSITION accessor share
// those vertices); TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN become triangles;
// POINTS and LINES primitives, and primitives without POSITION, are skipped
// and counted; a mirroring transform (negative determinant) flips the winding
// so that triangles stay counter-clockwise seen from outside.
//
// Vertex attributes (gltf_attributes.hpp) follow the same merge: each
// appended POSITION accessor gets its rows from the primitive that appended
// it; a later primitive of the instance that shares that accessor but has
// other attributes or another material is noted, its shared vertices keep
// the first primitive's values.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "gltf_accessor.hpp"
#include "gltf_attributes.hpp"
#include "gltf_buffers.hpp"
#include "gltf_constants.hpp"
#include "gltf_json.hpp"
#include "gltf_scene_graph.hpp"
#include "gltf_texture.hpp"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

class MeshAssembler {
 public:
  /// `allow_quantized`: integer positions are allowed (KHR_mesh_quantization).
  MeshAssembler(const Json& root, BufferStore& buffers, TextureStore& textures, bool allow_quantized,
                std::string where);

  TriangleMesh assemble(const std::vector<MeshInstance>& instances);

  /// The vertex attributes of the mesh assemble() returned (one row per vertex), moved out.
  VertexAttributes take_attributes();
  /// The base colour texture kept whole (AttributeReader::take_texture) on the assembled faces.
  SurfaceTexture take_texture(const FaceMatrix& faces) {
    return attributes_.take_texture(faces, std::move(face_image_));
  }

  /// Remarks on what was skipped, converted, transformed or read, for
  /// ReadInfo::notes (complete after take_attributes()).
  std::vector<std::string> notes() const;

 private:
  // A triangle primitive, validated but not yet read.
  struct PrimitivePlan {
    PrimitiveMode mode = PrimitiveMode::triangles;
    std::size_t position_accessor = 0;
    AccessorView positions;
    std::optional<AccessorView> indices;
    PrimitiveAttributes attributes;
    std::string where;
  };

  struct MeshPlan {
    std::vector<PrimitivePlan> primitives;
    std::size_t vertices = 0;   // per instance
    std::size_t triangles = 0;  // per instance, at most (strips and fans may drop degenerates)
  };

  const MeshPlan& plan_mesh(std::size_t mesh, const std::string& where);
  std::optional<PrimitivePlan> plan_primitive(const Json& primitive, std::string where);
  void read_instance(const MeshPlan& plan, const MeshInstance& instance);
  std::size_t append_positions(const PrimitivePlan& primitive, const MeshInstance& instance);
  void append_triangles(const PrimitivePlan& primitive, std::size_t first_vertex, bool flip);

  const Json& root_;
  BufferStore& buffers_;
  bool allow_quantized_;
  std::string where_;
  AttributeReader attributes_;
  std::map<std::size_t, MeshPlan> plans_;  // by mesh index
  std::vector<double> vertices_;           // x, y, z per vertex
  std::vector<Index> faces_;               // three per triangle
  std::vector<std::int32_t>
      face_image_;  // per triangle, its primitive's texture kept whole (AttributeReader::kept_image)

  std::size_t instances_ = 0;
  std::size_t transformed_instances_ = 0;
  std::size_t mirrored_instances_ = 0;
  std::map<std::string, std::size_t> skipped_by_mode_;
  std::size_t without_position_ = 0;
  std::size_t strips_and_fans_ = 0;
  std::size_t degenerate_dropped_ = 0;
  std::size_t trailing_ignored_ = 0;
  std::size_t attribute_conflicts_ = 0;  // primitives sharing POSITION with different attribute sources
};

}  // namespace geodual::io::detail::gltf
