#include "geodual/remesh/follow_segments.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace geodual::remesh {
namespace {

Eigen::Vector3d face_normal(const TriangleMesh& mesh, Index a, Index b, Index c) {
  const Eigen::Vector3d p = mesh.vertices.row(a), q = mesh.vertices.row(b), r = mesh.vertices.row(c);
  return (q - p).cross(r - p);
}

/// The smallest angle of triangle (a, b, c), in radians.
double min_angle(const TriangleMesh& mesh, Index a, Index b, Index c) {
  const Eigen::Vector3d p[3] = {mesh.vertices.row(a), mesh.vertices.row(b), mesh.vertices.row(c)};
  double smallest = std::numbers::pi;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  return smallest;
}

/// The corner of face f at vertex v (-1: none).
int corner_of(const TriangleMesh& mesh, Index f, Index v) {
  for (int k = 0; k < 3; ++k) {
    if (mesh.faces(f, k) == v) return k;
  }
  return -1;
}

}  // namespace

FollowedSegments follow_segments(TriangleMesh& mesh, std::span<const std::array<Index, 2>> segments,
                                 const FollowSegmentsOptions& options) {
  const double min_new_angle = options.min_angle_degrees * std::numbers::pi / 180;
  FollowedSegments result;
  result.segments = static_cast<std::int64_t>(segments.size());
  std::vector<std::vector<Index>> faces_at(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) faces_at[mesh.faces(f, k)].push_back(f);
  }
  const auto joined = [&](Index a, Index b) {
    return std::any_of(faces_at[a].begin(), faces_at[a].end(), [&](Index f) { return corner_of(mesh, f, b) >= 0; });
  };
  for (const auto& [a, b] : segments) {
    if (a == b || a < 0 || b < 0 || a >= mesh.num_vertices() || b >= mesh.num_vertices()) continue;
    if (joined(a, b)) {
      ++result.edges;
      continue;
    }
    // A face (a, c, d) and a face (d, c, b): flip c-d to a-b.
    bool done = false;
    for (const Index f : faces_at[a]) {
      const int k = corner_of(mesh, f, a);
      const Index c = mesh.faces(f, (k + 1) % 3), d = mesh.faces(f, (k + 2) % 3);
      for (const Index g : faces_at[b]) {
        const int m = corner_of(mesh, g, b);
        if (mesh.faces(g, (m + 1) % 3) != d || mesh.faces(g, (m + 2) % 3) != c) continue;
        const Eigen::Vector3d before =
            face_normal(mesh, a, c, d).normalized() + face_normal(mesh, d, c, b).normalized();
        const Eigen::Vector3d left = face_normal(mesh, a, c, b), right = face_normal(mesh, a, b, d);
        if (!(left.dot(before) > 0) || !(right.dot(before) > 0) || !(left.dot(right) > 0)) continue;
        const double old_angle = std::min(min_angle(mesh, a, c, d), min_angle(mesh, d, c, b));
        const double new_angle = std::min(min_angle(mesh, a, c, b), min_angle(mesh, a, b, d));
        if (new_angle < std::min(old_angle, min_new_angle)) continue;
        mesh.faces.row(f) << a, c, b;
        mesh.faces.row(g) << a, b, d;
        std::erase(faces_at[c], g);
        std::erase(faces_at[d], f);
        faces_at[b].push_back(f);
        faces_at[a].push_back(g);  // after the loops over it: they stop here
        done = true;
        break;
      }
      if (done) break;
    }
    if (done) ++result.edges, ++result.flipped;
  }
  return result;
}

}  // namespace geodual::remesh
