// glTF 2.0 writing: the public entry points of geodual/io/gltf.hpp. The scene
// becomes a tinygltf::Model (gltf_model_builder.hpp), which tinygltf writes
// (and gltf_meshopt_views.hpp completes for meshopt compression); this file
// picks the container and writes atomically.

#include "geodual/io/gltf.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/mesh_format.hpp"
#include "geodual/mesh/error.hpp"
#include "gltf_asset_extras.hpp"
#include "gltf_meshopt_views.hpp"
#include "gltf_model_builder.hpp"

#include <cstdint>
#include <limits>
#include <ostream>
#include <sstream>

namespace geodual::io {
namespace {

constexpr std::string_view unnamed_output = "glTF output";

std::vector<std::byte> write_model(const detail::gltf::ModelBuilder& builder, tinygltf::Model model,
                                   const detail::gltf::AssetExtras& extras, GltfContainer container,
                                   const std::string& where) {
  model.asset.extras = extras.placeholder();
  const bool glb = container == GltfContainer::glb;
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false, /*writeBinary=*/glb) || !stream) {
    throw Error(where + ": tinygltf could not write the glTF file");
  }
  std::string file = std::move(stream).str();
  if (!builder.meshopt_views().empty()) detail::gltf::add_meshopt_views(file, glb, builder.meshopt_views());
  if (glb && file.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error(where + ": " + std::to_string(file.size()) +
                " bytes do not fit a GLB file (at most 4 GiB); write fewer or smaller meshes");
  }
  extras.fill_in(file);
  const auto* begin = reinterpret_cast<const std::byte*>(file.data());
  return {begin, begin + file.size()};
}

std::vector<std::byte> encode_scene(const GltfScene& scene, GltfContainer container, const std::string& where) {
  detail::gltf::ModelBuilder builder(where, scene.compression);
  for (const GltfTriangleMesh& entry : scene.triangle_meshes) {
    builder.add_triangles(entry.name, entry.mesh, entry);
  }
  for (const GltfLineSet& entry : scene.line_sets) builder.add_lines(entry);
  for (const GltfPointSet& entry : scene.point_sets) builder.add_points(entry);
  tinygltf::Model model = builder.finish();
  model.asset.generator = scene.generator;
  return write_model(builder, std::move(model), detail::gltf::AssetExtras(scene.extras_json, where), container, where);
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

std::string_view gltf_compression_name(GltfCompression compression) {
  switch (compression) {
    case GltfCompression::none: return "none";
    case GltfCompression::meshopt: return "meshopt";
    case GltfCompression::draco: return "draco";
  }
  return "?";
}

std::vector<std::byte> encode_gltf(const GltfScene& scene, GltfContainer container) {
  return encode_scene(scene, container, std::string(unnamed_output));
}

void write_gltf(const std::filesystem::path& path, const GltfScene& scene) {
  const GltfContainer container = container_for(path);
  write_bytes(path, encode_scene(scene, container, path.string()));
}

GltfTriangleMesh gltf_triangle_mesh(std::string name, TriangleMesh mesh, const VertexAttributes& attributes) {
  GltfTriangleMesh entry{.name = std::move(name), .mesh = std::move(mesh)};
  entry.colors = attributes.colors.unaryExpr([](float c) { return linear_from_srgb(c); });
  if (entry.colors.cols() == 4) entry.colors.col(3) = attributes.colors.col(3);  // alpha is linear already
  entry.normals = attributes.normals;
  for (const VertexScalar& scalar : attributes.scalars) {
    GltfVertexScalar& out = entry.scalars.emplace_back();
    out.name = "_" + scalar.name;
    out.values.assign(scalar.values.begin(), scalar.values.end());  // float32: glTF's one scalar type
  }
  return entry;
}

void write_gltf(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes,
                GltfCompression compression) {
  const GltfContainer container = container_for(path);
  if (!attributes.empty()) {
    GltfScene scene{.triangle_meshes = {gltf_triangle_mesh({}, mesh, attributes)}, .compression = compression};
    write_bytes(path, encode_scene(scene, container, path.string()));
    return;
  }
  detail::gltf::ModelBuilder builder(path.string(), compression);
  builder.add_triangles({}, mesh, GltfTriangleMesh{});  // no copy of the mesh
  tinygltf::Model model = builder.finish();
  write_bytes(path, write_model(builder, std::move(model), detail::gltf::AssetExtras({}, path.string()), container,
                                path.string()));
}

}  // namespace geodual::io
