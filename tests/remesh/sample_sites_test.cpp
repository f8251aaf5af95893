// Site sampling: count, validity, determinism, area uniformity, spacing of
// the blue-noise and farthest-point strategies, boundary loops, components,
// degenerate faces and bad requests. Oracles: analytic shapes built here
// (areas, perimeters, arc lengths known in closed form), brute-force
// distances, and boundary/component structure recomputed independently.

#include "remesh/analytic_surfaces.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

constexpr SamplingStrategy kStrategies[] = {SamplingStrategy::random, SamplingStrategy::poisson, SamplingStrategy::fps};

// ---------------------------------------------------------------- meshes

/// [0, 1]^2 in z = 0, n x n cells of two triangles; interior vertices moved
/// by up to `jitter` cells (a fixed LCG), so face areas differ.
TriangleMesh square_grid(int n, double jitter) {
  TriangleMesh mesh;
  mesh.vertices.resize((n + 1) * (n + 1), 3);
  std::uint64_t state = 12345;
  auto next = [&]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1p-53 - 0.5;
  };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      double x = double(i) / n, y = double(j) / n;
      const double dx = next() * jitter / n, dy = next() * jitter / n;
      if (i > 0 && i < n) x += dx;
      if (j > 0 && j < n) y += dy;
      mesh.vertices.row(j * (n + 1) + i) << x, y, 0;
    }
  }
  mesh.faces.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      mesh.faces.row(f++) << a, a + 1, a + n + 2;
      mesh.faces.row(f++) << a, a + n + 2, a + n + 1;
    }
  }
  return mesh;
}

/// An annulus r <= |x| <= R in z = 0: `rings` rings of `segments` quads.
TriangleMesh annulus(double r, double R, int segments, int rings) {
  TriangleMesh mesh;
  mesh.vertices.resize((rings + 1) * segments, 3);
  for (int j = 0; j <= rings; ++j) {
    const double radius = r + (R - r) * j / rings;
    for (int i = 0; i < segments; ++i) {
      const double angle = 2 * std::numbers::pi * i / segments;
      mesh.vertices.row(j * segments + i) << radius * std::cos(angle), radius * std::sin(angle), 0;
    }
  }
  mesh.faces.resize(2 * rings * segments, 3);
  int f = 0;
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const int a = j * segments + i, b = j * segments + (i + 1) % segments;
      mesh.faces.row(f++) << a, b, b + segments;
      mesh.faces.row(f++) << a, b + segments, a + segments;
    }
  }
  return mesh;
}

/// Two triangles sharing an edge, of areas 0.5 (face 0) and 1.5 (face 1).
TriangleMesh two_triangles() {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 2, 0;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 1, 3, 2;
  return mesh;
}

TriangleMesh read(const std::string& name) { return io::read_mesh("tests/data/" + name).mesh; }

// ---------------------------------------------------------------- oracles

Eigen::Vector3d corner(const TriangleMesh& mesh, Index f, int k) {
  return mesh.vertices.row(mesh.faces(f, k)).transpose();
}

double face_area(const TriangleMesh& mesh, Index f) {
  return 0.5 * (corner(mesh, f, 1) - corner(mesh, f, 0)).cross(corner(mesh, f, 2) - corner(mesh, f, 0)).norm();
}

bool proper(const TriangleMesh& mesh, Index f) {
  const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  return a != b && b != c && c != a;
}

std::vector<Eigen::Vector3d> positions(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites) {
  std::vector<Eigen::Vector3d> p;
  for (const SurfacePoint& s : sites) p.push_back(s.position(mesh));
  return p;
}

/// Everything the contract promises about each site, and exactly `count`.
void expect_valid_sites(const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites, std::int64_t count) {
  ASSERT_EQ(static_cast<std::int64_t>(sites.size()), count);
  std::set<std::array<double, 3>> seen;
  int failures = 0;
  for (std::size_t i = 0; i < sites.size() && failures < 5; ++i) {
    const SurfacePoint& s = sites[i];
    const std::string where = "site " + std::to_string(i);
    bool ok = s.kind == SurfacePoint::Kind::face && s.element >= 0 && s.element < mesh.num_faces();
    EXPECT_TRUE(ok) << where << " is not a face point of the mesh";
    if (!ok) {
      ++failures;
      continue;
    }
    ok = proper(mesh, s.element) && face_area(mesh, s.element) > 0;
    EXPECT_TRUE(ok) << where << " is on face " << s.element << ", degenerate";
    int zeros = 0;
    for (int k = 0; k < 3; ++k) {
      const double b = s.barycentric[k];
      const bool on_lattice = b >= 0 && b < 1 && std::ldexp(b, 32) == std::floor(std::ldexp(b, 32));
      EXPECT_TRUE(on_lattice) << where << " barycentric " << b;
      ok = ok && on_lattice;
      zeros += b == 0;
    }
    EXPECT_LE(zeros, 1) << where << " is at a vertex";
    EXPECT_EQ(s.barycentric[0] + s.barycentric[1] + s.barycentric[2], 1.0) << where;
    EXPECT_EQ(s.barycentric[2] + s.barycentric[1] + s.barycentric[0], 1.0) << where;
    const Eigen::Vector3d p = s.position(mesh);
    for (int k = 0; k < 3; ++k) EXPECT_NE(p, corner(mesh, s.element, k)) << where << " is at a vertex position";
    EXPECT_TRUE(seen.insert({p.x(), p.y(), p.z()}).second) << where << " repeats a position";
    ok = ok && zeros <= 1;
    if (!ok) ++failures;
  }
}

double min_pairwise_distance(const std::vector<Eigen::Vector3d>& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) best = std::min(best, (p[i] - p[j]).squaredNorm());
  }
  return std::sqrt(best);
}

/// Largest distance from a probe point to its nearest site: how well the
/// sites cover the surface.
double covering_radius(const std::vector<Eigen::Vector3d>& sites, const std::vector<Eigen::Vector3d>& probes) {
  double worst = 0;
  for (const Eigen::Vector3d& q : probes) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : sites) nearest = std::min(nearest, (p - q).squaredNorm());
    worst = std::max(worst, nearest);
  }
  return std::sqrt(worst);
}

double hexagonal_spacing(double area, std::int64_t n) { return std::sqrt(2 * area / (std::sqrt(3.0) * double(n))); }

std::uint64_t edge_key(Index a, Index b) {
  return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint64_t>(std::max(a, b));
}

Index find(std::vector<Index>& parent, Index x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/// Boundary edges (used by exactly one face with distinct corners) -> the
/// id of their loop (connected piece of the boundary-edge graph).
std::map<std::uint64_t, int> boundary_loop_of_edge(const TriangleMesh& mesh, int* num_loops) {
  std::map<std::uint64_t, int> uses;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!proper(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) ++uses[edge_key(mesh.faces(f, k), mesh.faces(f, (k + 1) % 3))];
  }
  std::vector<Index> parent(static_cast<std::size_t>(mesh.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [key, n] : uses) {
    if (n == 1) parent[find(parent, Index(key >> 32))] = find(parent, Index(key & 0xffffffffu));
  }
  std::map<Index, int> loop_of_root;
  std::map<std::uint64_t, int> loop;
  for (const auto& [key, n] : uses) {
    if (n != 1) continue;
    const Index root = find(parent, Index(key >> 32));
    const auto [it, added] = loop_of_root.emplace(root, static_cast<int>(loop_of_root.size()));
    loop[key] = it->second;
  }
  *num_loops = static_cast<int>(loop_of_root.size());
  return loop;
}

/// The boundary edge a site lies on (one barycentric exactly 0), or 0 for an
/// interior site.
std::uint64_t site_edge(const TriangleMesh& mesh, const SurfacePoint& s) {
  for (int k = 0; k < 3; ++k) {
    if (s.barycentric[k] == 0) return edge_key(mesh.faces(s.element, (k + 1) % 3), mesh.faces(s.element, (k + 2) % 3));
  }
  return 0;
}

/// Per face: its connected component (faces with distinct corners sharing
/// vertices), -1 for the others.
std::vector<int> face_components(const TriangleMesh& mesh, int* num_components) {
  std::vector<Index> parent(static_cast<std::size_t>(mesh.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!proper(mesh, f)) continue;
    parent[find(parent, mesh.faces(f, 1))] = find(parent, mesh.faces(f, 0));
    parent[find(parent, mesh.faces(f, 2))] = find(parent, mesh.faces(f, 0));
  }
  std::map<Index, int> id;
  std::vector<int> component(static_cast<std::size_t>(mesh.num_faces()), -1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!proper(mesh, f)) continue;
    component[f] = id.emplace(find(parent, mesh.faces(f, 0)), static_cast<int>(id.size())).first->second;
  }
  *num_components = static_cast<int>(id.size());
  return component;
}

SamplingOptions options_for(SamplingStrategy strategy, std::uint64_t seed = 1, bool on_boundary = true) {
  SamplingOptions o;
  o.strategy = strategy;
  o.seed = seed;
  o.sites_on_boundary = on_boundary;
  return o;
}

bool identical(const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].kind != b[i].kind || a[i].element != b[i].element || a[i].barycentric != b[i].barycentric) return false;
  }
  return true;
}

// ---------------------------------------------------------------- tests

TEST(SampleSites, ExactCountValidAndDeterministicForEveryStrategy) {
  const TriangleMesh sphere = test::icosphere(3);
  const TriangleMesh square = square_grid(12, 0.6);
  for (const SamplingStrategy strategy : kStrategies) {
    SCOPED_TRACE(sampling_strategy_name(strategy));
    for (const std::int64_t count : {4, 5, 17, 300, 3000}) {
      SCOPED_TRACE(count);
      const auto a = sample_sites(sphere, count, options_for(strategy, 7));
      expect_valid_sites(sphere, a, count);
      EXPECT_TRUE(identical(a, sample_sites(sphere, count, options_for(strategy, 7))));
      EXPECT_FALSE(identical(a, sample_sites(sphere, count, options_for(strategy, 8))));
      const auto b = sample_sites(square, count, options_for(strategy, 7));
      expect_valid_sites(square, b, count);
      EXPECT_TRUE(identical(b, sample_sites(square, count, options_for(strategy, 7))));
    }
  }
}

TEST(SampleSites, RandomChoosesFacesInProportionToArea) {
  // Face 1 has three times the area of face 0: a quarter of the sites on
  // face 0, binomial standard deviation sqrt(n / 4 * 3 / 4).
  const TriangleMesh mesh = two_triangles();
  const std::int64_t n = 100000;
  const auto sites = sample_sites(mesh, n, options_for(SamplingStrategy::random, 3, false));
  expect_valid_sites(mesh, sites, n);
  const auto on_face0 = std::count_if(sites.begin(), sites.end(), [](const SurfacePoint& s) { return s.element == 0; });
  const double sigma = std::sqrt(n * 0.25 * 0.75);
  EXPECT_LT(std::abs(double(on_face0) - 0.25 * n), 5 * sigma) << on_face0 << " sites on face 0";
}

TEST(SampleSites, RandomIsUniformOverAJitteredGrid) {
  // Faces of unequal area; sites binned by position into 10 x 10 equal
  // squares, whatever triangles they fall in: chi-square with 99 degrees of
  // freedom (mean 99, sd 14) must stay below 99 + 6 sd.
  const TriangleMesh mesh = square_grid(23, 0.8);
  const std::int64_t n = 50000;
  const auto sites = sample_sites(mesh, n, options_for(SamplingStrategy::random, 11, false));
  expect_valid_sites(mesh, sites, n);
  std::vector<double> bins(100, 0.0);
  for (const Eigen::Vector3d& p : positions(mesh, sites)) {
    const int i = std::min(9, int(p.x() * 10)), j = std::min(9, int(p.y() * 10));
    bins[j * 10 + i] += 1;
  }
  double chi2 = 0;
  const double expected = double(n) / 100;
  for (const double b : bins) chi2 += (b - expected) * (b - expected) / expected;
  EXPECT_LT(chi2, 99 + 6 * 14.07);
  EXPECT_GT(chi2, 99 - 6 * 14.07) << "suspiciously regular for independent samples";
}

TEST(SampleSites, PoissonAndFpsAreWellSpacedOnASphere) {
  const TriangleMesh mesh = test::icosphere(4);
  double area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) area += face_area(mesh, f);
  const std::int64_t n = 800;
  const double s = hexagonal_spacing(area, n);
  std::vector<Eigen::Vector3d> probes;
  for (const SurfacePoint& p : sample_sites(mesh, 20000, options_for(SamplingStrategy::random, 99))) {
    probes.push_back(p.position(mesh));
  }
  std::map<SamplingStrategy, double> min_distance, cover;
  for (const SamplingStrategy strategy : kStrategies) {
    const auto sites = sample_sites(mesh, n, options_for(strategy, 5));
    expect_valid_sites(mesh, sites, n);
    min_distance[strategy] = min_pairwise_distance(positions(mesh, sites));
    cover[strategy] = covering_radius(positions(mesh, sites), probes);
    std::printf("%-8s min distance %.3f s, covering radius %.3f s\n", sampling_strategy_name(strategy).c_str(),
                min_distance[strategy] / s, cover[strategy] / s);
  }
  // The documented spacing: measured 0.63 s (poisson) and 0.67 s (fps) here.
  EXPECT_GE(min_distance[SamplingStrategy::poisson], 0.5 * s);
  EXPECT_GE(min_distance[SamplingStrategy::fps], 0.45 * s);
  EXPECT_GT(min_distance[SamplingStrategy::poisson], 5 * min_distance[SamplingStrategy::random]);
  EXPECT_GT(min_distance[SamplingStrategy::fps], 5 * min_distance[SamplingStrategy::random]);
  // Hexagonal packing covers with radius s / sqrt(3) = 0.58 s; measured
  // 0.89 s (fps), 0.91 s (poisson), 1.56 s (random).
  EXPECT_LT(cover[SamplingStrategy::fps], 1.0 * s);
  EXPECT_LT(cover[SamplingStrategy::poisson], 1.05 * s);
  EXPECT_LT(cover[SamplingStrategy::fps], 0.7 * cover[SamplingStrategy::random]);
}

TEST(SampleSites, FpsMeasuresAlongTheSurfaceNotAcrossAGap) {
  // Two 4 x 1 plates 0.02 apart (z = 0 and z = 0.02), joined along x = 4 by
  // a strip 0.02 high: a long U. Straight-line distance would let sites on
  // one plate cover the other; distances along the surface give both plates
  // their share of the sites.
  const int nx = 80, ny = 20;
  const double gap = 0.02;
  TriangleMesh mesh;
  // Vertex columns: the lower plate from x = 0 to 4, then the upper plate
  // back from x = 4 to 0; the two columns at x = 4 are joined by the strip.
  mesh.vertices.resize(2 * (nx + 1) * (ny + 1), 3);
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i <= nx; ++i) {
      for (int j = 0; j <= ny; ++j) {
        const double x = 4.0 * (side == 0 ? i : nx - i) / nx;
        mesh.vertices.row((side * (nx + 1) + i) * (ny + 1) + j) << x, double(j) / ny, side * gap;
      }
    }
  }
  const int columns = 2 * (nx + 1);
  mesh.faces.resize(2 * (columns - 1) * ny, 3);
  int f = 0;
  for (int i = 0; i + 1 < columns; ++i) {
    for (int j = 0; j < ny; ++j) {
      const int a = i * (ny + 1) + j, b = (i + 1) * (ny + 1) + j;
      mesh.faces.row(f++) << a, b, b + 1;
      mesh.faces.row(f++) << a, b + 1, a + 1;
    }
  }
  const auto sites = sample_sites(mesh, 200, options_for(SamplingStrategy::fps, 3, false));
  expect_valid_sites(mesh, sites, 200);
  std::vector<Eigen::Vector2d> lower, upper;
  for (const SurfacePoint& site : sites) {
    const Eigen::Vector3d p = site.position(mesh);
    if (p.z() < 0.25 * gap) lower.push_back(p.head<2>());
    if (p.z() > 0.75 * gap) upper.push_back(p.head<2>());
  }
  EXPECT_GE(lower.size() + upper.size(), 195u);
  EXPECT_NEAR(double(lower.size()) / double(upper.size()), 1.0, 0.2)
      << lower.size() << " sites below, " << upper.size() << " above";
  // Far from the fold, each plate is sampled on its own: some site of one
  // plate lies almost above a site of the other (farthest point sampling by
  // straight-line distance would keep every pair a spacing apart).
  const double s = hexagonal_spacing(8 + gap, 200);
  double closest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& a : lower) {
    for (const Eigen::Vector2d& b : upper) {
      if (a.x() < 3 && b.x() < 3) closest = std::min(closest, (a - b).norm());
    }
  }
  std::printf("closest sites across the gap, seen from above: %.3f s\n", closest / s);
  EXPECT_LT(closest, 0.25 * s);
}

TEST(SampleSites, AMillionRandomSitesOnAQuarterMillionFaces) {
  const TriangleMesh mesh = square_grid(360, 0.5);  // 259,200 faces
  const std::int64_t n = 1000000;
  const auto start = std::chrono::steady_clock::now();
  const auto sites = sample_sites(mesh, n, options_for(SamplingStrategy::random, 5));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("10^6 random sites on %d faces: %.2f s\n", mesh.num_faces(), seconds);
  ASSERT_EQ(static_cast<std::int64_t>(sites.size()), n);
  std::vector<std::array<double, 3>> p;
  p.reserve(sites.size());
  for (const SurfacePoint& site : sites) {
    ASSERT_EQ(site.kind, SurfacePoint::Kind::face);
    ASSERT_EQ(site.barycentric.sum(), 1.0);
    ASSERT_GE(site.barycentric.minCoeff(), 0.0);
    const Eigen::Vector3d q = site.position(mesh);
    p.push_back({q.x(), q.y(), q.z()});
  }
  std::sort(p.begin(), p.end());
  EXPECT_EQ(std::adjacent_find(p.begin(), p.end()), p.end()) << "two sites at one position";
}

TEST(SampleSites, SquareBoundaryGetsASiteAtEachCornerAndEvenlySpacedSitesBetween) {
  // The unit square's boundary has length 4; with n sites the loop gets
  // round(4 / s) of them, s the hexagonal spacing: one at each of its four
  // corners (straight sides meeting at 90 degrees) where the sides are two
  // spacings long or more, and on each side the others evenly between them.
  // Arc lengths are measured from the corner (0, 0) counter-clockwise.
  const TriangleMesh mesh = square_grid(16, 0.5);
  int num_loops = 0;
  const auto loop_of = boundary_loop_of_edge(mesh, &num_loops);
  ASSERT_EQ(num_loops, 1);
  for (const SamplingStrategy strategy : kStrategies) {
    for (const std::int64_t n : {4, 40, 400}) {
      SCOPED_TRACE(sampling_strategy_name(strategy) + " " + std::to_string(n));
      const auto sites = sample_sites(mesh, n, options_for(strategy, 2));
      expect_valid_sites(mesh, sites, n);
      std::vector<double> arc;
      for (const SurfacePoint& site : sites) {
        const std::uint64_t edge = site_edge(mesh, site);
        if (edge == 0) continue;
        EXPECT_TRUE(loop_of.contains(edge)) << "a site with a zero barycentric off the boundary";
        const Eigen::Vector3d p = site.position(mesh);
        const double x = p.x(), y = p.y();
        if (y == 0)
          arc.push_back(x);
        else if (x == 1)
          arc.push_back(1 + y);
        else if (y == 1)
          arc.push_back(3 - x);
        else if (x == 0)
          arc.push_back(4 - y);
        else
          ADD_FAILURE() << "boundary site off the square's sides at " << x << ", " << y;
      }
      const auto k = static_cast<std::int64_t>(arc.size());
      const std::int64_t expected = std::clamp<std::int64_t>(std::llround(4 / hexagonal_spacing(1, n)), 3, n - 1);
      EXPECT_EQ(k, expected);
      // At 4 sites the sides (1 long) are shorter than two spacings: no corners.
      if (n == 4) continue;
      // A corner's site is just off its vertex (2^-20 of an edge).
      auto at_corner = [](double a) { return std::abs(a - std::round(a)) < 1e-5; };
      std::vector<std::vector<double>> side(4);
      int corners = 0;
      for (const double a : arc) {
        const double wrapped = a > 4 - 1e-5 ? a - 4 : a;
        if (at_corner(wrapped)) {
          ++corners;
          continue;
        }
        side[static_cast<std::size_t>(std::floor(wrapped))].push_back(wrapped);
      }
      EXPECT_EQ(corners, 4);
      for (int j = 0; j < 4; ++j) {
        std::vector<double>& on = side[static_cast<std::size_t>(j)];
        std::sort(on.begin(), on.end());
        const double gap = 1.0 / static_cast<double>(on.size() + 1);
        for (std::size_t i = 0; i < on.size(); ++i) {
          EXPECT_NEAR(on[i], j + gap * static_cast<double>(i + 1), 1e-5) << "side " << j << ", site " << i;
        }
      }
    }
  }
}

TEST(SampleSites, ASlitsEndGetsASite) {
  // The loop runs into the slit along y = 1/2 and back: one site at its end
  // (1/2, 1/2), just off the vertex; the rest of the loop's sites evenly
  // between (they come back to the end from both sides).
  const TriangleMesh mesh = test::slit_square(16);
  const auto sites = sample_sites(mesh, 300);
  expect_valid_sites(mesh, sites, 300);
  const auto at_end = std::count_if(sites.begin(), sites.end(), [&](const SurfacePoint& s) {
    return (s.position(mesh) - Eigen::Vector3d(0.5, 0.5, 0)).norm() < 1e-6;
  });
  EXPECT_EQ(at_end, 1);
}

TEST(SampleSites, AnnulusGetsSitesOnBothLoopsInProportionToLength) {
  const TriangleMesh mesh = annulus(1, 3, 96, 12);
  int num_loops = 0;
  const auto loop_of = boundary_loop_of_edge(mesh, &num_loops);
  ASSERT_EQ(num_loops, 2);
  for (const SamplingStrategy strategy : kStrategies) {
    SCOPED_TRACE(sampling_strategy_name(strategy));
    const std::int64_t n = 1000;
    const auto sites = sample_sites(mesh, n, options_for(strategy, 4));
    expect_valid_sites(mesh, sites, n);
    std::array<std::vector<double>, 2> angles;  // per loop: inner (radius 1) and outer (radius 3)
    for (const SurfacePoint& site : sites) {
      const std::uint64_t edge = site_edge(mesh, site);
      if (edge == 0) continue;
      ASSERT_TRUE(loop_of.contains(edge));
      const Eigen::Vector3d p = site.position(mesh);
      angles[p.norm() < 2 ? 0 : 1].push_back(std::atan2(p.y(), p.x()));
    }
    ASSERT_GE(angles[0].size(), 3u);
    ASSERT_GE(angles[1].size(), 3u);
    // Outer loop 3 times as long; each gets round(length / s) sites.
    double area = 0;
    for (Index f = 0; f < mesh.num_faces(); ++f) area += face_area(mesh, f);
    const double s = hexagonal_spacing(area, n);
    const double inner = 2 * 96 * std::sin(std::numbers::pi / 96), outer = 3 * inner;
    EXPECT_NEAR(double(angles[0].size()), inner / s, 1.0);
    EXPECT_NEAR(double(angles[1].size()), outer / s, 1.0);
    for (auto& a : angles) {
      // On a polygon close to a circle, even arc length is nearly even angle.
      std::sort(a.begin(), a.end());
      const double even = 2 * std::numbers::pi / double(a.size());
      for (std::size_t j = 0; j < a.size(); ++j) {
        const double gap = j + 1 < a.size() ? a[j + 1] - a[j] : a[0] + 2 * std::numbers::pi - a[j];
        EXPECT_NEAR(gap, even, 0.02 * even);
      }
    }
  }
}

TEST(SampleSites, TooFewSitesForTheBoundaryLoops) {
  const TriangleMesh mesh = annulus(1, 2, 24, 3);
  for (const SamplingStrategy strategy : kStrategies) {
    // Two loops need 6 sites; 6 gives exactly 3 + 3 and no interior site.
    const auto sites = sample_sites(mesh, 6, options_for(strategy));
    expect_valid_sites(mesh, sites, 6);
    for (const SurfacePoint& s : sites) EXPECT_NE(site_edge(mesh, s), 0u);
    try {
      sample_sites(mesh, 5, options_for(strategy));
      ADD_FAILURE() << "5 sites cannot cover two loops";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("at least 6"), std::string::npos) << e.what();
    }
    // Without boundary sites 5 is fine.
    const auto free = sample_sites(mesh, 5, options_for(strategy, 1, false));
    expect_valid_sites(mesh, free, 5);
    for (const SurfacePoint& s : free) EXPECT_EQ(site_edge(mesh, s), 0u);
  }
}

TEST(SampleSites, ComponentsShareSitesByArea) {
  // Two separate squares of areas 1 and 9 (no boundary sites): 10% / 90%.
  TriangleMesh small = square_grid(4, 0.3), big = square_grid(6, 0.3);
  TriangleMesh mesh;
  mesh.vertices.resize(small.num_vertices() + big.num_vertices(), 3);
  mesh.vertices << small.vertices, (big.vertices * 3).rowwise() + Eigen::RowVector3d(5, 0, 0);
  mesh.faces.resize(small.num_faces() + big.num_faces(), 3);
  mesh.faces << small.faces, big.faces.array() + small.num_vertices();
  for (const SamplingStrategy strategy : kStrategies) {
    SCOPED_TRACE(sampling_strategy_name(strategy));
    const auto sites = sample_sites(mesh, 500, options_for(strategy, 1, false));
    expect_valid_sites(mesh, sites, 500);
    const auto on_small =
        std::count_if(sites.begin(), sites.end(), [&](const SurfacePoint& s) { return s.element < small.num_faces(); });
    EXPECT_EQ(on_small, 50);
    // With 6 sites, 4 on each square is impossible: the larger one gets its
    // 4 first, the small one the remaining 2.
    const auto few = sample_sites(mesh, 6, options_for(strategy, 1, false));
    expect_valid_sites(mesh, few, 6);
    const auto few_on_small =
        std::count_if(few.begin(), few.end(), [&](const SurfacePoint& s) { return s.element < small.num_faces(); });
    EXPECT_EQ(few_on_small, 2);
  }
}

TEST(SampleSites, DegenerateFacesNeverCarrySites) {
  // A unit square (faces 0, 1) plus a zero-area face with distinct corners
  // (collinear: (0,0), (0.5,0.5), (1,1)), a face with a repeated corner, and
  // a zero-area face whose corners coincide in space.
  TriangleMesh mesh;
  mesh.vertices.resize(7, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 0, 0.25, 0.25, 0, 0.25, 0.25, 0;
  mesh.faces.resize(5, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3, 0, 4, 2, 1, 1, 2, 5, 6, 0;
  for (const SamplingStrategy strategy : kStrategies) {
    for (const bool on_boundary : {true, false}) {
      const auto sites = sample_sites(mesh, 2000, options_for(strategy, 1, on_boundary));
      expect_valid_sites(mesh, sites, 2000);
      for (const SurfacePoint& s : sites) ASSERT_LT(s.element, 2) << "site on degenerate face " << s.element;
    }
  }
  TriangleMesh flat;
  flat.vertices = mesh.vertices;
  flat.faces = mesh.faces.bottomRows(3);
  EXPECT_THROW(sample_sites(flat, 10), Error);
}

TEST(SampleSites, BadRequests) {
  const TriangleMesh mesh = two_triangles();
  for (const std::int64_t count : {-1, 0, 1, 3}) EXPECT_THROW(sample_sites(mesh, count), UsageError) << count;
  EXPECT_THROW(sample_sites(mesh, std::int64_t{1} << 31), UsageError);
  EXPECT_THROW(parse_sampling_strategy("blue"), UsageError);
  EXPECT_THROW(parse_sampling_strategy(""), UsageError);
  EXPECT_THROW(parse_sampling_strategy("Random"), UsageError);
  for (const SamplingStrategy strategy : kStrategies) {
    EXPECT_EQ(parse_sampling_strategy(sampling_strategy_name(strategy)), strategy);
  }
  EXPECT_EQ(sampling_strategy_name(SamplingStrategy::poisson), "poisson");
  TriangleMesh broken = mesh;
  broken.faces(1, 2) = 4;  // only vertices 0..3 exist
  EXPECT_THROW(sample_sites(broken, 10), Error);
  TriangleMesh infinite = mesh;
  infinite.vertices(3, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(sample_sites(infinite, 10), Error);
  infinite.vertices(3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sample_sites(infinite, 10), Error);
}

TEST(SampleSites, BunnyScanEveryLoopGetsSites) {
  // 5 boundary loops, 1,113 unreferenced vertices (MANIFEST.md).
  const TriangleMesh mesh = read("bunny.ply");
  int num_loops = 0;
  const auto loop_of = boundary_loop_of_edge(mesh, &num_loops);
  ASSERT_EQ(num_loops, 5);
  for (const SamplingStrategy strategy : kStrategies) {
    SCOPED_TRACE(sampling_strategy_name(strategy));
    const auto sites = sample_sites(mesh, 2000, options_for(strategy));
    expect_valid_sites(mesh, sites, 2000);
    std::vector<int> per_loop(5, 0);
    for (const SurfacePoint& s : sites) {
      const std::uint64_t edge = site_edge(mesh, s);
      if (edge == 0) continue;
      ASSERT_TRUE(loop_of.contains(edge));
      ++per_loop[loop_of.at(edge)];
    }
    for (int l = 0; l < 5; ++l) EXPECT_GE(per_loop[l], 3) << "loop " << l;
    // The smallest count that covers the loops.
    expect_valid_sites(mesh, sample_sites(mesh, 15, options_for(strategy)), 15);
    EXPECT_THROW(sample_sites(mesh, 14, options_for(strategy)), UsageError);
  }
}

TEST(SampleSites, OgreEveryComponentGetsSites) {
  // 44 components, 12 boundary loops, 4 zero-area faces (MANIFEST.md).
  const TriangleMesh mesh = read("ogre.ply");
  int num_components = 0;
  const std::vector<int> component = face_components(mesh, &num_components);
  ASSERT_EQ(num_components, 44);
  std::vector<double> area(44, 0.0);
  int zero_area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (component[f] < 0) continue;
    const double a = face_area(mesh, f);
    area[component[f]] += a;
    zero_area += a == 0;
  }
  EXPECT_EQ(zero_area, 4);
  for (const SamplingStrategy strategy : kStrategies) {
    SCOPED_TRACE(sampling_strategy_name(strategy));
    const std::int64_t n = 3000;
    const auto sites = sample_sites(mesh, n, options_for(strategy));
    expect_valid_sites(mesh, sites, n);
    std::vector<std::int64_t> per_component(44, 0);
    for (const SurfacePoint& s : sites) ++per_component[component[s.element]];
    int largest = 0;
    for (int c = 0; c < 44; ++c) {
      if (area[c] > area[largest]) largest = c;
      if (area[c] > 0) {
        EXPECT_GE(per_component[c], 4) << "component " << c;
      }
    }
    // Components above their minimum share the rest in proportion to area:
    // the same sites per unit area as the largest one, up to rounding.
    const double density = double(per_component[largest]) / area[largest];
    for (int c = 0; c < 44; ++c) {
      if (per_component[c] > 40) {
        EXPECT_NEAR(double(per_component[c]), density * area[c], 1.0) << "component " << c;
      }
    }
  }
}

}  // namespace
}  // namespace geodual::remesh
