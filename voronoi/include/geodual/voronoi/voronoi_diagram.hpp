#pragma once
// The exact geodesic Voronoi diagram of sites on a triangle mesh, extracted
// from the windows that window-VTP with Redundant Window Removal keeps
// (Qin, Yu & Zhang, CGF 2017, §3.3 and Fig. 4).
//
//   auto diagram = geodual::voronoi::compute_voronoi(mesh, sites);  // or a GeodesicSurface
//   diagram.vertices   // points equidistant to three (or more) sites
//   diagram.arcs       // the boundaries between cells, as polylines
//   diagram.cell_area  // per site
//
// Inside a triangle crossed by a cell boundary, the distance to each site is
// the lower envelope of cones sigma + |p - s| seen through the windows on the
// triangle's edges; a boundary piece is where two sites' envelopes are equal,
// a conic arc in the unfolded triangle. Its end points on mesh edges and the
// Voronoi vertices are solved to machine precision; between them, arcs are
// traced as polylines that stay within `boundary_tolerance` of the exact curve.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::voronoi {

struct VoronoiOptions {
  GeodesicOptions geodesic;
  /// Largest distance allowed between a traced boundary polyline and the exact
  /// bisector, as a fraction of the mesh's bounding-box diagonal.
  double boundary_tolerance = 1e-5;
  /// How many times a triangle may be split in four to resolve what happens
  /// inside it (several Voronoi vertices, a whole cell inside one triangle).
  /// Structure finer than 2^-max_refinement of the triangle's size is taken as
  /// one Voronoi vertex of higher degree; a triangle holding k sites may be
  /// split log4(k) times more (its cells are that much smaller).
  int max_refinement = 10;
};

/// A point equidistant to three or more sites.
struct VoronoiVertex {
  SurfacePoint location;  ///< a face point (barycentric; on an edge if a coordinate is 0)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double distance = 0;  ///< geodesic distance to each of its sites
  /// Its sites are vertex_sites[site_begin .. site_begin + degree), in
  /// counter-clockwise order as seen with the input's orientation; they are
  /// the corners of the dual triangle(s).
  Index site_begin = 0;
  int degree = 0;
};

/// A maximal piece of boundary between two cells. It runs from a Voronoi vertex
/// or a point of the mesh boundary to another, or is a closed loop. Walking
/// from its first point to its last, `left_site`'s cell lies on the left (the
/// input's orientation gives left and right).
struct VoronoiArc {
  Index left_site = -1;
  Index right_site = -1;
  Index start_vertex = -1;  ///< index into vertices; -1 where it starts on the mesh boundary or is closed
  Index end_vertex = -1;
  bool closed = false;
  double length = 0;
  /// Its polyline is points[point_begin .. point_end).
  Index point_begin = 0;
  Index point_end = 0;
};

/// Two cells that share boundary.
struct CellAdjacency {
  Index site_a = -1;  ///< site_a < site_b
  Index site_b = -1;
  double boundary_length = 0;
  int arc_count = 0;  ///< separate arcs between the two cells; 1 when the cells meet properly
};

struct VoronoiStats {
  double geodesic_seconds = 0;
  double extraction_seconds = 0;
  std::int64_t boundary_faces = 0;      ///< triangles crossed by a cell boundary
  std::int64_t refined_faces = 0;       ///< of those, how many needed splitting
  std::int64_t unresolved_regions = 0;  ///< pieces too fine for max_refinement, closed approximately
  double max_vertex_residual = 0;       ///< largest spread of a Voronoi vertex's site distances
  double max_area_mismatch = 0;         ///< largest gap between a triangle's area and its cells' parts
};

struct VoronoiDiagram {
  /// Distances, nearest sites and the windows the diagram came from.
  GeodesicField field;
  std::vector<VoronoiVertex> vertices;
  std::vector<Index> vertex_sites;
  std::vector<VoronoiArc> arcs;
  std::vector<Eigen::Vector3d> points;        ///< polyline points of all arcs
  std::vector<SurfacePoint> point_locations;  ///< the same points as face points
  /// Per site: the area of its cell. Cells of sites on components that no
  /// other site reaches are whole components.
  std::vector<double> cell_area;
  /// Per site: the CVT energy of its cell, the integral of d(x, site)^2 over it.
  std::vector<double> cell_energy;
  /// Per site: the integral over its cell of the log map at the site (the
  /// vector of length d(x, site) pointing, in the site's tangent plane, along
  /// the geodesic to x), as a 3D vector in the plane of the site's face (for
  /// a vertex site, normal to its area-weighted normal). Divided by the cell's
  /// area it is the step of one Lloyd iteration towards the geodesic centroid.
  /// See voronoi/src/cell_moments.hpp for what is exact.
  std::vector<Eigen::Vector3d> cell_log_moment;
  /// Sorted by (site_a, site_b).
  std::vector<CellAdjacency> adjacency;
  VoronoiStats stats;

  std::span<const Index> sites_of(const VoronoiVertex& vertex) const {
    return {vertex_sites.data() + vertex.site_begin, static_cast<std::size_t>(vertex.degree)};
  }
  std::span<const Eigen::Vector3d> polyline(const VoronoiArc& arc) const {
    return {points.data() + arc.point_begin, static_cast<std::size_t>(arc.point_end - arc.point_begin)};
  }
  /// The sites' mean spacing: the square root of the mean cell area.
  double mean_spacing() const {
    double area = 0;
    for (const double a : cell_area) area += a;
    return std::sqrt(area / static_cast<double>(std::max<std::size_t>(cell_area.size(), 1)));
  }
};

/// Computes the geodesic field of the sites (see compute_geodesic_field, whose
/// errors it shares) and extracts the diagram from it.
VoronoiDiagram compute_voronoi(const GeodesicSurface& surface, std::span<const SurfacePoint> sites,
                               const VoronoiOptions& options = {});

/// The same on a surface prepared for this call alone.
VoronoiDiagram compute_voronoi(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                               const VoronoiOptions& options = {});

/// Extracts the diagram from a field already computed for `mesh`.
VoronoiDiagram extract_voronoi(const TriangleMesh& mesh, GeodesicField field, const VoronoiOptions& options = {});

}  // namespace geodual::voronoi
