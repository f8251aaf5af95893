#pragma once
// Points on feature chains in terms the twins of a cut share (feature_cut.hpp):
// a site on a chain is a point of a surface edge at a lattice parameter, so
// that its copy on the edge's other face, at 1 - t, is exact.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/features.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <vector>

namespace geodual::remesh::detail {

/// Site barycentrics along an edge are multiples of 2^-32 (as sample_sites
/// makes them), kept 2^-20 off the edge's ends, so that a twin's
/// coordinates, 1 - t on the other face, are exact.
constexpr double kLattice = 0x1p32;
constexpr double kLatticeMargin = 0x1p-20;
double lattice_parameter(double t);

/// The point at t from a to b (t at b) on face f of the surface, whose
/// corners include a and b.
SurfacePoint point_on_edge(const TriangleMesh& surface, Index f, Index a, Index b, double t);

/// Where a site lies on the surface, in terms the twins share: a vertex
/// (lo == hi), a point of edge (lo, hi) at t towards hi, or inside a face
/// (lo == -1).
struct SiteKey {
  Index lo = -1, hi = -1;
  double t = 0;
  auto tie() const { return std::tie(lo, hi, t); }
  bool operator<(const SiteKey& other) const { return tie() < other.tie(); }
  bool operator==(const SiteKey& other) const { return tie() == other.tie(); }
};

/// The key of a site on cut.mesh (whose faces are the surface's, in order).
SiteKey site_key(const TriangleMesh& surface, const FeatureCut& cut, const SurfacePoint& site);

/// A chain's points by arc length.
struct ChainWalk {
  const TriangleMesh& surface;
  const FeatureChain& chain;
  std::vector<double> at;  ///< arc length at each vertex

  ChainWalk(const TriangleMesh& mesh, const FeatureChain& c);
  double length() const { return at.back(); }
  /// The edge (index i: vertices i, i + 1) at arc length s, and t along it.
  std::size_t locate(double s, double& t) const;
  /// The key of the point at arc length s (on the edge locate gives, at a lattice parameter).
  SiteKey key_at(double s) const;
  Eigen::Vector3d point(double s) const;
  /// Whether every vertex of the chain strictly between arc lengths from and
  /// to lies within `error` of the chord between the chain's points there.
  bool within(double from, double to, double error) const;
};

}  // namespace geodual::remesh::detail
