#include "geodual/remesh/texture_atlas.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/union_find.hpp"
#include "remesh/analytic_surfaces.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>

namespace geodual::remesh {
namespace {

using test::icosphere;
using test::torus;
using test::unit_square;

Eigen::Vector2d texel_point(const TextureAtlas& atlas, Index v, double scale) {
  return scale * atlas.uvs.row(v).transpose();
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Twice face f's signed area in image coordinates (x = u size, y = v size).
double twice_signed_area(const TextureAtlas& atlas, Index f, double size) {
  const Eigen::Vector2d a = texel_point(atlas, atlas.faces(f, 0), size);
  const Eigen::Vector2d b = texel_point(atlas, atlas.faces(f, 1), size);
  const Eigen::Vector2d c = texel_point(atlas, atlas.faces(f, 2), size);
  return cross(b - a, c - a);
}

/// Whether triangle (a, b, c) and the square [x, x + 1] x [y, y + 1] share a
/// point: no separating axis among the square's two and the triangle's three
/// edge normals.
bool triangle_touches_square(const Eigen::Vector2d (&p)[3], int x, int y) {
  const double sign = cross(p[1] - p[0], p[2] - p[0]) < 0 ? -1.0 : 1.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& a = p[k];
    const Eigen::Vector2d edge = p[(k + 1) % 3] - a;
    bool all_outside = true;
    for (int corner = 0; corner < 4 && all_outside; ++corner) {
      const Eigen::Vector2d q(x + (corner & 1), y + (corner >> 1));
      all_outside = sign * cross(edge, q - a) < 0;
    }
    if (all_outside) return false;
  }
  return true;
}

/// Per texel, the chart whose triangles touch it (-1: none, -2: several).
std::vector<Index> chart_texels(const TextureAtlas& atlas, int size) {
  std::vector<Index> owner(static_cast<std::size_t>(size) * size, -1);
  for (Index f = 0; f < atlas.faces.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) p[k] = texel_point(atlas, atlas.faces(f, k), size);
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(size - 1, static_cast<int>(std::floor(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(size - 1, static_cast<int>(std::floor(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (!triangle_touches_square(p, x, y)) continue;
        Index& o = owner[static_cast<std::size_t>(y) * size + x];
        const Index chart = atlas.chart_of_face[f];
        o = o == -1 || o == chart ? chart : -2;
      }
    }
  }
  return owner;
}

/// Texel centres of a grid `resolution` cells a side claimed by two faces
/// (strictly inside both).
long doubly_covered(const TextureAtlas& atlas, int resolution) {
  std::vector<std::uint8_t> count(static_cast<std::size_t>(resolution) * resolution, 0);
  long twice = 0;
  for (Index f = 0; f < atlas.faces.rows(); ++f) {
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) p[k] = texel_point(atlas, atlas.faces(f, k), resolution);
    const double sign = cross(p[1] - p[0], p[2] - p[0]) < 0 ? -1.0 : 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(resolution - 1, static_cast<int>(std::floor(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(resolution - 1, static_cast<int>(std::floor(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d centre(x + 0.5, y + 0.5);
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) inside = sign * cross(p[(k + 1) % 3] - p[k], centre - p[k]) > 0;
        if (inside && count[static_cast<std::size_t>(y) * resolution + x]++ > 0) ++twice;
      }
    }
  }
  return twice;
}

/// Per chart, its faces as a surface on the atlas's vertices: connected,
/// one boundary loop, Euler characteristic 1.
void expect_charts_are_disks(const TextureAtlas& atlas) {
  std::vector<std::vector<Index>> faces_of(atlas.charts);
  for (Index f = 0; f < atlas.faces.rows(); ++f) faces_of[atlas.chart_of_face[f]].push_back(f);
  for (Index c = 0; c < atlas.charts; ++c) {
    const std::vector<Index>& faces = faces_of[c];
    ASSERT_FALSE(faces.empty()) << "chart " << c;
    std::map<std::array<Index, 2>, std::vector<Index>> edge_faces;
    std::set<Index> vertices;
    for (const Index f : faces) {
      for (int k = 0; k < 3; ++k) {
        const Index a = atlas.faces(f, k), b = atlas.faces(f, (k + 1) % 3);
        edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
        vertices.insert(a);
      }
    }
    UnionFind joined(atlas.faces.rows());
    std::map<Index, Index> boundary_next;  // boundary edges as directed in their face
    for (const auto& [edge, incident] : edge_faces) {
      ASSERT_LE(incident.size(), 2u) << "chart " << c;
      if (incident.size() == 2) joined.unite(incident[0], incident[1]);
    }
    for (const Index f : faces) {
      EXPECT_EQ(joined.find(f), joined.find(faces.front())) << "chart " << c << " is not connected";
      for (int k = 0; k < 3; ++k) {
        const Index a = atlas.faces(f, k), b = atlas.faces(f, (k + 1) % 3);
        if (edge_faces[{std::min(a, b), std::max(a, b)}].size() == 1) {
          EXPECT_TRUE(boundary_next.emplace(a, b).second) << "chart " << c << " pinches at atlas vertex " << a;
        }
      }
    }
    const auto chi =
        static_cast<long>(vertices.size()) - static_cast<long>(edge_faces.size()) + static_cast<long>(faces.size());
    EXPECT_EQ(chi, 1) << "chart " << c;
    long loops = 0;
    std::set<Index> seen;
    for (const auto& [start, next] : boundary_next) {
      if (seen.count(start)) continue;
      ++loops;
      for (Index v = start; v >= 0 && seen.insert(v).second;) {
        const auto at = boundary_next.find(v);
        v = at == boundary_next.end() ? -1 : at->second;
      }
    }
    EXPECT_EQ(loops, 1) << "chart " << c;
  }
}

/// Everything the atlas promises, checked face by face and texel by texel.
void expect_valid_atlas(const TriangleMesh& mesh, const TextureAtlas& atlas, const AtlasOptions& options) {
  const int size = options.texture_size;
  ASSERT_EQ(atlas.faces.rows(), mesh.faces.rows());
  ASSERT_EQ(atlas.uvs.rows(), static_cast<Eigen::Index>(atlas.source_vertex.size()));
  ASSERT_EQ(atlas.chart_of_face.size(), static_cast<std::size_t>(mesh.num_faces()));
  ASSERT_GE(atlas.charts, 1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    ASSERT_GE(atlas.chart_of_face[f], 0);
    ASSERT_LT(atlas.chart_of_face[f], atlas.charts);
    for (int k = 0; k < 3; ++k) {
      const Index v = atlas.faces(f, k);
      ASSERT_GE(v, 0);
      ASSERT_LT(v, atlas.uvs.rows());
      // The atlas's faces map back to the mesh's exactly.
      ASSERT_EQ(atlas.source_vertex[v], mesh.faces(f, k)) << "face " << f;
    }
    // Counter-clockwise seen as an image (y down): negative in (u, v) with v up.
    EXPECT_LT(twice_signed_area(atlas, f, size), 0) << "face " << f << " flipped or degenerate";
  }
  // Every copy of a vertex serves one chart.
  std::vector<Index> chart_of_vertex(atlas.uvs.rows(), -1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      Index& chart = chart_of_vertex[atlas.faces(f, k)];
      EXPECT_TRUE(chart == -1 || chart == atlas.chart_of_face[f]);
      chart = atlas.chart_of_face[f];
    }
  }
  const double margin = static_cast<double>(options.gutter) / size;
  for (Index v = 0; v < atlas.uvs.rows(); ++v) {
    ASSERT_TRUE(atlas.uvs.row(v).allFinite()) << "atlas vertex " << v;
    EXPECT_GE(atlas.uvs.row(v).minCoeff(), margin) << "atlas vertex " << v;
    EXPECT_LE(atlas.uvs.row(v).maxCoeff(), 1 - margin) << "atlas vertex " << v;
  }
  expect_charts_are_disks(atlas);

  // No two triangles overlap, at four samples a texel.
  EXPECT_EQ(doubly_covered(atlas, std::min(4 * size, 4096)), 0);
  // Charts 2 gutter texels apart and gutter texels from the border: a
  // texel a chart touches has no other chart's texel within 2 gutter.
  const std::vector<Index> owner = chart_texels(atlas, size);
  const int reach = 2 * options.gutter;
  long too_close = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const Index chart = owner[static_cast<std::size_t>(y) * size + x];
      if (chart == -1) continue;
      if (chart == -2 || x < options.gutter || y < options.gutter || x >= size - options.gutter ||
          y >= size - options.gutter) {
        ++too_close;
        continue;
      }
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
          const Index other = owner[static_cast<std::size_t>(yy) * size + xx];
          if (other != -1 && other != chart) ++too_close;
        }
      }
    }
  }
  EXPECT_EQ(too_close, 0);
  EXPECT_GT(atlas.texture_used, 0);
  EXPECT_LE(atlas.texture_used, 1);
}

void report(const char* name, const TriangleMesh& mesh, const TextureAtlas& atlas, double seconds) {
  std::vector<Index> chart_faces(atlas.charts, 0);
  for (const Index c : atlas.chart_of_face) ++chart_faces[c];
  const auto small = std::count_if(chart_faces.begin(), chart_faces.end(), [](Index faces) { return faces < 10; });
  std::cout << name << ": " << mesh.num_vertices() << " vertices, " << mesh.num_faces() << " faces, " << atlas.charts
            << " charts (" << small << " of fewer than 10 faces), texture used " << atlas.texture_used
            << ", area distortion mean " << atlas.mean_area_distortion << " max " << atlas.max_area_distortion
            << ", angle distortion mean " << atlas.mean_angle_distortion << " max " << atlas.max_angle_distortion
            << " deg, " << seconds << " s\n";
}

TextureAtlas timed_atlas(const char* name, const TriangleMesh& mesh, const AtlasOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  TextureAtlas atlas = make_texture_atlas(mesh, options);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  report(name, mesh, atlas, elapsed.count());
  return atlas;
}

AtlasOptions small_texture(int size, int gutter) {
  AtlasOptions options;
  options.texture_size = size;
  options.gutter = gutter;
  return options;
}

TEST(TextureAtlas, FlatSquareIsOneChartWithoutDistortion) {
  const TriangleMesh square = unit_square(8);
  const AtlasOptions options;
  const TextureAtlas atlas = make_texture_atlas(square, options);
  EXPECT_EQ(atlas.charts, 1);
  EXPECT_EQ(atlas.uvs.rows(), square.vertices.rows());
  EXPECT_LT(atlas.max_angle_distortion, 0.1);
  EXPECT_LT(atlas.max_area_distortion, 1e-6);
  expect_valid_atlas(square, atlas, options);
  // One square chart in a square texture fills it but for the gutter.
  EXPECT_GT(atlas.texture_used, 0.97);
}

TEST(TextureAtlas, SphereIsCutIntoSeveralDisks) {
  const TriangleMesh sphere = icosphere(3);
  const AtlasOptions options = small_texture(512, 2);
  const TextureAtlas atlas = timed_atlas("icosphere(3)", sphere, options);
  EXPECT_GT(atlas.charts, 1);
  expect_valid_atlas(sphere, atlas, options);
  EXPECT_LT(atlas.mean_angle_distortion, 3);
  EXPECT_GT(atlas.texture_used, 0.55);
}

TEST(TextureAtlas, TorusIsCutIntoDisks) {
  const TriangleMesh ring = torus(1.0, 0.4, 48, 24);
  const AtlasOptions options = small_texture(512, 2);
  const TextureAtlas atlas = timed_atlas("torus", ring, options);
  EXPECT_GT(atlas.charts, 1);
  expect_valid_atlas(ring, atlas, options);
  EXPECT_LT(atlas.mean_angle_distortion, 3);
}

TEST(TextureAtlas, ChartAnglesLimitChartNormals) {
  // A narrower cone cuts the sphere into more, flatter charts.
  const TriangleMesh sphere = icosphere(3);
  AtlasOptions narrow = small_texture(512, 2);
  narrow.max_chart_angle = 30;
  const TextureAtlas wide_atlas = make_texture_atlas(sphere, small_texture(512, 2));
  const TextureAtlas narrow_atlas = make_texture_atlas(sphere, narrow);
  EXPECT_GT(narrow_atlas.charts, wide_atlas.charts);
  EXPECT_LT(narrow_atlas.mean_area_distortion, wide_atlas.mean_area_distortion);
  expect_valid_atlas(sphere, narrow_atlas, narrow);
}

TEST(TextureAtlas, SeamAcrossSquareMakesTwoCharts) {
  const int n = 8;
  const TriangleMesh square = unit_square(n);
  AtlasOptions options;
  for (Index i = 0; i < n; ++i) options.seams.push_back({(n / 2) * (n + 1) + i, (n / 2) * (n + 1) + i + 1});
  options.seams.push_back({0, 999});  // not an edge: ignored
  const TextureAtlas atlas = make_texture_atlas(square, options);
  ASSERT_EQ(atlas.charts, 2);
  expect_valid_atlas(square, atlas, options);
  // The charts are the halves below and above y = 1/2.
  Index below = -1, above = -1;
  for (Index f = 0; f < square.num_faces(); ++f) {
    double y = 0;
    for (int k = 0; k < 3; ++k) y += square.vertices(square.faces(f, k), 1) / 3;
    Index& side = y > 0.5 ? above : below;
    if (side == -1) side = atlas.chart_of_face[f];
    EXPECT_EQ(atlas.chart_of_face[f], side) << "face " << f;
  }
  EXPECT_NE(below, above);
  // The seam's n + 1 vertices have two copies, the others one.
  std::vector<int> copies(square.num_vertices(), 0);
  for (const Index v : atlas.source_vertex) ++copies[v];
  for (Index v = 0; v < square.num_vertices(); ++v) {
    const bool on_seam = v / (n + 1) == n / 2;
    EXPECT_EQ(copies[v], on_seam ? 2 : 1) << "vertex " << v;
  }
  EXPECT_LT(atlas.max_angle_distortion, 0.1);
}

TEST(TextureAtlas, SquareWithHoleIsSplitIntoDisks) {
  // A flat annulus grows as one chart within any normal cone; it is no disk
  // and must be cut.
  const int n = 8;
  const TriangleMesh square = unit_square(n);
  std::vector<Eigen::Vector3d> vertices;
  for (Index v = 0; v < square.num_vertices(); ++v) vertices.emplace_back(square.vertices.row(v));
  std::vector<std::array<Index, 3>> faces;
  for (Index f = 0; f < square.num_faces(); ++f) {
    const Eigen::Vector3d centre = (square.vertices.row(square.faces(f, 0)) + square.vertices.row(square.faces(f, 1)) +
                                    square.vertices.row(square.faces(f, 2))) /
                                   3;
    if (std::abs(centre.x() - 0.5) < 0.25 && std::abs(centre.y() - 0.5) < 0.25) continue;
    faces.push_back({square.faces(f, 0), square.faces(f, 1), square.faces(f, 2)});
  }
  const TriangleMesh annulus = test::mesh_from_lists(vertices, faces);
  const AtlasOptions options = small_texture(256, 2);
  const TextureAtlas atlas = make_texture_atlas(annulus, options);
  EXPECT_GE(atlas.charts, 2);
  expect_valid_atlas(annulus, atlas, options);
}

TEST(TextureAtlas, FacesWithoutAreaGetFiniteCoordinates) {
  const TriangleMesh square = unit_square(4);
  std::vector<Eigen::Vector3d> vertices;
  for (Index v = 0; v < square.num_vertices(); ++v) vertices.emplace_back(square.vertices.row(v));
  std::vector<std::array<Index, 3>> faces;
  for (Index f = 0; f < square.num_faces(); ++f)
    faces.push_back({square.faces(f, 0), square.faces(f, 1), square.faces(f, 2)});
  faces.push_back({0, 1, 2});  // three points on a line, along the boundary
  faces.push_back({6, 6, 7});  // a repeated corner
  const TriangleMesh mesh = test::mesh_from_lists(vertices, faces);
  const AtlasOptions options = small_texture(256, 2);
  const TextureAtlas atlas = make_texture_atlas(mesh, options);
  EXPECT_TRUE(atlas.uvs.allFinite());
  EXPECT_TRUE(std::isfinite(atlas.mean_area_distortion) && std::isfinite(atlas.max_angle_distortion));
  expect_valid_atlas(mesh, atlas, options);
}

TEST(TextureAtlas, FandiskWithFeatureSeams) {
  const TriangleMesh fandisk = io::read_mesh("tests/data/fandisk.ply").mesh;
  const MeshTopology topology = build_mesh_topology(fandisk);
  AtlasOptions options = small_texture(1024, 2);
  for (const Index e : sharp_edges(fandisk, topology, 45)) options.seams.push_back(topology.edge_vertices[e]);
  ASSERT_FALSE(options.seams.empty());
  const TextureAtlas atlas = timed_atlas("fandisk, creases as seams", fandisk, options);
  expect_valid_atlas(fandisk, atlas, options);
  // No chart crosses a seam: the faces on either side share no atlas edge.
  for (const auto& [a, b] : options.seams) {
    const Index e = topology.find_edge(a, b);
    const auto faces = topology.edge_faces(e);
    ASSERT_EQ(faces.size(), 2u);
    std::set<Index> copies[2];
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < 3; ++k) {
        if (fandisk.faces(faces[side], k) == a || fandisk.faces(faces[side], k) == b) {
          copies[side].insert(atlas.faces(faces[side], k));
        }
      }
    }
    EXPECT_NE(copies[0], copies[1]) << "seam " << a << " " << b;
  }
  // The packer packs the charts' shapes, not their bounding rectangles: a
  // realistic case (some twenty charts of many shapes) fills well over half the texture.
  EXPECT_GE(atlas.texture_used, 0.55);
  EXPECT_LT(atlas.mean_angle_distortion, 3);
}

TEST(TextureAtlas, SameMeshSameAtlas) {
  const TriangleMesh sphere = icosphere(2);
  const AtlasOptions options = small_texture(256, 2);
  const TextureAtlas first = make_texture_atlas(sphere, options);
  const TextureAtlas second = make_texture_atlas(sphere, options);
  EXPECT_EQ(first.uvs, second.uvs);
  EXPECT_EQ(first.faces, second.faces);
  EXPECT_EQ(first.chart_of_face, second.chart_of_face);
}

TEST(TextureAtlas, TheAtlasDoesNotDependOnTheThreads) {
  const TriangleMesh sphere = icosphere(4);
  TextureAtlas one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = make_texture_atlas(sphere, {.texture_size = 512});
  }
  const TextureAtlas all = make_texture_atlas(sphere, {.texture_size = 512});
  EXPECT_EQ(one.uvs, all.uvs);
  EXPECT_EQ(one.faces, all.faces);
}

TEST(TextureAtlas, RefusesEmptyMeshesAndBadIndices) {
  EXPECT_THROW(make_texture_atlas(TriangleMesh{}), Error);
  TriangleMesh bad = unit_square(2);
  bad.faces(3, 1) = 100;
  EXPECT_THROW(make_texture_atlas(bad), Error);
  AtlasOptions options;
  options.gutter = 0;
  EXPECT_THROW(make_texture_atlas(unit_square(2), options), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
