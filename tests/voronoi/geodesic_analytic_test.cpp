// Exact geodesic distances on polyhedral surfaces whose geodesics are known in
// closed form: a flat jittered square, a flat L (reflex boundary corner), an
// open prism (unrolls onto a periodic strip), a cube (finite set of
// unfoldings), and cones with a convex or a saddle apex (paths behind a saddle
// apex go through it). Every vertex distance must match to 1e-9 of the size,
// labels must name a nearest site, and query() must be exact in valid faces
// (everywhere with RWR off) and never below the true distance elsewhere.

#include "geodual/mesh/error.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "voronoi/test_meshes.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace geodual::voronoi {
namespace {

using test::Rng;

/// Exact distance between a site and any surface point.
using ExactDistance = std::function<double(const SurfacePoint& site, const SurfacePoint& point)>;

struct AnalyticReport {
  double max_vertex_error = 0;  ///< relative to the size
  double max_query_error = 0;   ///< in valid faces (all faces with RWR off), relative
  int vertices_checked = 0;
  int queries_exact_checked = 0;
  int queries_bound_checked = 0;
};

/// Best and second best exact distance at `point` over all sites.
std::pair<double, double> best_two(const std::vector<SurfacePoint>& sites, const SurfacePoint& point,
                                   const ExactDistance& exact, Index* argmin) {
  double best = std::numeric_limits<double>::infinity(), second = best;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const double d = exact(sites[i], point);
    if (d < best) {
      second = best;
      best = d;
      *argmin = static_cast<Index>(i);
    } else if (d < second) {
      second = d;
    }
  }
  return {best, second};
}

/// Random face points: a few per face on small meshes, including points on
/// the face's edges.
std::vector<SurfacePoint> query_points(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<SurfacePoint> points;
  for (int i = 0; i < count; ++i) {
    const Index f = static_cast<Index>(rng.below(mesh.num_faces()));
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    if (i % 10 == 0) v = 0;  // on an edge
    points.push_back(SurfacePoint::in_face(f, u, v, 1 - u - v));
  }
  return points;
}

AnalyticReport check_field(const std::string& name, const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                           const ExactDistance& exact, bool rwr) {
  const double size = test::bbox_diagonal(mesh);
  const double tol = 1e-9 * size;
  GeodesicOptions options;
  options.remove_redundant_windows = rwr;
  const GeodesicField field = compute_geodesic_field(mesh, sites, options);
  AnalyticReport report;
  EXPECT_EQ(field.distance.size(), static_cast<std::size_t>(mesh.num_vertices()));
  EXPECT_EQ(field.nearest_site.size(), static_cast<std::size_t>(mesh.num_vertices()));
  if (field.distance.size() != static_cast<std::size_t>(mesh.num_vertices()) ||
      field.nearest_site.size() != static_cast<std::size_t>(mesh.num_vertices())) {
    return report;
  }

  int reported = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    Index argmin = -1;
    const auto [best, second] = best_two(sites, SurfacePoint::at_vertex(v), exact, &argmin);
    const double d = field.distance[v];
    const double error = std::abs(d - best);
    report.max_vertex_error = std::max(report.max_vertex_error, std::isfinite(error) ? error / size : 1e300);
    ++report.vertices_checked;
    const Index label = field.nearest_site[v];
    bool ok = error <= tol && label >= 0 && label < static_cast<Index>(sites.size());
    if (ok && label != argmin) {
      // A tie: the label's own exact distance must be the smallest as well.
      ok = std::abs(exact(sites[static_cast<std::size_t>(label)], SurfacePoint::at_vertex(v)) - best) <= tol;
    }
    if (!ok && reported++ < 10) {
      ADD_FAILURE() << name << (rwr ? " (RWR on)" : " (RWR off)") << ": vertex " << v << " at (" << mesh.vertices.row(v)
                    << "): ours " << d << " label " << label << ", exact " << best << " nearest site " << argmin
                    << " (second best " << second << "), error " << error / size << " of the size";
    }
  }
  EXPECT_EQ(reported, 0) << name << ": vertices with a wrong distance or label";

  // Sites at vertices: distance 0, their own label.
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (sites[i].kind != SurfacePoint::Kind::vertex) continue;
    EXPECT_EQ(field.distance[sites[i].element], 0.0) << name << ": site " << i;
    EXPECT_EQ(field.nearest_site[sites[i].element], static_cast<Index>(i)) << name << ": site " << i;
  }

  // query(): exact in valid faces (in every face when no window was freed),
  // an upper bound elsewhere, never below the true distance.
  int query_failures = 0;
  for (const SurfacePoint& p : query_points(mesh, 400, 99)) {
    Index argmin = -1;
    const auto [best, second] = best_two(sites, p, exact, &argmin);
    const PointDistance q = query(field, mesh, p);
    const bool must_be_exact = !rwr || field.valid_face.at(static_cast<std::size_t>(p.element));
    bool ok = q.distance >= best - tol && q.site >= 0 && q.site < static_cast<Index>(sites.size());
    if (ok) {
      // Whatever the distance, it must be realised by the site it names.
      ok = exact(sites[static_cast<std::size_t>(q.site)], p) <= q.distance + tol;
    }
    if (must_be_exact) {
      ++report.queries_exact_checked;
      report.max_query_error = std::max(report.max_query_error, std::abs(q.distance - best) / size);
      ok = ok && std::abs(q.distance - best) <= tol;
    } else {
      ++report.queries_bound_checked;
    }
    if (!ok && query_failures++ < 10) {
      ADD_FAILURE() << name << (rwr ? " (RWR on)" : " (RWR off)") << ": query in face " << p.element << " barycentric ("
                    << p.barycentric.transpose() << ")" << (must_be_exact ? " [must be exact]" : " [upper bound]")
                    << ": ours " << q.distance << " site " << q.site << ", exact " << best << " site " << argmin;
    }
  }
  EXPECT_EQ(query_failures, 0) << name << ": wrong query() results";

  std::cout << "[analytic] " << name << (rwr ? " RWR on " : " RWR off") << ": " << mesh.num_faces() << " faces, "
            << sites.size() << " sites, max vertex error " << report.max_vertex_error << ", max query error "
            << report.max_query_error << " (relative to the size; " << report.queries_exact_checked << " exact / "
            << report.queries_bound_checked << " bound-only queries), peak windows " << field.stats.peak_windows
            << ", pseudo-sources " << field.stats.pseudo_sources << "\n";
  return report;
}

void check_both(const std::string& name, const TriangleMesh& mesh, const std::vector<SurfacePoint>& sites,
                const ExactDistance& exact) {
  check_field(name, mesh, sites, exact, true);
  check_field(name, mesh, sites, exact, false);
}

// ---------------------------------------------------------------------------

TEST(GeodesicAnalytic, FlatSquareOneVertexSite) {
  const TriangleMesh mesh = test::flat_square(24, 0.3, 11);
  const std::vector<SurfacePoint> sites = {SurfacePoint::at_vertex(7 * 25 + 9)};
  check_both("flat square, one vertex site", mesh, sites, [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  });
}

TEST(GeodesicAnalytic, FlatSquareOneFaceSite) {
  const TriangleMesh mesh = test::flat_square(24, 0.3, 12);
  const std::vector<SurfacePoint> sites = {SurfacePoint::in_face(301, 0.21, 0.33, 0.46)};
  check_both("flat square, one face site", mesh, sites, [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  });
}

TEST(GeodesicAnalytic, FlatSquareSeveralSites) {
  const TriangleMesh mesh = test::flat_square(24, 0.3, 13);
  std::vector<SurfacePoint> sites = test::random_face_sites(mesh, 5, 14);
  for (const SurfacePoint& s : test::random_vertex_sites(mesh, 4, 15)) sites.push_back(s);
  sites.push_back(SurfacePoint::in_face(600, 0.4, 0.6, 0.0));  // on an edge
  sites.push_back(SurfacePoint::at_vertex(0));                 // a boundary corner
  check_both("flat square, 11 sites", mesh, sites, [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  });
}

TEST(GeodesicAnalytic, FlatSquareManySites) {
  const TriangleMesh mesh = test::flat_square(50, 0.3, 16);
  std::vector<SurfacePoint> sites = test::random_face_sites(mesh, 40, 17);
  for (const SurfacePoint& s : test::random_vertex_sites(mesh, 40, 18)) sites.push_back(s);
  check_both("flat square, 80 sites", mesh, sites, [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  });
}

// The smallest case of the above: the unit square a b c d with m the midpoint
// of a-c and faces (a,b,m) (m,b,c) (a,m,c) (a,c,d); (a,m,c) has zero area and
// must be crossed. Sites at m, or on the edges a-m / m-c, reach d straight.
TEST(GeodesicAnalytic, ZeroAreaFaceNextToTheSite) {
  TriangleMesh mesh;
  mesh.vertices.resize(5, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 0;
  mesh.faces.resize(4, 3);
  mesh.faces << 0, 1, 4, 4, 1, 2, 0, 4, 2, 0, 2, 3;
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  };
  for (const SurfacePoint& site :
       {SurfacePoint::at_vertex(4), SurfacePoint::in_face(0, 0.5, 0.0, 0.5), SurfacePoint::in_face(1, 0.5, 0.0, 0.5),
        SurfacePoint::in_face(0, 0.2, 0.2, 0.6), SurfacePoint::at_vertex(1)}) {
    std::ostringstream name;
    name << "minimal zero-area square, site " << (site.kind == SurfacePoint::Kind::vertex ? "vertex " : "face ")
         << site.element << " (" << site.barycentric.transpose() << ")";
    check_both(name.str(), mesh, {site}, exact);
  }
}

TEST(GeodesicAnalytic, FlatSquareWithZeroAreaFaces) {
  const test::ZeroAreaSquare square = test::flat_square_with_zero_area_faces(16, 12, 0.3, 19);
  const TriangleMesh& mesh = square.mesh;
  ASSERT_GE(square.zero_area_faces.size(), 8u);
  for (Index f : square.zero_area_faces) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    ASSERT_EQ((b - a).cross(c - a).norm(), 0.0) << "face " << f;
  }
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) {
    return (s.position(mesh) - p.position(mesh)).norm();
  };
  check_both("zero-area faces, one site", mesh, {SurfacePoint::at_vertex(3)}, exact);
  // Sites at the midpoints themselves (vertices of a zero-area face) and
  // elsewhere.
  std::vector<SurfacePoint> sites = test::random_face_sites(mesh, 6, 20);
  sites.push_back(SurfacePoint::at_vertex(square.midpoints[0]));
  sites.push_back(SurfacePoint::at_vertex(square.midpoints[1]));
  check_both("zero-area faces, 8 sites", mesh, sites, exact);
}

TEST(GeodesicAnalytic, LShapeAroundTheReflexCorner) {
  const TriangleMesh mesh = test::l_shape(8, 0.3, 21);
  // Sites in the arm x > 1: the arm y > 1 is reached around the corner (1, 1).
  std::vector<SurfacePoint> sites;
  std::vector<SurfacePoint> candidates = test::random_face_sites(mesh, 60, 23);
  for (const SurfacePoint& s : candidates) {
    const Eigen::Vector3d p = s.position(mesh);
    if (p.x() > 1.2 && p.y() < 0.8 && sites.size() < 2) sites.push_back(s);
  }
  ASSERT_EQ(sites.size(), 2u);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) {
    return test::l_shape_distance(s.position(mesh), p.position(mesh));
  };
  // Make sure the bent paths are exercised.
  int bent = 0;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
    bent += exact(sites[0], SurfacePoint::at_vertex(v)) > (p - sites[0].position(mesh)).norm() + 1e-6;
  }
  EXPECT_GT(bent, 20);
  check_both("L plate, 2 face sites", mesh, sites, exact);
  sites.push_back(SurfacePoint::at_vertex(0));
  check_both("L plate, 3 sites", mesh, sites, exact);
}

TEST(GeodesicAnalytic, BookOfThreePagesCrossesOnlyAtSpineVertices) {
  const test::NonManifold book = test::book(3, 8, 6, 1.0, 0.3, 71);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) { return book.distance(s, p); };
  // A site in page 0 reaches pages 1 and 2 through the spine's vertices.
  Index face = -1;
  for (Index f = 0; f < book.mesh.num_faces() && face < 0; ++f) {
    if (book.face_page[f] == 0 && SurfacePoint::in_face(f, 0.3, 0.3, 0.4).position(book.mesh).y() > 0.4) face = f;
  }
  ASSERT_GE(face, 0);
  check_both("book of 3 pages, face site", book.mesh, {SurfacePoint::in_face(face, 0.3, 0.3, 0.4)}, exact);
  check_both("book of 3 pages, site on the spine", book.mesh, {SurfacePoint::at_vertex(book.shared[3])}, exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(book.mesh, 4, 72);
  sites.push_back(SurfacePoint::at_vertex(book.shared.back()));
  check_both("book of 3 pages, 5 sites", book.mesh, sites, exact);
}

TEST(GeodesicAnalytic, BowtieThroughThePinchVertex) {
  const test::NonManifold bowtie = test::bowtie(8, 0.3, 81);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) { return bowtie.distance(s, p); };
  check_both("bowtie, face site", bowtie.mesh, {SurfacePoint::in_face(20, 0.3, 0.3, 0.4)}, exact);
  check_both("bowtie, site at the pinch", bowtie.mesh, {SurfacePoint::at_vertex(0)}, exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(bowtie.mesh, 3, 82);
  check_both("bowtie, 3 sites", bowtie.mesh, sites, exact);
}

TEST(GeodesicAnalytic, PrismUnrolls) {
  const test::Prism prism = test::prism(12, 8, 1.0, 3.0, 0.3, 31);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) { return prism.distance(s, p); };
  check_both("prism, one vertex site", prism.mesh, {SurfacePoint::at_vertex(4 * 12 + 3)}, exact);
  check_both("prism, one face site", prism.mesh, {SurfacePoint::in_face(77, 0.3, 0.3, 0.4)}, exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(prism.mesh, 3, 32);
  sites.push_back(SurfacePoint::at_vertex(5));            // on the bottom boundary
  sites.push_back(SurfacePoint::at_vertex(6 * 12 + 11));  // next to the seam
  check_both("prism, 5 sites", prism.mesh, sites, exact);
}

TEST(GeodesicAnalytic, CubeUnfoldings) {
  const test::Cube cube = test::cube(6, 0.25, 41);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) {
    return cube.distance(s.position(cube.mesh), p.position(cube.mesh));
  };
  // A face site near a cube corner: paths to the far faces fan out over
  // several unfoldings.
  Index near_corner = -1;
  for (Index f = 0; f < cube.mesh.num_faces() && near_corner < 0; ++f) {
    const Eigen::Vector3d c = SurfacePoint::in_face(f, 1.0 / 3, 1.0 / 3, 1.0 / 3).position(cube.mesh);
    if (c.z() > 1 - 1e-12 && c.x() < 0.15 && c.y() < 0.15) near_corner = f;
  }
  ASSERT_GE(near_corner, 0);
  check_both("cube, face site near a corner", cube.mesh, {SurfacePoint::in_face(near_corner, 0.5, 0.3, 0.2)}, exact);
  // A site at a cube corner (convex vertex of angle 3 pi / 2).
  Index corner = -1;
  for (Index v = 0; v < cube.mesh.num_vertices(); ++v) {
    if (cube.mesh.vertices.row(v).isZero()) corner = v;
  }
  ASSERT_GE(corner, 0);
  check_both("cube, site at a cube corner", cube.mesh, {SurfacePoint::at_vertex(corner)}, exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(cube.mesh, 4, 42);
  for (const SurfacePoint& s : test::random_vertex_sites(cube.mesh, 3, 43)) sites.push_back(s);
  check_both("cube, 7 sites", cube.mesh, sites, exact);
  sites = test::random_face_sites(cube.mesh, 12, 44);
  for (const SurfacePoint& s : test::random_vertex_sites(cube.mesh, 12, 45)) sites.push_back(s);
  check_both("cube, 24 sites", cube.mesh, sites, exact);
}

TEST(GeodesicAnalytic, SaddleConePathsThroughTheApex) {
  const test::Cone cone = test::cone(16, 10, 1.0, 2.5 * std::numbers::pi, 0.3, 51);
  ASSERT_NEAR(cone.total_angle, 2.5 * std::numbers::pi, 1e-12);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) { return cone.distance(s, p); };
  // A face site half way out in sector 2: points whose angular separation at
  // the apex reaches pi are reached through the apex.
  const Index face = 16 + 4 * 32 + 2 * 2;  // ring 5, sector 2
  ASSERT_EQ(cone.face_sector[face], 2);
  const SurfacePoint site = SurfacePoint::in_face(face, 0.3, 0.3, 0.4);
  int through_apex = 0;
  const Eigen::Vector2d ps = cone.polar(site);
  for (Index v = 1; v < cone.mesh.num_vertices(); ++v) {
    const Eigen::Vector2d pv = cone.polar(SurfacePoint::at_vertex(v));
    through_apex += std::abs(exact(site, SurfacePoint::at_vertex(v)) - (ps.x() + pv.x())) < 1e-12;
  }
  EXPECT_GE(through_apex, 20) << "the test must exercise paths through the saddle apex";
  check_both("saddle cone (2.5 pi), face site", cone.mesh, {site}, exact);
  check_both("saddle cone (2.5 pi), vertex site", cone.mesh, {SurfacePoint::at_vertex(1 + 6 * 16 + 9)}, exact);
  check_both("saddle cone (2.5 pi), site at the apex", cone.mesh, {SurfacePoint::at_vertex(0)}, exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(cone.mesh, 3, 52);
  sites.push_back(SurfacePoint::at_vertex(1 + 2 * 16 + 12));
  check_both("saddle cone (2.5 pi), 4 sites", cone.mesh, sites, exact);
}

TEST(GeodesicAnalytic, ConvexCone) {
  const test::Cone cone = test::cone(16, 10, 1.0, 1.5 * std::numbers::pi, 0.3, 61);
  ASSERT_NEAR(cone.total_angle, 1.5 * std::numbers::pi, 1e-12);
  const ExactDistance exact = [&](const SurfacePoint& s, const SurfacePoint& p) { return cone.distance(s, p); };
  check_both("convex cone (1.5 pi), face site", cone.mesh, {SurfacePoint::in_face(16 + 3 * 32 + 7, 0.2, 0.5, 0.3)},
             exact);
  std::vector<SurfacePoint> sites = test::random_face_sites(cone.mesh, 3, 62);
  sites.push_back(SurfacePoint::at_vertex(0));
  check_both("convex cone (1.5 pi), 4 sites", cone.mesh, sites, exact);
}

}  // namespace
}  // namespace geodual::voronoi
