#pragma once
// Exact multi-source geodesic distances on a triangle mesh, computed with
// window-VTP and Redundant Window Removal (Qin, Yu & Zhang, "Fast and
// Memory-Efficient Voronoi Diagram Construction on Triangle Meshes", CGF 2017;
// windows as in Surazhsky et al., "Fast Exact and Approximate Geodesics on
// Meshes", SIGGRAPH 2005).
//
//   auto field = geodual::voronoi::compute_geodesic_field(mesh, sites);
//   field.distance[v], field.nearest_site[v]     // exact, per vertex
//   geodual::voronoi::query(field, mesh, point)  // any point of a valid triangle
//
// Many fields on one mesh: prepare it once (geodesic_surface.hpp) and pass
// the GeodesicSurface instead of the mesh.
//
// The surface is the mesh's triangles with their intrinsic edge lengths. Faces
// with a repeated vertex index take no part; zero-area faces with distinct
// vertices are crossed. Edges with three or more faces are treated as boundary
// edges of each of their faces, so paths do not cross such an edge's interior
// but may pass through its end points (every boundary or non-manifold vertex is
// a pseudo-source, as every saddle vertex is).

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace geodual::voronoi {

struct GeodesicOptions {
  /// Free the windows that cannot matter for the Voronoi diagram as soon as
  /// their faces are inactive ([QYZ17] §3.2, Proposition 3.1). Off keeps every window, as MMP and
  /// [LCT11] do (with several site groups: every window no longer than the
  /// groups' distance bound); distances and labels are the same either way.
  bool remove_redundant_windows = true;
  /// Stop with a geodual::Error when the windows held at one time need more
  /// than this many bytes (a clear error instead of being killed for memory).
  /// With several site groups the limit holds for each group: as many groups
  /// as threads may hold their windows at once.
  std::size_t window_memory_limit_bytes = std::size_t{8} << 30;
  /// Hand freed heap memory back to the system between the computation's
  /// phases, where 32 MB or more of the heap are free (glibc's malloc_trim,
  /// which is process-wide): keeps the peak resident memory low on large
  /// meshes. false leaves the heap to the allocator, for callers that trim
  /// on their own schedule.
  bool release_memory_between_phases = true;
  /// The sites propagate in this many groups, each on its own (in parallel,
  /// on the threads of the caller's TBB arena), and the groups' results are
  /// merged; 0 (or less) picks one group per 256 sites, 2 to 16 (1 for a
  /// single site). The result depends on this number (never on the thread
  /// count) and is exact for any; 1 holds the fewest windows.
  int site_groups = 0;
  /// Called now and then with the fraction of faces reached, in [0, 1];
  /// returning false cancels the computation (geodual::Cancelled is thrown).
  /// With several site groups it is called from the worker threads, one call
  /// at a time.
  std::function<bool(double fraction)> progress;
};

struct GeodesicStats {
  std::int64_t windows_created = 0;  ///< windows that survived insertion on an edge
  std::int64_t windows_stored = 0;   ///< windows held at the end
  std::int64_t peak_windows = 0;     ///< most windows held at one time (several groups: the sum of theirs)
  /// Peak bytes of window storage (live windows, unused block capacity and
  /// freed blocks awaiting reuse); window_memory_limit_bytes is checked
  /// against the same figure, per group (several groups: the sum of theirs).
  std::int64_t peak_window_bytes = 0;
  std::int64_t vertices_popped = 0;  ///< vertices taken from the priority queue to expand
  std::int64_t pseudo_sources = 0;   ///< saddle / boundary vertices that emitted windows
  std::int64_t faces_inactive = 0;   ///< faces that reached the inactive region
  int site_groups = 1;               ///< groups the sites propagated in (GeodesicOptions::site_groups)
  double setup_seconds = 0;        ///< checking the sites; with a mesh rather than a GeodesicSurface, preparing it too
  double propagation_seconds = 0;  ///< window-VTP including RWR
  double total_seconds = 0;
};

/// One retained window, in the frame of its edge: the edge runs from its
/// end v0 at x = 0 to v1 at x = length along the x axis (edge_vertices); `edge_faces[e][0]` lies on the side y > 0. The
/// window covers [b0, b1] and its distance at x is sigma + |(x, 0) - source|.
struct EdgeWindow {
  double b0 = 0, b1 = 0;
  double source_x = 0, source_y = 0;  ///< unfolded (pseudo-)source
  double sigma = 0;                   ///< distance from the real site to the pseudo-source
  Index site = -1;
};

/// A point source that lies in a face or on one of its edges: a site, or a
/// pseudo-source seen through a zero-area neighbour. No window shows it to
/// points of that face, so queries there consider it directly.
struct FacePointSource {
  Index face = -1;
  Index site = -1;
  double sigma = 0;                                       ///< distance of the point itself
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  ///< in `face`
};

/// The result of compute_geodesic_field: plain data.
struct GeodesicField {
  /// Per mesh vertex: geodesic distance to the nearest site, +inf where no
  /// site can be reached (other components, unreferenced vertices).
  std::vector<double> distance;
  /// Per mesh vertex: index of the nearest site, -1 where unreachable.
  std::vector<Index> nearest_site;

  /// The sites, as given.
  std::vector<SurfacePoint> sites;

  /// The surface's topology (see SurfaceTopology), shared by every field
  /// computed on one GeodesicSurface and kept alive by each; the three views
  /// below are its tables.
  std::shared_ptr<const SurfaceTopology> topology;
  std::span<const std::array<Index, 2>> edge_faces;
  std::span<const double> edge_length;
  std::span<const std::array<Index, 3>> face_edges;
  /// The edge's end vertices (SurfaceTopology::edge_vertices); `mesh` is
  /// the one the field was computed on.
  std::array<Index, 2> edge_vertices(const TriangleMesh& mesh, Index edge) const {
    return topology->edge_vertices(mesh, edge);
  }

  /// Retained windows, grouped by edge and sorted along it: those of edge e are
  /// windows[window_begin[e] .. window_begin[e + 1]).
  std::vector<Index> window_begin;
  std::vector<EdgeWindow> windows;

  /// Sorted by face.
  std::vector<FacePointSource> face_point_sources;

  /// Per face: true where windows from different sites meet on the face's
  /// edges or vertices (the face is crossed by a Voronoi boundary: not
  /// redundant in the sense of [QYZ17] Definition 3.1). query() is exact inside these faces and at every vertex.
  std::vector<bool> valid_face;

  GeodesicStats stats;
};

/// Computes exact geodesic distances from every site. Throws geodual::Error for
/// bad sites (index out of range, negative or non-normalised barycentric
/// coordinates, a site on a face that takes no part or on an unreferenced
/// vertex, two sites at the same point) and when the window memory limit is
/// exceeded.
GeodesicField compute_geodesic_field(const GeodesicSurface& surface, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options = {});

/// The same on a surface prepared for this call alone.
GeodesicField compute_geodesic_field(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options = {});

struct PointDistance {
  double distance = 0;
  Index site = -1;
};

/// Distance and nearest site at any surface point: exact at vertices and inside
/// valid faces; elsewhere (faces whose windows RWR freed) an upper bound
/// through the face's vertices.
PointDistance query(const GeodesicField& field, const TriangleMesh& mesh, const SurfacePoint& point);

}  // namespace geodual::voronoi
