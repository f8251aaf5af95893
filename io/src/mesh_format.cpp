#include "geodual/io/mesh_format.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/mesh/error.hpp"

#include <string>

namespace geodual::io {

MeshFormat format_from_extension(const std::filesystem::path& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".obj") return MeshFormat::obj;
  if (ext == ".ply") return MeshFormat::ply;
  if (ext == ".off") return MeshFormat::off;
  if (ext == ".stl") return MeshFormat::stl;
  if (ext == ".gltf") return MeshFormat::gltf;
  if (ext == ".glb") return MeshFormat::glb;
  throw Error(path.string() + ": unknown mesh file extension '" + ext +
              "' (expected .obj, .ply, .off, .stl, .gltf or .glb)");
}

std::string_view format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj: return "OBJ";
    case MeshFormat::ply: return "PLY";
    case MeshFormat::off: return "OFF";
    case MeshFormat::stl: return "STL";
    case MeshFormat::gltf: return "glTF";
    case MeshFormat::glb: return "GLB";
  }
  return "unknown";
}

}  // namespace geodual::io
