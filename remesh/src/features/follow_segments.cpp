#include "geodual/remesh/follow_segments.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace geodual::remesh {
namespace {

/// A triangle mesh's faces with the faces round each vertex, edited by edge
/// flips that can be undone.
class FlipMesh {
 public:
  explicit FlipMesh(TriangleMesh& mesh) : mesh_(mesh), faces_at_(static_cast<std::size_t>(mesh.num_vertices())) {
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) faces_at_[mesh.faces(f, k)].push_back(f);
    }
  }

  Eigen::Vector3d position(Index v) const { return mesh_.vertices.row(v); }
  Index corner(Index f, int k) const { return mesh_.faces(f, ((k % 3) + 3) % 3); }

  /// The corner of face f at vertex v (-1: none).
  int corner_of(Index f, Index v) const {
    for (int k = 0; k < 3; ++k) {
      if (mesh_.faces(f, k) == v) return k;
    }
    return -1;
  }

  bool joined(Index a, Index b) const {
    return std::any_of(faces_at_[a].begin(), faces_at_[a].end(), [&](Index f) { return corner_of(f, b) >= 0; });
  }

  const std::vector<Index>& faces_at(Index v) const { return faces_at_[v]; }

  /// The face that runs the edge p -> q (-1: none).
  Index face_running(Index p, Index q) const {
    for (const Index f : faces_at_[p]) {
      const int k = corner_of(f, p);
      if (corner(f, k + 1) == q) return f;
    }
    return -1;
  }

  Eigen::Vector3d normal(Index a, Index b, Index c) const {
    return (position(b) - position(a)).cross(position(c) - position(a));
  }

  /// The smallest angle of triangle (a, b, c), in radians.
  double min_angle(Index a, Index b, Index c) const {
    const Eigen::Vector3d p[3] = {position(a), position(b), position(c)};
    double smallest = std::numbers::pi;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
      smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
    }
    return smallest;
  }
  double min_angle(Index f) const { return min_angle(corner(f, 0), corner(f, 1), corner(f, 2)); }

  struct Flip {
    Index f, g;
    Eigen::Matrix<Index, 1, 3> old_f, old_g;
  };

  /// Face f = (x, p, q) and face g = (y, q, p) become (x, p, y) and (x, y, q),
  /// unless the new faces would fold against the old ones.
  bool flip(Index f, Index g, Index x, Index p, Index q, Index y, std::vector<Flip>& done) {
    const Eigen::Vector3d before = normal(x, p, q).normalized() + normal(y, q, p).normalized();
    const Eigen::Vector3d left = normal(x, p, y), right = normal(x, y, q);
    if (!(left.dot(before) > 0) || !(right.dot(before) > 0) || !(left.dot(right) > 0)) return false;
    done.push_back({f, g, mesh_.faces.row(f), mesh_.faces.row(g)});
    set_face(f, {x, p, y});
    set_face(g, {x, y, q});
    return true;
  }

  void undo(const std::vector<Flip>& done) {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      set_face(it->f, {it->old_f[0], it->old_f[1], it->old_f[2]});
      set_face(it->g, {it->old_g[0], it->old_g[1], it->old_g[2]});
    }
  }

 private:
  void set_face(Index f, const std::array<Index, 3>& corners) {
    for (int k = 0; k < 3; ++k) std::erase(faces_at_[mesh_.faces(f, k)], f);
    for (int k = 0; k < 3; ++k) {
      mesh_.faces(f, k) = corners[static_cast<std::size_t>(k)];
      faces_at_[corners[static_cast<std::size_t>(k)]].push_back(f);
    }
  }

  TriangleMesh& mesh_;
  std::vector<std::vector<Index>> faces_at_;
};

/// Makes a-b an edge by flipping, one at a time, the edge opposite a that
/// the segment crosses (in the plane of its face round a) [Slo93], at
/// most `max_flips` of them. Kept only where every face the flips made has
/// no angle below min(min_angle, the smallest of the faces they replaced);
/// undone otherwise. Returns the flips made.
int recover_segment(FlipMesh& mesh, Index a, Index b, int max_flips, double min_angle) {
  std::vector<FlipMesh::Flip> done;
  double before = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d to_b = mesh.position(b) - mesh.position(a);
  while (!mesh.joined(a, b) && static_cast<int>(done.size()) < max_flips) {
    Index f = -1, c = -1, d = -1;
    for (const Index face : mesh.faces_at(a)) {
      const int k = mesh.corner_of(face, a);
      const Index p = mesh.corner(face, k + 1), q = mesh.corner(face, k + 2);
      const Eigen::Vector3d n = mesh.normal(a, p, q);
      const Eigen::Vector3d to_p = mesh.position(p) - mesh.position(a), to_q = mesh.position(q) - mesh.position(a);
      if (to_p.cross(to_b).dot(n) >= 0 && to_b.cross(to_q).dot(n) >= 0) {
        f = face, c = p, d = q;
        break;
      }
    }
    const Index g = f < 0 ? -1 : mesh.face_running(d, c);
    if (g < 0) break;
    const Index e = mesh.corner(g, mesh.corner_of(g, d) + 2);  // g = (d, c, e)
    if (e == a || mesh.joined(a, e)) break;                    // a flip there would double an edge
    before = std::min({before, mesh.min_angle(f), mesh.min_angle(g)});
    if (!mesh.flip(f, g, a, c, d, e, done)) break;
  }
  bool kept = mesh.joined(a, b);
  for (const FlipMesh::Flip& flip : done) {
    kept = kept && std::min(mesh.min_angle(flip.f), mesh.min_angle(flip.g)) >= std::min(before, min_angle);
  }
  if (!kept) {
    mesh.undo(done);
    return 0;
  }
  return static_cast<int>(done.size());
}

}  // namespace

FollowedSegments follow_segments(TriangleMesh& mesh, std::span<const std::array<Index, 2>> segments,
                                 const FollowSegmentsOptions& options) {
  const double min_angle = options.min_angle_degrees * std::numbers::pi / 180;
  FollowedSegments result;
  result.segments = static_cast<std::int64_t>(segments.size());
  FlipMesh flips(mesh);
  for (const auto& [a, b] : segments) {
    if (a == b || a < 0 || b < 0 || a >= mesh.num_vertices() || b >= mesh.num_vertices()) continue;
    if (flips.joined(a, b)) {
      ++result.edges;
    } else if (const int made = recover_segment(flips, a, b, options.max_flips, min_angle); made > 0) {
      ++result.edges;
      result.flipped += made;
    }
  }
  return result;
}

FollowedSegments follow_pin_segments(TriangleMesh& mesh, std::span<const Index> pin_vertex,
                                     std::span<const std::array<std::size_t, 2>> segments,
                                     const FollowSegmentsOptions& options) {
  if (segments.empty() || mesh.num_faces() == 0) return {};
  std::vector<std::array<Index, 2>> joined;
  for (const auto& [a, b] : segments) {
    if (pin_vertex[a] >= 0 && pin_vertex[b] >= 0) joined.push_back({pin_vertex[a], pin_vertex[b]});
  }
  return follow_segments(mesh, joined, options);
}

}  // namespace geodual::remesh
