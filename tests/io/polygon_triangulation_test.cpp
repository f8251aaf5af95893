// Polygons with more than three corners, as OBJ, OFF, PLY and ASCII STL
// readers triangulate them: concave ones cover exactly their own area with
// triangles that do not overlap, in the polygon's orientation; convex ones get
// the fan (c0, c1, c2), (c0, c2, c3), ... as before; polygons that are not
// simple are triangulated all the same and counted in the read notes.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace geodual::test {
namespace {

using Point3 = Eigen::Vector3d;
using Point2 = Eigen::Vector2d;

/// One polygon in an OBJ file: `v` lines for the corners, one `f` line.
std::string obj_polygon(const std::vector<Point3>& corners) {
  std::string text;
  for (const Point3& p : corners) {
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  text += "f";
  for (std::size_t i = 0; i < corners.size(); ++i) {
    text += " " + std::to_string(i + 1);
  }
  return text + "\n";
}

std::vector<Point3> in_plane_z0(const std::vector<Point2>& corners) {
  std::vector<Point3> out;
  for (const Point2& p : corners) {
    out.emplace_back(p.x(), p.y(), 0.0);
  }
  return out;
}

/// Values that print exactly with std::to_string (six decimals): the tests
/// compare areas to rounding, so the file must hold the polygon itself.
std::vector<Point2> star(int tips, double outer, double inner) {
  std::vector<Point2> corners;
  for (int i = 0; i < 2 * tips; ++i) {
    const double angle = std::numbers::pi / 2 + std::numbers::pi * i / tips;
    const double radius = i % 2 == 0 ? outer : inner;
    corners.emplace_back(std::round(1e6 * radius * std::cos(angle)) / 1e6,
                         std::round(1e6 * radius * std::sin(angle)) / 1e6);
  }
  return corners;
}

const std::vector<Point2> c_shape = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {0, 3}};
const std::vector<Point2> l_shape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

/// Newell's normal: twice the vector area of a polygon, planar or not.
Point3 newell_normal(const std::vector<Point3>& corners) {
  Point3 normal = Point3::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i) {
    normal += corners[i].cross(corners[(i + 1) % corners.size()]);
  }
  return normal;
}

/// The mesh's triangles seen along `normal` (unit), in a right-handed frame:
/// counter-clockwise about the normal means positive signed area.
std::vector<std::array<Point2, 3>> projected_triangles(const TriangleMesh& mesh, const Point3& normal) {
  const Point3 u = normal.unitOrthogonal();
  const Point3 v = normal.cross(u);
  std::vector<std::array<Point2, 3>> triangles;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    std::array<Point2, 3> triangle;
    for (int c = 0; c < 3; ++c) {
      const Point3 p = mesh.vertices.row(mesh.faces(f, c)).transpose();
      triangle[static_cast<std::size_t>(c)] = Point2(p.dot(u), p.dot(v));
    }
    triangles.push_back(triangle);
  }
  return triangles;
}

double signed_area(const std::array<Point2, 3>& t) {
  const Point2 a = t[1] - t[0];
  const Point2 b = t[2] - t[0];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

/// Whether the interiors of two triangles meet: no edge of either separates them.
bool interiors_overlap(const std::array<Point2, 3>& s, const std::array<Point2, 3>& t, double tolerance) {
  for (const auto* triangle : {&s, &t}) {
    for (int e = 0; e < 3; ++e) {
      const Point2 edge = (*triangle)[static_cast<std::size_t>((e + 1) % 3)] - (*triangle)[static_cast<std::size_t>(e)];
      const Point2 axis(-edge.y(), edge.x());
      constexpr double infinity = std::numeric_limits<double>::infinity();
      double s_low = infinity, s_high = -infinity, t_low = infinity, t_high = -infinity;
      for (const Point2& p : s) {
        s_low = std::min(s_low, p.dot(axis));
        s_high = std::max(s_high, p.dot(axis));
      }
      for (const Point2& p : t) {
        t_low = std::min(t_low, p.dot(axis));
        t_high = std::max(t_high, p.dot(axis));
      }
      const double scale = tolerance * axis.norm();
      if (s_high <= t_low + scale || t_high <= s_low + scale) {
        return false;
      }
    }
  }
  return true;
}

/// The polygon was split into corners - 2 triangles that cover exactly its
/// area (seen along its Newell normal), none flipped, degenerate or
/// overlapping another.
void expect_exact_triangulation(const io::LoadedMesh& loaded, const std::vector<Point3>& corners) {
  const Point3 normal = newell_normal(corners);
  const double polygon_area = 0.5 * normal.norm();
  const auto triangles = projected_triangles(loaded.mesh, normal.normalized());
  ASSERT_EQ(triangles.size(), corners.size() - 2);
  double total = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const double area = signed_area(triangles[i]);
    EXPECT_GT(area, 1e-9 * polygon_area) << "triangle " << i << " is flipped or degenerate";
    total += std::abs(area);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_FALSE(interiors_overlap(triangles[i], triangles[j], 1e-12 * std::sqrt(polygon_area)))
          << "triangles " << j << " and " << i << " overlap";
    }
  }
  EXPECT_NEAR(total, polygon_area, 1e-12 * polygon_area);
}

bool has_note(const io::LoadedMesh& loaded, std::string_view text) {
  return std::any_of(loaded.info.notes.begin(), loaded.info.notes.end(),
                     [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

std::vector<Index> fan(Index corners) {
  std::vector<Index> faces;
  for (Index i = 1; i + 1 < corners; ++i) {
    faces.insert(faces.end(), {0, i, i + 1});
  }
  return faces;
}

TEST(PolygonTriangulation, StarCoversItsAreaOnce) {
  TempDir dir;
  const auto corners = in_plane_z0(star(5, 1.0, 0.4));
  const io::LoadedMesh loaded = read_text(dir, "star.obj", obj_polygon(corners));
  expect_exact_triangulation(loaded, corners);
  EXPECT_EQ(loaded.info.polygons_split, 1);
  EXPECT_TRUE(has_note(loaded, "1 polygon not convex, triangulated by ear clipping"));
}

TEST(PolygonTriangulation, CShapeCoversItsAreaOnce) {
  TempDir dir;
  const auto corners = in_plane_z0(c_shape);
  const io::LoadedMesh loaded = read_text(dir, "c.obj", obj_polygon(corners));
  expect_exact_triangulation(loaded, corners);
}

TEST(PolygonTriangulation, LShape) {
  TempDir dir;
  const auto corners = in_plane_z0(l_shape);
  expect_exact_triangulation(read_text(dir, "l.obj", obj_polygon(corners)), corners);
}

TEST(PolygonTriangulation, ConvexQuadAndHexagonKeepTheFan) {
  TempDir dir;
  const io::LoadedMesh quad = read_text(dir, "quad.obj", obj_polygon(in_plane_z0({{0, 0}, {2, 0}, {3, 2}, {0, 1}})));
  EXPECT_EQ(face_list(quad.mesh), fan(4));
  std::vector<Point2> hexagon;
  for (int i = 0; i < 6; ++i) {
    hexagon.emplace_back(std::round(1e6 * std::cos(i * std::numbers::pi / 3)) / 1e6,
                         std::round(1e6 * std::sin(i * std::numbers::pi / 3)) / 1e6);
  }
  const io::LoadedMesh six = read_text(dir, "hexagon.obj", obj_polygon(in_plane_z0(hexagon)));
  EXPECT_EQ(face_list(six.mesh), fan(6));
  expect_exact_triangulation(six, in_plane_z0(hexagon));
  EXPECT_TRUE(six.info.notes.empty());
  // Clockwise, and tilted out of the coordinate planes: still the fan.
  std::vector<Point3> tilted;
  for (auto it = hexagon.rbegin(); it != hexagon.rend(); ++it) {
    tilted.emplace_back(it->x(), it->y(), 0.5 * it->x() - 0.25 * it->y());
  }
  const io::LoadedMesh clockwise = read_text(dir, "tilted.obj", obj_polygon(tilted));
  EXPECT_EQ(face_list(clockwise.mesh), fan(6));
}

TEST(PolygonTriangulation, ClockwisePolygonKeepsItsOrientation) {
  TempDir dir;
  std::vector<Point2> reversed(c_shape.rbegin(), c_shape.rend());
  const auto corners = in_plane_z0(reversed);
  const io::LoadedMesh loaded = read_text(dir, "clockwise.obj", obj_polygon(corners));
  ASSERT_LT(newell_normal(corners).z(), 0);     // seen from +z, the polygon winds clockwise
  expect_exact_triangulation(loaded, corners);  // every triangle winds like the polygon
  EXPECT_NEAR(0.5 * newell_normal(corners).norm(), 7.0, 1e-12);
}

TEST(PolygonTriangulation, NonPlanarPolygonsFollowTheirBestFitPlane) {
  TempDir dir;
  const std::vector<Point3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
  const io::LoadedMesh saddle = read_text(dir, "quad.obj", obj_polygon(quad));
  EXPECT_EQ(face_list(saddle.mesh), fan(4));
  expect_exact_triangulation(saddle, quad);
  // A C-shape on a wavy surface: concave seen along its Newell normal.
  std::vector<Point3> wavy;
  for (std::size_t i = 0; i < c_shape.size(); ++i) {
    wavy.emplace_back(c_shape[i].x(), c_shape[i].y(), i % 2 == 0 ? 0.25 : -0.25);
  }
  const io::LoadedMesh loaded = read_text(dir, "wavy.obj", obj_polygon(wavy));
  expect_exact_triangulation(loaded, wavy);
  EXPECT_FALSE(has_note(loaded, "not simple"));
}

TEST(PolygonTriangulation, CollinearConsecutiveCornersMakeNoDegenerateTriangle) {
  TempDir dir;
  // The fan's first triangle, (0,0) (1,0) (2,0), would have no area.
  const auto square = in_plane_z0({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}});
  expect_exact_triangulation(read_text(dir, "square.obj", obj_polygon(square)), square);
  const auto c_with_midpoints = in_plane_z0(
      {{0, 0}, {1.5, 0}, {3, 0}, {3, 1}, {2, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {1.5, 3}, {0, 3}, {0, 1.5}});
  expect_exact_triangulation(read_text(dir, "c_mid.obj", obj_polygon(c_with_midpoints)), c_with_midpoints);
}

TEST(PolygonTriangulation, PolygonWithAHoleJoinedByABridge) {
  TempDir dir;
  // A 4 x 4 square with a 2 x 2 hole, joined by the edge (0,0)-(1,1) walked both ways.
  const io::LoadedMesh loaded = read_text(dir, "keyhole.obj",
                                          "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\n"
                                          "v 1 1 0\nv 1 3 0\nv 3 3 0\nv 3 1 0\n"
                                          "f 1 2 3 4 1 5 6 7 8 5\n");
  const auto triangles = projected_triangles(loaded.mesh, Point3::UnitZ());
  ASSERT_EQ(triangles.size(), 8u);
  double total = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    EXPECT_GT(signed_area(triangles[i]), 0.0);
    total += signed_area(triangles[i]);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_FALSE(interiors_overlap(triangles[i], triangles[j], 1e-12));
    }
  }
  EXPECT_NEAR(total, 12.0, 1e-12);
  EXPECT_FALSE(has_note(loaded, "not simple"));
}

TEST(PolygonTriangulation, SelfIntersectingPolygonsAreCountedInTheNotes) {
  TempDir dir;
  // A pentagram drawn in one stroke, a bow tie (no area: its halves cancel),
  // and a C-shape: two of three are not simple.
  const auto pentagram = star(5, 1.0, 1.0);
  std::string text;
  for (int i = 0; i < 5; ++i) {
    const Point2& p = pentagram[static_cast<std::size_t>(4 * i % 10)];
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " 0\n";
  }
  text += "f 1 2 3 4 5\n";
  text += "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 6 7 8 9\n";
  for (const Point2& p : c_shape) {
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " 0\n";
  }
  text += "f 10 11 12 13 14 15 16 17\n";
  const io::LoadedMesh loaded = read_text(dir, "crossing.obj", text);
  EXPECT_EQ(loaded.mesh.num_faces(), 3 + 2 + 6);
  EXPECT_TRUE(has_note(loaded, "2 polygons not simple")) << ::testing::PrintToString(loaded.info.notes);
  EXPECT_TRUE(has_note(loaded, "1 polygon not convex, triangulated by ear clipping"));
  // Every corner of each polygon is used; no index beyond it.
  for (Eigen::Index f = 0; f < loaded.mesh.faces.rows(); ++f) {
    const Index first = f < 3 ? 0 : f < 5 ? 5 : 9;
    const Index last = f < 3 ? 4 : f < 5 ? 8 : 16;
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(loaded.mesh.faces(f, c), first);
      EXPECT_LE(loaded.mesh.faces(f, c), last);
    }
  }
}

TEST(PolygonTriangulation, OffPlyAndAsciiStlSplitPolygonsTheSameWay) {
  TempDir dir;
  const auto corners = star(5, 1.0, 0.4);
  const io::LoadedMesh obj = read_text(dir, "star.obj", obj_polygon(in_plane_z0(corners)));
  std::string vertices;
  std::string face = "10";
  for (std::size_t i = 0; i < corners.size(); ++i) {
    vertices += std::to_string(corners[i].x()) + " " + std::to_string(corners[i].y()) + " 0\n";
    face += " " + std::to_string(i);
  }
  const io::LoadedMesh off = read_text(dir, "star.off", "OFF\n10 1 0\n" + vertices + face + "\n");
  EXPECT_EQ(face_list(off.mesh), face_list(obj.mesh));
  const std::string ply_header =
      "element vertex 10\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const io::LoadedMesh ply_ascii =
      read_text(dir, "star.ply", "ply\nformat ascii 1.0\n" + ply_header + vertices + face + "\n");
  EXPECT_EQ(face_list(ply_ascii.mesh), face_list(obj.mesh));
  ByteWriter binary;
  binary.text("ply\nformat binary_little_endian 1.0\n" + ply_header);
  for (Eigen::Index v = 0; v < obj.mesh.vertices.rows(); ++v) {
    binary.put(obj.mesh.vertices(v, 0)).put(obj.mesh.vertices(v, 1)).put(obj.mesh.vertices(v, 2));
  }
  binary.put<std::uint8_t>(10);
  for (std::int32_t i = 0; i < 10; ++i) {
    binary.put(i);
  }
  const io::LoadedMesh ply_binary = read_text(dir, "star_binary.ply", binary.str());
  EXPECT_EQ(face_list(ply_binary.mesh), face_list(obj.mesh));
  // ASCII STL facets may have more than three vertices; STL welds them by position.
  std::string stl = "solid star\nfacet normal 0 0 1\nouter loop\n";
  for (const Point2& p : corners) {
    stl += "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " 0\n";
  }
  stl += "endloop\nendfacet\nendsolid star\n";
  const io::LoadedMesh facet = read_text(dir, "star.stl", stl);
  EXPECT_EQ(face_list(facet.mesh), face_list(obj.mesh));
  expect_exact_triangulation(facet, in_plane_z0(corners));
}

TEST(PolygonTriangulation, FacesBeforeTheirVerticesAreTriangulatedTheSame) {
  // Readers triangulate a polygon at once when its vertices are known, else
  // at the end of the file: both give the same triangles.
  TempDir dir;
  const auto corners = in_plane_z0(c_shape);
  const std::string text = obj_polygon(corners);
  const std::size_t face_line = text.rfind("f ");
  const io::LoadedMesh in_order = read_text(dir, "in_order.obj", text);
  const io::LoadedMesh face_first =
      read_text(dir, "face_first.obj", text.substr(face_line) + text.substr(0, face_line));
  EXPECT_EQ(face_list(face_first.mesh), face_list(in_order.mesh));
  EXPECT_EQ(face_first.info.notes, in_order.info.notes);
  expect_exact_triangulation(face_first, corners);
  std::string vertices;
  for (const Point3& p : corners) {
    vertices += std::to_string(p.x()) + " " + std::to_string(p.y()) + " 0\n";
  }
  const io::LoadedMesh ply = read_text(dir, "face_first.ply",
                                       "ply\nformat ascii 1.0\nelement face 2\n"
                                       "property list uchar int vertex_indices\n"
                                       "element vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
                                       "end_header\n8 0 1 2 3 4 5 6 7\n3 0 1 2\n" +
                                           vertices);
  std::vector<Index> expected = face_list(in_order.mesh);
  expected.insert(expected.end(), {0, 1, 2});
  EXPECT_EQ(face_list(ply.mesh), expected);
  EXPECT_EQ(ply.info.polygons_split, 1);
}

TEST(PolygonTriangulation, LargePolygons) {
  TempDir dir;
  // A convex 5000-gon: the fan, without ear clipping's quadratic cost.
  std::vector<Point2> circle;
  for (int i = 0; i < 5000; ++i) {
    const double angle = 2 * std::numbers::pi * i / 5000;
    circle.emplace_back(std::cos(angle), std::sin(angle));
  }
  std::string text;
  for (const Point2& p : circle) {
    char line[96];
    std::snprintf(line, sizeof line, "v %.17g %.17g 0\n", p.x(), p.y());
    text += line;
  }
  text += "f";
  for (int i = 1; i <= 5000; ++i) {
    text += " " + std::to_string(i);
  }
  const io::LoadedMesh round = read_text(dir, "circle.obj", text + "\n");
  EXPECT_EQ(face_list(round.mesh), fan(5000));
  EXPECT_TRUE(round.info.notes.empty());
  // A comb of 2001 teeth (4004 corners) is over the ear-clipping limit: the fan, said in the notes.
  std::vector<Point2> comb = {{0, -1}};
  for (int i = 0; i <= 2000; ++i) {
    comb.emplace_back(2 * i, 0);
    comb.emplace_back(2 * i + 1, 1);
  }
  comb.emplace_back(4001, -1);
  const io::LoadedMesh teeth = read_text(dir, "comb.obj", obj_polygon(in_plane_z0(comb)));
  EXPECT_EQ(face_list(teeth.mesh), fan(static_cast<Index>(comb.size())));
  EXPECT_TRUE(has_note(teeth, "1 polygon not convex with more than 2000 corners, too many for ear clipping"))
      << ::testing::PrintToString(teeth.info.notes);
}

TEST(PolygonTriangulation, NonFiniteOrHugeCoordinatesNeitherHangNorCrash) {
  TempDir dir;
  // The reader triangulates before read_mesh checks the coordinates: that
  // check must still be the one to answer.
  const std::string message = error_message(
      [&] { read_text(dir, "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1 2 3 4 5\n"); });
  EXPECT_NE(message.find("nan.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("non-finite coordinate"), std::string::npos) << message;
  // Products of coordinates near 1e300 overflow: the polygon has no usable
  // plane, keeps the fan and is counted.
  const io::LoadedMesh huge = read_text(dir, "huge.obj",
                                        "v 0 0 0\nv 3e300 0 0\nv 3e300 1e300 0\nv 1e300 1e300 0\n"
                                        "v 1e300 2e300 0\nv 0 2e300 0\nf 1 2 3 4 5 6\n");
  EXPECT_EQ(face_list(huge.mesh), fan(6));
  EXPECT_TRUE(has_note(huge, "1 polygon not simple"));
}

}  // namespace
}  // namespace geodual::test
