#include "geodual/remesh/texture_bake.hpp"
#include "geodual/mesh/error.hpp"
#include "remesh/analytic_surfaces.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

namespace geodual::remesh {
namespace {

// An atlas with every face a chart of its own, in a grid of square cells:
// corners at (0.1, 0.1), (0.9, 0.1) and (0.1, 0.9) of the face's cell.
// Distorted, but every texel of it maps to one point of one face.
TextureAtlas per_face_atlas(const TriangleMesh& mesh) {
  const auto faces = mesh.num_faces();
  const int cells = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(faces))));
  TextureAtlas atlas;
  atlas.faces.resize(faces, 3);
  atlas.uvs.resize(3 * faces, 2);
  const std::array<Eigen::Vector2d, 3> corner = {Eigen::Vector2d(0.1, 0.1), Eigen::Vector2d(0.9, 0.1),
                                                 Eigen::Vector2d(0.1, 0.9)};
  for (Index f = 0; f < faces; ++f) {
    const Eigen::Vector2d origin(f % cells, f / cells);
    for (int c = 0; c < 3; ++c) {
      atlas.faces(f, c) = 3 * f + c;
      atlas.source_vertex.push_back(mesh.faces(f, c));
      atlas.uvs.row(3 * f + c) = ((origin + corner[c]) / cells).transpose();
    }
    atlas.chart_of_face.push_back(f);
  }
  atlas.charts = faces;
  return atlas;
}

// The texel's centre as a point of the atlas's face f: barycentric coordinates (or nothing outside it).
std::optional<Eigen::Vector3d> texel_in_face(const TextureAtlas& atlas, Index f, int i, int j, int size) {
  std::array<Eigen::Vector2d, 3> t;
  for (int c = 0; c < 3; ++c) t[c] = atlas.uvs.row(atlas.faces(f, c)).transpose() * size;
  Eigen::Matrix2d m;
  m << t[1] - t[0], t[2] - t[0];
  const Eigen::Vector2d ab = m.inverse() * (Eigen::Vector2d(i + 0.5, j + 0.5) - t[0]);
  const Eigen::Vector3d w(1 - ab.x() - ab.y(), ab.x(), ab.y());
  if (w.minCoeff() < 1e-9) return std::nullopt;
  return w;
}

// Calls visit(face, i, j, barycentric, point on mesh) for every texel centre strictly inside a face of the atlas.
template <typename Visit>
void for_each_texel(const TriangleMesh& mesh, const TextureAtlas& atlas, int size, Visit visit) {
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int j = 0; j < size; ++j) {
      for (int i = 0; i < size; ++i) {
        const auto w = texel_in_face(atlas, f, i, j, size);
        if (!w) continue;
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        for (int c = 0; c < 3; ++c)
          p += (*w)[c] * mesh.vertices.row(atlas.source_vertex[atlas.faces(f, c)]).transpose();
        visit(f, i, j, *w, p);
      }
    }
  }
}

// A colour field linear in linear light over the unit square: exact under
// barycentric interpolation in linear light.
Eigen::Vector3d linear_field(const Eigen::Vector3d& p) {
  return {0.1 + 0.8 * p.x(), 0.1 + 0.8 * p.y(), 0.25 + 0.5 * p.x()};
}

TEST(BakeTextures, VertexColoursAreInterpolatedInLinearLightAndStoredAsSrgb) {
  const TriangleMesh input = test::unit_square(30);
  ColorMatrix colors(input.num_vertices(), 3);
  for (Index v = 0; v < input.num_vertices(); ++v) {
    const Eigen::Vector3d linear = linear_field(input.vertices.row(v).transpose());
    for (int k = 0; k < 3; ++k) colors(v, k) = srgb_from_linear(static_cast<float>(linear[k]));
  }
  const TriangleMesh remesh = test::unit_square(3);
  const TextureAtlas atlas = per_face_atlas(remesh);
  constexpr int size = 256;
  const BakedTextures baked = bake_textures(input, {.colors = colors}, remesh, atlas, {.texture_size = size});
  ASSERT_EQ(baked.base_color.width, size);
  ASSERT_EQ(baked.base_color.channels, 3);
  EXPECT_TRUE(baked.normal_map.empty());
  int checked = 0;
  int worst = 0;
  for_each_texel(remesh, atlas, size, [&](Index, int i, int j, const Eigen::Vector3d&, const Eigen::Vector3d& p) {
    const Eigen::Vector3d linear = linear_field(p);
    const std::size_t at = baked.base_color.offset(i, j);
    for (int k = 0; k < 3; ++k) {
      const int expected = static_cast<int>(std::lround(srgb_from_linear(static_cast<float>(linear[k])) * 255));
      worst = std::max(worst, std::abs(expected - baked.base_color.texels[at + k]));
    }
    ++checked;
  });
  EXPECT_GT(checked, 10000);
  EXPECT_LE(worst, 1) << "the baked colour is the input's, interpolated in linear light, to the byte";
  EXPECT_GE(baked.texels_baked, checked);
}

TEST(BakeTextures, ChartsAreSpreadByThePaddingAndNoFurther) {
  const TriangleMesh input = test::unit_square(4);
  ColorMatrix colors = ColorMatrix::Constant(input.num_vertices(), 4, 1.0F);
  const TriangleMesh remesh = test::unit_square(1);
  const TextureAtlas atlas = per_face_atlas(remesh);  // 2 faces in a 2 x 2 grid of cells
  constexpr int size = 128;
  const BakedTextures baked =
      bake_textures(input, {.colors = colors}, remesh, atlas, {.texture_size = size, .padding = 3});
  ASSERT_EQ(baked.base_color.channels, 4);
  // Cell (1, 1) holds no face: its texels more than 3 from the charts stay empty.
  const auto alpha = [&](int i, int j) { return baked.base_color.texels[baked.base_color.offset(i, j) + 3]; };
  EXPECT_EQ(alpha(100, 100), 0);
  // Face 0's hypotenuse runs from texel (57.6, 6.4) to (6.4, 57.6); beside it, within 3 texels, all is filled.
  EXPECT_EQ(alpha(32, 32), 255) << "a texel just past the chart's border";
  EXPECT_EQ(alpha(33, 33), 255);
  EXPECT_EQ(alpha(36, 36), 0) << "more than 3 texels past the border";
  EXPECT_EQ(alpha(3, 3), 255) << "into the gutter below the chart, within 3 texels";
  EXPECT_EQ(alpha(1, 30), 0) << "more than 3 texels left of the chart (which starts at 6.4)";
}

// An independent reading of a checker texture: blocks of 8 x 8 texels, the
// block (bx, by) of sRGB colour (30 bx, 50 + 20 by, 200) on a 64 x 64 image.
TEST(BakeTextures, ATexturedInputIsSampledThroughItsCornerCoordinates) {
  const TriangleMesh input = test::unit_square(4);
  SurfaceTexture texture;
  TextureImage& image = texture.images.emplace_back(TextureImage{.width = 64, .height = 64, .channels = 3});
  image.texels.resize(64 * 64 * 3);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const std::size_t at = image.offset(x, y);
      image.texels[at] = static_cast<std::uint8_t>(30 * (x / 8));
      image.texels[at + 1] = static_cast<std::uint8_t>(50 + 20 * (y / 8));
      image.texels[at + 2] = 200;
    }
  }
  // u = x, v = 1 - y: the image upright on the square seen from +z.
  texture.corner_uvs.resize(3 * input.num_faces(), 2);
  for (Index f = 0; f < input.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const auto p = input.vertices.row(input.faces(f, c));
      texture.corner_uvs.row(3 * f + c) << p.x(), 1 - p.y();
    }
  }
  const TriangleMesh remesh = test::unit_square(2);
  const TextureAtlas atlas = per_face_atlas(remesh);
  constexpr int size = 512;
  const BakedTextures baked = bake_textures(input, {.texture = texture}, remesh, atlas, {.texture_size = size});
  int checked = 0;
  for_each_texel(remesh, atlas, size, [&](Index, int i, int j, const Eigen::Vector3d&, const Eigen::Vector3d& p) {
    const double x = p.x() * 64, y = (1 - p.y()) * 64;  // in image texels
    const double off_x = std::abs(x / 8 - std::round(x / 8)) * 8, off_y = std::abs(y / 8 - std::round(y / 8)) * 8;
    if (off_x < 1.5 || off_y < 1.5) return;  // near a block's border, where bilinear filtering mixes
    const std::size_t at = baked.base_color.offset(i, j);
    EXPECT_NEAR(baked.base_color.texels[at], 30 * static_cast<int>(x / 8), 1);
    EXPECT_NEAR(baked.base_color.texels[at + 1], 50 + 20 * static_cast<int>(y / 8), 1);
    EXPECT_NEAR(baked.base_color.texels[at + 2], 200, 1);
    ++checked;
  });
  EXPECT_GT(checked, 1000);
}

TEST(BakeTextures, EachFaceIsSampledInItsOwnImage) {
  // The unit square's left half in a red image, its right half in a blue one.
  const TriangleMesh input = test::unit_square(4);
  SurfaceTexture texture;
  for (const std::uint8_t red : {std::uint8_t{220}, std::uint8_t{30}}) {
    TextureImage& image = texture.images.emplace_back(TextureImage{.width = 4, .height = 4, .channels = 3});
    for (int t = 0; t < 16; ++t)
      image.texels.insert(image.texels.end(), {red, 60, static_cast<std::uint8_t>(250 - red)});
  }
  texture.corner_uvs =
      Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>::Constant(3 * input.num_faces(), 2, 0.5);
  for (Index f = 0; f < input.num_faces(); ++f) {
    const double x = (input.vertices(input.faces(f, 0), 0) + input.vertices(input.faces(f, 1), 0) +
                      input.vertices(input.faces(f, 2), 0)) /
                     3;
    texture.face_image.push_back(x < 0.5 ? 0 : 1);
  }
  const TriangleMesh remesh = test::unit_square(2);
  const TextureAtlas atlas = per_face_atlas(remesh);
  constexpr int size = 256;
  const BakedTextures baked = bake_textures(input, {.texture = texture}, remesh, atlas, {.texture_size = size});
  int left = 0, right = 0;
  for_each_texel(remesh, atlas, size, [&](Index, int i, int j, const Eigen::Vector3d&, const Eigen::Vector3d& p) {
    if (std::abs(p.x() - 0.5) < 0.05) return;  // the faces on either side of x = 1/2 meet there
    const std::uint8_t red = baked.base_color.texels[baked.base_color.offset(i, j)];
    EXPECT_EQ(red, p.x() < 0.5 ? 220 : 30) << p.transpose();
    ++(p.x() < 0.5 ? left : right);
  });
  EXPECT_GT(left, 1000);
  EXPECT_GT(right, 1000);
  texture.face_image[0] = 2;
  EXPECT_THROW(bake_textures(input, {.texture = texture}, remesh, atlas, {.texture_size = size}), UsageError);
}

// The shading normal a glTF viewer shows at a texel: the vertices' NORMAL and
// TANGENT interpolated, normalised, and the texel's (x, y, z) taken in that frame.
Eigen::Vector3d shown_normal(const BakedTextures& baked, const TextureAtlas& atlas, Index f, const Eigen::Vector3d& w,
                             int i, int j) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) {
    const Index v = atlas.faces(f, c);
    const Eigen::Vector3d nv = baked.normals.row(v).transpose();
    const Eigen::Vector3d tv = baked.tangents.row(v).head<3>().transpose();
    n += w[c] * nv;
    t += w[c] * tv;
    b += w[c] * nv.cross(tv) * baked.tangents(v, 3);
  }
  const std::size_t at = baked.normal_map.offset(i, j);
  Eigen::Vector3d local;
  for (int k = 0; k < 3; ++k) local[k] = baked.normal_map.texels[at + k] / 255.0 * 2 - 1;
  return (t.normalized() * local.x() + b.normalized() * local.y() + n.normalized() * local.z()).normalized();
}

double degrees_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi;
}

// A shading normal field on the unit sphere with detail a coarse remesh cannot
// show: the radial direction tilted by a smooth tangential wave.
Eigen::Vector3d detailed_normal(const Eigen::Vector3d& p) {
  const Eigen::Vector3d r = p.normalized();
  const Eigen::Vector3d wave(std::sin(5 * r.z()), std::cos(5 * r.x()), std::sin(5 * r.y()));
  return (r + 0.3 * (wave - wave.dot(r) * r)).normalized();
}

TEST(BakeTextures, TheNormalMapShowsTheInputsShadingNormalsOnACoarseSphere) {
  const TriangleMesh input = test::icosphere(5);
  VertexMatrix normals(input.num_vertices(), 3);
  for (Index v = 0; v < input.num_vertices(); ++v) {
    normals.row(v) = detailed_normal(input.vertices.row(v).transpose()).transpose();
  }
  const TriangleMesh remesh = test::icosphere(1);  // 80 flat faces
  const TextureAtlas atlas = per_face_atlas(remesh);
  constexpr int size = 512;
  const BakedTextures baked =
      bake_textures(input, {.normals = normals}, remesh, atlas, {.texture_size = size, .normal_map = true});
  ASSERT_EQ(baked.normal_map.channels, 3);
  ASSERT_EQ(baked.tangents.rows(), atlas.uvs.rows());
  EXPECT_TRUE(baked.base_color.empty()) << "no colour in the source";
  for (Eigen::Index v = 0; v < baked.tangents.rows(); ++v) {
    EXPECT_NEAR(baked.tangents.row(v).head<3>().norm(), 1, 1e-9);
    EXPECT_NEAR(baked.tangents.row(v).head<3>().dot(baked.normals.row(v)), 0, 1e-9);
    EXPECT_EQ(std::abs(baked.tangents(v, 3)), 1);
  }
  double mapped_sum = 0, mapped_worst = 0, smooth_sum = 0, flat_sum = 0;
  int count = 0;
  for_each_texel(remesh, atlas, size, [&](Index f, int i, int j, const Eigen::Vector3d& w, const Eigen::Vector3d& p) {
    const Eigen::Vector3d truth = detailed_normal(p);  // where the remesh's point projects onto the sphere
    const double mapped = degrees_between(shown_normal(baked, atlas, f, w, i, j), truth);
    Eigen::Vector3d smooth = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) smooth += w[c] * baked.normals.row(atlas.faces(f, c)).transpose();
    std::array<Eigen::Vector3d, 3> corner;
    for (int c = 0; c < 3; ++c) corner[c] = remesh.vertices.row(remesh.faces(f, c)).transpose();
    const Eigen::Vector3d flat = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
    mapped_sum += mapped;
    mapped_worst = std::max(mapped_worst, mapped);
    smooth_sum += degrees_between(smooth.normalized(), truth);
    flat_sum += degrees_between(flat, truth);
    ++count;
  });
  ASSERT_GT(count, 20000);
  EXPECT_LT(mapped_sum / count, 0.8) << "mean error of the normal-mapped shading, degrees";
  EXPECT_LT(mapped_worst, 3.0);
  EXPECT_GT(smooth_sum / count, 5 * (mapped_sum / count)) << "smooth shading alone misses the detail";
  EXPECT_GT(flat_sum / count, 5 * (mapped_sum / count)) << "and so does flat shading";
}

TEST(BakeTextures, TheBytesDoNotDependOnTheThreads) {
  const TriangleMesh input = test::icosphere(4);
  ColorMatrix colors(input.num_vertices(), 3);
  for (Index v = 0; v < input.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) colors(v, k) = static_cast<float>(0.5 + 0.5 * input.vertices(v, k));
  }
  const TriangleMesh remesh = test::icosphere(2);
  const TextureAtlas atlas = per_face_atlas(remesh);
  const BakeOptions options{.texture_size = 256, .normal_map = true};
  BakedTextures one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_textures(input, {.colors = colors}, remesh, atlas, options);
  }
  const BakedTextures all = bake_textures(input, {.colors = colors}, remesh, atlas, options);
  EXPECT_EQ(one.base_color.texels, all.base_color.texels);
  EXPECT_EQ(one.normal_map.texels, all.normal_map.texels);
}

TEST(BakeTextures, RefusesSizesThatDoNotMatch) {
  const TriangleMesh input = test::unit_square(2);
  const TriangleMesh remesh = test::unit_square(1);
  const TextureAtlas atlas = per_face_atlas(remesh);
  EXPECT_THROW(bake_textures(input, {.colors = ColorMatrix::Zero(3, 3)}, remesh, atlas), UsageError);
  EXPECT_THROW(bake_textures(input, {.normals = VertexMatrix::Zero(2, 3)}, remesh, atlas), UsageError);
  EXPECT_THROW(bake_textures(input, {}, test::unit_square(2), atlas), UsageError);
  EXPECT_THROW(bake_textures(input, {}, remesh, atlas, {.texture_size = 0}), UsageError);
  EXPECT_THROW(bake_textures(input, {}, remesh, atlas, {.padding = -1}), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
