#pragma once
// Writing a remesh with its texture atlas and the textures baked onto it
// (RemeshPipelineResult::atlas and ::textures). docs/formats.md#textures.

#include "geodual/io/gltf.hpp"
#include "geodual/io/image_file.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "geodual/remesh/texture_atlas.hpp"
#include "geodual/remesh/texture_bake.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace geodual {

struct RemeshTextures {
  const remesh::TextureAtlas& atlas;
  const remesh::BakedTextures& baked;
  /// The base colour's format; the normal map is always PNG (lossless).
  io::ImageFormat base_color_format = io::ImageFormat::png;
};

/// The files a textured remesh at `path` may consist of besides itself:
/// for .ply and .obj, the images beside it (<stem>_basecolor.png or .jpg as
/// `base_color_format` says, <stem>_normal.png) and, for .obj, <stem>.mtl;
/// none for glTF, which embeds its images. To check before the work that
/// none of them is an input.
std::vector<std::filesystem::path> textured_remesh_side_files(const std::filesystem::path& path,
                                                              io::ImageFormat base_color_format);

/// The remesh on the atlas's vertices (copies of its own along the seams,
/// each with its attributes), by extension:
///  - .glb / .gltf: TEXCOORD_0, the baked normals as NORMAL, TANGENT with a
///    normal map, and a material with the images embedded (baseColorTexture,
///    normalTexture); vertex colours are left out where a base colour texture
///    replaces them (glTF would multiply the two); `extras_json` and
///    `compression` as write_remesh;
///  - .obj: "vt" per vertex, "f a/a b/b c/c", and a .mtl (map_Kd, norm)
///    beside it with the images;
///  - .ply: texture_u and texture_v per vertex (v up, as MeshLab reads them),
///    "comment TextureFile <image>", and the images beside it.
/// Every file is written atomically, the images first. \throw geodual::Error
/// as write_remesh.
void write_textured_remesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const VertexAttributes& attributes, const RemeshTextures& textures,
                           const std::string& extras_json = {},
                           io::GltfCompression compression = io::GltfCompression::none);

}  // namespace geodual
