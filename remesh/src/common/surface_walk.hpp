#pragma once
// The exponential map on a triangle mesh: walking a straightest geodesic
// (Polthier & Schmies 1998) from a surface point in a tangent direction, face
// by face. Crossing an edge keeps the angle to the edge (the two faces are
// unfolded about it); the walk stops early at the mesh boundary.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// The point reached from `start` (a face point) after walking `length` along
/// `direction` (a 3D vector in the plane of start's face; its length is
/// ignored). Crosses edges as the surface's `topology` joins faces.
SurfacePoint walk_on_surface(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                             const SurfacePoint& start, const Eigen::Vector3d& direction, double length);

/// True for a face point on a boundary edge of the surface (a barycentric
/// coordinate 0, the side opposite it in one face only).
bool on_surface_boundary(const voronoi::SurfaceTopology& topology, const SurfacePoint& point);

/// Per vertex, the faces around it that take part in the propagation (see
/// `topology`): those of vertex v are around(v).
struct VertexFans {
  std::vector<Index> begin;
  std::vector<Index> face;
  std::span<const Index> around(Index v) const {
    return {face.data() + begin[v], static_cast<std::size_t>(begin[v + 1] - begin[v])};
  }
};
VertexFans vertex_fans(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology);
/// The same for every face of `mesh` (a remesh, whose faces all have three corners).
VertexFans vertex_fans(const TriangleMesh& mesh);

/// Whether any of `sites` is at a vertex (SurfacePoint::Kind::vertex): only
/// then are the fans round the vertices needed.
bool any_at_vertex(std::span<const SurfacePoint> sites);

/// Every site walked along the surface by its step (a 3D vector in the
/// site's tangent plane, as cvt_newton.hpp's frames describe it): a face site
/// from its face, a vertex site from the face around it whose corner angle
/// holds the step. A pair of sites landing on one point keeps its old places.
/// Bit-identical for any number of threads.
std::vector<SurfacePoint> move_sites(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                     std::span<const SurfacePoint> sites, std::span<const Eigen::Vector3d> steps);

}  // namespace geodual::remesh::detail
