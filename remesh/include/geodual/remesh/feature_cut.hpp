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
//   ... weld the dual back along the chains (welded_dual.hpp)

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/spacing_density.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh {

/// The surface a cut came from, as far as the weld checks a remesh against
/// it: its boundary, the faces of its sharp edges and its pieces. Kept with
/// the cut (a few bytes per face) so that no later stage builds the
/// surface's topology again.
struct SurfaceOutline {
  std::vector<std::array<Index, 2>> boundary_edges;    ///< vertex pairs (smaller first), sorted
  std::vector<Index> boundary_edge_loop;               ///< per boundary edge, its loop (MeshTopology's numbering)
  std::vector<std::uint8_t> vertex_on_boundary;        ///< per surface vertex
  std::vector<std::array<Index, 2>> sharp_edge_faces;  ///< per FeatureSet::sharp_edges, its two faces
  /// The pieces (MeshTopology's components): per face and per vertex (-1: none).
  std::vector<Index> face_component;
  std::vector<Index> vertex_component;
  std::vector<ComponentCounts> components;
  /// Whether vertices a and b (either order) are the ends of a boundary edge.
  bool is_boundary_edge(Index a, Index b) const;
};

struct FeatureCut {
  /// The surface's faces, in the same order, with vertices split along the
  /// sharp chains: one copy of a vertex per sector between chains.
  TriangleMesh mesh;
  std::vector<Index> original_vertex;  ///< per vertex of `mesh`, the surface vertex it copies
  SurfaceOutline surface;              ///< of the surface cut
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
  /// ... except on a chain where a chord would still leave it by more than
  /// twice max_chord_error: that chain is split at its own vertices where it
  /// bends (Douglas-Peucker), points about this far apart and never closer
  /// than 0.6 of it, so that its chords keep to twice the error (0: none).
  double tight_spacing = 0;
  /// Where a chain bends, split it at its own vertices (Douglas-Peucker);
  /// false: each stretch that bends evenly into the fewest parts down to
  /// tight_spacing that keep to twice max_chord_error, if any.
  bool split_at_bends = true;
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
  /// The chains split at their own vertices where they bend (options.split_at_bends).
  std::int64_t chains_split_at_bends = 0;
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

}  // namespace geodual::remesh
