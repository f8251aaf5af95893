#pragma once
// A point on a triangle mesh: a vertex, or a point of a face given by
// barycentric coordinates (which also covers points on edges).

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

namespace geodual {

struct SurfacePoint {
  enum class Kind { vertex, face };

  Kind kind = Kind::vertex;
  /// The vertex index (Kind::vertex) or the face index (Kind::face).
  Index element = 0;
  /// Barycentric coordinates with respect to the face's corners 0, 1, 2
  /// (Kind::face only); non-negative and summing to one.
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();

  static SurfacePoint at_vertex(Index vertex) { return {Kind::vertex, vertex, Eigen::Vector3d::Zero()}; }
  static SurfacePoint in_face(Index face, double u, double v, double w) {
    return {Kind::face, face, Eigen::Vector3d(u, v, w)};
  }

  /// The same point given the same way (not: the same position).
  friend bool operator==(const SurfacePoint& a, const SurfacePoint& b) {
    return a.kind == b.kind && a.element == b.element && a.barycentric == b.barycentric;
  }

  /// The point's position in space.
  Eigen::Vector3d position(const TriangleMesh& mesh) const {
    if (kind == Kind::vertex) return mesh.vertices.row(element).transpose();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int corner = 0; corner < 3; ++corner) {
      p += barycentric[corner] * mesh.vertices.row(mesh.faces(element, corner)).transpose();
    }
    return p;
  }
};

}  // namespace geodual
