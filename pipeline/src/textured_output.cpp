#include "geodual/pipeline/textured_output.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/mesh_format.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/diagram_output.hpp"

#include <ostream>
#include <span>
#include <utility>

namespace geodual {
namespace {

/// The rows of `values` at `rows`, in order.
template <typename Matrix>
Matrix rows_at(const Matrix& values, std::span<const Index> rows) {
  if (values.rows() == 0) return values;
  Matrix picked(static_cast<Eigen::Index>(rows.size()), values.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) picked.row(static_cast<Eigen::Index>(r)) = values.row(rows[r]);
  return picked;
}

/// The attributes of the remesh's vertices carried to the atlas's copies of
/// them; the baked normals replace the remesh's own, and the vertex colours
/// go where a base colour texture replaces them.
VertexAttributes atlas_attributes(const VertexAttributes& attributes, const RemeshTextures& textures) {
  const std::vector<Index>& source = textures.atlas.source_vertex;
  VertexAttributes out;
  out.color_type = attributes.color_type;
  out.normal_type = attributes.normal_type;
  if (textures.baked.base_color.empty()) out.colors = rows_at(attributes.colors, source);
  out.normals = textures.baked.normals;
  for (const VertexScalar& scalar : attributes.scalars) {
    if (scalar.name == "texture_u" || scalar.name == "texture_v") continue;  // the atlas's own replace the input's
    VertexScalar& copy = out.scalars.emplace_back(VertexScalar{.name = scalar.name, .type = scalar.type, .values = {}});
    copy.values.reserve(source.size());
    for (const Index v : source) copy.values.push_back(scalar.values[static_cast<std::size_t>(v)]);
  }
  return out;
}

std::filesystem::path beside(const std::filesystem::path& path, const std::string& suffix) {
  std::filesystem::path side = path;
  side.replace_filename(path.stem().string() + suffix);
  return side;
}

std::filesystem::path base_color_file(const std::filesystem::path& path, io::ImageFormat format) {
  return beside(path, "_basecolor" + std::string(io::image_extension(format)));
}

std::filesystem::path normal_map_file(const std::filesystem::path& path) { return beside(path, "_normal.png"); }

io::GltfImage embedded(const TextureImage& image, io::ImageFormat format) {
  return {.bytes = io::encode_image(image, format), .mime_type = std::string(io::image_mime_type(format))};
}

void write_images(const std::filesystem::path& path, const RemeshTextures& textures) {
  if (!textures.baked.base_color.empty()) {
    io::write_image(base_color_file(path, textures.base_color_format), textures.baked.base_color,
                    textures.base_color_format);
  }
  if (!textures.baked.normal_map.empty()) {
    io::write_image(normal_map_file(path), textures.baked.normal_map, io::ImageFormat::png);
  }
}

/// The OBJ's material: white diffuse under the base colour map, the normal map
/// as `norm` (and `map_Bump`, which more readers know).
void write_material_library(const std::filesystem::path& path, const RemeshTextures& textures) {
  std::string text = "# written by geodual\nnewmtl remesh\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\n";
  if (!textures.baked.base_color.empty()) {
    text += "map_Kd " + base_color_file(path, textures.base_color_format).filename().string() + "\n";
  }
  if (!textures.baked.normal_map.empty()) {
    const std::string normal = normal_map_file(path).filename().string();
    text += "norm " + normal + "\nmap_Bump " + normal + "\n";
  }
  io::write_file_atomically(beside(path, ".mtl"), [&](std::ostream& out) { out << text; });
}

}  // namespace

std::vector<std::filesystem::path> textured_remesh_side_files(const std::filesystem::path& path,
                                                              io::ImageFormat base_color_format) {
  const std::string extension = io::lowercase_extension(path);
  if (extension != ".ply" && extension != ".obj") return {};
  std::vector<std::filesystem::path> files{base_color_file(path, base_color_format), normal_map_file(path)};
  if (extension == ".obj") files.push_back(beside(path, ".mtl"));
  return files;
}

void write_textured_remesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const VertexAttributes& attributes, const RemeshTextures& textures,
                           const std::string& extras_json, io::GltfCompression compression) {
  const remesh::TextureAtlas& atlas = textures.atlas;
  if (atlas.faces.rows() != mesh.faces.rows()) {
    throw Error(path.string() + ": the texture atlas has " + std::to_string(atlas.faces.rows()) +
                " faces for a remesh of " + std::to_string(mesh.faces.rows()));
  }
  const TriangleMesh on_atlas{.vertices = rows_at(mesh.vertices, atlas.source_vertex), .faces = atlas.faces};
  const VertexAttributes copied = atlas_attributes(attributes, textures);
  const std::string extension = io::lowercase_extension(path);
  if (extension == ".glb" || extension == ".gltf") {
    io::GltfTriangleMesh entry = io::gltf_triangle_mesh("remesh", on_atlas, copied);
    entry.texcoords = atlas.uvs.cast<float>();
    if (!textures.baked.normal_map.empty()) entry.tangents = textures.baked.tangents.cast<float>();
    if (!textures.baked.base_color.empty()) {
      entry.base_color_texture = embedded(textures.baked.base_color, textures.base_color_format);
    }
    if (!textures.baked.normal_map.empty()) {
      entry.normal_texture = embedded(textures.baked.normal_map, io::ImageFormat::png);
    }
    write_remesh_gltf(path, std::move(entry), extras_json, compression);
    return;
  }
  if (extension != ".ply" && extension != ".obj") {
    throw Error(path.string() + ": a remesh is written as .glb, .gltf, .ply or .obj");
  }
  if (compression != io::GltfCompression::none) {
    throw Error(path.string() + ": " + std::string(io::gltf_compression_name(compression)) +
                " compression is for glTF; write .glb or .gltf");
  }
  if (extension == ".obj") {
    // Everything that could fail checked or encoded before the first file is written.
    const std::string library = beside(path, ".mtl").filename().string();
    if (library.find_first_of("\r\n") != std::string::npos) throw Error(path.string() + ": a name with a line break");
    write_images(path, textures);
    write_material_library(path, textures);
    io::write_obj(path, on_atlas, copied.colors,
                  {.texcoords = atlas.uvs, .material_library = library, .material = "remesh"});
    return;
  }
  // PLY: texture_u and texture_v per vertex with v up, as MeshLab reads them.
  VertexAttributes with_uvs = copied;
  VertexScalar u{.name = "texture_u", .type = ValueType::float32, .values = {}};
  VertexScalar v{.name = "texture_v", .type = ValueType::float32, .values = {}};
  for (Eigen::Index row = 0; row < atlas.uvs.rows(); ++row) {
    u.values.push_back(atlas.uvs(row, 0));
    v.values.push_back(1 - atlas.uvs(row, 1));
  }
  with_uvs.scalars.push_back(std::move(u));
  with_uvs.scalars.push_back(std::move(v));
  if (const std::string problem = io::ply_attribute_problem(with_uvs); !problem.empty()) {
    throw Error(path.string() + ": " + problem);
  }
  const std::string texture_file =
      textures.baked.base_color.empty()
          ? (textures.baked.normal_map.empty() ? std::string() : normal_map_file(path).filename().string())
          : base_color_file(path, textures.base_color_format).filename().string();
  write_images(path, textures);
  io::write_ply(path, on_atlas, with_uvs, texture_file);
}

}  // namespace geodual
