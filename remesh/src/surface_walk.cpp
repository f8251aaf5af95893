#include "surface_walk.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace geodual::remesh::detail {
namespace {

Eigen::Vector3d corner(const TriangleMesh& mesh, Index face, int c) {
  return mesh.vertices.row(mesh.faces(face, c)).transpose();
}

/// Barycentric coordinates of p (in the face's plane) with respect to the face.
Eigen::Vector3d barycentric_in(const TriangleMesh& mesh, Index face, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = corner(mesh, face, 0), b = corner(mesh, face, 1), c = corner(mesh, face, 2);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double twice = n.squaredNorm();
  Eigen::Vector3d w(n.dot((c - b).cross(p - b)), n.dot((a - c).cross(p - c)), 0.0);
  w /= twice;
  w = w.cwiseMax(0.0);
  w[2] = std::max(0.0, 1.0 - w[0] - w[1]);
  return w / w.sum();
}

}  // namespace

SurfacePoint walk_on_surface(const TriangleMesh& mesh, const voronoi::GeodesicField& field, const SurfacePoint& start,
                             const Eigen::Vector3d& direction, double length) {
  if (start.kind != SurfacePoint::Kind::face || !(length > 0) || !direction.allFinite()) return start;
  Index face = start.element;
  Eigen::Vector3d p = start.position(mesh);
  Eigen::Vector3d normal = (corner(mesh, face, 1) - corner(mesh, face, 0)).cross(corner(mesh, face, 2) - corner(mesh, face, 0));
  if (!(normal.norm() > 0)) return start;
  normal.normalize();
  Eigen::Vector3d v = direction - normal * normal.dot(direction);
  if (!(v.norm() > 0)) return start;
  v.normalize();
  double remaining = length;
  Index entry_edge = -1;
  for (int step = 0; step < 1'000'000; ++step) {
    // The nearest side the ray leaves through (not the one it came in by).
    double exit_t = INFINITY;
    int exit_side = -1;
    for (int k = 0; k < 3; ++k) {
      if (field.face_edges[face][k] == entry_edge) continue;
      const Eigen::Vector3d a = corner(mesh, face, k), b = corner(mesh, face, (k + 1) % 3);
      const Eigen::Vector3d side = b - a;
      // p + t v = a + u side, within the face's plane.
      const double denominator = normal.dot(v.cross(side));
      if (!(std::abs(denominator) > 0)) continue;
      const double t = normal.dot((a - p).cross(side)) / denominator;
      const double u = normal.dot((a - p).cross(v)) / denominator;
      if (t > 0 && u >= -1e-12 && u <= 1 + 1e-12 && t < exit_t) exit_t = t, exit_side = k;
    }
    if (exit_side < 0 || exit_t >= remaining) {
      p += std::min(remaining, exit_side < 0 ? 0.0 : remaining) * v;
      const Eigen::Vector3d b = barycentric_in(mesh, face, p);
      return SurfacePoint::in_face(face, b[0], b[1], b[2]);
    }
    p += exit_t * v;
    remaining -= exit_t;
    const Index edge = field.face_edges[face][exit_side];
    const Index next = field.edge_faces[edge][0] == face ? field.edge_faces[edge][1] : field.edge_faces[edge][0];
    if (next < 0) {  // the mesh boundary: stop on it
      const Eigen::Vector3d b = barycentric_in(mesh, face, p);
      return SurfacePoint::in_face(face, b[0], b[1], b[2]);
    }
    // Unfold about the edge: keep the component along it, and turn the rest
    // into the next face's plane, pointing into that face.
    const Eigen::Vector3d a = corner(mesh, face, exit_side), b = corner(mesh, face, (exit_side + 1) % 3);
    const Eigen::Vector3d along = (b - a).normalized();
    Eigen::Vector3d next_normal =
        (corner(mesh, next, 1) - corner(mesh, next, 0)).cross(corner(mesh, next, 2) - corner(mesh, next, 0));
    if (!(next_normal.norm() > 0)) next_normal = normal;  // a zero-area face: cross it flat
    next_normal.normalize();
    Eigen::Vector3d inward = next_normal.cross(along);
    // `inward` must point from the edge into the next face.
    Eigen::Vector3d opposite = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index vertex = mesh.faces(next, c);
      if (vertex != mesh.faces(face, exit_side) && vertex != mesh.faces(face, (exit_side + 1) % 3)) {
        opposite = mesh.vertices.row(vertex).transpose();
      }
    }
    if (inward.dot(opposite - a) < 0) inward = -inward;
    const double tangential = v.dot(along);
    const double across = std::sqrt(std::max(0.0, 1 - tangential * tangential));
    v = (tangential * along + across * inward).normalized();
    face = next;
    normal = next_normal;
    entry_edge = edge;
  }
  const Eigen::Vector3d b = barycentric_in(mesh, face, p);
  return SurfacePoint::in_face(face, b[0], b[1], b[2]);
}

}  // namespace geodual::remesh::detail
