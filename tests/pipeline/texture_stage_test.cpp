// The pipeline's texture stage is the public stages in a row: the atlas with
// atlas_seams, bake_textures on the input's look, byte for byte; a textured
// input's seams welded by weld_texture_seams.

#include "geodual/io/read_mesh.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/remesh/texture_atlas.hpp"
#include "geodual/remesh/texture_bake.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  input.texture.image = {.width = 1, .height = 1, .channels = 3, .texels = {9, 9, 9}};
  input.texture.corner_uvs = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>::Zero(6, 2);
  const std::vector<Index> welded = pipeline::weld_texture_seams(input);
  EXPECT_EQ(welded, (std::vector<Index>{0, 1, 2, 2, 3, 0}));
  EXPECT_EQ(input.mesh.num_vertices(), 4);
  EXPECT_EQ(input.mesh.faces, (FaceMatrix{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(input.attributes.colors, (ColorMatrix{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}}));
  EXPECT_EQ(input.texture.corner_uvs.rows(), 6) << "the corners keep their coordinates";
  EXPECT_FALSE(input.info.notes.empty());
}

}  // namespace
}  // namespace geodual
