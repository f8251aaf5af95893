#include "geodual/io/mesh_format.hpp"

#include "geodual/error.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace geodual::io {

MeshFormat format_from_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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
