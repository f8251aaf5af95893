// glTF 2.0 writing: the public entry points of geodual/io/gltf.hpp. The
// format work is in gltf_encoder.cpp; this file picks the container and
// writes atomically.

#include "geodual/io/gltf.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/io/atomic_file.hpp"
#include "geodual/io/mesh_format.hpp"
#include "gltf_encoder.hpp"

#include <ostream>

namespace geodual::io {
namespace {

constexpr std::string_view unnamed_output = "glTF output";

std::vector<std::byte> encode_scene(const GltfScene& scene, GltfContainer container, std::string where) {
  detail::gltf::Encoder encoder(std::move(where));
  for (const GltfTriangleMesh& entry : scene.triangle_meshes) {
    encoder.add_triangles(entry.name, entry.mesh, entry.colors, entry.scalars);
  }
  for (const GltfLineSet& entry : scene.line_sets) encoder.add_lines(entry);
  for (const GltfPointSet& entry : scene.point_sets) encoder.add_points(entry);
  return encoder.finish(container, scene.extras_json);
}

GltfContainer container_for(const std::filesystem::path& path) {
  switch (format_from_extension(path)) {
    case MeshFormat::glb: return GltfContainer::glb;
    case MeshFormat::gltf: return GltfContainer::gltf_embedded;
    default: throw Error(path.string() + ": a glTF file name must end in .glb or .gltf");
  }
}

void write_bytes(const std::filesystem::path& path, const std::vector<std::byte>& bytes) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace

std::vector<std::byte> encode_gltf(const GltfScene& scene, GltfContainer container) {
  return encode_scene(scene, container, std::string(unnamed_output));
}

void write_gltf(const std::filesystem::path& path, const GltfScene& scene) {
  const GltfContainer container = container_for(path);
  write_bytes(path, encode_scene(scene, container, path.string()));
}

void write_gltf(const std::filesystem::path& path, const TriangleMesh& mesh) {
  const GltfContainer container = container_for(path);
  detail::gltf::Encoder encoder(path.string());
  encoder.add_triangles({}, mesh, ColorMatrix{}, {});  // no copy of the mesh
  write_bytes(path, encoder.finish(container, {}));
}

}  // namespace geodual::io
