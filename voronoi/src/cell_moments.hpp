#pragma once
// Integrals over Voronoi cells, gathered face by face as the diagram is
// extracted: the CVT energy  E_i = int_cell d(x, s_i)^2 dA  and the first
// moment of the log map  M_i = int_cell log_{s_i}(x) dA, from which Lloyd
// relaxation steps each site towards its geodesic centroid.
//
// What is exact and what is not:
//  - d(x) is the exact geodesic distance (the cell's own cone envelope in
//    faces crossed by a boundary; in faces inside one cell, the cone through
//    the three exact corner distances, exact when one window covers the face
//    straight from the site).
//  - Integration uses the three edge-midpoint rule on a fan of each cell
//    piece: exact for |x - a|^2 and x - a, i.e. wherever one straight cone
//    covers the piece.
//  - log_{s}(x) has length d(x) and, in the face, the direction of the
//    geodesic arriving at x (away from its unfolded source); that direction
//    is carried to the site's tangent plane by the rotation that takes the
//    face's normal to the site's normal, instead of parallel transport along
//    the geodesic (they differ by the curvature enclosed between the two).
//    Behind a pseudo-source the direction is that of the last straight piece.

#include "face_distance.hpp"

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace geodual::voronoi::detail {

/// The unit normal of each site's tangent plane: a face site's face normal,
/// a vertex site's area-weighted normal of the faces around it.
std::vector<Eigen::Vector3d> site_normals(const TriangleMesh& mesh, const GeodesicField& field);

/// The integrals over one piece of one cell.
struct CellIntegrals {
  double energy = 0;
  Eigen::Vector3d log_moment = Eigen::Vector3d::Zero();
};

/// Integrates cell pieces face by face. Holds the current face; one per thread.
class CellMoments {
 public:
  /// `site_normals` (from site_normals()) must outlive this.
  CellMoments(const TriangleMesh& mesh, const GeodesicField& field, std::span<const Eigen::Vector3d> site_normals);

  /// The face whose pieces are integrated next, laid out as `layout`.
  void set_face(Index face, const FaceLayout& layout);
  /// The integrals over `polygon` (counter-clockwise, in the face layout) for
  /// `site`, with distances from `envelope`; zero where no cone of it reaches.
  CellIntegrals polygon(Index site, std::span<const Eigen::Vector2d> polygon, const ConeEnvelope& envelope) const;
  /// The integrals over the whole current face for `site`, for a face inside
  /// one cell whose windows are gone: the cone through its corners' exact distances.
  CellIntegrals face_from_corners(Index site) const;

 private:
  template <class Distance>
  CellIntegrals integrate(Index site, std::span<const Eigen::Vector2d> polygon, const Distance& distance) const;

  const TriangleMesh& mesh_;
  const GeodesicField& field_;
  std::span<const Eigen::Vector3d> site_normal_;
  // The current face: layout, 3D frame of the layout's axes, unit normal.
  Index face_ = -1;
  FaceLayout layout_;
  Eigen::Vector3d axis_x_, axis_y_, normal_;
};

}  // namespace geodual::voronoi::detail
