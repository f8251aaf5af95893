#pragma once
// The procedural look of the texture benchmark's assets (make_textured_scan,
// texture_bench): a colour defined at every point of space, so that a
// remesh's baked texture can be checked against the truth itself rather than
// against another sampled copy of it.
//
//   f(p) = mix(dark(t), light(t), s(p)),  t = (p - lo) / (hi - lo)  (the box's coordinates in [0, 1]^3)
//   s(p) = 1/2 + 1/2 tanh(c(p) / 0.3),    c(p) = sin(k (x - lo_x)) sin(k (y - lo_y)) sin(k (z - lo_z))
//   k = 2 pi / period,                    period = |hi - lo| / 40
//
// i.e. a 3D checkerboard of cells half a period wide (1/80 of the bounding
// box's diagonal), with soft edges (tanh, no aliasing however finely it is
// sampled), whose two colours run along smooth gradients over the box. The
// frequency (1/40 of the diagonal) and the edge softness (0.3) were chosen
// before any measurement and are not tuned to the results. Colours are
// sRGB-encoded in [0, 1], as a base colour texture stores them.
//
// Also here: angle-weighted vertex normals and per-face barycentric helpers,
// written for the benchmark without geodual's own code, so that the
// benchmark measures the baker rather than repeating it.
//
// Header-only: every bench/*.cpp is its own executable (bench/CMakeLists.txt).

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geodual::bench {

struct ProceduralTexture {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();  ///< the box's corners: the mesh's bounding box
  Eigen::Vector3d hi = Eigen::Vector3d::Ones();
  double period = 1.0 / 40.0;  ///< of the checkerboard: two cells

  /// The texture of a mesh: its bounding box, period 1/40 of its diagonal.
  static ProceduralTexture of(const TriangleMesh& mesh) {
    ProceduralTexture texture;
    texture.lo = mesh.vertices.colwise().minCoeff().transpose();
    texture.hi = mesh.vertices.colwise().maxCoeff().transpose();
    texture.period = (texture.hi - texture.lo).norm() / 40.0;
    return texture;
  }

  /// The checkerboard's mix in [0, 1]: 0 dark, 1 light.
  double mix(const Eigen::Vector3d& p) const {
    const double k = 2 * std::numbers::pi / period;
    const Eigen::Vector3d q = k * (p - lo);
    const double c = std::sin(q.x()) * std::sin(q.y()) * std::sin(q.z());
    return 0.5 + 0.5 * std::tanh(c / 0.3);
  }

  /// f(p): sRGB-encoded RGB in [0, 1].
  Eigen::Vector3d color(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d size = (hi - lo).cwiseMax(Eigen::Vector3d::Constant(1e-300));
    const Eigen::Vector3d t = ((p - lo).cwiseQuotient(size)).cwiseMax(0.0).cwiseMin(1.0);
    const Eigen::Vector3d light(0.95 - 0.25 * t.z(), 0.55 + 0.40 * t.x(), 0.25 + 0.70 * t.y());
    const Eigen::Vector3d dark(0.10 + 0.30 * t.y(), 0.05 + 0.15 * t.z(), 0.35 - 0.25 * t.x());
    const double s = mix(p);
    return ((1 - s) * dark + s * light).cwiseMax(0.0).cwiseMin(1.0);
  }
};

/// sRGB encoding and decoding of one channel in [0, 1] (IEC 61966-2-1),
/// written out here rather than taken from geodual.
inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
inline double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

/// The angle-weighted vertex normals of `mesh` (each face's unit normal
/// weighted by its corner's angle), unit length; (0, 0, 1) where they cancel.
inline VertexMatrix angle_weighted_normals(const TriangleMesh& mesh) {
  VertexMatrix normals = VertexMatrix::Zero(mesh.num_vertices(), 3);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double length = cross.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector3d n = cross / length;
    const Eigen::Vector3d corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = corners[(k + 1) % 3] - corners[k];
      const Eigen::Vector3d e2 = corners[(k + 2) % 3] - corners[k];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      normals.row(mesh.faces(f, k)) += angle * n.transpose();
    }
  }
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const double length = normals.row(v).norm();
    if (length > 0) {
      normals.row(v) /= length;
    } else {
      normals.row(v) << 0, 0, 1;
    }
  }
  return normals;
}

/// The barycentric coordinates of `p` in triangle (a, b, c), for a point on
/// (or very near) it; the centroid's for a degenerate triangle.
inline Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(denominator > 1e-300)) return Eigen::Vector3d::Constant(1.0 / 3);
  const double v = (d11 * d20 - d01 * d21) / denominator;
  const double w = (d00 * d21 - d01 * d20) / denominator;
  Eigen::Vector3d weights(1 - v - w, v, w);
  weights = weights.cwiseMax(0.0);
  return weights / weights.sum();
}

}  // namespace geodual::bench
