// The pipeline's texture stage is the public stages in a row: the atlas with
// atlas_seams, bake_textures on the input's look, byte for byte; a textured
// input's seams welded by weld_texture_seams.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/remesh/texture_atlas.hpp"
#include "geodual/remesh/texture_bake.hpp"
#include "procedural_texture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace geodual {
namespace {

TEST(TextureStage, IsTheAtlasAndTheBakeInARowByteForByte) {
  io::LoadedMesh loaded = io::read_mesh("tests/data/bunny.ply");
  // Vertex colours from the position, so that there is a base colour to bake.
  loaded.attributes.colors.resize(loaded.mesh.num_vertices(), 3);
  for (Index v = 0; v < loaded.mesh.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      loaded.attributes.colors(v, k) = static_cast<float>(0.5 + 0.5 * std::sin(60 * loaded.mesh.vertices(v, k)));
    }
  }
  const io::LoadedMesh input = loaded;
  pipeline::RemeshPipelineOptions options;
  options.sites = 600;
  options.statistics = false;
  options.texture_size = 256;
  options.bake_normal_map = true;
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(std::move(loaded), options);
  ASSERT_TRUE(result.atlas.has_value());
  EXPECT_FALSE(result.textures.base_color.empty());
  EXPECT_FALSE(result.textures.normal_map.empty());

  const TriangleMesh& remeshed = result.remesh.mesh;
  const remesh::TextureAtlas atlas =
      remesh::make_texture_atlas(remeshed, {.texture_size = 256, .seams = pipeline::atlas_seams(remeshed, 60)});
  EXPECT_EQ(atlas.uvs, result.atlas->uvs);
  EXPECT_EQ(atlas.faces, result.atlas->faces);
  const remesh::BakedTextures baked = remesh::bake_textures(input.mesh, {.colors = input.attributes.colors}, remeshed,
                                                            atlas, {.texture_size = 256, .normal_map = true});
  EXPECT_EQ(baked.base_color.texels, result.textures.base_color.texels);
  EXPECT_EQ(baked.normal_map.texels, result.textures.normal_map.texels);
  EXPECT_EQ(baked.tangents, result.textures.tangents);

  // Seams: the remesh's edges turning by 60 degrees or more are cut in the
  // atlas (the faces on either side use different copies of the edge's ends).
  for (const auto& [a, b] : pipeline::atlas_seams(remeshed, 60)) {
    std::vector<Index> faces_of_edge;
    for (Index f = 0; f < remeshed.num_faces(); ++f) {
      const auto row = remeshed.faces.row(f);
      if ((row.array() == a).any() && (row.array() == b).any()) faces_of_edge.push_back(f);
    }
    if (faces_of_edge.size() != 2) continue;
    const auto copies = [&](Index f) {
      std::vector<Index> ends;
      for (int c = 0; c < 3; ++c) {
        const Index copy = atlas.faces(f, c);
        if (atlas.source_vertex[copy] == a || atlas.source_vertex[copy] == b) ends.push_back(copy);
      }
      std::sort(ends.begin(), ends.end());
      return ends;
    };
    EXPECT_NE(copies(faces_of_edge[0]), copies(faces_of_edge[1]));
  }
}

TEST(TextureStage, WeldTextureSeamsJoinsCopiesAndKeepsTheFirstCopysAttributes) {
  io::LoadedMesh input;
  // Two triangles of a square, the diagonal's vertices copied (a seam).
  input.mesh.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
  input.mesh.faces = FaceMatrix{{0, 1, 2}, {5, 3, 4}};
  input.attributes.colors = ColorMatrix{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  EXPECT_TRUE(pipeline::weld_texture_seams(input).empty()) << "no texture: nothing welded";
  input.texture.images = {{.width = 1, .height = 1, .channels = 3, .texels = {9, 9, 9}}};
  input.texture.corner_uvs = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>::Zero(6, 2);
  const std::vector<Index> welded = pipeline::weld_texture_seams(input);
  EXPECT_EQ(welded, (std::vector<Index>{0, 1, 2, 2, 3, 0}));
  EXPECT_EQ(input.mesh.num_vertices(), 4);
  EXPECT_EQ(input.mesh.faces, (FaceMatrix{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(input.attributes.colors, (ColorMatrix{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}}));
  EXPECT_EQ(input.texture.corner_uvs.rows(), 6) << "the corners keep their coordinates";
  EXPECT_FALSE(input.info.notes.empty());
}

// The textured scan of the texture benchmark (spot painted with the
// procedural colour f, bench/procedural_texture.hpp), remeshed at 1,500
// sites: the baked texture, read at the remesh's vertices as a viewer reads
// it, keeps f's checker where today's per-vertex colours blur it.
TEST(TextureStage, ATexturedScanKeepsItsLook) {
  io::LoadedMesh loaded = io::read_mesh("tests/data/textured/spot_procedural.glb");
  ASSERT_FALSE(loaded.texture.empty());
  const TriangleMesh input = loaded.mesh;
  const bench::ProceduralTexture f = bench::ProceduralTexture::of(loaded.mesh);
  pipeline::RemeshPipelineOptions options;
  options.sites = 1500;
  options.statistics = false;
  options.texture_size = 1024;
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(std::move(loaded), options);
  ASSERT_TRUE(result.atlas.has_value());
  EXPECT_EQ(result.remesh.mesh.num_vertices(), 1500);
  const TextureImage& image = result.textures.base_color;
  ASSERT_EQ(image.channels, 3);
  // At each atlas face's centroid: the baked texture (bilinear in linear
  // light, as a GPU samples an sRGB texture) against f there, and today's
  // vertex colours interpolated there, in sRGB 0-255 units.
  const auto sample = [&](const Eigen::Vector2d& uv) {
    const double x = uv.x() * image.width - 0.5, y = uv.y() * image.height - 0.5;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    Eigen::Vector3d linear = Eigen::Vector3d::Zero();
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const double weight = (dx ? x - x0 : 1 - (x - x0)) * (dy ? y - y0 : 1 - (y - y0));
        const std::size_t at =
            image.offset(std::clamp(x0 + dx, 0, image.width - 1), std::clamp(y0 + dy, 0, image.height - 1));
        for (int k = 0; k < 3; ++k) linear[k] += weight * linear_from_srgb(image.texels[at + k] / 255.0F);
      }
    }
    return linear;
  };
  const remesh::TextureAtlas& atlas = *result.atlas;
  std::vector<double> baked_errors, vertex_errors;
  for (Eigen::Index face = 0; face < atlas.faces.rows(); ++face) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), vertex_color = Eigen::Vector3d::Zero();
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index copy = atlas.faces(face, c);
      const Index v = atlas.source_vertex[copy];
      p += result.remesh.mesh.vertices.row(v).transpose() / 3;
      uv += atlas.uvs.row(copy).transpose() / 3;
      for (int k = 0; k < 3; ++k) vertex_color[k] += linear_from_srgb(result.attributes.colors(v, k)) / 3;
    }
    // f where the point stands on the input: its nearest point there (by brute force).
    Eigen::Vector3d nearest = p;
    double best = std::numeric_limits<double>::infinity();
    for (Index g = 0; g < input.num_faces(); ++g) {
      const Eigen::Vector3d a = input.vertices.row(input.faces(g, 0)), b = input.vertices.row(input.faces(g, 1)),
                            c = input.vertices.row(input.faces(g, 2));
      const Eigen::Vector3d w = nearest_point_on_triangle(p, a, b, c);
      const Eigen::Vector3d q = w[0] * a + w[1] * b + w[2] * c;
      if ((q - p).squaredNorm() < best) best = (q - p).squaredNorm(), nearest = q;
    }
    const Eigen::Vector3d truth = f.color(nearest) * 255;
    const Eigen::Vector3d texel = sample(uv);
    double baked = 0, vertex = 0;
    for (int k = 0; k < 3; ++k) {
      baked = std::max(baked, std::abs(255 * srgb_from_linear(static_cast<float>(texel[k])) - truth[k]));
      vertex = std::max(vertex, std::abs(255 * srgb_from_linear(static_cast<float>(vertex_color[k])) - truth[k]));
    }
    baked_errors.push_back(baked);
    vertex_errors.push_back(vertex);
  }
  const auto mean = [](const std::vector<double>& values) {
    return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  };
  EXPECT_LT(mean(baked_errors), 6.0) << "the input itself is about 2 units from f";
  EXPECT_GT(mean(vertex_errors), 5 * mean(baked_errors)) << "per-vertex colours blur the checker";
}

}  // namespace
}  // namespace geodual
