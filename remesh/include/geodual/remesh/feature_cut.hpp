#pragma once
// A surface cut open along its sharp chains (features.hpp), so that the
// geodesic Voronoi diagram sees each chain as a boundary on both sides: no
// cell straddles a crease, and sites on a chain carry it into the dual.
// Every point of a chain becomes one site per side ("twins", at the same
// position on different faces); the dual of the cut surface is welded back
// along the chains by merging twins into one vertex.
//
//   auto features = detect_features(surface, {.min_chain_length = h});
//   auto cut = cut_along_features(surface, features);
//   auto sites = feature_sites(surface, features, cut, {.spacing = h});  // fixed sites, twins included
//   ... sample the rest on cut.mesh, relax, dual_with_repair on cut.mesh ...
//   auto welded = weld_along_features(surface, features, cut, dual.mesh, dual.sites);

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/dual_repair.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/spacing_density.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace geodual::remesh {

struct FeatureCut {
  /// The surface's faces, in the same order, with vertices split along the
  /// sharp chains: one copy of a vertex per sector between chains.
  TriangleMesh mesh;
  std::vector<Index> original_vertex;  ///< per vertex of `mesh`, the surface vertex it copies
};

/// \pre surface is a 2-manifold and features were detected on it.
FeatureCut cut_along_features(const TriangleMesh& surface, const FeatureSet& features);
FeatureCut cut_along_features(const RemeshSurface& surface, const FeatureSet& features);

struct FeatureSiteOptions {
  double spacing = 0;  ///< the remesh's edge length (> 0)
  /// Sites are added along a curved chain until its polyline stays within
  /// this distance of the chords between consecutive sites (a stretch split
  /// into 16 parts at most) ...
  double max_chord_error = 0;
  /// ... but no closer than this along it (0: no bound) ...
  double min_spacing = 0;
  /// ... except where a chord would still leave the chain by more than twice
  /// max_chord_error: there down to this spacing, if parts that far apart
  /// or farther keep to twice the error (0: min_spacing).
  double tight_spacing = 0;
};

struct FeatureSites {
  /// On cut.mesh: every corner at each of its copies (vertex sites), and the
  /// points along each chain on the faces of each side.
  std::vector<SurfacePoint> sites;
  std::int64_t points = 0;  ///< distinct points: vertices of the welded remesh
  /// Where the chord error made sites closer than options.min_spacing: each
  /// such point (stretch ends included) and its distance to its neighbours
  /// along the chain. The sites around them should be as close
  /// (chain_density), or the triangles between make slivers.
  std::vector<SpacedPoint> dense_points;
};

/// Sites along every chain, evenly by arc length between its corners (a
/// closed chain at least 3), at most options.spacing apart and closer where
/// the chord error asks for it.
FeatureSites feature_sites(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                           const FeatureSiteOptions& options);
FeatureSites feature_sites(const RemeshSurface& surface, const FeatureSet& features, const FeatureCut& cut,
                           const FeatureSiteOptions& options);

/// The twins `sites` (on cut.mesh) lack: for each site on a sharp edge, the
/// same point on the edge's other face, and for each site at a vertex the cut
/// split, a site at its other copies, where no site holds them.
std::vector<SurfacePoint> missing_twins(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                                        std::span<const SurfacePoint> sites);

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
