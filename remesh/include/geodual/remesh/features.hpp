#pragma once
// The sharp features of a surface, for a remesh that keeps them: chains of
// sharp edges (mesh/sharp_edges.hpp) long at the remesh's scale, the
// boundary loops they run into, and the corners where chains meet, end or
// turn sharply. The remesher cuts the surface along the chains
// (feature_cut.hpp), so that no Voronoi cell straddles one, puts sites along
// them and welds the dual back together.
//
//   auto features = geodual::remesh::detect_features(surface, {.sharp_angle = 60, .scale = h / 2, .min_chain_length =
//   h}); features.chains[0].vertices  // a polyline of surface vertices, corner to corner

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/remesh_surface.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace geodual::remesh {

struct FeatureOptions {
  /// An edge is sharp where its faces' normals turn by at least this many
  /// degrees; 0: no sharp features.
  double sharp_angle = 60;
  /// A crease continues through edges whose faces turn by at least this many
  /// degrees (0: off; below sharp_angle), reached from the sharp edges along
  /// a path of them, where both sides are smooth at the scale: every face
  /// normal there within continuation_max_spread degrees of its side's mean.
  /// A machined crease whose angle fades keeps its weaker part; a scan's
  /// noisy sides keep none.
  double continuation_angle = 30;
  double continuation_max_spread = 10;
  /// The radius at which an edge's sharpness is judged (0: its two faces
  /// only). An edge stays sharp when the faces within this distance of its
  /// midpoint on either side, reached without crossing a sharp edge, are two
  /// separate regions whose mean normals still turn by sharp_angle: a lone
  /// noisy edge, which the faces round its ends join across, is dropped.
  double scale = 0;
  /// On a machined surface, the folds between its planar facets part the two
  /// sides in that test as sharp edges do: the edges that turn by
  /// continuation_angle or more (where that is on) between two facets (faces
  /// joined across edges that turn by under 0.05 degrees), each at least an
  /// equilateral triangle of side 2 scale in area. A surface is machined
  /// where half its area or more lies on facets of two faces or more, which
  /// a scan's does not. A CAD part's crease whose sides meet round its ends
  /// across a weaker fold stays sharp.
  bool facet_folds_part_sides = true;
  /// Chains of sharp edges (corner to corner) shorter than this are dropped,
  /// again and again until none is left (chains that met at a dropped one may
  /// join into a longer one): scan noise and details below the remesh's
  /// resolution.
  double min_chain_length = 0;
  /// A chain with a free end (on no other sharp edge, off the boundary)
  /// shorter than this is dropped too: a crease that fades out within a
  /// couple of spacings holds too few sites to be kept as one.
  double min_dangling_chain_length = 0;
  /// The chains round a region narrower than min_region_width are dropped
  /// too, and round one narrower than min_rough_region_width where it is
  /// rough: an edge inside it turns by smooth_region_angle degrees or more,
  /// and its folds (the edges that turn by a degree or more) are not two or
  /// more lines parallel within parallel_fold_angle degrees (0: never), as on
  /// a faceted prism's or cylinder's side. The region's width is twice its
  /// area over its border's length (the width of a strip, the radius of a
  /// disc), its faces joined across edges that are not sharp. A sliver boxed
  /// in by a scan's noisy creases has no room for a cell; a machined part's
  /// thin wall, smooth or faceted between its creases, keeps them.
  double min_region_width = 0;
  double min_rough_region_width = 0;
  double smooth_region_angle = 20;
  double parallel_fold_angle = 10;
  /// On a machined surface (as for facet_folds_part_sides) no region is
  /// rough: its folds are the part's shape, not a scan's noise, and an
  /// engraved stroke's or a thin rib's creases stay down to min_region_width.
  bool machined_regions_smooth = true;
  /// A chain that turns by at least this many degrees at a vertex has a corner there.
  double corner_angle = 60;
  /// Edges kept as features whatever their angle, length or neighbours
  /// (vertex pairs of the surface, such as a user's feature file): only an
  /// edge whose ends touch no other feature or boundary, which cannot be cut
  /// open, is left out. Pairs that are not edges with two faces are ignored.
  std::vector<std::array<Index, 2>> given_edges = {};
  /// Edges never kept, given or sharp (vertex pairs of the surface): such as
  /// those where a remesh that kept them could not be made.
  std::vector<std::array<Index, 2>> excluded_edges = {};
};

/// A polyline of mesh vertices between two corners (first and last, the same
/// one for a loop through a single corner), or a closed loop without a corner
/// (first == last, `closed`).
struct FeatureChain {
  std::vector<Index> vertices;
  bool closed = false;
  /// A stretch of a boundary loop (one side), not a crease between two faces.
  bool on_boundary = false;
  double length = 0;
};

struct FeatureSet {
  /// The sharp edges kept, as vertex pairs (smaller index first), sorted:
  /// where the remesher cuts the surface.
  std::vector<std::array<Index, 2>> sharp_edges;
  /// The sharp chains first, then the stretches of the boundary loops that
  /// sharp chains run into (loops without one keep their usual sampling).
  std::vector<FeatureChain> chains;
  std::vector<Index> corners;  ///< vertices, increasing
  std::int64_t sharp_chains = 0;
  double sharp_length = 0;  ///< of the sharp chains
  /// The edges whose own two faces turn by sharp_angle but that no chain
  /// keeps (too short or too weak at the scale to cut along), as chains of
  /// their own: where the remesher pins sites instead (crease_pins.hpp).
  std::vector<FeatureChain> short_creases;
  bool empty() const { return sharp_edges.empty(); }
  /// The index in sharp_edges of the edge between vertices a and b (either
  /// order), or -1 where it is not sharp.
  Index find_sharp_edge(Index a, Index b) const;
  bool is_sharp(Index a, Index b) const;
};

/// The options the remesh pipeline detects features with for `sites` sites
/// on `surface`: sharpness judged at half the remesh's spacing, chains at
/// least min_length spacings long (two, where one end is free), regions
/// between them at least a tenth of a spacing wide (half, where rough),
/// creases continued at continuation_angle between smooth sides.
FeatureOptions remesh_feature_options(const TriangleMesh& surface, std::int64_t sites, double sharp_angle,
                                      double min_length, double continuation_angle = 30);

/// The features of `surface`, a 2-manifold (such as cut_to_manifold's
/// mesh): sharp edges have exactly two faces. Deterministic.
FeatureSet detect_features(const TriangleMesh& surface, const FeatureOptions& options = {});
FeatureSet detect_features(const RemeshSurface& surface, const FeatureOptions& options = {});

/// The narrowest angle at a corner of `features` (detected on `surface`)
/// between two features that meet there: at each corner, the faces round it
/// fall into sectors bounded by its sharp edges and boundary edges, and a
/// sector's angle is the sum of its faces' angles at the corner. A remesh
/// that keeps the features, with a vertex at each corner, has a triangle
/// angle about this small or smaller there, so it bounds the smallest angle
/// any such remesh reaches. A corner where one chain ends inside the
/// surface has one sector all round, between no two features, and bounds
/// nothing. In degrees; 360 where no corner joins two features.
double narrowest_corner_angle(const TriangleMesh& surface, const FeatureSet& features);

}  // namespace geodual::remesh
