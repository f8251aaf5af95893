#pragma once
// The dual-with-repair stage of a remesh: the dual of the sites' geodesic
// Voronoi diagram (dual_delaunay.hpp) and, where it falls short of the
// surface's topology (the closed-ball property), sites added where it fails
// and the diagram recomputed, until the dual is a valid remesh.
//
//   auto relaxed = geodual::remesh::lloyd_relax(surface, sites);
//   auto remesh = geodual::remesh::dual_with_repair(surface, relaxed.sites, std::move(relaxed.diagram));

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace geodual::remesh {

/// Options of the dual-with-repair stage.
struct RepairOptions {
  /// Rounds of "add sites where the dual fails, recompute" before giving up
  /// with a geodual::Error ...
  int max_rounds = 10;
  /// ... unless each round past them asks for fewer sites than the one before
  /// (the repair converging): then up to as many rounds again.
  bool extend_while_converging = true;
  /// Gives up the same way once the rounds have added more than this many
  /// sites (0: no bound).
  std::int64_t max_sites_added = 0;
  voronoi::VoronoiOptions voronoi;  ///< for the repair rounds' diagrams
  DualOptions dual;                 ///< for every round's dual
};

/// The dual-with-repair stage's result: the remesh.
struct RepairedDual {
  TriangleMesh mesh;  ///< vertex i is sites[i] (unless vertex_of_site says otherwise)
  /// The given sites (less DualCheck::redundant_sites), then those added by repair.
  std::vector<SurfacePoint> sites;
  /// Per site, its vertex in `mesh` where twins along sharp chains were
  /// welded into one (welded_dual.hpp); empty: vertex i is sites[i].
  std::vector<Index> vertex_of_site;
  voronoi::VoronoiDiagram diagram;  ///< of the final sites
  DualCheck check;                  ///< of the final dual (valid)
  std::int64_t sites_added = 0;
  /// Given sites left out by repair: each cut a corner off its one
  /// neighbour's cell (DualCheck::redundant_sites).
  std::int64_t sites_left_out = 0;
  /// Why repair ran: the problems of the first dual that failed its checks
  /// (DualCheck::problems; welded_dual_with_repair adds those of each weld
  /// round); empty when the first dual was valid.
  std::vector<std::string> repair_problems;
  int repair_rounds = 0;
  /// welded_dual_with_repair's last resort: cracks of the weld that moving
  /// sites did not close, closed with triangles on their own vertices
  /// (crack_fill.hpp), and those triangles.
  std::int64_t cracks_closed = 0;
  std::int64_t crack_triangles = 0;
  double geodesic_seconds = 0;  ///< the repair rounds' diagrams
  double diagram_seconds = 0;
  double dual_seconds = 0;  ///< building and checking the duals
};

/// A dual that repair could not make a valid remesh: the geodual::Error of
/// dual_with_repair and welded_dual_with_repair, with where its faults lie
/// (points of the surface, a spacing apart; empty where the fault is not at
/// a place, such as a bound on the sites added).
class DualRepairError : public Error {
 public:
  DualRepairError(const std::string& message, std::vector<Eigen::Vector3d> places)
      : Error(message), places_(std::move(places)) {}
  const std::vector<Eigen::Vector3d>& places() const { return places_; }

 private:
  std::vector<Eigen::Vector3d> places_;
};

/// The dual of `diagram` (of `sites` on `surface`'s mesh, a 2-manifold such
/// as cut_to_manifold's mesh); where it fails the checks, sites are added
/// where it fails and the diagram recomputed on the prepared surface. \throw DualRepairError if it is still
/// not a valid remesh after options.max_rounds, naming what is wrong and where.
RepairedDual dual_with_repair(const voronoi::GeodesicSurface& surface, std::vector<SurfacePoint> sites,
                              voronoi::VoronoiDiagram diagram, const RepairOptions& options = {});

/// The same on a mesh, prepared for the repair rounds only if one is needed.
RepairedDual dual_with_repair(const TriangleMesh& surface, std::vector<SurfacePoint> sites,
                              voronoi::VoronoiDiagram diagram, const RepairOptions& options = {});

}  // namespace geodual::remesh
