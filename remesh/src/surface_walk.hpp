#pragma once
// The exponential map on a triangle mesh: walking a straightest geodesic
// (Polthier & Schmies 1998) from a surface point in a tangent direction, face
// by face. Crossing an edge keeps the angle to the edge (the two faces are
// unfolded about it); the walk stops early at the mesh boundary.

#include "geodual/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "geodual/voronoi/surface_point.hpp"

#include <Eigen/Core>

namespace geodual::remesh::detail {

/// The point reached from `start` (a face point) after walking `length` along
/// `direction` (a 3D vector in the plane of start's face; its length is
/// ignored). Uses the propagation topology of `field` to cross edges.
SurfacePoint walk_on_surface(const TriangleMesh& mesh, const voronoi::GeodesicField& field, const SurfacePoint& start,
                             const Eigen::Vector3d& direction, double length);

}  // namespace geodual::remesh::detail
