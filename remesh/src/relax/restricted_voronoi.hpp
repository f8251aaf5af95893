#pragma once
// The restricted Voronoi diagram (RVD) of sites on a surface: each site's
// Euclidean Voronoi cell in space (the points nearer to it than to any other
// site) intersected with the surface, keeping the piece reached from the site
// through faces (so that a cell does not jump across a thin part of the
// surface). It is the diagram geogram's CVT remeshing relaxes (Yan, Lévy et
// al., "Isotropic remeshing with fast and exact computation of restricted
// Voronoi diagram", SGP 2009). It needs no geodesics: a Delaunay
// triangulation of the sites gives each cell's neighbours, and each face the
// cell reaches is clipped by their bisector planes. Where the cells are
// small against the surface's curvature it is close to the geodesic diagram,
// which is why it serves as a cheap warm start for the geodesic relaxation.
// Where two sheets of the surface come closer than a cell's size (a thin
// part, a fold), the sites of one still cut the cells of the other, unlike
// geodesic cells: there the warm start is off, and the geodesic iterations
// after it make up for it.
//
// Integrals under a density rho (linear inside faces; none: 1) use the
// three-edge-midpoint rule on a fan of each clipped polygon: exact for the
// area and the first moment, and for the energy when rho is constant.

#include "common/surface_walk.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// The boundary between the cells of sites `site` and `other` (site <
/// other): straight segments, one per face it crosses, whose ends are
/// RestrictedCells::segment_ends[begin .. end) in pairs; with the density's
/// mean along it.
struct RestrictedBoundary {
  Index site = -1;
  Index other = -1;
  double density = 1;
  Index begin = 0;
  Index end = 0;
};

struct RestrictedCells {
  std::vector<double> area;                    ///< int dA
  std::vector<double> mass;                    ///< int rho dA
  std::vector<Eigen::Vector3d> moment;         ///< int rho (x - s) dA, a 3D vector
  std::vector<double> energy;                  ///< int rho |x - s|^2 dA
  std::vector<RestrictedBoundary> boundaries;  ///< sorted by site, then other
  std::vector<Eigen::Vector3d> segment_ends;
  double total_energy() const;
};

/// The surface as restricted_voronoi needs it, prepared once for the many
/// diagrams of a relaxation (prepare_restricted_surface); it refers to the
/// mesh, topology and density, which must outlive it.
struct RestrictedSurface {
  const TriangleMesh& mesh;
  const voronoi::SurfaceTopology& topology;  ///< how the cells cross edges
  std::span<const double> density;           ///< one value per mesh vertex, or empty for 1
  double area = 0;                           ///< of the faces the topology keeps
  /// Where a vertex site's cell starts: the faces round each vertex; empty
  /// when prepared for face sites only.
  VertexFans fans;
  /// Per face, the face across each side k (corners k and k + 1), -1 where
  /// none: the topology's two look-ups folded into one.
  std::vector<std::array<Index, 3>> across;
};

/// `vertex_sites`: whether the diagrams will have sites at vertices (the
/// fans round every vertex, 4 bytes per face corner, are kept only then).
RestrictedSurface prepare_restricted_surface(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                             std::span<const double> density, bool vertex_sites = true);

/// The cells of `sites` on the surface. A site that shares its position with
/// another gets an empty cell. With `only` (one flag per site), only the
/// cells of the sites flagged are integrated (each still cut by every
/// site); the others are left empty, and a boundary is kept only where its
/// lower-numbered site is flagged. Bit-identical for any number of threads.
/// \throw geodual::Error for a site at a vertex on a surface prepared
/// without vertex sites.
RestrictedCells restricted_voronoi(const RestrictedSurface& surface, std::span<const SurfacePoint> sites,
                                   std::span<const std::uint8_t> only = {});

}  // namespace geodual::remesh::detail
