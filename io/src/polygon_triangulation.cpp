#include "polygon_triangulation.hpp"

#include "str_cat.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace geodual::io::detail {
namespace {

using Point = std::array<double, 2>;

Point minus(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1]}; }
double cross(const Point& u, const Point& v) { return u[0] * v[1] - u[1] * v[0]; }
double length(const Point& u) { return std::sqrt(u[0] * u[0] + u[1] * u[1]); }

// A turn of less than 1e-12 radians is straight; projected coordinates carry
// a few units of rounding in the last place of the polygon's extent.
constexpr double turn_angle_tolerance = 1e-12;
constexpr double rounding_tolerance = 16 * std::numeric_limits<double>::epsilon();

/// Directions in [0, pi): above the x axis, or along it to the right.
bool upper_half(const Point& d) { return d[1] > 0 || (d[1] == 0 && d[0] > 0); }

void write_fan(std::span<const Index> corners, std::span<Index> triangles) {
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
    triangles[3 * (i - 1)] = corners[0];
    triangles[3 * (i - 1) + 1] = corners[i];
    triangles[3 * (i - 1) + 2] = corners[i + 1];
  }
}

}  // namespace

double PolygonTriangulator::tolerance(const Point& u, const Point& v) const {
  const double lu = length(u);
  const double lv = length(v);
  return turn_angle_tolerance * lu * lv + rounding_tolerance * extent_ * (lu + lv);
}

bool PolygonTriangulator::project(std::span<const Index> corners, std::span<const double> xyz) {
  const std::size_t n = corners.size();
  const auto position = [&](std::size_t corner) {
    return Eigen::Map<const Eigen::Vector3d>(xyz.data() + 3 * static_cast<std::size_t>(corners[corner]));
  };
  const Eigen::Vector3d origin = position(0);
  // Newell's normal: twice the polygon's vector area, whatever its shape.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double extent_squared = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = position(i) - origin;
    const Eigen::Vector3d b = position((i + 1) % n) - origin;
    normal += a.cross(b);
    extent_squared = std::max(extent_squared, a.squaredNorm());
  }
  const double area_twice = normal.norm();
  // No area to speak of (all corners on a line, or areas that cancel), or
  // coordinates so large that the products overflow: no plane to work in.
  if (!(area_twice > 1e-14 * extent_squared) || !std::isfinite(area_twice)) {
    return false;
  }
  const Eigen::Vector3d w = normal / area_twice;
  // u, v, w right-handed: the polygon winds counter-clockwise in (u, v).
  Eigen::Index least = 0;
  w.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d u = Eigen::Vector3d::Unit(least).cross(w).normalized();
  const Eigen::Vector3d v = w.cross(u);
  points_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = position(i) - origin;
    points_[i] = {p.dot(u), p.dot(v)};
  }
  extent_ = std::sqrt(extent_squared);
  return true;
}

bool PolygonTriangulator::is_convex_quad(std::span<const Index> corners, std::span<const double> xyz) {
  std::array<Eigen::Vector3d, 4> p;
  for (std::size_t i = 0; i < 4; ++i) {
    p[i] = Eigen::Map<const Eigen::Vector3d>(xyz.data() + 3 * static_cast<std::size_t>(corners[i]));
  }
  // A quad's Newell normal is the cross product of its diagonals. A turn in
  // the plane along it is the triple product (e_before x e_after) . normal;
  // four left turns make one lap (each is less than half a lap).
  const Eigen::Vector3d normal = (p[2] - p[0]).cross(p[3] - p[1]);
  const double normal_length = normal.norm();
  double extent = 0;
  for (std::size_t i = 1; i < 4; ++i) {
    extent = std::max(extent, (p[i] - p[0]).norm());
  }
  if (!(normal_length > 1e-14 * extent * extent) || !std::isfinite(normal_length)) {
    return false;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d before = p[i] - p[(i + 3) % 4];
    const Eigen::Vector3d after = p[(i + 1) % 4] - p[i];
    const double lb = before.norm();
    const double la = after.norm();
    // tolerance() in 3D: edge lengths are at least their projections.
    const double tolerance = (turn_angle_tolerance * lb * la + rounding_tolerance * extent * (lb + la)) * normal_length;
    if (!(before.cross(after).dot(normal) > tolerance)) {
      return false;
    }
  }
  return true;
}

/// Every corner turns left, and the edge directions go round exactly once.
bool PolygonTriangulator::is_convex() const {
  const std::size_t n = points_.size();
  std::size_t laps = 0;
  Point before = minus(points_[0], points_[n - 1]);
  for (std::size_t i = 0; i < n; ++i) {
    const Point after = minus(points_[(i + 1) % n], points_[i]);
    if (!(cross(before, after) > tolerance(before, after))) {
      return false;
    }
    // Each left turn is less than half a lap, so a direction passing angle 0
    // (from the lower half to the upper one) counts a lap.
    if (!upper_half(before) && upper_half(after)) {
      ++laps;
    }
    before = after;
  }
  return laps == 1;
}

bool PolygonTriangulator::turns_left(std::size_t corner) const {
  const Point ab = minus(points_[corner], points_[previous_[corner]]);
  const Point bc = minus(points_[next_[corner]], points_[corner]);
  return cross(ab, bc) > tolerance(ab, bc);
}

bool PolygonTriangulator::is_ear(std::size_t tip) const {
  if (!turns_left_[tip]) {
    return false;  // not a strictly convex corner
  }
  const std::size_t a = previous_[tip];
  const std::size_t c = next_[tip];
  const Point& pa = points_[a];
  const Point& pb = points_[tip];
  const Point& pc = points_[c];
  const Point ab = minus(pb, pa);
  const Point bc = minus(pc, pb);
  const Point ca = minus(pa, pc);
  // Does an edge from corner j, at the triangle corner `at`, enter the
  // triangle? Only if its direction lies strictly between the triangle's two
  // edges there, `along` (counter-clockwise) and `back`.
  const auto edge_enters = [&](const Point& at, const Point& along, const Point& back, std::size_t j) {
    for (const std::size_t neighbour : {previous_[j], next_[j]}) {
      const Point d = minus(points_[neighbour], at);
      if (cross(along, d) > tolerance(along, d) && cross(d, back) > tolerance(d, back)) {
        return true;
      }
    }
    return false;
  };
  const auto in_closed_triangle = [&](const Point& p) {
    const Point from_a = minus(p, pa);
    const Point from_b = minus(p, pb);
    const Point from_c = minus(p, pc);
    return cross(ab, from_a) >= -tolerance(ab, from_a) && cross(bc, from_b) >= -tolerance(bc, from_b) &&
           cross(ca, from_c) >= -tolerance(ca, from_c);
  };
  for (std::size_t j = next_[c]; j != a; j = next_[j]) {
    // A corner repeated at a triangle corner (a polygon joined to its hole by
    // a bridge, or a vertex visited twice) blocks the ear only if one of its
    // edges enters the triangle. Otherwise, if a corner lies in the triangle,
    // so does one that does not turn left (the one farthest from the line
    // a c): testing those suffices.
    const Point& p = points_[j];
    const bool blocks = p == pa   ? edge_enters(pa, ab, minus(pc, pa), j)
                        : p == pb ? edge_enters(pb, bc, minus(pa, pb), j)
                        : p == pc ? edge_enters(pc, ca, minus(pb, pc), j)
                                  : !turns_left_[j] && in_closed_triangle(p);
    if (blocks) {
      return false;
    }
  }
  return true;
}

/// The first strictly convex corner from `start`, else the corner that turns
/// right the least: a corner that is no ear, for polygons that have none.
std::size_t PolygonTriangulator::least_bad_tip(std::size_t start, std::size_t remaining) const {
  std::size_t best = start;
  double best_turn = -std::numeric_limits<double>::infinity();
  std::size_t tip = start;
  for (std::size_t tried = 0; tried < remaining; ++tried, tip = next_[tip]) {
    const Point ab = minus(points_[tip], points_[previous_[tip]]);
    const Point bc = minus(points_[next_[tip]], points_[tip]);
    const double turn = cross(ab, bc);
    if (turn > tolerance(ab, bc)) {
      return tip;
    }
    if (turn > best_turn) {
      best_turn = turn;
      best = tip;
    }
  }
  return best;
}

bool PolygonTriangulator::clip_ears(std::span<const Index> corners, std::span<Index> triangles) {
  const std::size_t n = points_.size();
  previous_.resize(n);
  next_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    previous_[i] = (i + n - 1) % n;
    next_[i] = (i + 1) % n;
  }
  turns_left_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    turns_left_[i] = turns_left(i);
  }
  std::size_t written = 0;
  const auto clip = [&](std::size_t tip) {
    triangles[3 * written] = corners[previous_[tip]];
    triangles[3 * written + 1] = corners[tip];
    triangles[3 * written + 2] = corners[next_[tip]];
    ++written;
    next_[previous_[tip]] = next_[tip];
    previous_[next_[tip]] = previous_[tip];
    turns_left_[previous_[tip]] = turns_left(previous_[tip]);
    turns_left_[next_[tip]] = turns_left(next_[tip]);
  };
  bool every_clip_an_ear = true;
  // Starting at corner 1 and moving on to the next corner after each clip
  // gives a convex polygon its fan: (c0, c1, c2), (c0, c2, c3), ...
  std::size_t cursor = 1;
  for (std::size_t remaining = n; remaining > 3; --remaining) {
    // Once a whole lap had no ear the polygon is not simple, and ears are
    // looked for among a few corners only: a full lap each time would cost
    // the cube of the corner count.
    constexpr std::size_t corners_tried_once_not_simple = 32;
    const std::size_t limit = every_clip_an_ear ? remaining : std::min(remaining, corners_tried_once_not_simple);
    std::size_t tip = cursor;
    std::size_t tried = 0;
    while (tried < limit && !is_ear(tip)) {
      tip = next_[tip];
      ++tried;
    }
    if (tried == limit) {
      every_clip_an_ear = false;
      tip = least_bad_tip(cursor, remaining);
    }
    cursor = next_[tip];
    clip(tip);
  }
  const Point ab = minus(points_[cursor], points_[previous_[cursor]]);
  const Point bc = minus(points_[next_[cursor]], points_[cursor]);
  const bool last_flipped = cross(ab, bc) < -tolerance(ab, bc);
  clip(cursor);
  return every_clip_an_ear && !last_flipped;
}

/// Whether two edges that share no corner cross at a point inside both.
bool PolygonTriangulator::has_crossing_edges() const {
  const std::size_t n = points_.size();
  const auto side = [&](const Point& from, const Point& to, const Point& p) {
    const Point edge = minus(to, from);
    const Point offset = minus(p, from);
    const double turn = cross(edge, offset);
    const double tol = tolerance(edge, offset);
    return turn > tol ? 1 : turn < -tol ? -1 : 0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p0 = points_[i];
    const Point& p1 = points_[(i + 1) % n];
    // Edges i and i + 1, and the last and the first, are neighbours.
    for (std::size_t j = i + 2; j < n && !(i == 0 && j == n - 1); ++j) {
      const Point& q0 = points_[j];
      const Point& q1 = points_[(j + 1) % n];
      if (std::max(p0[0], p1[0]) < std::min(q0[0], q1[0]) || std::max(q0[0], q1[0]) < std::min(p0[0], p1[0]) ||
          std::max(p0[1], p1[1]) < std::min(q0[1], q1[1]) || std::max(q0[1], q1[1]) < std::min(p0[1], p1[1])) {
        continue;
      }
      if (side(p0, p1, q0) * side(p0, p1, q1) < 0 && side(q0, q1, p0) * side(q0, q1, p1) < 0) {
        return true;
      }
    }
  }
  return false;
}

PolygonShape PolygonTriangulator::triangulate(std::span<const Index> corners, std::span<const double> xyz,
                                              std::span<Index> triangles) {
  if (corners.size() == 3) {
    write_fan(corners, triangles);
    return PolygonShape::convex;
  }
  if (corners.size() == 4 && is_convex_quad(corners, xyz)) {
    write_fan(corners, triangles);
    return PolygonShape::convex;
  }
  if (!project(corners, xyz)) {
    write_fan(corners, triangles);
    return PolygonShape::non_simple;
  }
  if (is_convex()) {
    write_fan(corners, triangles);
    return PolygonShape::convex;
  }
  if (corners.size() > options_.max_ear_clipping_corners) {
    write_fan(corners, triangles);
    return PolygonShape::too_large;
  }
  const bool clean = clip_ears(corners, triangles);
  return clean && !has_crossing_edges() ? PolygonShape::simple : PolygonShape::non_simple;
}

void FaceBuffer::add_triangulated() {
  scratch_triangles_.resize(3 * (corners_.size() - 2));
  ++shapes_[static_cast<std::size_t>(triangulator_.triangulate(corners_, known_xyz_, scratch_triangles_))];
  for (std::size_t t = 0; t < scratch_triangles_.size(); t += 3) {
    triangles_.add(scratch_triangles_[t], scratch_triangles_[t + 1], scratch_triangles_[t + 2]);
  }
}

FaceMatrix FaceBuffer::take(const VertexMatrix& vertices, ReadInfo& info) {
  info.polygons_split = polygons_split_;
  FaceMatrix faces = triangles_.take();
  const std::span<const double> xyz(vertices.data(), static_cast<std::size_t>(vertices.size()));
  for (const PendingPolygon& polygon : polygons_) {
    const std::span<Index> fan(faces.data() + 3 * polygon.first_triangle, 3 * (polygon.corners - 2));
    // The fan holds every corner: c0 and c1 in its first triangle, then each triangle's third.
    corners_.assign({fan[0], fan[1]});
    for (std::size_t t = 0; t + 2 < polygon.corners; ++t) {
      corners_.push_back(fan[3 * t + 2]);
    }
    ++shapes_[static_cast<std::size_t>(triangulator_.triangulate(corners_, xyz, fan))];
  }
  polygons_ = {};
  const auto count = [&](PolygonShape shape) { return shapes_[static_cast<std::size_t>(shape)]; };
  const auto polygons = [](std::int64_t n) { return n == 1 ? " polygon" : " polygons"; };
  if (const std::int64_t n = count(PolygonShape::simple); n > 0) {
    info.notes.push_back(str_cat(n, polygons(n), " not convex, triangulated by ear clipping in ",
                                 n == 1 ? "its" : "their", " best-fit plane"));
  }
  if (const std::int64_t n = count(PolygonShape::non_simple); n > 0) {
    info.notes.push_back(str_cat(n, polygons(n),
                                 " not simple (edges that cross, or no area, in the best-fit plane): "
                                 "triangulated as well as possible; the triangles may overlap"));
  }
  if (const std::int64_t n = count(PolygonShape::too_large); n > 0) {
    info.notes.push_back(str_cat(n, polygons(n), " not convex with more than ", options_.max_ear_clipping_corners,
                                 " corners, too many for ear clipping: fan-triangulated; the triangles may "
                                 "overlap"));
  }
  return faces;
}

}  // namespace geodual::io::detail
