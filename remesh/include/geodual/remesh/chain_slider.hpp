#pragma once
// The relaxation's move for the sites on feature chains (LloydOptions::
// slide_boundary_sites): each point on a chain, with all its twins, slides
// along the chain by the Lloyd step of their cells taken along the chain's
// tangent (the constrained CVT's gradient, docs/algorithms.md#sharp-features),
// at most a third of the way to the next point on either side; corners stay.
//
//   ChainSlider slide(surface, features, cut);
//   lloyd_options.slide_boundary_sites = std::cref(slide);

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/features.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

namespace geodual::remesh {

class ChainSlider {
 public:
  /// Holds references to all three. \pre cut = cut_along_features(surface, features).
  ChainSlider(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut);
  ChainSlider(const RemeshSurface& surface, const FeatureSet& features, const FeatureCut& cut);

  /// `sites` on cut.mesh, each with its cell's mass and first moment (of the
  /// log map, or of x - site: moment / mass is Lloyd's step); returns them
  /// with the points on chains moved, on the lattice of feature_sites (twins
  /// stay exact copies). Deterministic.
  std::vector<SurfacePoint> operator()(std::span<const SurfacePoint> sites, std::span<const double> mass,
                                       std::span<const Eigen::Vector3d> moment) const;

 private:
  struct EdgeOnChain {
    std::array<Index, 2> edge;  ///< surface vertices, smaller first
    Index chain = 0;
    Index segment = 0;  ///< edge i of the chain joins its vertices i and i + 1
  };
  const TriangleMesh* surface_;
  const FeatureSet* features_;
  const FeatureCut* cut_;
  /// Per chain, per edge, its face on each side (-1: none, on a boundary
  /// stretch), the sides consistent along the chain.
  std::vector<std::vector<std::array<Index, 2>>> side_faces_;
  std::vector<EdgeOnChain> edges_;  ///< sorted by edge
};

}  // namespace geodual::remesh
