// write_mesh: picks the writer by the output's extension.

#include "geodual/io/write_mesh.hpp"

#include "file_error.hpp"

#include "geodual/io/gltf.hpp"

namespace geodual::io {

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes) {
  MeshFormat format{};
  try {
    format = format_from_extension(path);
  } catch (const Error&) {
    detail::throw_file_error(path, "unknown output extension '", detail::excerpt(path.extension().string()),
                             "' (expected .ply, .obj, .glb or .gltf)");
  }
  switch (format) {
    case MeshFormat::ply: write_ply(path, mesh, attributes); return;
    case MeshFormat::obj: write_obj(path, mesh, attributes.colors); return;
    case MeshFormat::glb:
    case MeshFormat::gltf: write_gltf(path, mesh, attributes); return;
    case MeshFormat::off:
    case MeshFormat::stl:
      detail::throw_file_error(path, "writing ", format_name(format),
                               " is not supported (use .ply, .obj, .glb or .gltf)");
  }
}

}  // namespace geodual::io
