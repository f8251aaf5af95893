#pragma once
// The distance from a point to a segment or a triangle in space, shared by
// the quality statistics' nearest-primitive searches, the crease pins, and
// the smoothing's check that the remesh stays close to the surface; and the
// nearest point itself, for the texture baker.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>

namespace geodual {

/// Squared distance from p to segment ab: to the foot of the perpendicular,
/// clamped to the segment.
inline double squared_distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).squaredNorm();
}

/// Squared distance from p to triangle abc: the Voronoi region of its
/// vertices, edges and face that holds p decides which one is nearest
/// (Ericson, Real-Time Collision Detection, 5.1.5); a handful of dot products.
inline double squared_distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();  // vertex a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();  // edge ab
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {  // edge bc
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  }
  // Inside the face: the distance to its plane, |ap . n| / |n|, which keeps
  // its accuracy on needles (the barycentric point a + v ab + w ac does not).
  const Eigen::Vector3d normal = ab.cross(ac);
  const double normal2 = normal.squaredNorm();
  if (!(normal2 > 0)) {
    // So thin that the area underflows: the nearest point is on an edge.
    return std::min({squared_distance_to_segment(p, a, b), squared_distance_to_segment(p, b, c),
                     squared_distance_to_segment(p, c, a)});
  }
  const double height = ap.dot(normal);
  return height * height / normal2;
}

/// The point of triangle abc nearest to p, as barycentric coordinates
/// (weights of a, b, c): the same Voronoi regions as
/// squared_distance_to_triangle (Ericson, 5.1.5). A triangle of zero area
/// gives the nearest point of its longest edge.
inline Eigen::Vector3d nearest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // no area: the nearest point of the longest edge
    const double lab = ab.squaredNorm(), lac = ac.squaredNorm(), lbc = (c - b).squaredNorm();
    if (lab >= lac && lab >= lbc) {
      const double t = lab > 0 ? std::clamp(d1 / lab, 0.0, 1.0) : 0.0;
      return {1 - t, t, 0};
    }
    if (lac >= lbc) {
      const double t = std::clamp(d2 / lac, 0.0, 1.0);
      return {1 - t, 0, t};
    }
    const double t = std::clamp((p - b).dot(c - b) / lbc, 0.0, 1.0);
    return {0, 1 - t, t};
  }
  return {va / sum, vb / sum, vc / sum};
}

}  // namespace geodual
