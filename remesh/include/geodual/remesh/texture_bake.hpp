#pragma once
// Textures baked onto a remesh's atlas (texture_atlas.hpp) from the input it
// was made of: every texel whose centre lies in a chart's triangle takes the
// input's base colour -- from its texture or its vertex colours -- and shading
// normal at the input's point nearest to the texel's point on the remesh.
// Colours are interpolated in linear light and stored sRGB-encoded; the normal
// map is in the tangent space of the TANGENT frames returned with it, as glTF
// viewers rebuild it. Charts' colours are then spread a few texels past their
// borders (edge padding), so that filtering and mip-maps do not mix in the
// background. See docs/algorithms.md#baking.
//
//   auto atlas = geodual::remesh::make_texture_atlas(remesh, {.texture_size = 2048});
//   auto baked = geodual::remesh::bake_textures(input, {.colors = colors}, remesh, atlas, {.normal_map = true});

#include "geodual/mesh/texture_image.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "geodual/remesh/texture_atlas.hpp"

#include <Eigen/Core>

#include <cstdint>

namespace geodual::remesh {

/// What is baked from: the input's appearance. The base colour is the
/// texture's where there is one, else the vertex colours; the shading normals
/// are `normals`, or the input's angle-weighted vertex normals where empty.
struct BakeSource {
  ColorMatrix colors{};      ///< sRGB-encoded, one row per input vertex, or empty
  VertexMatrix normals{};    ///< one row per input vertex, or empty
  SurfaceTexture texture{};  ///< or empty
};

struct BakeOptions {
  /// The texture's texels per side: the atlas's AtlasOptions::texture_size.
  int texture_size = 2048;
  /// Texels the charts' colours (and normals) are spread past their borders.
  int padding = 4;
  bool base_color = true;   ///< bake the base colour (where the source has one)
  bool normal_map = false;  ///< bake a tangent-space normal map
};

struct BakedTextures {
  /// sRGB-encoded RGB, or RGBA where the source has alpha; empty where not baked.
  TextureImage base_color;
  /// Tangent-space normals (x, y, z) in [-1, 1] stored as RGB (c + 1) / 2; empty where not baked.
  TextureImage normal_map;
  /// Per atlas vertex, its shading normal (the remesh's angle-weighted vertex
  /// normal, unit) and, with a normal map, its tangent (x, y, z, w): unit xyz
  /// perpendicular to the normal along increasing u, and w = +-1 such that
  /// cross(normal, tangent) w points along decreasing v (glTF's TANGENT).
  VertexMatrix normals;
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> tangents;
  std::int64_t texels_baked = 0;  ///< texels whose centres lie in a chart's triangle
};

/// \throw geodual::UsageError naming the first option out of range.
void check_options(const BakeOptions& options);

/// Bakes `source` (the appearance of `input`) onto `atlas`, the atlas of
/// `remesh`. Deterministic, whatever the number of threads. \throw
/// geodual::UsageError as check_options, or where the source's or the
/// atlas's sizes do not match their meshes.
BakedTextures bake_textures(const TriangleMesh& input, const BakeSource& source, const TriangleMesh& remesh,
                            const TextureAtlas& atlas, const BakeOptions& options = {});

}  // namespace geodual::remesh
