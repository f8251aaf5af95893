#pragma once
// Internal: triangulating the polygons readers meet (OBJ, OFF and PLY faces,
// ASCII STL facets with more than three corners). A polygon is projected onto
// its best-fit plane (Newell's normal) and triangulated there by ear clipping,
// each triangle in the polygon's own orientation. Convex polygons get the fan
// (c0, c1, c2), (c0, c2, c3), ..., which ear clipping from c1 also gives them.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include "triangle_buffer.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::io::detail {

struct PolygonTriangulationOptions {
  /// Non-convex polygons with more corners keep the fan (and ReadInfo says so):
  /// ear clipping costs up to the cube of the corner count.
  std::size_t max_ear_clipping_corners = 2000;
};

/// How a polygon was triangulated.
enum class PolygonShape : std::uint8_t {
  convex,      ///< strictly convex: the fan
  simple,      ///< not convex (or with collinear corners): ear clipping, every triangle inside the polygon
  non_simple,  ///< edges cross (ear clipping as well as it goes), or no area in its plane (the fan)
  too_large,   ///< not convex and over max_ear_clipping_corners: the fan, whose triangles may overlap
};

/// Triangulates polygons one after another, reusing its scratch memory.
class PolygonTriangulator {
 public:
  explicit PolygonTriangulator(PolygonTriangulationOptions options = {}) : options_(options) {}

  /// Writes the polygon's corners.size() - 2 triangles, three vertex indices
  /// each, to `triangles`. `xyz` holds x, y, z of each vertex in turn;
  /// `corners` (at least 3) index vertices in it.
  PolygonShape triangulate(std::span<const Index> corners, std::span<const double> xyz, std::span<Index> triangles);

 private:
  using Point = std::array<double, 2>;

  /// Fills points_ with the corners in the plane of the Newell normal; false
  /// when the polygon has no usable normal (no area, or non-finite coordinates).
  bool project(std::span<const Index> corners, std::span<const double> xyz);
  /// is_convex() for a quad, without projecting it (most polygons are quads).
  static bool is_convex_quad(std::span<const Index> corners, std::span<const double> xyz);
  bool is_convex() const;
  /// Ear clipping over points_; false when it had to clip a corner that is no
  /// ear, or the last triangle is flipped.
  bool clip_ears(std::span<const Index> corners, std::span<Index> triangles);
  /// Whether the corner turns strictly left in the ring of corners not yet clipped.
  bool turns_left(std::size_t corner) const;
  bool is_ear(std::size_t tip) const;
  /// The corner to clip when no corner is an ear.
  std::size_t least_bad_tip(std::size_t start, std::size_t remaining) const;
  bool has_crossing_edges() const;
  /// The tolerance for a cross product of edge vectors u and v: rounding, not geometry.
  double tolerance(const Point& u, const Point& v) const;

  PolygonTriangulationOptions options_;
  std::vector<Point> points_;
  std::vector<std::size_t> previous_;  // the ring of corners not yet clipped
  std::vector<std::size_t> next_;
  std::vector<std::uint8_t> turns_left_;  // turns_left() of each corner in the ring
  double extent_ = 0;                     // the largest distance of a corner from the first, in the plane
};

/// Collects a reader's faces: triangles as given, polygons triangulated at
/// once when their vertices are known (know_vertices), else fan-triangulated
/// and remembered until take() replaces each fan, once every vertex is known.
class FaceBuffer {
 public:
  explicit FaceBuffer(std::size_t expected_triangles = 0, PolygonTriangulationOptions options = {})
      : triangles_(expected_triangles), triangulator_(options), options_(options) {}

  [[gnu::always_inline]] void add(Index a, Index b, Index c) { triangles_.add(a, b, c); }

  /// The vertices read so far, x, y, z each in turn; the storage must stay
  /// put until the next add_polygon.
  void know_vertices(std::span<const double> xyz) { known_xyz_ = xyz; }
  void know_vertices(const VertexMatrix& vertices) {
    known_xyz_ = {vertices.data(), static_cast<std::size_t>(vertices.size())};
  }

  /// A face of `corners` (at least 3) corners; `corner(i)` returns the i-th
  /// corner's vertex index (not negative), and is called once for each.
  template <class CornerAt>
  void add_polygon(std::size_t corners, CornerAt&& corner) {
    if (corners == 3) {
      const Index a = corner(0);
      const Index b = corner(1);
      triangles_.add(a, b, corner(2));
      return;
    }
    ++polygons_split_;
    corners_.clear();
    bool known = true;
    const std::size_t known_count = known_xyz_.size() / 3;
    for (std::size_t i = 0; i < corners; ++i) {
      corners_.push_back(corner(i));
      known = known && static_cast<std::size_t>(corners_.back()) < known_count;
    }
    if (known) {
      add_triangulated();
    } else {
      polygons_.push_back(PendingPolygon{.first_triangle = triangles_.size(), .corners = corners});
      triangles_.add_polygon(corners, [this](std::size_t i) { return corners_[i]; });
    }
  }

  /// The triangles, in the order their faces were added. Every index must be
  /// a row of `vertices`. Sets info.polygons_split and notes how polygons
  /// that are not convex were triangulated.
  FaceMatrix take(const VertexMatrix& vertices, ReadInfo& info);

 private:
  struct PendingPolygon {
    Eigen::Index first_triangle = 0;
    std::size_t corners = 0;
  };

  /// Triangulates corners_ over the known vertices and adds the triangles.
  void add_triangulated();

  TriangleBuffer triangles_;
  PolygonTriangulator triangulator_;
  PolygonTriangulationOptions options_;
  std::span<const double> known_xyz_;
  std::vector<PendingPolygon> polygons_;  // fan-triangulated until take()
  std::vector<Index> corners_;            // reused for every polygon: no allocation per face
  std::vector<Index> scratch_triangles_;
  std::int64_t polygons_split_ = 0;
  std::array<std::int64_t, 4> shapes_{};  // polygons of each PolygonShape
};

}  // namespace geodual::io::detail
