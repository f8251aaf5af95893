#pragma once
// The dual of a surface cut along its features (feature_cut.hpp) welded back
// along the chains: twins, the sites on either side of a chain at one
// position, become one vertex. Where a piece's dual leaves the boundary for a
// site inside (a crack), that site moves onto the boundary and the diagram
// is computed again (welded_dual_with_repair).
//
//   auto dual = dual_with_repair(cut.mesh, sites, diagram);
//   auto welded = weld_along_features(surface, features, cut, dual.mesh, dual.sites);

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/dual_repair.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/features.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace geodual::remesh {

struct WeldedDual {
  TriangleMesh mesh;                  ///< twins merged into one vertex
  std::vector<Index> vertex_of_site;  ///< per site, its vertex in `mesh`
  /// Sites inside a piece that reached its boundary, each with a point of
  /// that boundary: halfway between its two neighbours along the crack where
  /// both are on the boundary, else nearest the site. Moved there (and given
  /// twins), they close the cracks. The weld is a remesh only when there are none.
  std::vector<std::pair<std::size_t, SurfacePoint>> site_moves;
  /// Sites inside a piece whose point of the boundary is all but at another
  /// site (a thousandth of the mean edge): they would make a needle there,
  /// and that site serves the crack. Left out, like unused_sites.
  std::vector<std::size_t> doubling_sites;
  std::int64_t cracked_edges = 0;      ///< boundary edges of `mesh` off the surface's boundary
  std::vector<Index> crack_vertices;   ///< their ends, vertices of `mesh` (repeated where two meet)
  std::int64_t nonmanifold_edges = 0;  ///< edges of `mesh` with three or more triangles
  /// Pairs of triangles on the same three vertices in opposite orientations
  /// (a flap folded onto itself where cells reach the same sites from both
  /// sides of a chain), left out of `mesh`.
  std::int64_t folded_pairs = 0;
  /// Sites whose vertex is left in no triangle once the folds are out: the
  /// weld is a remesh only when there are none.
  std::vector<std::size_t> unused_sites;
};

/// Welds `dual` (vertex i is sites[i], on cut.mesh) along the chains. A
/// boundary edge of the welded mesh with an end off the surface's boundary is
/// a crack: some piece's dual left the boundary there for a site inside,
/// which site_moves moves onto the boundary.
WeldedDual weld_along_features(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                               const TriangleMesh& dual, std::span<const SurfacePoint> sites);

/// dual_with_repair on the prepared cut surface, then the weld; while it
/// cracks, the sites inside that reached a boundary move onto it, the twins
/// of sites on chains are added (repair sites among them) and everything is
/// recomputed. The result's mesh is the welded remesh
/// (vertex_of_site filled in). \throw DualRepairError as dual_with_repair, or
/// when the cracks persist after options.max_rounds (where the weld fails).
RepairedDual welded_dual_with_repair(const voronoi::GeodesicSurface& cut_surface, const TriangleMesh& surface,
                                     const FeatureSet& features, const FeatureCut& cut, std::vector<SurfacePoint> sites,
                                     voronoi::VoronoiDiagram diagram, const RepairOptions& options = {});

}  // namespace geodual::remesh
