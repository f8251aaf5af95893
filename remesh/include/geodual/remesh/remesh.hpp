#pragma once
// Remeshing from sites: the geodesic Voronoi diagram of the sites, its dual,
// and, where the dual falls short of the input's topology (closed-ball
// property), sites added where it fails and everything recomputed.
//
//   auto sites = geodual::remesh::sample_sites(mesh, 4000);
//   auto result = geodual::remesh::remesh_from_sites(mesh, sites);  // 10 Lloyd iterations first
//   result.dual.mesh  // one vertex per site, oriented like the input

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/remesh/lloyd.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <array>
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
  /// welded into one (feature_cut.hpp); empty: vertex i is sites[i].
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

struct RemeshOptions {
  /// Lloyd relaxation of the given sites first (iterations = 0: none). Its
  /// `voronoi` options are used for every diagram, repair rounds included.
  LloydOptions lloyd;
  /// Curvature-adapted sizing (> 0, with lloyd.density empty): Lloyd relaxes
  /// towards the weighted CVT of curvature_density with this strength, at the
  /// remesh's spacing. 0: the uniform geodesic CVT.
  double curvature_adaptation = 0;
  double curvature_max_ratio = CurvatureDensityOptions{}.max_ratio;
  /// Rounds of "add sites where the dual fails, recompute" (RepairOptions::max_rounds;
  /// up to twice as many while the repair converges).
  int max_repair_rounds = 10;
  /// The same for the remesh that keeps the sharp features, at most (never
  /// extended): where its dual needs more, the creases are finer than the
  /// spacing there, and the remesh pipeline leaves out those near the faults.
  int max_feature_repair_rounds = 4;
  /// ... and where its repair would add more than this fraction of the
  /// sites (twins included), as creases finer than the spacing make it, it
  /// gives up too (0: no bound). Half: a coarse CAD part's creases may need
  /// that many more than the count asked; each added site is reported.
  double max_feature_sites_added = 0.5;
  /// Where that remesh fails at places (DualRepairError::places), the remesh
  /// pipeline tries again without the creases within this many spacings of
  /// them (up to six times, each leaving out more where the last failed)
  /// before it drops them all (0: no such try).
  double feature_retry_radius = 2;
  /// That remesh closes its dual along the chains' sides
  /// (DualOptions::close_boundary_stretches): the stretch between two
  /// consecutive chain sites is an edge by construction where another cell
  /// reaches the chain between them, or a strip narrower than the spacing
  /// lies between two chains, instead of a repair that adds sites there.
  /// false: the repair alone.
  bool close_crease_stretches = true;
  /// Sharp features kept (features.hpp, feature_cut.hpp) by the remesh
  /// pipeline when it samples the sites: creases where the normals turn by at
  /// least this many degrees at half the remesh's spacing, in chains at least
  /// min_feature_length spacings long, are cut open, lined with sites and
  /// welded in the dual. 0: none. See docs/algorithms.md#sharp-features.
  /// (The pipeline rejects a sharp angle outside [0, 180], a negative length
  /// or round count with geodual::UsageError.)
  double sharp_angle = 60;
  double min_feature_length = 0.5;
  /// A sharp crease continues through edges whose normals turn by at least
  /// this many degrees, where both sides are smooth at the scale (a machined
  /// crease whose angle fades; a scan's noisy sides keep none). 0, or not
  /// below sharp_angle: off.
  double continuation_angle = 30;
  /// Creases at sharp_angle too short or too weak at the remesh's scale to
  /// cut along (a fillet's coarse edges, a crease that fades within a
  /// spacing) get sites pinned at their vertices, the sites round them as
  /// close, and edges flipped onto them (crease_pins.hpp): they add sites
  /// beyond the count, up to twice as many on parts with many such creases.
  bool pin_short_creases = false;
  /// Edges of the input (vertex index pairs) kept as features too, whatever
  /// their angle (a feature file's), sharp_angle 0 included.
  std::vector<std::array<Index, 2>> feature_edges = {};
  /// The remesh pipeline's last step: the corners of triangles with an
  /// angle below this many degrees move along the surface to where the
  /// smallest angle round them is largest (angle_smoothing.hpp); chain,
  /// corner, boundary and pinned vertices stay. 0, or no relaxation
  /// (lloyd.iterations 0): none, every vertex at its site. (The pipeline
  /// rejects a value outside [0, 60].)
  double smoothing_angle = 30;
  /// Before that, the vertices that answer for the surface's points farthest
  /// from the remesh (a crease or a scan's rim that the dual cuts off) move
  /// along the surface to where that distance is least, without lowering
  /// the smallest angle below 30 degrees or the remesh's own, nor the worst
  /// Q (smooth_largest_deviations in angle_smoothing.hpp); the same vertices
  /// stay. None without a relaxation.
  bool fit_deviations = true;
};

/// The Lloyd options remesh_from_sites relaxes `site_count` sites on
/// `surface` with: options.lloyd, with the curvature density filled in when
/// options.curvature_adaptation asks for it.
LloydOptions relaxation_options(const TriangleMesh& surface, std::int64_t site_count, const RemeshOptions& options);

struct RemeshResult {
  /// Input vertices cut apart first and faces of scraps left out (see
  /// manifold_cut.hpp); the remesh has the topology of the cut surface.
  std::int64_t vertices_split = 0;
  std::int64_t faces_disabled = 0;
  LloydResult relaxation;  ///< the relaxation stage (its diagram moved on to `dual`)
  RepairedDual dual;       ///< the dual-with-repair stage: the remesh
};

/// The three stages in a row: cut_to_manifold(input), lloyd_relax with
/// relaxation_options, dual_with_repair (both on one GeodesicSurface). \throw geodual::Error as
/// dual_with_repair, and for bad sites as compute_geodesic_field.
RemeshResult remesh_from_sites(const TriangleMesh& input, std::vector<SurfacePoint> sites,
                               const RemeshOptions& options = {});

}  // namespace geodual::remesh
