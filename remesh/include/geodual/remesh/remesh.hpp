#pragma once
// Remeshing from sites: the geodesic Voronoi diagram of the sites, its dual,
// and, where the dual falls short of the input's topology (closed-ball
// property), sites added where it fails and everything recomputed.
//
//   auto sites = geodual::remesh::sample_sites(mesh, 4000);
//   auto result = geodual::remesh::remesh_from_sites(mesh, sites);  // 10 Lloyd iterations first
//   result.mesh  // one vertex per site, oriented like the input

#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/remesh/lloyd.hpp"
#include "geodual/triangle_mesh.hpp"
#include "geodual/voronoi/surface_point.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <cstdint>
#include <vector>

namespace geodual::remesh {

struct RemeshOptions {
  /// Lloyd relaxation of the given sites first (iterations = 0: none). Its
  /// `voronoi` options are used for every diagram.
  LloydOptions lloyd;
  /// Curvature-adapted sizing: when > 0 and lloyd.density is empty, Lloyd
  /// relaxes towards the weighted CVT of curvature_density(surface,
  /// {.strength = curvature_adaptation, .spacing = uniform_spacing(surface,
  /// sites), .max_ratio = curvature_max_ratio}), so that sites gather where
  /// the surface bends sharply at the scale of the remesh's edges (smaller
  /// chord error there, hence a smaller Hausdorff distance) with the same
  /// number of vertices. 0: the uniform geodesic CVT. A density given in
  /// lloyd.density is used as it is (one value per vertex of the surface
  /// remeshed, i.e. of the input cut to a manifold).
  double curvature_adaptation = 0;
  double curvature_max_ratio = CurvatureDensityOptions{}.max_ratio;
  /// Rounds of "add sites where the dual fails, recompute" before giving up
  /// with a geodual::Error.
  int max_repair_rounds = 10;
};

struct RemeshResult {
  TriangleMesh mesh;                ///< vertex i is sites[i]
  std::vector<SurfacePoint> sites;  ///< the given sites, then those added by repair
  voronoi::VoronoiDiagram diagram;  ///< of the final sites
  DualCheck check;                  ///< of the final dual (valid)
  std::int64_t sites_added = 0;
  /// Input vertices cut apart first (non-manifold edges and pinch vertices,
  /// see manifold_cut.hpp); the remesh has the topology of the cut surface.
  std::int64_t vertices_split = 0;
  /// Faces of scraps too small to remesh (see ManifoldCutOptions), left out.
  std::int64_t faces_disabled = 0;
  int repair_rounds = 0;
  std::vector<double> energy;   ///< CVT energy (density-weighted with curvature_adaptation) before and after each Lloyd iteration
  int lloyd_iterations = 0;
  int warm_start_iterations = 0;  ///< Lloyd's warm-start steps on the restricted Voronoi diagram
  int lloyd_diagrams = 0;       ///< diagrams Lloyd computed: one per iteration, one per rejected step, plus the first (and the warm start's)
  double lloyd_seconds = 0;     ///< Lloyd's centroid steps (its diagrams count below)
  double warm_start_seconds = 0;  ///< Lloyd's warm start (its one geodesic diagram counts below)
  double geodesic_seconds = 0;  ///< every diagram: Lloyd iterations and repair rounds
  double diagram_seconds = 0;
  double dual_seconds = 0;
};

/// The surface remeshed is `input` cut to a manifold (cut_to_manifold); the
/// topology checks compare with that. Throws geodual::Error if the dual is
/// still not a valid remesh after
/// options.max_repair_rounds, naming what is wrong; bad sites as
/// compute_geodesic_field does.
RemeshResult remesh_from_sites(const TriangleMesh& input, std::vector<SurfacePoint> sites,
                               const RemeshOptions& options = {});

}  // namespace geodual::remesh
