// Sharp features: detect_features on a box (12 creases, 8 corners) and a
// sphere (none), the length filter, the cut along the creases, the sites
// lining them (twins at one position) and the weld of a dual back together;
// the short creases no chain keeps and the pins on them.

#include "hard_cases.hpp"
#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/remesh/chain_slider.hpp"
#include "geodual/remesh/crease_pins.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/feature_sampling.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/welded_dual.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace geodual {
namespace {

/// The unit cube, n x n cells per side, two triangles per cell.
TriangleMesh cube(int n) {
  const std::vector<double> steps = bench::hard_case_detail::even_steps(0.0, 1.0, n + 1);
  return bench::hard_case_detail::voxel_surface({steps, steps, steps}, [](int, int, int) { return true; });
}

TEST(Features, BoxHasTwelveCreasesAndEightCorners) {
  const TriangleMesh box = cube(6);
  const remesh::FeatureSet features = remesh::detect_features(box);
  EXPECT_EQ(features.sharp_chains, 12);
  EXPECT_EQ(features.corners.size(), 8u);
  EXPECT_NEAR(features.sharp_length, 12.0, 1e-12);
  EXPECT_EQ(features.sharp_edges.size(), 12u * 6u);
  for (const remesh::FeatureChain& chain : features.chains) {
    EXPECT_FALSE(chain.closed);
    EXPECT_FALSE(chain.on_boundary);
    EXPECT_NEAR(chain.length, 1.0, 1e-12);
    EXPECT_EQ(chain.vertices.size(), 7u);
  }
}

TEST(Features, SmoothSphereHasNoneAndShortNetworksAreDropped) {
  EXPECT_TRUE(remesh::detect_features(test::icosphere(3)).empty());
  // The box's creases are chains 1 long, corner to corner.
  EXPECT_EQ(remesh::detect_features(cube(4), {.min_chain_length = 0.99}).sharp_chains, 12);
  EXPECT_TRUE(remesh::detect_features(cube(4), {.min_chain_length = 1.01}).empty());
  EXPECT_TRUE(remesh::detect_features(cube(4), {.sharp_angle = 91}).empty());
  EXPECT_TRUE(remesh::detect_features(cube(4), {.sharp_angle = 0}).empty());
}

TEST(Features, BoundaryLoopsThatCreasesRunIntoBecomeChains) {
  // The box without its top: the rim meets four vertical creases.
  TriangleMesh open = cube(4);
  // Drop the faces of the top side (z = 1).
  std::vector<Index> kept;
  for (Index f = 0; f < open.num_faces(); ++f) {
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && open.vertices(open.faces(f, k), 2) == 1.0;
    if (!top) kept.push_back(f);
  }
  FaceMatrix faces(static_cast<Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) faces.row(static_cast<Index>(i)) = open.faces.row(kept[i]);
  open.faces = faces;
  const remesh::FeatureSet features = remesh::detect_features(open);
  EXPECT_EQ(features.sharp_chains, 8);  // 4 vertical, 4 round the floor
  std::int64_t boundary_chains = 0;
  double rim = 0;
  for (const remesh::FeatureChain& chain : features.chains) {
    if (chain.on_boundary) ++boundary_chains, rim += chain.length;
  }
  EXPECT_EQ(boundary_chains, 4);  // the rim, split at the four creases' ends
  EXPECT_NEAR(rim, 4.0, 1e-12);
  EXPECT_EQ(features.corners.size(), 8u);
}

TEST(Features, CreasesRoundARegionNarrowerThanTheMinimumWidthAreDropped) {
  // A slab 1 x 1 x 0.05: its rims are long creases, but the band between
  // them (the four sides, joined once their short vertical creases go) is
  // 0.05 wide: twice its area over its border, 2 (4 x 0.05) / 8.
  const std::vector<double> xy = bench::hard_case_detail::even_steps(0.0, 1.0, 5);
  const TriangleMesh slab =
      bench::hard_case_detail::voxel_surface({xy, xy, {0.0, 0.05}}, [](int, int, int) { return true; });
  const remesh::FeatureOptions options{.min_chain_length = 0.5};
  EXPECT_EQ(remesh::detect_features(slab, options).sharp_chains, 8);  // the two rims, four sides each
  remesh::FeatureOptions narrow = options;
  narrow.min_region_width = 0.04;
  EXPECT_EQ(remesh::detect_features(slab, narrow).sharp_chains, 8);
  narrow.min_region_width = 0.06;
  EXPECT_TRUE(remesh::detect_features(slab, narrow).empty());
  // A box's sides are 1 wide (a square's width: twice 1 over 4): kept at a width under a half.
  EXPECT_EQ(remesh::detect_features(cube(4), {.min_region_width = 0.49}).sharp_chains, 12);
  EXPECT_TRUE(remesh::detect_features(cube(4), {.min_region_width = 0.51}).empty());
  // The band's corners' vertical edges turn by 90 degrees, but they are
  // parallel, a prism's side: smooth, judged at the smaller width. Where
  // folds must not be parallel to be smooth, it is rough: judged at the
  // rough width, but for a machined surface's, as the slab's (all flat
  // facets), where no region is rough.
  narrow = {.min_chain_length = 0.5, .min_region_width = 0.04, .min_rough_region_width = 0.06};
  EXPECT_EQ(remesh::detect_features(slab, narrow).sharp_chains, 8);
  narrow.parallel_fold_angle = 0;
  EXPECT_EQ(remesh::detect_features(slab, narrow).sharp_chains, 8);
  narrow.machined_regions_smooth = false;
  EXPECT_TRUE(remesh::detect_features(slab, narrow).empty());
  // The remesh's detection asks for a tenth of the spacing, half where rough.
  const remesh::FeatureOptions remesh_options = remesh::remesh_feature_options(slab, 100, 60, 0.5);
  EXPECT_DOUBLE_EQ(remesh_options.min_region_width, 0.2 * remesh_options.scale);
  EXPECT_DOUBLE_EQ(remesh_options.min_rough_region_width, remesh_options.scale);
}

/// An open step: the floor y in [0, 1/2] at z = 0, a wall `height` high at
/// y = 1/2 (its middle line pushed out by `bulge` along y, at every other
/// vertex only where `bumps`) and the tread y in [1/2, 1] at z = height, each
/// `n` quads along x in [0, 1]; the wall's fold lines are creases of 90
/// degrees (flat wall) 1 long.
TriangleMesh step(double height, int n, double bulge = 0, bool bumps = false) {
  constexpr int kRows = 5;
  const std::array<Eigen::Vector2d, kRows> profile = {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.5, 0),
                                                      Eigen::Vector2d(0.5 + bulge, height / 2),
                                                      Eigen::Vector2d(0.5, height), Eigen::Vector2d(1, height)};
  TriangleMesh mesh;
  mesh.vertices.resize(kRows * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    for (int r = 0; r < kRows; ++r) {
      const double y = bumps && i % 2 == 0 && r == 2 ? 0.5 : profile[r].x();  // the middle line
      mesh.vertices.row(kRows * i + r) << static_cast<double>(i) / n, y, profile[r].y();
    }
  }
  mesh.faces.resize(2 * (kRows - 1) * n, 3);
  Index f = 0;
  for (int i = 0; i < n; ++i) {
    for (int r = 0; r + 1 < kRows; ++r) {
      const Index a = kRows * i + r, b = a + kRows;  // the quad a, b, b + 1, a + 1
      mesh.faces.row(f++) << a, b, b + 1;
      mesh.faces.row(f++) << a, b + 1, a + 1;
    }
  }
  return mesh;
}

TEST(Features, ASmoothNarrowRegionKeepsItsCreasesDownToTheSmallerWidth) {
  // The wall between the step's two creases is flat, 0.05 high: width
  // 2 (0.05) / 2.1 = 0.048 (its border: the two creases and two boundary
  // edges). The step, all quads, is machined: its regions are judged
  // smooth or rough by their folds with machined_regions_smooth off.
  const remesh::FeatureOptions options{
      .min_region_width = 0.04, .min_rough_region_width = 0.5, .machined_regions_smooth = false};
  const remesh::FeatureSet wall = remesh::detect_features(step(0.05, 4), options);
  EXPECT_EQ(wall.sharp_chains, 2);
  EXPECT_NEAR(wall.sharp_length, 2.0, 1e-12);
  EXPECT_TRUE(
      remesh::detect_features(step(0.05, 4), {.min_region_width = 0.05, .min_rough_region_width = 0.5}).empty());
  // Folded by 40 degrees along its middle line (each half tilted by 20), the
  // fold no crease, the wall is ruled (its folds parallel): still smooth.
  const double bulge = 0.025 * std::tan(20 * std::numbers::pi / 180);
  EXPECT_EQ(remesh::detect_features(step(0.05, 4, bulge), options).sharp_chains, 2);
  // Bumped out at every other vertex of that line, its folds cross: rough,
  // the rough width applies.
  const TriangleMesh bumpy = step(0.05, 4, bulge, true);
  EXPECT_TRUE(remesh::detect_features(bumpy, options).empty());
  EXPECT_EQ(remesh::detect_features(bumpy, {.min_region_width = 0.04}).sharp_chains, 2);
  // With the option on, as by default, a machined surface's bumps are its shape: smooth.
  remesh::FeatureOptions machined = options;
  machined.machined_regions_smooth = true;
  EXPECT_EQ(remesh::detect_features(bumpy, machined).sharp_chains, 2);
}

TEST(Features, AThinPlatesFacetedRimKeepsItsCreasesAtTheSmallerWidth) {
  // A coin: a 16-gon of radius 1, 0.05 thick. Its two rims are creases of 90
  // degrees; its side, 0.05 wide, folds by 22.5 degrees at each of its 16
  // vertical edges, steep but parallel: a faceted cylinder's side, as
  // CAD exports a thin plate's round rim.
  const TriangleMesh coin = bench::revolved_profile({{{0, 0}, {1, 0}, {1, 0.05}, {0, 0.05}}}, 16);
  const remesh::FeatureOptions options{.min_region_width = 0.04, .min_rough_region_width = 0.5};
  const remesh::FeatureSet rims = remesh::detect_features(coin, options);
  EXPECT_EQ(rims.sharp_chains, 2);
  EXPECT_NEAR(rims.sharp_length, 2 * 16 * 2 * std::sin(std::numbers::pi / 16), 1e-9);
  // Its side bulging out at mid-height folds along a ring as well, across
  // the vertical edges: rough, the rims go at the rough width (the coin,
  // made of flat facets, is machined: judged so with machined_regions_smooth
  // off; with it on, its side is smooth whatever its folds).
  const TriangleMesh bulging = bench::revolved_profile({{{0, 0}, {1, 0}, {1.01, 0.025}, {1, 0.05}, {0, 0.05}}}, 16);
  EXPECT_EQ(remesh::detect_features(bulging, options).sharp_chains, 2);
  remesh::FeatureOptions by_folds = options;
  by_folds.machined_regions_smooth = false;
  EXPECT_TRUE(remesh::detect_features(bulging, by_folds).empty());
  EXPECT_EQ(remesh::detect_features(bulging, {.min_region_width = 0.04}).sharp_chains, 2);
}

TEST(Features, NarrowestCornerAngleIsTheSmallestSectorBetweenFeatures) {
  // A box's corners: three sectors of 90 degrees each.
  const TriangleMesh box = cube(3);
  EXPECT_NEAR(remesh::narrowest_corner_angle(box, remesh::detect_features(box)), 90.0, 1e-9);
  // No corner, no bound.
  const TriangleMesh sphere = test::icosphere(2);
  EXPECT_EQ(remesh::narrowest_corner_angle(sphere, remesh::detect_features(sphere)), 360.0);
  // A square pyramid, base [-0.5, 0.5]^2, apex 2 above: its lateral faces
  // meet at the apex at 2 atan(0.5 / slant), slant = sqrt(2^2 + 0.5^2); at a
  // base corner a lateral face has (180 - that) / 2 and the base 90 (its two
  // triangles joined across their flat diagonal).
  TriangleMesh pyramid;
  pyramid.vertices.resize(5, 3);
  pyramid.vertices << -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0, 0, 0, 2;
  pyramid.faces.resize(6, 3);
  pyramid.faces << 0, 2, 1, 0, 3, 2, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
  const remesh::FeatureSet features = remesh::detect_features(pyramid);
  ASSERT_EQ(features.corners.size(), 5u);
  const double apex = 2 * std::atan(0.5 / std::sqrt(4.25)) * 180 / std::numbers::pi;
  EXPECT_NEAR(remesh::narrowest_corner_angle(pyramid, features), apex, 1e-9);
  // With the base's rim alone as features (given, no angle), the lateral
  // faces at a base corner are one sector of 180 degrees less the apex
  // angle, joined across the lateral edge, and the base's 90 is narrowest.
  const remesh::FeatureSet rim =
      remesh::detect_features(pyramid, {.sharp_angle = 0, .given_edges = {{{0, 1}}, {{1, 2}}, {{2, 3}}, {{0, 3}}}});
  ASSERT_EQ(rim.corners.size(), 4u);
  EXPECT_NEAR(remesh::narrowest_corner_angle(pyramid, rim), 90.0, 1e-9);
}

/// A flat grid [0, 8] x [0, 4], cells of 1, with a ridge along y = 2: the
/// vertices at x = 2 ... 6 raised to z = 1, so that its edges turn by 90
/// degrees and the crease fades out at both ends.
TriangleMesh ridge() {
  TriangleMesh mesh;
  mesh.vertices.resize(9 * 5, 3);
  for (int y = 0; y <= 4; ++y) {
    for (int x = 0; x <= 8; ++x) mesh.vertices.row(9 * y + x) << x, y, (y == 2 && x >= 2 && x <= 6) ? 1.0 : 0.0;
  }
  mesh.faces.resize(2 * 8 * 4, 3);
  Index f = 0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      const Index v = 9 * y + x;
      mesh.faces.row(f++) << v, v + 1, v + 10;
      mesh.faces.row(f++) << v, v + 10, v + 9;
    }
  }
  return mesh;
}

TEST(Features, ACreaseIsJudgedWithTheFacesRoundItsEndsEvenWhereItsEdgesOutreachTheScale) {
  const TriangleMesh mesh = ridge();
  const remesh::FeatureSet edge_only =
      remesh::detect_features(mesh, {.continuation_angle = 0, .min_chain_length = 0.5});
  // Every ridge edge is sharp on its own, the two where it rises included.
  ASSERT_FALSE(edge_only.empty());
  EXPECT_GT(edge_only.sharp_length, 4.0 + 1.0);
  // At a scale of a tenth of an edge, the faces round each end of the
  // crease, which go round its free ends, join: those edges are not a crease
  // at any scale; the four between the raised vertices stay.
  const remesh::FeatureSet at_scale =
      remesh::detect_features(mesh, {.continuation_angle = 0, .scale = 0.1, .min_chain_length = 0.5});
  EXPECT_EQ(at_scale.sharp_chains, 1);
  EXPECT_NEAR(at_scale.sharp_length, 4.0, 1e-12);
  // Its two ends are corners, but no corner joins two features: no narrowest angle.
  EXPECT_EQ(at_scale.corners.size(), 2u);
  EXPECT_EQ(remesh::narrowest_corner_angle(mesh, at_scale), 360.0);
  for (const auto& [a, b] : at_scale.sharp_edges) {
    EXPECT_EQ(mesh.vertices(a, 2), 1.0);
    EXPECT_EQ(mesh.vertices(b, 2), 1.0);
  }
}

TEST(Features, ACreaseWithAFreeEndMustBeTheDanglingLengthLong) {
  // The ridge's crease, 4 long, ends in the open at both ends.
  const remesh::FeatureOptions options{.continuation_angle = 0, .scale = 0.1, .min_chain_length = 0.5};
  remesh::FeatureOptions dangling = options;
  dangling.min_dangling_chain_length = 3.9;
  EXPECT_NEAR(remesh::detect_features(ridge(), dangling).sharp_length, 4.0, 1e-12);
  dangling.min_dangling_chain_length = 4.1;
  EXPECT_TRUE(remesh::detect_features(ridge(), dangling).empty());
  // The box's creases, 1 long, all end at corners where three meet: none dangles.
  EXPECT_EQ(remesh::detect_features(cube(4), {.min_chain_length = 0.5, .min_dangling_chain_length = 5}).sharp_chains,
            12);
  // The remesh's detection asks for two spacings.
  const remesh::FeatureOptions remesh_options = remesh::remesh_feature_options(cube(4), 100, 60, 0.5);
  EXPECT_DOUBLE_EQ(remesh_options.min_dangling_chain_length, 4 * remesh_options.scale);
}

/// A sheet over [-1, 1] x [0, 2] (cells of 0.05) folded along x = 0 by an
/// angle that fades from 70 degrees at y = 0 to 10 at y = 2: flat for x <= 0,
/// z = x tan(angle(y)) beyond. From y = noise_from_y on, the folded side's
/// vertices are moved up and down by up to `noise`.
TriangleMesh fading_fold(double noise_from_y = 2, double noise = 0.01) {
  constexpr int columns = 41, rows = 41;
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const double x = -1 + 0.05 * i, y = 0.05 * j;
      const double angle = (70 - 30 * y) * std::numbers::pi / 180;
      double z = i > 20 ? x * std::tan(angle) : 0.0;
      if (i > 20 && y >= noise_from_y) z += noise * std::sin(37.0 * i + 11.0 * j);
      vertices.emplace_back(x, y, z);
    }
  }
  std::vector<std::array<Index, 3>> faces;
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < columns; ++i) {
      const Index v = j * columns + i;
      faces.push_back({v, v + 1, v + columns + 1});
      faces.push_back({v, v + columns + 1, v + columns});
    }
  }
  return test::mesh_from_lists(vertices, faces);
}

TEST(Features, ACreaseContinuesWhereItsAngleFadesBetweenSmoothSidesOnly) {
  // The largest y of the fold's edges kept (those at x = 0).
  const auto reach = [](const TriangleMesh& mesh, const remesh::FeatureOptions& options) {
    double y = -1;
    for (const auto& [a, b] : remesh::detect_features(mesh, options).sharp_edges) {
      if (mesh.vertices(a, 0) == 0 && mesh.vertices(b, 0) == 0) {
        y = std::max({y, mesh.vertices(a, 1), mesh.vertices(b, 1)});
      }
    }
    return y;
  };
  // The fold's line turns by 60 degrees up to y = 1/3 and by 30 up to
  // y = 4/3; judged at the scale, with the faces round the edges' ends,
  // somewhat less far.
  const remesh::FeatureOptions sharp{.sharp_angle = 60, .continuation_angle = 0, .scale = 0.1};
  const double sharp_reach = reach(fading_fold(), sharp);
  EXPECT_GT(sharp_reach, 0.1);
  EXPECT_LE(sharp_reach, 0.35);
  remesh::FeatureOptions continued = sharp;
  continued.continuation_angle = 30;
  const double continued_reach = reach(fading_fold(), continued);
  EXPECT_GT(continued_reach, 1.0);
  EXPECT_LE(continued_reach, 1.35);
  // Not into a noisy side (its normals spread by more than 10 degrees at the
  // scale): the continuation stops before the noise starts.
  const double noisy_reach = reach(fading_fold(0.8), continued);
  EXPECT_GT(noisy_reach, sharp_reach);
  EXPECT_LE(noisy_reach, 0.8);
  // Without that test it runs on into the noise.
  remesh::FeatureOptions unsmoothed = continued;
  unsmoothed.continuation_max_spread = 0;
  EXPECT_GT(reach(fading_fold(0.8), unsmoothed), 0.8);
  // Nor without a sharp edge to start from.
  continued.sharp_angle = 75;
  EXPECT_TRUE(remesh::detect_features(fading_fold(), continued).empty());
}

/// `mesh` with every triangle split in four at its edges' midpoints: the
/// same surface at twice the resolution.
TriangleMesh split_at_midpoints(const TriangleMesh& mesh) {
  std::map<std::pair<Index, Index>, Index> midpoint;
  std::vector<Eigen::RowVector3d> added;
  const auto middle = [&](Index a, Index b) {
    const auto [it, inserted] = midpoint.try_emplace({std::min(a, b), std::max(a, b)}, 0);
    if (inserted) {
      it->second = mesh.num_vertices() + static_cast<Index>(added.size());
      added.push_back(0.5 * (mesh.vertices.row(a) + mesh.vertices.row(b)));
    }
    return it->second;
  };
  TriangleMesh split;
  split.faces.resize(4 * mesh.num_faces(), 3);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    const Index ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
    split.faces.row(4 * f) << a, ab, ca;
    split.faces.row(4 * f + 1) << ab, b, bc;
    split.faces.row(4 * f + 2) << ca, bc, c;
    split.faces.row(4 * f + 3) << ab, bc, ca;
  }
  split.vertices.resize(mesh.num_vertices() + static_cast<Index>(added.size()), 3);
  split.vertices.topRows(mesh.num_vertices()) = mesh.vertices;
  for (std::size_t i = 0; i < added.size(); ++i)
    split.vertices.row(mesh.num_vertices() + static_cast<Index>(i)) = added[i];
  return split;
}

/// `mesh` refined unevenly to `faces` faces: again and again, an edge of a
/// random face (its longest with `longest`, else any) split at a random point
/// between `lo` and `hi` of its length, with both its faces. The same
/// surface; `seed` picks the splits.
TriangleMesh split_at_random(const TriangleMesh& mesh, Index faces, std::uint32_t seed, double lo = 0.2,
                             double hi = 0.8, bool longest = true) {
  std::mt19937 random(seed);
  const auto uniform = [&] { return static_cast<double>(random()) / 4294967296.0; };
  std::vector<Eigen::RowVector3d> vertices;
  for (Index v = 0; v < mesh.num_vertices(); ++v) vertices.push_back(mesh.vertices.row(v));
  std::vector<std::array<Index, 3>> triangles;
  std::map<std::pair<Index, Index>, std::size_t> face_of;  // directed edge -> face
  const auto set = [&](std::size_t f, std::array<Index, 3> t) {
    triangles[f] = t;
    for (int k = 0; k < 3; ++k) face_of[{t[k], t[(k + 1) % 3]}] = f;
  };
  triangles.resize(static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) set(f, {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)});
  while (static_cast<Index>(triangles.size()) < faces) {
    const auto t = triangles[static_cast<std::size_t>(uniform() * static_cast<double>(triangles.size()))];
    int k = static_cast<int>(uniform() * 3);
    if (longest) {
      for (int j = 0; j < 3; ++j) {
        const auto length = [&](int i) { return (vertices[t[i]] - vertices[t[(i + 1) % 3]]).squaredNorm(); };
        if (length(j) > length(k)) k = j;
      }
    }
    const Index a = t[k], b = t[(k + 1) % 3];
    const Index p = static_cast<Index>(vertices.size());
    vertices.push_back(vertices[a] + (lo + (hi - lo) * uniform()) * (vertices[b] - vertices[a]));
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
      const auto it = face_of.find({x, y});
      if (it == face_of.end()) continue;
      const std::size_t f = it->second;
      face_of.erase(it);
      const auto g = triangles[f];
      int i = 0;
      while (g[i] != x) ++i;
      const Index opposite = g[(i + 2) % 3];
      set(f, {x, p, opposite});
      triangles.emplace_back();
      set(triangles.size() - 1, {p, y, opposite});
    }
  }
  TriangleMesh split;
  split.vertices.resize(static_cast<Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v) split.vertices.row(static_cast<Index>(v)) = vertices[v];
  split.faces.resize(static_cast<Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) split.faces(static_cast<Index>(f), k) = triangles[f][k];
  }
  return split;
}

/// The features detected on `mesh` with the remesh pipeline's options for
/// `sites` sites (remesh_feature_options at RemeshOptions' defaults).
remesh::FeatureSet pipeline_features(const TriangleMesh& mesh, std::int64_t sites) {
  const remesh::FeatureSamplingOptions defaults;
  return remesh::detect_features(
      mesh, remesh::remesh_feature_options(mesh, sites, defaults.sharp_angle, defaults.min_feature_length,
                                           defaults.continuation_angle));
}

TEST(Features, FinerTessellationsOfTheSamePartGiveTheSameCreases) {
  // fandisk (13K faces) split once at its edges' midpoints (52K), and split
  // unevenly to 31K faces, at random points of its faces' longest edges or
  // of any edge, near their ends too (needles): the same surface, so the
  // same creases at the remesh's scale, whatever the input's edge lengths.
  const TriangleMesh fandisk = io::read_mesh("tests/data/fandisk.ply").mesh;
  const std::vector<std::pair<std::string, TriangleMesh>> finer = {
      {"midpoints", split_at_midpoints(fandisk)},
      {"uneven", split_at_random(fandisk, 31000, 1)},
      {"needles", split_at_random(fandisk, 31000, 2, 0.02, 0.98, false)}};
  for (const std::int64_t sites : {2000, 500}) {
    const remesh::FeatureSet coarse = pipeline_features(fandisk, sites);
    EXPECT_GE(coarse.sharp_chains, 30);
    for (const auto& [name, mesh] : finer) {
      SCOPED_TRACE(name + " at " + std::to_string(sites) + " sites");
      const remesh::FeatureSet fine = pipeline_features(mesh, sites);
      EXPECT_EQ(fine.sharp_chains, coarse.sharp_chains);
      EXPECT_NEAR(fine.sharp_length, coarse.sharp_length, 0.05 * coarse.sharp_length);
    }
  }
}

/// The share of the length of `mesh`'s edges that turn by `angle` degrees or
/// more which lies on `features`' sharp edges.
double share_of_sharp_length_kept(const TriangleMesh& mesh, const remesh::FeatureSet& features, double angle) {
  const MeshTopology topology = build_mesh_topology(mesh);
  double all = 0, kept = 0;
  for (const Index e : sharp_edges(mesh, topology, angle)) {
    const auto [a, b] = topology.edge_vertices[e];
    const double length = (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
    all += length;
    if (features.is_sharp(a, b)) kept += length;
  }
  return kept / all;
}

/// The sharp edges the remesh's detection finds on `mesh` at `sites`, with
/// `option` on and with it off.
std::array<std::vector<std::array<Index, 2>>, 2> sharp_edges_on_and_off(const TriangleMesh& mesh, std::int64_t sites,
                                                                        bool remesh::FeatureOptions::*option) {
  const remesh::FeatureSamplingOptions defaults;
  remesh::FeatureOptions options = remesh::remesh_feature_options(
      mesh, sites, defaults.sharp_angle, defaults.min_feature_length, defaults.continuation_angle);
  options.*option = true;
  std::vector<std::array<Index, 2>> on = remesh::detect_features(mesh, options).sharp_edges;
  options.*option = false;
  return {std::move(on), remesh::detect_features(mesh, options).sharp_edges};
}

TEST(Features, FoldsBetweenPlanarFacetsPartACreasesSidesOnMachinedPartsOnly) {
  // example019's creases (70-120 degrees) have sides that meet round their
  // ends across weaker folds between flat faces. At the scale of 2,000
  // sites, those folds part the sides as the creases do, and the creases
  // stay; taken as smooth, they let about a third of the length go.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/example019.stl").mesh).mesh;
  const remesh::FeatureSamplingOptions defaults;
  remesh::FeatureOptions options = remesh::remesh_feature_options(
      part, 2000, defaults.sharp_angle, defaults.min_feature_length, defaults.continuation_angle);
  const remesh::FeatureSet parted = remesh::detect_features(part, options);
  options.facet_folds_part_sides = false;
  const remesh::FeatureSet joined = remesh::detect_features(part, options);
  EXPECT_GT(share_of_sharp_length_kept(part, parted, 60), 0.99);
  EXPECT_LT(share_of_sharp_length_kept(part, joined, 60), 0.8);
  // Split at its edges' midpoints, the part has the same facets: the same creases.
  const remesh::FeatureSet finer = pipeline_features(split_at_midpoints(part), 2000);
  EXPECT_EQ(finer.sharp_chains, parted.sharp_chains);
  EXPECT_NEAR(finer.sharp_length, parted.sharp_length, 0.05 * parted.sharp_length);
  // A scan has no such facets, nor has it once split into coplanar
  // quadruples, each smaller than a remesh triangle at 20,000 sites: its
  // folds never part the sides.
  const TriangleMesh bunny = io::read_mesh("tests/data/bunny.ply").mesh;
  for (const TriangleMesh& scan : {bunny, split_at_midpoints(bunny)}) {
    SCOPED_TRACE(std::to_string(scan.num_faces()) + " faces");
    const auto [on, off] = sharp_edges_on_and_off(scan, 20000, &remesh::FeatureOptions::facet_folds_part_sides);
    EXPECT_EQ(on, off);
  }
}

TEST(Features, AMachinedPartsNarrowRegionsAreSmoothWhateverTheirFolds) {
  // children_indexed's engraved digits are strokes narrower than half a
  // spacing at 2,000 sites, their sides folded between flat facets: rough
  // by their folds, they would lose their creases; on a machined part they
  // are judged as smooth, down to a tenth of a spacing.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/children_indexed.stl").mesh).mesh;
  const remesh::FeatureSamplingOptions defaults;
  remesh::FeatureOptions options = remesh::remesh_feature_options(
      part, 2000, defaults.sharp_angle, defaults.min_feature_length, defaults.continuation_angle);
  const remesh::FeatureSet smooth = remesh::detect_features(part, options);
  options.machined_regions_smooth = false;
  const remesh::FeatureSet rough = remesh::detect_features(part, options);
  // Measured: 94 % of the length of the edges that turn by 60 degrees or
  // more, against 69 % where the strokes are rough.
  EXPECT_GT(share_of_sharp_length_kept(part, smooth, 60), 0.9);
  EXPECT_LT(share_of_sharp_length_kept(part, rough, 60), 0.75);
  // Split at its edges' midpoints, the part has the same regions: the same creases.
  const remesh::FeatureSet finer = pipeline_features(split_at_midpoints(part), 2000);
  EXPECT_EQ(finer.sharp_chains, smooth.sharp_chains);
  EXPECT_NEAR(finer.sharp_length, smooth.sharp_length, 0.05 * smooth.sharp_length);
  // A scan is not machined: its noisy narrow slivers stay rough.
  const TriangleMesh bunny = io::read_mesh("tests/data/bunny.ply").mesh;
  for (const std::int64_t sites : {5000, 20000}) {
    SCOPED_TRACE(std::to_string(sites) + " sites");
    const auto [on, off] = sharp_edges_on_and_off(bunny, sites, &remesh::FeatureOptions::machined_regions_smooth);
    EXPECT_EQ(on, off);
  }
}

TEST(Features, ABoxGivesItsTwelveCreasesAtEveryResolution) {
  // 4 x 4 and 24 x 24 cells per side, unevenly split too: the edges and
  // nothing else, at the scale of 500 and of 100 sites.
  for (const std::int64_t sites : {500, 100}) {
    for (const TriangleMesh& box : {cube(4), cube(24), split_at_random(cube(4), 3000, 3, 0.02, 0.98, false)}) {
      SCOPED_TRACE(std::to_string(box.num_faces()) + " faces at " + std::to_string(sites) + " sites");
      const remesh::FeatureSet features = pipeline_features(box, sites);
      EXPECT_EQ(features.sharp_chains, 12);
      EXPECT_EQ(features.corners.size(), 8u);
      EXPECT_NEAR(features.sharp_length, 12.0, 1e-9);
    }
  }
}

/// The vertex of `mesh` at p (exactly), or -1.
Index vertex_at(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.vertices.row(v).transpose() == p) return v;
  }
  return -1;
}

TEST(Features, GivenEdgesAreKeptWhateverTheirAngleOrLength) {
  // A path across the bottom of the box, along y = 1/2 from one crease to the opposite one.
  const TriangleMesh box = cube(4);
  std::vector<std::array<Index, 2>> path;
  for (int i = 0; i < 4; ++i) {
    path.push_back({vertex_at(box, {i / 4.0, 0.5, 0}), vertex_at(box, {(i + 1) / 4.0, 0.5, 0})});
    ASSERT_GE(std::min(path.back()[0], path.back()[1]), 0);
  }
  // Alone (no angle): one chain, kept though shorter than the minimum length.
  const remesh::FeatureSet alone =
      remesh::detect_features(box, {.sharp_angle = 0, .min_chain_length = 1.5, .given_edges = path});
  EXPECT_EQ(alone.sharp_chains, 1);
  EXPECT_EQ(alone.corners.size(), 2u);
  EXPECT_NEAR(alone.sharp_length, 1.0, 1e-12);
  // With the creases: the two it ends on are split there.
  const remesh::FeatureSet both = remesh::detect_features(box, {.given_edges = path});
  EXPECT_EQ(both.sharp_chains, 12 + 2 + 1);
  EXPECT_EQ(both.corners.size(), 8u + 2u);
  EXPECT_NEAR(both.sharp_length, 13.0, 1e-12);
  // One edge whose ends touch nothing cannot be cut open: left out.
  EXPECT_TRUE(remesh::detect_features(box, {.sharp_angle = 0, .given_edges = {path[1]}}).empty());
  // A pair that is not an edge is ignored.
  EXPECT_TRUE(remesh::detect_features(box, {.sharp_angle = 0, .given_edges = {{path[0][0], path[3][1]}}}).empty());
}

TEST(Features, ExcludedEdgesAreNeverFeatures) {
  // The box less half of one crease's edges, the half at its corner (0, 0, 0)
  // along x: that crease ends there in the open, 0.5 long; with a minimum
  // dangling length of 0.6 it goes too.
  const TriangleMesh box = cube(4);
  std::vector<std::array<Index, 2>> half;
  for (int i = 0; i < 2; ++i) half.push_back({vertex_at(box, {i / 4.0, 0, 0}), vertex_at(box, {(i + 1) / 4.0, 0, 0})});
  const remesh::FeatureSet less = remesh::detect_features(box, {.excluded_edges = half});
  EXPECT_EQ(less.sharp_chains, 12);
  EXPECT_NEAR(less.sharp_length, 11.5, 1e-12);
  for (const auto& edge : half) {
    const std::array<Index, 2> sorted = {std::min(edge[0], edge[1]), std::max(edge[0], edge[1])};
    EXPECT_FALSE(std::binary_search(less.sharp_edges.begin(), less.sharp_edges.end(), sorted));
  }
  const remesh::FeatureSet dangling_dropped =
      remesh::detect_features(box, {.min_dangling_chain_length = 0.6, .excluded_edges = half});
  EXPECT_EQ(dangling_dropped.sharp_chains, 11);
  EXPECT_NEAR(dangling_dropped.sharp_length, 11.0, 1e-12);
  // Given edges are left out too.
  EXPECT_TRUE(remesh::detect_features(box, {.sharp_angle = 0, .given_edges = half, .excluded_edges = half}).empty());
}

/// A site at the centre of each side of a cut cube(8) (a face there).
void add_side_centres(const remesh::FeatureCut& cut, std::vector<SurfacePoint>& sites) {
  const MeshTopology topology = build_mesh_topology(cut.mesh);
  std::set<Index> seen;
  for (Index f = 0; f < cut.mesh.num_faces(); ++f) {
    const Eigen::Vector3d centre = SurfacePoint::in_face(f, 1.0 / 3, 1.0 / 3, 1.0 / 3).position(cut.mesh);
    int at_middle = 0;
    for (int d = 0; d < 3; ++d) at_middle += std::abs(centre[d] - 0.5) < 0.07;
    if (at_middle == 2 && seen.insert(topology.face_component[static_cast<std::size_t>(f)]).second) {
      sites.push_back(SurfacePoint::in_face(f, 1.0 / 3, 1.0 / 3, 1.0 / 3));
    }
  }
}

TEST(CreasePins, CreasesTooShortForChainsComeBackAsShortCreases) {
  const TriangleMesh box = cube(4);
  const remesh::FeatureSet kept = remesh::detect_features(box, {.min_chain_length = 0.99});
  EXPECT_EQ(kept.sharp_chains, 12);
  EXPECT_TRUE(kept.short_creases.empty());
  const remesh::FeatureSet dropped = remesh::detect_features(box, {.min_chain_length = 1.01});
  EXPECT_TRUE(dropped.empty());
  ASSERT_EQ(dropped.short_creases.size(), 12u);
  for (const remesh::FeatureChain& crease : dropped.short_creases) {
    EXPECT_NEAR(crease.length, 1.0, 1e-12);
    EXPECT_EQ(crease.vertices.size(), 5u);
  }
  EXPECT_TRUE(remesh::detect_features(box, {.sharp_angle = 91, .min_chain_length = 1.01}).short_creases.empty());
}

TEST(CreasePins, PinsAtMostASpacingApartOnePerCornerAndSegmentsAlongTheCreases) {
  const TriangleMesh box = cube(4);
  const remesh::FeatureSet features = remesh::detect_features(box, {.min_chain_length = 1.01});
  struct Case {
    double spacing;
    std::size_t per_crease;  // pins inside each crease
    double apart;
  };
  for (const Case c : {Case{0.3, 3, 0.25}, Case{0.6, 1, 0.5}, Case{1.0, 0, 1.0}}) {
    SCOPED_TRACE(c.spacing);
    const remesh::CreasePins pins = remesh::crease_pins(box, features, {.spacing = c.spacing, .max_chord_error = 1e-3});
    EXPECT_EQ(pins.sites.size(), 8 + 12 * c.per_crease);  // the corners once each
    EXPECT_EQ(pins.segments.size(), 12 * (c.per_crease + 1));
    ASSERT_EQ(pins.spacing.size(), pins.sites.size());
    std::set<Index> vertices;
    for (std::size_t i = 0; i < pins.sites.size(); ++i) {
      ASSERT_EQ(pins.sites[i].kind, SurfacePoint::Kind::vertex);
      vertices.insert(pins.sites[i].element);
      EXPECT_EQ(pins.spacing[i].position, pins.sites[i].position(box));
      EXPECT_NEAR(pins.spacing[i].spacing, std::min(1.5 * c.apart, c.spacing), 1e-12);
    }
    EXPECT_EQ(vertices.size(), pins.sites.size());
    for (const auto& [a, b] : pins.segments) {
      const Eigen::Vector3d d = pins.sites[a].position(box) - pins.sites[b].position(box);
      EXPECT_NEAR(d.norm(), c.apart, 1e-12);
      EXPECT_EQ((d.array().abs() > 1e-12).count(), 1);  // along an axis: on a crease
    }
  }
}

TEST(CreasePins, ACurvedCreaseGetsPinsCloserWhereItsChordsWouldLeaveIt) {
  // The turned shaft's circular creases (72 edges a circle) as short creases:
  // pins a spacing apart would leave them by more than the error.
  const TriangleMesh shaft = bench::stepped_shaft();
  const remesh::FeatureSet features = remesh::detect_features(shaft, {.min_chain_length = 1e9});
  ASSERT_FALSE(features.short_creases.empty());
  const double error = 1e-3;
  const remesh::CreasePins pins = remesh::crease_pins(shaft, features, {.spacing = 1e9, .max_chord_error = error});
  ASSERT_FALSE(pins.segments.empty());
  for (const remesh::FeatureChain& crease : features.short_creases) {
    for (const Index v : crease.vertices) {
      // Every crease vertex lies within the error of some segment's chord.
      const Eigen::Vector3d x = shaft.vertices.row(v);
      double nearest = 1e300;
      for (const auto& [a, b] : pins.segments) {
        const Eigen::Vector3d p = pins.sites[a].position(shaft), q = pins.sites[b].position(shaft);
        const double t = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
        nearest = std::min(nearest, (p + t * (q - p) - x).norm());
      }
      EXPECT_LE(nearest, error + 1e-12);
    }
  }
}

TEST(CreasePins, PinsAtOnePointAreOne) {
  // A 4 x 4 grid (vertex 4 j + i at (i, j)) and vertex 16, a copy of vertex
  // 6's position that no face uses (as a scan's duplicate point): the creases
  // 5-6 and 16-10 meet there.
  std::vector<Eigen::Vector3d> vertices;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) vertices.emplace_back(i, j, 0);
  }
  vertices.push_back(vertices[6]);
  std::vector<std::array<Index, 3>> faces;
  for (Index j = 0; j < 3; ++j) {
    for (Index i = 0; i < 3; ++i) {
      const Index a = 4 * j + i;
      faces.push_back({a, a + 1, a + 5});
      faces.push_back({a, a + 5, a + 4});
    }
  }
  const TriangleMesh grid = test::mesh_from_lists(vertices, faces);
  remesh::FeatureSet features;
  features.short_creases = {{.vertices = {5, 6}, .length = 1}, {.vertices = {16, 10}, .length = std::sqrt(2.0)}};
  const remesh::CreasePins pins = remesh::crease_pins(grid, features, {.spacing = 2, .max_chord_error = 1e-3});
  ASSERT_EQ(pins.sites.size(), 3u);
  EXPECT_EQ(pins.sites[0].element, 5);
  EXPECT_EQ(pins.sites[1].element, 6);
  EXPECT_EQ(pins.sites[2].element, 10);
  EXPECT_EQ(pins.segments, (std::vector<std::array<std::size_t, 2>>{{0, 1}, {1, 2}}));
  EXPECT_NEAR(pins.spacing[0].spacing, 1.5, 1e-12);  // its nearest pin 1 away
  EXPECT_NEAR(pins.spacing[2].spacing, 1.5, 1e-12);  // 10 is 1 from 6, 1.41 from 5
}

TEST(CreasePins, OptionsOutOfRangeAreRefused) {
  const TriangleMesh box = cube(2);
  const remesh::FeatureSet features = remesh::detect_features(box, {.min_chain_length = 1.01});
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 0, .max_chord_error = 1e-3}), UsageError);
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 1, .max_chord_error = 0}), UsageError);
  EXPECT_THROW(remesh::crease_pins(box, features, {.spacing = 1, .max_chord_error = 1e-3, .neighbour_spacing = 0.5}),
               UsageError);
}

TEST(FeatureCut, KeepsTheOutlineOfTheSurfaceItCut) {
  // A box without its top: a boundary loop, 8 creases, one piece.
  const TriangleMesh box = cube(6);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<Index, 3>> faces;
  for (Index v = 0; v < box.num_vertices(); ++v) points.push_back(box.vertices.row(v));
  for (Index f = 0; f < box.num_faces(); ++f) {
    const bool top = box.vertices(box.faces(f, 0), 2) == 1.0 && box.vertices(box.faces(f, 1), 2) == 1.0 &&
                     box.vertices(box.faces(f, 2), 2) == 1.0;
    if (!top) faces.push_back({box.faces(f, 0), box.faces(f, 1), box.faces(f, 2)});
  }
  const TriangleMesh open_box = test::mesh_from_lists(points, faces);
  const remesh::FeatureSet features = remesh::detect_features(open_box);
  ASSERT_FALSE(features.empty());
  const remesh::FeatureCut cut = remesh::cut_along_features(open_box, features);
  const remesh::SurfaceOutline& outline = cut.surface;
  const MeshTopology topology = build_mesh_topology(open_box);
  std::size_t boundary_edges = 0;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto [a, b] = topology.edge_vertices[e];
    EXPECT_EQ(outline.is_boundary_edge(a, b), topology.is_boundary_edge(e));
    EXPECT_EQ(outline.is_boundary_edge(b, a), topology.is_boundary_edge(e));
    boundary_edges += topology.is_boundary_edge(e) ? 1 : 0;
  }
  EXPECT_EQ(outline.boundary_edges.size(), boundary_edges);
  EXPECT_EQ(boundary_edges, 4u * 6);  // the top's rim
  EXPECT_EQ(outline.vertex_on_boundary, topology.vertex_on_boundary);
  ASSERT_EQ(outline.sharp_edge_faces.size(), features.sharp_edges.size());
  for (std::size_t i = 0; i < features.sharp_edges.size(); ++i) {
    const auto [a, b] = features.sharp_edges[i];
    const auto faces_of_edge = topology.edge_faces(topology.find_edge(a, b));
    ASSERT_EQ(faces_of_edge.size(), 2u);
    EXPECT_EQ(outline.sharp_edge_faces[i][0], faces_of_edge[0]);
    EXPECT_EQ(outline.sharp_edge_faces[i][1], faces_of_edge[1]);
    EXPECT_EQ(features.find_sharp_edge(b, a), static_cast<Index>(i));
  }
  EXPECT_EQ(features.find_sharp_edge(topology.edge_vertices[0][0], topology.edge_vertices[0][0]), -1);
  EXPECT_EQ(outline.face_component, topology.face_component);
  EXPECT_EQ(outline.vertex_component, topology.vertex_component);
  ASSERT_EQ(outline.components.size(), 1u);
  EXPECT_EQ(outline.components[0].euler_characteristic(), 1);  // a disk: the cut's six sides make one piece here
  EXPECT_EQ(outline.components[0].boundary_loops, 1);
}

TEST(FeatureCut, BoxFallsIntoSixSidesAndSitesComeInTwins) {
  const TriangleMesh box = cube(6);
  const remesh::FeatureSet features = remesh::detect_features(box);
  const remesh::FeatureCut cut = remesh::cut_along_features(box, features);
  const MeshTopology topology = build_mesh_topology(cut.mesh);
  ASSERT_EQ(topology.num_components(), 6);
  for (const ComponentCounts& side : topology.components) {
    EXPECT_EQ(side.euler_characteristic(), 1);  // a disk
    EXPECT_EQ(side.boundary_loops, 1);
  }
  // Corners: 3 copies; other crease vertices: 2.
  EXPECT_EQ(cut.mesh.vertices.rows(), box.vertices.rows() + 8 * 2 + 12 * 5);

  const remesh::FeatureSites sites = remesh::feature_sites(box, features, cut, {.spacing = 0.26});
  // 8 corners and 3 points inside each crease (4 stretches of 0.25).
  EXPECT_EQ(sites.points, 8 + 12 * 3);
  EXPECT_EQ(sites.sites.size(), 8u * 3 + 12u * 3 * 2);
  std::map<std::array<double, 3>, int> at;
  for (const SurfacePoint& site : sites.sites) {
    const Eigen::Vector3d p = site.position(cut.mesh);
    ++at[{p.x(), p.y(), p.z()}];
    // On a crease: two coordinates are 0 or 1.
    int on_faces = 0;
    for (int d = 0; d < 3; ++d) on_faces += p[d] == 0.0 || p[d] == 1.0;
    EXPECT_GE(on_faces, 2);
  }
  EXPECT_EQ(at.size(), static_cast<std::size_t>(sites.points));  // twins at exactly one position
  EXPECT_TRUE(remesh::missing_twins(box, features, cut, sites.sites).empty());
  // One side's site alone lacks its twin.
  const std::vector<SurfacePoint> one = {sites.sites.back()};
  EXPECT_EQ(remesh::missing_twins(box, features, cut, one).size(), 1u);
  // A site at one copy of a split vertex lacks the others.
  const Index copy = static_cast<Index>(box.vertices.rows());  // the first extra copy
  const Index original = cut.original_vertex[static_cast<std::size_t>(copy)];
  const auto copies = std::count(cut.original_vertex.begin(), cut.original_vertex.end(), original);
  ASSERT_GE(copies, 2);
  const std::vector<SurfacePoint> at_copy = {SurfacePoint::at_vertex(copy)};
  EXPECT_EQ(static_cast<std::ptrdiff_t>(remesh::missing_twins(box, features, cut, at_copy).size()), copies - 1);
}

/// The largest distance from a vertex of `chain` to the chord between the
/// chain's points (`sites`, on cut.mesh) on either side of it along the chain.
double largest_chord_error(const TriangleMesh& mesh, const remesh::FeatureChain& chain, const TriangleMesh& cut_mesh,
                           std::span<const SurfacePoint> sites) {
  // Each site on this chain by arc length: on one of its edges, within 1e-9.
  std::vector<double> at = {0};
  for (std::size_t i = 1; i < chain.vertices.size(); ++i) {
    at.push_back(at.back() + (mesh.vertices.row(chain.vertices[i]) - mesh.vertices.row(chain.vertices[i - 1])).norm());
  }
  const auto point_at = [&](double s) {
    const auto i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(at.begin(), at.end(), s) - at.begin()) - 1, at.size() - 2);
    const double t = at[i + 1] > at[i] ? std::clamp((s - at[i]) / (at[i + 1] - at[i]), 0.0, 1.0) : 0.0;
    return Eigen::Vector3d((1 - t) * mesh.vertices.row(chain.vertices[i]) +
                           t * mesh.vertices.row(chain.vertices[i + 1]));
  };
  std::vector<double> stops = {0, at.back()};
  for (const SurfacePoint& site : sites) {
    const Eigen::Vector3d x = site.position(cut_mesh);
    for (std::size_t i = 0; i + 1 < chain.vertices.size(); ++i) {
      const Eigen::Vector3d a = mesh.vertices.row(chain.vertices[i]), b = mesh.vertices.row(chain.vertices[i + 1]);
      const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      if ((a + t * (b - a) - x).norm() < 1e-9) {
        stops.push_back(at[i] + t * (at[i + 1] - at[i]));
        break;
      }
    }
  }
  std::sort(stops.begin(), stops.end());
  double largest = 0;
  for (std::size_t i = 1; i + 1 < chain.vertices.size(); ++i) {
    const auto after = std::lower_bound(stops.begin(), stops.end(), at[i]);
    if (after == stops.begin() || after == stops.end()) continue;
    const Eigen::Vector3d p = point_at(*(after - 1)), q = point_at(*after), x = mesh.vertices.row(chain.vertices[i]);
    const double t = (q - p).squaredNorm() > 0 ? std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0) : 0.0;
    largest = std::max(largest, (p + t * (q - p) - x).norm());
  }
  return largest;
}

TEST(FeatureCut, ChordRefinementOfACurvedChainKeepsTheMinimumSpacing) {
  // A cone's base rim is a circular crease of length 2 pi: at spacing 0.5,
  // 13 stretches whose chords leave the circle by about 0.03.
  const TriangleMesh cone =
      bench::hard_case_detail::closed_cone({0, 0, 0}, {0, 0, 1}, 1.0, 1.0, /*segments=*/256, /*rings=*/8);
  const remesh::FeatureSet features = remesh::detect_features(cone);
  ASSERT_EQ(features.sharp_chains, 1);
  ASSERT_TRUE(features.chains[0].closed);
  const remesh::FeatureCut cut = remesh::cut_along_features(cone, features);
  // The smallest gap between the rim's points (by angle, as a chord).
  const auto smallest_gap = [&](const remesh::FeatureSiteOptions& options) {
    std::vector<double> angles;
    for (const SurfacePoint& site : remesh::feature_sites(cone, features, cut, options).sites) {
      const Eigen::Vector3d p = site.position(cut.mesh);
      angles.push_back(std::atan2(p.y(), p.x()));
    }
    std::sort(angles.begin(), angles.end());
    angles.erase(std::unique(angles.begin(), angles.end()), angles.end());  // twins
    double gap = 2 * std::numbers::pi + angles.front() - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k) gap = std::min(gap, angles[k] - angles[k - 1]);
    return 2 * std::sin(gap / 2);
  };
  EXPECT_GT(smallest_gap({.spacing = 0.5}), 0.45);
  // A chord error of 1e-3 asks for 6 parts a stretch...
  EXPECT_LT(smallest_gap({.spacing = 0.5, .max_chord_error = 1e-3}), 0.1);
  // ... but none closer than the minimum spacing: 2 parts of 0.24.
  const double floored = smallest_gap({.spacing = 0.5, .max_chord_error = 1e-3, .min_spacing = 0.2});
  EXPECT_GT(floored, 0.2 * (1 - 1e-3));
  EXPECT_LT(floored, 0.3);
  EXPECT_TRUE(remesh::feature_sites(cone, features, cut, {.spacing = 0.5, .max_chord_error = 1e-3, .min_spacing = 0.2})
                  .dense_points.empty());
  // Where the floor leaves the chords 0.007 off the rim, beyond twice the
  // error, the rim is split (evenly where that keeps to twice the error,
  // else at its own vertices where it bends) into parts no shorter than 0.6
  // of the tight spacing whose chords keep to twice the error; every point
  // closer than the minimum spacing is reported with its spacing, for the
  // sites around it.
  const remesh::FeatureSiteOptions tight{
      .spacing = 0.5, .max_chord_error = 1e-3, .min_spacing = 0.2, .tight_spacing = 0.1};
  const double tightened = smallest_gap(tight);
  EXPECT_GT(tightened, 0.06);
  EXPECT_LT(tightened, 0.13);
  const remesh::FeatureSites sites = remesh::feature_sites(cone, features, cut, tight);
  EXPECT_LE(largest_chord_error(cone, features.chains[0], cut.mesh, sites.sites), 2e-3);
  ASSERT_FALSE(sites.dense_points.empty());
  for (const remesh::SpacedPoint& point : sites.dense_points) {
    EXPECT_LT(point.spacing, 0.2);
    EXPECT_GT(point.spacing, 0.06);
    EXPECT_NEAR(std::hypot(point.position.x(), point.position.y()), 1.0, 1e-3);
  }
}

TEST(FeatureCut, ChainSitesFollowACoarseCircleWithinTwiceTheChordError) {
  // A cylinder of radius 1 whose rims are 48-gons (sides 0.13), at a spacing
  // of 0.5: chords 3/4 of a spacing apart leave a rim by up to 0.03. With a
  // chord error of 2e-3 the rims' own vertices are their points where they
  // bend: every chord keeps to twice the error (the statistics' feature
  // recall tolerance, where the chord error is half of it), by construction.
  const TriangleMesh cylinder = bench::revolved_profile({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 48);
  const remesh::FeatureSet features = remesh::detect_features(cylinder);
  ASSERT_EQ(features.sharp_chains, 2);
  const remesh::FeatureCut cut = remesh::cut_along_features(cylinder, features);
  const remesh::FeatureSiteOptions options{
      .spacing = 0.5, .max_chord_error = 2e-3, .min_spacing = 0.375, .tight_spacing = 0.2};
  const remesh::FeatureSites sites = remesh::feature_sites(cylinder, features, cut, options);
  EXPECT_EQ(sites.chains_split_at_bends, 2);
  for (const remesh::FeatureChain& chain : features.chains) {
    EXPECT_LE(largest_chord_error(cylinder, chain, cut.mesh, sites.sites), 2 * options.max_chord_error);
  }
  // Without the closer points the chords leave the rim by more than that.
  remesh::FeatureSiteOptions loose = options;
  loose.tight_spacing = 0;
  const remesh::FeatureSites even = remesh::feature_sites(cylinder, features, cut, loose);
  EXPECT_EQ(even.chains_split_at_bends, 0);
  EXPECT_GT(largest_chord_error(cylinder, features.chains[0], cut.mesh, even.sites), 4 * options.max_chord_error);
  // Within a chord error of 0.05, chords 3/4 of a spacing apart keep to the rims.
  remesh::FeatureSiteOptions coarse_error = options;
  coarse_error.max_chord_error = 0.05;
  EXPECT_EQ(remesh::feature_sites(cylinder, features, cut, coarse_error).chains_split_at_bends, 0);
}

TEST(FeatureCut, ChainSitesFollowAMachinedPartsCreasesWithinTwiceTheChordError) {
  // OpenSCAD's example005 at the scale of 2,000 sites: circles of 60 sides
  // 2.1 long against a spacing of 12, whose chords 3/4 of a spacing apart
  // left them by twice the recall tolerance (93.7 % of its creases kept).
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/example005.stl").mesh).mesh;
  const remesh::RemeshSurface prepared(part);
  const remesh::FeatureSampling sampling = remesh::sample_features(prepared, 2000);
  ASSERT_GT(sampling.features.sharp_chains, 10);
  EXPECT_GT(sampling.points_tightened, 0);
  const double diagonal = (part.vertices.colwise().maxCoeff() - part.vertices.colwise().minCoeff()).norm();
  for (const remesh::FeatureChain& chain : sampling.features.chains) {
    EXPECT_LE(largest_chord_error(part, chain, sampling.cut.mesh, sampling.sites.sites), 1e-3 * diagonal);
  }
}

TEST(FeatureSampling, CloserChainSitesStayWithoutTheSitesBesideThemUnlessTheyAreTooMany) {
  // fandisk at 500 sites: its round creases' chain sites are closer than
  // 3/4 of a spacing; the sites beside them would be half as many again as
  // the count, so there are none (no density), but the chain keeps its
  // closer sites. Where those may add none (max_share_tightened 0), the
  // chains are sampled no closer than 3/4 of a spacing.
  const TriangleMesh fandisk = io::read_mesh("tests/data/fandisk.ply").mesh;
  const remesh::RemeshSurface prepared(fandisk);
  const remesh::FeatureSampling tight = remesh::sample_features(prepared, 500);
  EXPECT_GT(tight.points_tightened, 0);
  EXPECT_FALSE(tight.sites.dense_points.empty());
  EXPECT_TRUE(tight.density.empty());
  EXPECT_EQ(tight.sites_near_features, 0);
  remesh::FeatureSamplingOptions none_added;
  none_added.max_share_tightened = 0;
  const remesh::FeatureSampling loose = remesh::sample_features(prepared, 500, none_added);
  EXPECT_EQ(loose.points_tightened, 0);
  EXPECT_EQ(tight.sites.points - loose.sites.points, tight.points_tightened);
  remesh::FeatureSamplingOptions never;
  never.tight_spacing = 0;
  EXPECT_EQ(remesh::sample_features(prepared, 500, never).sites.sites.size(), loose.sites.sites.size());
}

TEST(FeatureSampling, CreasesRoundNarrowSmoothRegionsGoWhereTheChainsWouldTakeTheWholeCount) {
  // OpenSCAD's candleStand at 500 sites (cut to a manifold as the pipeline
  // does): with the creases round its narrow smooth faces the chains hold
  // more points than the count, and the remesh had no site left inside its
  // large faces (H 22 % of the diagonal); judged at the rough width
  // everywhere they hold fewer. At 2,000 sites they fit, and stay.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/candleStand.stl").mesh).mesh;
  const remesh::RemeshSurface prepared(part);
  remesh::FeatureSamplingOptions all_kept;
  all_kept.max_share_narrow_regions = std::numeric_limits<double>::max();
  const remesh::FeatureSampling crowded = remesh::sample_features(prepared, 500, all_kept);
  EXPECT_GT(crowded.sites.points, 500);
  const remesh::FeatureSampling fewer = remesh::sample_features(prepared, 500);
  // (besides the points where they bend, which the fewer take where the crowded exceed max_share_tightened)
  EXPECT_LT(fewer.sites.points - fewer.points_tightened, crowded.sites.points - crowded.points_tightened);
  EXPECT_LT(fewer.features.sharp_length, crowded.features.sharp_length);
  const remesh::FeatureSampling fitting = remesh::sample_features(prepared, 2000);
  EXPECT_LE(fitting.sites.points, 2000);
  EXPECT_DOUBLE_EQ(fitting.features.sharp_length,
                   remesh::sample_features(prepared, 2000, all_kept).features.sharp_length);
  all_kept.max_share_narrow_regions = -0.1;
  EXPECT_THROW(remesh::sample_features(prepared, 500, all_kept), UsageError);
  remesh::FeatureSamplingOptions wrong;
  wrong.parallel_fold_angle = 91;
  EXPECT_THROW(remesh::sample_features(prepared, 500, wrong), UsageError);
}

TEST(FeatureSampling, CreasesRoundNarrowFacetedSidesGoFirstWhereTheChainsWouldTakeTooMuchOfTheCount) {
  // OpenSCAD's projection at 500 sites: without the points where they bend,
  // its chains hold 475 points with the creases round its narrow faceted
  // sides (thin plates' polygonal rims) and its regions judged rough by
  // their folds, 451 without those. Where the chains may take 0.92 of the
  // count (460), its regions are judged by their folds, then those round
  // the faceted sides go, and the creases round its other narrow smooth
  // regions stay.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/projection.stl").mesh).mesh;
  const remesh::RemeshSurface prepared(part);
  remesh::FeatureSamplingOptions all_kept;
  all_kept.max_share_narrow_regions = std::numeric_limits<double>::max();
  remesh::FeatureSamplingOptions evenly = all_kept;
  evenly.tight_spacing = 0;
  EXPECT_GT(remesh::sample_features(prepared, 500, evenly).sites.points, 460);
  evenly.machined_regions_smooth = false;
  EXPECT_GT(remesh::sample_features(prepared, 500, evenly).sites.points, 460);
  evenly.parallel_fold_angle = 0;
  const remesh::FeatureSampling without_faceted = remesh::sample_features(prepared, 500, evenly);
  EXPECT_LE(without_faceted.sites.points, 460);
  remesh::FeatureSamplingOptions share;
  share.max_share_narrow_regions = 0.92;
  const remesh::FeatureSampling sampled = remesh::sample_features(prepared, 500, share);
  EXPECT_EQ(sampled.features.sharp_edges, without_faceted.features.sharp_edges);
  // Judged at the rough width everywhere, fewer would stay.
  evenly.max_share_narrow_regions = 0;
  EXPECT_LT(remesh::sample_features(prepared, 500, evenly).features.sharp_length, sampled.features.sharp_length);
}

TEST(FeatureSampling, PointsWhereChainsBendGoBeforeCreasesWhereTheyAloneExceedTheShare) {
  // projection at 500 sites: the points where its chains bend take them
  // from 475 points to more than the count. Those points go, and every
  // crease stays, at the chains' even spacing.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/projection.stl").mesh).mesh;
  const remesh::RemeshSurface prepared(part);
  remesh::FeatureSamplingOptions all_kept;
  all_kept.max_share_narrow_regions = std::numeric_limits<double>::max();
  const remesh::FeatureSampling tightened = remesh::sample_features(prepared, 500, all_kept);
  ASSERT_GT(tightened.sites.points, 500);
  all_kept.tight_spacing = 0;
  const remesh::FeatureSampling evenly = remesh::sample_features(prepared, 500, all_kept);
  ASSERT_LE(evenly.sites.points, 500);
  const remesh::FeatureSampling sampled = remesh::sample_features(prepared, 500);
  EXPECT_EQ(sampled.features.sharp_edges, tightened.features.sharp_edges);
  EXPECT_EQ(sampled.sites.points, evenly.sites.points);
  EXPECT_EQ(sampled.points_tightened, 0);
  EXPECT_TRUE(sampled.density.empty());
}

TEST(FeatureSampling, EvenlyCloserPointsWhereThoseAtTheBendsAreMoreThanTheCountCarries) {
  // OpenSCAD's CSG-modules at 500 sites: its chains' points at their own
  // vertices where they bend would add more than a quarter of the count
  // (max_share_tightened); evenly closer ones add fewer, and stay.
  const TriangleMesh part = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/CSG-modules.stl").mesh).mesh;
  const remesh::RemeshSurface prepared(part);
  remesh::FeatureSamplingOptions unbounded;
  unbounded.max_share_tightened = std::numeric_limits<double>::max();
  const remesh::FeatureSampling at_bends = remesh::sample_features(prepared, 500, unbounded);
  ASSERT_GT(at_bends.sites.chains_split_at_bends, 0);
  ASSERT_GT(at_bends.points_tightened, 125);
  const remesh::FeatureSampling sampled = remesh::sample_features(prepared, 500);
  EXPECT_EQ(sampled.features.sharp_edges, at_bends.features.sharp_edges);
  EXPECT_EQ(sampled.sites.chains_split_at_bends, 0);
  EXPECT_GT(sampled.points_tightened, 0);
  EXPECT_LE(sampled.points_tightened, 125);
}

TEST(FeatureCut, WeldMergesTwinsAndFindsNoCrackInAClosedDual) {
  // Sites at the corners, the crease midpoints and each side's centre: the
  // sides' duals must weld into one closed surface.
  const TriangleMesh box = cube(8);
  const remesh::FeatureSet features = remesh::detect_features(box);
  const remesh::FeatureCut cut = remesh::cut_along_features(box, features);
  remesh::FeatureSites sites = remesh::feature_sites(box, features, cut, {.spacing = 0.5});
  const voronoi::GeodesicSurface surface(cut.mesh);
  std::vector<SurfacePoint> all = sites.sites;
  add_side_centres(cut, all);
  ASSERT_EQ(all.size(), sites.sites.size() + 6);
  const remesh::RepairedDual dual =
      remesh::welded_dual_with_repair(surface, box, features, cut, all, voronoi::compute_voronoi(surface, all));
  const MeshTopology welded = build_mesh_topology(dual.mesh);
  ASSERT_EQ(welded.num_components(), 1);
  EXPECT_EQ(welded.components[0].euler_characteristic(), 2);
  EXPECT_EQ(welded.num_boundary_loops, 0);
  for (Index e = 0; e < welded.num_edges(); ++e) EXPECT_TRUE(welded.is_manifold_edge(e));
  // One vertex per distinct position of the sites: twins welded, nothing else.
  std::set<std::array<double, 3>> positions;
  for (const SurfacePoint& site : dual.sites) {
    const Eigen::Vector3d p = site.position(cut.mesh);
    positions.insert({p.x(), p.y(), p.z()});
  }
  EXPECT_EQ(dual.mesh.vertices.rows(), static_cast<Index>(positions.size()));
}

/// cube(8) cut along its creases, sites at spacing 0.5 on the creases and
/// at each side's centre, and the dual of their diagram on the cut surface:
/// the sides' duals, which weld into one closed surface.
struct CutBoxDual {
  TriangleMesh box = cube(8);
  remesh::FeatureSet features = remesh::detect_features(box);
  remesh::FeatureCut cut = remesh::cut_along_features(box, features);
  std::vector<SurfacePoint> sites;
  TriangleMesh dual;
  CutBoxDual() {
    sites = remesh::feature_sites(box, features, cut, {.spacing = 0.5}).sites;
    add_side_centres(cut, sites);
    const voronoi::GeodesicSurface surface(cut.mesh);
    dual = remesh::dual_delaunay(cut.mesh, voronoi::compute_voronoi(surface, sites)).mesh;
  }
};

TEST(FeatureCut, WeldLeavesOutAFlapFoldedOntoItselfAndTheSitesOnlyItHeld) {
  // The box's sides' dual, welded: then the same with a triangle and its
  // mirror image added on a new site, as cells reaching the same three sites
  // from both sides of a chain make them.
  CutBoxDual cut_box;
  auto& [box, features, cut, sites, dual] = cut_box;
  const remesh::WeldedDual plain = remesh::weld_along_features(box, features, cut, dual, sites);
  ASSERT_EQ(plain.cracked_edges, 0);
  ASSERT_EQ(plain.nonmanifold_edges, 0);
  EXPECT_EQ(plain.folded_pairs, 0);
  EXPECT_TRUE(plain.unused_sites.empty());

  TriangleMesh folded = dual;
  const Index a = dual.faces(0, 0), b = dual.faces(0, 1), extra = dual.num_vertices();
  sites.push_back(SurfacePoint::in_face(0, 0.2, 0.3, 0.5));
  folded.vertices.conservativeResize(extra + 1, 3);
  folded.vertices.row(extra) = sites.back().position(cut.mesh).transpose();
  folded.faces.conservativeResize(dual.num_faces() + 2, 3);
  folded.faces.row(dual.num_faces()) << a, b, extra;
  folded.faces.row(dual.num_faces() + 1) << b, a, extra;
  const remesh::WeldedDual welded = remesh::weld_along_features(box, features, cut, folded, sites);
  EXPECT_EQ(welded.folded_pairs, 1);
  EXPECT_EQ(welded.nonmanifold_edges, 0);
  EXPECT_EQ(welded.cracked_edges, 0);
  EXPECT_EQ(welded.mesh.faces, plain.mesh.faces);
  EXPECT_EQ(welded.unused_sites, std::vector<std::size_t>{sites.size() - 1});
}

TEST(FeatureCut, ASiteThatCracksTheWeldBetweenTwoChainSitesMovesHalfwayBetweenThem) {
  // The box's sides' dual with its triangle on corner A = (0, 0, 0), the
  // crease midpoint B = (0.5, 0, 0) and a third site of the bottom side split
  // at a site X next to A inside that side: X's cell would reach the crease
  // between A and B, so the weld cracks along A-X-B.
  CutBoxDual cut_box;
  auto& [box, features, cut, sites, dual] = cut_box;
  const Eigen::Vector3d a(0, 0, 0), b(0.5, 0, 0);
  const auto at = [&](Index v, const Eigen::Vector3d& p) {
    return (dual.vertices.row(v).transpose() - p).norm() < 1e-6;
  };
  Index split = -1;
  int rotation = 0;  // where A is in the split triangle
  for (Index f = 0; f < dual.num_faces() && split < 0; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index next = dual.faces(f, (k + 1) % 3), after = dual.faces(f, (k + 2) % 3);
      const bool bottom = dual.vertices(next, 2) == 0 && dual.vertices(after, 2) == 0;
      if (at(dual.faces(f, k), a) && (at(next, b) || at(after, b)) && bottom) {
        split = f;
        rotation = k;
      }
    }
  }
  ASSERT_GE(split, 0);
  const Index va = dual.faces(split, rotation), next = dual.faces(split, (rotation + 1) % 3),
              after = dual.faces(split, (rotation + 2) % 3);
  // X at (0.1, 0.05, 0), on the bottom side's face holding it.
  const Eigen::Vector2d x(0.1, 0.05);
  SurfacePoint at_x;
  for (Index f = 0; f < cut.mesh.num_faces(); ++f) {
    Eigen::Matrix<double, 3, 3> corners;
    for (int k = 0; k < 3; ++k) corners.col(k) = cut.mesh.vertices.row(cut.mesh.faces(f, k)).transpose();
    if (corners.row(2).cwiseAbs().maxCoeff() != 0) continue;
    Eigen::Matrix2d edges;
    edges << corners.block<2, 1>(0, 1) - corners.block<2, 1>(0, 0),
        corners.block<2, 1>(0, 2) - corners.block<2, 1>(0, 0);
    const Eigen::Vector2d uv = edges.inverse() * (x - corners.block<2, 1>(0, 0));
    if (uv.minCoeff() > 0 && uv.sum() < 1) at_x = SurfacePoint::in_face(f, 1 - uv.sum(), uv.x(), uv.y());
  }
  ASSERT_EQ(at_x.kind, SurfacePoint::Kind::face);
  sites.push_back(at_x);
  const Index vx = dual.num_vertices();
  dual.vertices.conservativeResize(vx + 1, 3);
  dual.vertices.row(vx) = at_x.position(cut.mesh).transpose();
  // X on edge A-B of the triangle, the orientation kept.
  dual.faces.conservativeResize(dual.num_faces() + 1, 3);
  if (at(next, b)) {  // A, B, C
    dual.faces.row(split) << va, vx, after;
    dual.faces.row(dual.num_faces() - 1) << vx, next, after;
  } else {  // A, C, B
    dual.faces.row(split) << va, next, vx;
    dual.faces.row(dual.num_faces() - 1) << vx, next, after;
  }

  const remesh::WeldedDual welded = remesh::weld_along_features(box, features, cut, dual, sites);
  EXPECT_GT(welded.cracked_edges, 0);
  ASSERT_EQ(welded.site_moves.size(), 1u);
  EXPECT_EQ(welded.site_moves[0].first, sites.size() - 1);
  // Not the crease's point nearest X, (0.1, 0, 0): the middle of A-B (to
  // the lattice's margin: there it is the mesh vertex at (0.25, 0, 0)).
  const Eigen::Vector3d middle =
      (dual.vertices.row(va) + dual.vertices.row(at(next, b) ? next : after)).transpose() / 2;
  EXPECT_LT((welded.site_moves[0].second.position(cut.mesh) - middle).norm(), 1e-6);
}

TEST(ChainSlider, APointAndItsTwinSlideTogetherAlongTheirChainByTheCellsPullAlongIt) {
  const TriangleMesh box = cube(6);
  const remesh::FeatureSet features = remesh::detect_features(box);
  const remesh::FeatureCut cut = remesh::cut_along_features(box, features);
  // Per crease: the corners at 0 and 1, points at 0.25, 0.5 and 0.75 (twins).
  const std::vector<SurfacePoint> sites = remesh::feature_sites(box, features, cut, {.spacing = 0.26}).sites;
  const remesh::ChainSlider slide(box, features, cut);
  const auto position = [&](const SurfacePoint& site) { return Eigen::Vector3d(site.position(cut.mesh)); };
  const auto same = [](const SurfacePoint& a, const SurfacePoint& b) {
    return a.kind == b.kind && a.element == b.element && a.barycentric == b.barycentric;
  };
  const auto normal = [&](Index f) {
    const Eigen::Vector3d a = cut.mesh.vertices.row(cut.mesh.faces(f, 0)),
                          b = cut.mesh.vertices.row(cut.mesh.faces(f, 1)),
                          c = cut.mesh.vertices.row(cut.mesh.faces(f, 2));
    return Eigen::Vector3d((b - a).cross(c - a).normalized());
  };
  // The twins of one crease's middle point, and the crease's direction.
  std::vector<std::size_t> twins;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Eigen::Vector3d p = position(sites[i]);
    if (std::abs(p.x() - 0.5) < 1e-6 && p.y() == 0 && p.z() == 0) twins.push_back(i);
  }
  ASSERT_EQ(twins.size(), 2u);
  const double x0 = position(sites[twins[0]]).x();  // 0.5, on the lattice of edge parameters
  const std::vector<double> mass(sites.size(), 1.0);
  const auto pulled = [&](const Eigen::Vector3d& pull) {
    std::vector<Eigen::Vector3d> moment(sites.size(), Eigen::Vector3d::Zero());
    for (const std::size_t i : twins) moment[i] = pull;  // mass 1 each: Lloyd's step is the pull
    return slide(sites, mass, moment);
  };
  const auto expect_only_twins_at = [&](const std::vector<SurfacePoint>& moved, double x) {
    for (std::size_t i = 0; i < sites.size(); ++i) {
      if (std::find(twins.begin(), twins.end(), i) == twins.end()) {
        EXPECT_TRUE(same(moved[i], sites[i])) << i;
        continue;
      }
      EXPECT_NEAR(position(moved[i]).x(), x, 1e-9);
      EXPECT_EQ(position(moved[i]).y(), 0.0);
      EXPECT_EQ(position(moved[i]).z(), 0.0);
      EXPECT_EQ(position(moved[i]), position(moved[twins[0]]));  // exactly one point still
      // On its own side: a face with the normal of the one it left.
      EXPECT_GT(normal(sites[i].element).dot(normal(moved[i].element)), 1 - 1e-12);
    }
  };
  // The twins' pulls along the crease (0.05 each, mass 1 each) move the point by 0.05.
  expect_only_twins_at(pulled({0.05, 0.02, 0.02}), x0 + 0.05);
  // Across it, they move nothing.
  expect_only_twins_at(pulled({0, 0.3, -0.1}), x0);
  // A pull past a neighbour goes a third of the way to it (at 0.25).
  expect_only_twins_at(pulled({-1, 0, 0}), x0 - (x0 - 0.25) / 3);
  // Corners (vertex sites) stay, whatever their pull.
  std::vector<Eigen::Vector3d> moment(sites.size(), Eigen::Vector3d(0.1, 0.1, 0.1));
  const std::vector<SurfacePoint> moved = slide(sites, mass, moment);
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (sites[i].kind == SurfacePoint::Kind::vertex) {
      EXPECT_TRUE(same(moved[i], sites[i]));
    }
  }
}

}  // namespace
}  // namespace geodual
