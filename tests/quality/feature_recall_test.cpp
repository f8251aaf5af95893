// Feature recall against figures worked out by hand: a cube against finer
// meshes of itself (every crease is an edge: recall 100, gap 0), against the
// cube with one corner cut off (three creases end in chords), against larger
// cubes (every crease at one known distance from the nearest edge), and a
// sphere (no crease at all); the recall on the long creases alone (sharp
// chains at least a length long) on the cut cube, a finer cube and a
// cylinder whose rims are loops.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace geodual::quality {
namespace {

using Vec = Eigen::Vector3d;

TriangleMesh make_mesh(const std::vector<Vec>& points, const std::vector<std::array<Index, 3>>& faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = points[i];
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) mesh.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];
  }
  return mesh;
}

/// Corner k of the unit cube: (k & 1, k >> 1 & 1, k >> 2 & 1).
std::vector<Vec> cube_corners() {
  std::vector<Vec> p;
  for (int k = 0; k < 8; ++k) p.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  return p;
}

/// The unit cube [0, 1]^3 in 12 triangles, counter-clockwise seen from outside.
TriangleMesh unit_cube() {
  return make_mesh(cube_corners(), {
                                       {0, 2, 3},
                                       {0, 3, 1},
                                       {4, 5, 7},
                                       {4, 7, 6},  // z = 0, z = 1
                                       {0, 1, 5},
                                       {0, 5, 4},
                                       {2, 6, 7},
                                       {2, 7, 3},  // y = 0, y = 1
                                       {0, 4, 6},
                                       {0, 6, 2},
                                       {1, 3, 7},
                                       {1, 7, 5},  // x = 0, x = 1
                                   });
}

/// The unit cube with each side an n x n grid of squares, each split by a
/// diagonal, vertices shared along the creases, oriented outwards.
TriangleMesh grid_cube(int n) {
  std::map<std::array<int, 3>, Index> index;
  std::vector<Vec> points;
  const auto vertex = [&](const std::array<int, 3>& lattice) {
    const auto [it, inserted] = index.try_emplace(lattice, static_cast<Index>(points.size()));
    if (inserted) points.emplace_back(Vec(lattice[0], lattice[1], lattice[2]) / n);
    return it->second;
  };
  std::vector<std::array<Index, 3>> faces;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (const int side : {0, n}) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<std::array<int, 3>, 4> quad;
          for (int c = 0; c < 4; ++c) {
            quad[c][axis] = side;
            quad[c][u] = i + (c == 1 || c == 2);
            quad[c][v] = j + (c >= 2);
          }
          // (u, v, axis) is right-handed: counter-clockwise seen from +axis.
          std::array<Index, 4> q{vertex(quad[0]), vertex(quad[1]), vertex(quad[2]), vertex(quad[3])};
          if (side == 0) std::swap(q[1], q[3]);
          faces.push_back({q[0], q[1], q[2]});
          faces.push_back({q[0], q[2], q[3]});
        }
      }
    }
  }
  return make_mesh(points, faces);
}

/// The unit cube with the corner (1, 1, 1) cut off by the plane through the
/// points a from it on its three edges. The three pentagons are fanned from
/// their corner opposite the cut, so that no diagonal comes nearer a crease
/// than the chords of the cut do.
TriangleMesh cube_cut_at_corner(double a) {
  std::vector<Vec> p = cube_corners();
  p.pop_back();  // corner 7, (1, 1, 1)
  const Index cx = 7, cy = 8, cz = 9;
  p.emplace_back(1 - a, 1, 1);
  p.emplace_back(1, 1 - a, 1);
  p.emplace_back(1, 1, 1 - a);
  return make_mesh(p, {
                          {0, 2, 3},
                          {0, 3, 1},
                          {0, 1, 5},
                          {0, 5, 4},
                          {0, 4, 6},
                          {0, 6, 2},  // x, y, z = 0
                          {4, 5, cy},
                          {4, cy, cx},
                          {4, cx, 6},  // z = 1
                          {2, 6, cx},
                          {2, cx, cz},
                          {2, cz, 3},  // y = 1
                          {1, 3, cz},
                          {1, cz, cy},
                          {1, cy, 5},    // x = 1
                          {cx, cy, cz},  // the cut
                      });
}

/// `mesh` scaled by `scale` about (0.5, 0.5, 0.5).
TriangleMesh scaled_about_centre(TriangleMesh mesh, double scale) {
  const Vec centre(0.5, 0.5, 0.5);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Vec p = mesh.vertices.row(v);
    mesh.vertices.row(v) = centre + scale * (p - centre);
  }
  return mesh;
}

QualityOptions with_tolerance(double pct) {
  QualityOptions options;
  options.feature_tolerance_pct = pct;
  return options;
}

const double cube_diagonal = std::sqrt(3.0);

TEST(FeatureRecall, CubeAgainstFinerCubesIsComplete) {
  // Every crease of the coarse cube is a chain of edges of the fine one, and
  // the reverse: nothing is farther than rounding.
  const TriangleMesh coarse = unit_cube();
  const TriangleMesh fine = grid_cube(4);
  const FeatureRecall forward = feature_recall(coarse, fine);
  EXPECT_EQ(forward.edges, 12);  // the face diagonals are flat
  EXPECT_NEAR(forward.length, 12.0, 1e-12);
  EXPECT_EQ(forward.recall_pct, 100.0);
  EXPECT_LT(forward.max_gap_pct, 1e-12);
  EXPECT_EQ(forward.sharp_angle_deg, 60.0);
  EXPECT_NEAR(forward.tolerance, 0.001 * cube_diagonal, 1e-15);
  // Both ends and a point every tenth of the tolerance: 5,775 per crease.
  EXPECT_EQ(forward.samples, 12 * (static_cast<std::int64_t>(std::ceil(1.0 / (forward.tolerance / 10))) + 1));

  const FeatureRecall backward = feature_recall(fine, coarse);
  EXPECT_EQ(backward.edges, 12 * 4);
  EXPECT_NEAR(backward.length, 12.0, 1e-12);
  EXPECT_EQ(backward.recall_pct, 100.0);
  EXPECT_LT(backward.max_gap_pct, 1e-12);
}

TEST(FeatureRecall, CornerCutOffByChords) {
  // A point s < a from the cut corner, on one of its three creases, is
  // (a - s) / sqrt(2) from the nearest chord of the cut (the foot of the
  // perpendicular is on the chord), nearer than any other edge. So it is
  // recalled when s >= a - sqrt(2) tau, and the corner itself is the farthest
  // point, a / sqrt(2) away.
  const double a = 0.05;
  const TriangleMesh cube = unit_cube();
  const TriangleMesh cut = cube_cut_at_corner(a);
  for (const double tolerance_pct : {0.1, 0.5, 1.0}) {
    const double tau = tolerance_pct / 100 * cube_diagonal;
    const double lost = 3 * (a - std::sqrt(2.0) * tau);
    const FeatureRecall recall = feature_recall(cube, cut, with_tolerance(tolerance_pct));
    EXPECT_EQ(recall.edges, 12);
    // The trapezoid rule errs by at most half a sample spacing (tau / 10) at
    // each of the three places where the distance crosses the tolerance.
    EXPECT_NEAR(recall.recall_pct, 100 * (12 - lost) / 12, 100 * 3 * (tau / 20) / 12) << tolerance_pct;
    EXPECT_NEAR(recall.max_gap, a / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(recall.max_gap_pct, 100 * a / std::sqrt(2.0) / cube_diagonal, 1e-10);
  }
  // A tolerance beyond the largest gap recalls everything.
  const double beyond_pct = 100 * a / std::sqrt(2.0) / cube_diagonal * 1.01;
  EXPECT_EQ(feature_recall(cube, cut, with_tolerance(beyond_pct)).recall_pct, 100.0);
  // The cut cube's own creases are all edges of itself.
  EXPECT_EQ(feature_recall(cut, cut).recall_pct, 100.0);
}

TEST(FeatureRecall, LargerCubeIsAtAKnownDistance) {
  // The cube grown by d on every side: each crease runs parallel to the
  // larger cube's, d sqrt(2) away, and no edge of the larger cube comes
  // nearer than d (its faces are d away from the inner cube). So with the
  // default tolerance tau = 0.001 sqrt(3): d = 0.001 is recalled everywhere
  // (d sqrt(2) < tau), d = 0.002 nowhere (d > tau).
  const TriangleMesh cube = unit_cube();
  for (const double d : {0.001, 0.002}) {
    const FeatureRecall recall = feature_recall(cube, scaled_about_centre(cube, 1 + 2 * d));
    EXPECT_EQ(recall.recall_pct, d == 0.001 ? 100.0 : 0.0) << d;
    EXPECT_NEAR(recall.max_gap, d * std::sqrt(2.0), 1e-12) << d;
    EXPECT_NEAR(recall.max_gap_pct, 100 * d * std::sqrt(2.0) / cube_diagonal, 1e-10) << d;
  }
}

TEST(FeatureRecall, SphereHasNoFeatures) {
  const TriangleMesh sphere = test::icosphere(3);
  TriangleMesh bumpy = sphere;
  for (Index v = 0; v < bumpy.num_vertices(); ++v) bumpy.vertices.row(v) *= 1.0 + 0.02 * std::sin(7.0 * v);
  const FeatureRecall recall = feature_recall(sphere, bumpy);
  EXPECT_EQ(recall.edges, 0);
  EXPECT_EQ(recall.length, 0.0);
  EXPECT_EQ(recall.samples, 0);
  EXPECT_EQ(recall.recall_pct, 100.0);
  EXPECT_EQ(recall.max_gap_pct, 0.0);
}

TEST(FeatureRecall, AngleChoosesTheCreases) {
  // The cube's creases turn by 90 degrees, the cut's chords by
  // acos(1 / sqrt(3)) = 54.7 degrees, the cut's diagonals by 0.
  const TriangleMesh cut = cube_cut_at_corner(0.25);
  QualityOptions options;
  options.sharp_angle_deg = 50;
  EXPECT_EQ(feature_recall(cut, cut, options).edges, 12 + 3);
  options.sharp_angle_deg = 60;
  EXPECT_EQ(feature_recall(cut, cut, options).edges, 12);
  EXPECT_NEAR(feature_recall(cut, cut, options).length, 12 - 3 * 0.25, 1e-12);
  options.sharp_angle_deg = 91;
  EXPECT_EQ(feature_recall(cut, cut, options).edges, 0);
}

TEST(FeatureRecall, CompareMeshesCarriesIt) {
  const TriangleMesh cube = unit_cube();
  const TriangleMesh cut = cube_cut_at_corner(0.05);
  QualityOptions options;
  options.samples_per_side = 1000;
  const QualityReport report = compare_meshes(cube, cut, options);
  ASSERT_TRUE(report.features.has_value());
  const FeatureRecall alone = feature_recall(cube, cut, options);
  EXPECT_EQ(report.features->edges, alone.edges);
  EXPECT_EQ(report.features->length, alone.length);
  EXPECT_EQ(report.features->samples, alone.samples);
  EXPECT_EQ(report.features->recall_pct, alone.recall_pct);
  EXPECT_EQ(report.features->max_gap_pct, alone.max_gap_pct);
  EXPECT_LT(report.features->recall_pct, 99.0);

  options.sharp_angle_deg = 0;  // off
  EXPECT_FALSE(compare_meshes(cube, cut, options).features.has_value());
}

TEST(FeatureRecall, DeterministicProgressAndCancel) {
  // 720 creases of the fine cube against the cut cube: about 70,000 samples.
  const TriangleMesh fine = grid_cube(60);
  const TriangleMesh cut = cube_cut_at_corner(0.05);
  const FeatureRecall plain = feature_recall(fine, cut);
  EXPECT_EQ(plain.edges, 720);
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    const FeatureRecall serial = feature_recall(fine, cut);
    EXPECT_EQ(serial.recall_pct, plain.recall_pct);
    EXPECT_EQ(serial.max_gap, plain.max_gap);
  }
  QualityOptions watched;
  std::vector<double> fractions;
  watched.progress = [&fractions](double fraction) {
    fractions.push_back(fraction);
    return true;
  };
  const FeatureRecall reported = feature_recall(fine, cut, watched);
  EXPECT_EQ(reported.recall_pct, plain.recall_pct);
  ASSERT_GT(fractions.size(), 5U);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));

  for (const int threads : {0, 1}) {
    QualityOptions cancelling;
    bool refused = false;
    int calls_after_refusal = 0;
    cancelling.progress = [&](double fraction) {
      if (refused) ++calls_after_refusal;
      refused = refused || fraction >= 0.6;  // while sampling
      return !refused;
    };
    std::optional<tbb::global_control> single;
    if (threads == 1) single.emplace(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_THROW(feature_recall(fine, cut, cancelling), Cancelled);
    EXPECT_TRUE(refused);
    EXPECT_EQ(calls_after_refusal, 0);
  }
}

TEST(FeatureRecall, BadRequestsAreErrors) {
  const TriangleMesh cube = unit_cube();
  for (const double angle : {0.0, -1.0, 181.0, std::numeric_limits<double>::quiet_NaN()}) {
    QualityOptions options;
    options.sharp_angle_deg = angle;
    EXPECT_THROW(feature_recall(cube, cube, options), Error) << angle;
    if (angle != 0.0) {
      EXPECT_THROW(compare_meshes(cube, cube, options), Error) << angle;
    }
  }
  for (const double tolerance : {0.0, -0.1, std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(feature_recall(cube, cube, with_tolerance(tolerance)), Error) << tolerance;
  }
  // 12 creases of length 1 at a hundred-millionth of the tolerance: too many samples.
  EXPECT_THROW(feature_recall(cube, cube, with_tolerance(1e-9)), Error);
  try {
    feature_recall(cube, make_mesh({Vec(0, 0, 0)}, {{0, 0, 1}}));
    FAIL() << "a face out of range must be refused";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("candidate mesh: ", 0), 0U) << error.what();
  }
  try {
    feature_recall(cube, make_mesh({Vec(0, 0, 0)}, {{0, 0, 0}}));
    FAIL() << "a candidate without edges must be refused";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()).rfind("candidate mesh: ", 0), 0U) << error.what();
  }
}

/// The segments from->to of `points` as the candidate's only edges: faces
/// (a, b, b), whose one edge is a-b.
TriangleMesh segments(const TriangleMesh& points, const std::vector<std::array<Index, 2>>& ends) {
  TriangleMesh mesh;
  mesh.vertices = points.vertices;
  mesh.faces.resize(static_cast<Eigen::Index>(ends.size()), 3);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    mesh.faces.row(static_cast<Eigen::Index>(i)) << ends[i][0], ends[i][1], ends[i][1];
  }
  return mesh;
}

/// A closed cylinder of radius 1 and height 1, its rims n-gons, its caps fans
/// from their centres, oriented outwards.
TriangleMesh closed_cylinder(int n) {
  std::vector<Vec> p{Vec(0, 0, 0), Vec(0, 0, 1)};
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    p.emplace_back(std::cos(t), std::sin(t), 0);
    p.emplace_back(std::cos(t), std::sin(t), 1);
  }
  std::vector<std::array<Index, 3>> faces;
  for (int i = 0; i < n; ++i) {
    const Index b = 2 + 2 * i, t = b + 1, b1 = 2 + 2 * ((i + 1) % n), t1 = b1 + 1;
    faces.push_back({b, b1, t1});
    faces.push_back({b, t1, t});
    faces.push_back({1, t, t1});
    faces.push_back({0, b1, b});
  }
  return make_mesh(p, faces);
}

TEST(FeatureRecall, LongCreasesAreTheChainsAtLeastTheLengthAsked) {
  // The cube with a corner cut off at a = 0.25 has 12 chains, one per
  // crease, between the cube's seven corners (three sharp edges each) and
  // the cut's three points (one each: the chords turn by 54.7 degrees): nine
  // of length 1 and three of 0.75 (6-cx, 5-cy, 3-cz; cx, cy, cz are 7, 8, 9).
  const TriangleMesh cut = cube_cut_at_corner(0.25);
  const std::vector<std::array<Index, 2>> full{{0, 1}, {0, 2}, {0, 4}, {1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  const std::vector<std::array<Index, 2>> truncated{{6, 7}, {5, 8}, {3, 9}};
  QualityOptions options;
  options.long_crease_length = 0.9;
  const FeatureRecall itself = feature_recall(cut, cut, options);
  EXPECT_EQ(itself.edges, 12);
  EXPECT_EQ(itself.chains, 12);
  EXPECT_EQ(itself.long_crease_length, 0.9);
  EXPECT_EQ(itself.long_chains, 9);
  EXPECT_EQ(itself.long_edges, 9);
  EXPECT_NEAR(itself.long_length, 9.0, 1e-12);
  EXPECT_EQ(itself.long_recall_pct, 100.0);

  // Only the full creases as edges: all of the long creases, and of the
  // short ones only what lies within the tolerance tau of a corner where
  // they meet a full one (tau each, up to the trapezoid rule's tau / 20).
  const double tau = 0.001 * cube_diagonal;
  const FeatureRecall on_full = feature_recall(cut, segments(cut, full), options);
  EXPECT_EQ(on_full.long_recall_pct, 100.0);
  EXPECT_NEAR(on_full.recall_pct, 100 * (9 + 3 * tau) / 11.25, 100 * 3 * (tau / 20) / 11.25);
  // Only the short ones: of the long creases, tau at each of the six ends
  // that meet a short one.
  const FeatureRecall on_truncated = feature_recall(cut, segments(cut, truncated), options);
  EXPECT_NEAR(on_truncated.long_recall_pct, 100 * 6 * tau / 9, 100 * 6 * (tau / 20) / 9);
  EXPECT_NEAR(on_truncated.recall_pct, 100 * (2.25 + 6 * tau) / 11.25, 100 * 6 * (tau / 20) / 11.25);

  // A shorter length takes all, a longer one none (and then the recall is 100).
  options.long_crease_length = 0.7;
  const FeatureRecall all = feature_recall(cut, segments(cut, full), options);
  EXPECT_EQ(all.long_chains, 12);
  EXPECT_NEAR(all.long_length, 11.25, 1e-12);
  EXPECT_EQ(all.long_recall_pct, all.recall_pct);
  options.long_crease_length = 1.5;
  const FeatureRecall none = feature_recall(cut, segments(cut, truncated), options);
  EXPECT_EQ(none.long_chains, 0);
  EXPECT_EQ(none.long_length, 0.0);
  EXPECT_EQ(none.long_recall_pct, 100.0);
  // 0: not measured, but the chains are counted.
  options.long_crease_length = 0;
  const FeatureRecall off = feature_recall(cut, segments(cut, truncated), options);
  EXPECT_EQ(off.chains, 12);
  EXPECT_EQ(off.long_crease_length, 0.0);
  EXPECT_EQ(off.long_chains, 0);
  EXPECT_EQ(off.long_recall_pct, 100.0);
  // compare_meshes carries it.
  options.long_crease_length = 0.9;
  options.samples_per_side = 100;
  const QualityReport report = compare_meshes(cut, cut, options);
  ASSERT_TRUE(report.features.has_value());
  EXPECT_EQ(report.features->long_chains, 9);

  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.long_crease_length = bad;
    EXPECT_THROW(feature_recall(cut, cut, options), Error) << bad;
  }
}

TEST(FeatureRecall, ChainsRunThroughVerticesOfTwoSharpEdgesAndClose) {
  // The cube as a 3 x 3 grid per side: each crease is three sharp edges whose
  // inner vertices have two, so one chain of length 1.
  QualityOptions options;
  options.long_crease_length = 0.9;
  const FeatureRecall grid = feature_recall(grid_cube(3), grid_cube(3), options);
  EXPECT_EQ(grid.edges, 36);
  EXPECT_EQ(grid.chains, 12);
  EXPECT_EQ(grid.long_chains, 12);
  EXPECT_EQ(grid.long_edges, 36);

  // A closed cylinder of 12 sides: the side's edges turn by 30 degrees, the
  // rims by 90: two loops without a corner, each 12 * 2 sin(pi / 12) long.
  const TriangleMesh cylinder = closed_cylinder(12);
  const double rim = 24 * std::sin(std::numbers::pi / 12);
  options.long_crease_length = rim * 0.999;
  const FeatureRecall loops = feature_recall(cylinder, cylinder, options);
  EXPECT_EQ(loops.edges, 24);
  EXPECT_EQ(loops.chains, 2);
  EXPECT_EQ(loops.long_chains, 2);
  EXPECT_NEAR(loops.long_length, 2 * rim, 1e-12);
  options.long_crease_length = rim * 1.001;
  EXPECT_EQ(feature_recall(cylinder, cylinder, options).long_chains, 0);
}

TEST(FeatureRecall, FandiskAgainstItself) {
  const TriangleMesh fandisk = io::read_mesh("tests/data/fandisk.ply").mesh;
  const FeatureRecall recall = feature_recall(fandisk, fandisk);
  EXPECT_GT(recall.edges, 100);
  EXPECT_GT(recall.length, 0.0);
  EXPECT_EQ(recall.recall_pct, 100.0);
  EXPECT_LT(recall.max_gap_pct, 1e-10);
}

}  // namespace
}  // namespace geodual::quality
