#pragma once
// The sampling stage of a remesh: the sites it starts from, around the
// features' sites and pins (feature_sampling.hpp) where there are any, with
// the sites beside dense chain sites and pins that their density asks for.
//
//   auto creases = geodual::remesh::sample_features(surface, 2000);
//   auto sites = geodual::remesh::sample_remesh_sites(surface, 2000, creases);

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/feature_sampling.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace geodual::remesh {

struct RemeshSites {
  /// On features.sites_surface(surface): the features' sites, the sampled
  /// ones, the pins, then the sites beside dense chain sites and pins.
  std::vector<SurfacePoint> sites;
  std::int64_t first_pin = 0;  ///< sites[first_pin, first_pin + pins) are the pins, in their order
  std::int64_t pins = 0;
  std::int64_t sites_added_near_features = 0;  ///< the last ones (FeatureSampling::density asked for them)
  /// Sites beyond the count that the surface's topology needs, and why (SampledSites).
  std::int64_t sites_added_for_topology = 0;
  std::string topology_reason;
  /// Sites beyond the count so that the pieces of the features' cut keep the
  /// density asked where chain sites crowd narrow pieces, and why.
  std::int64_t sites_added_for_crowding = 0;
  std::string crowding_reason;
  std::int64_t boundary_loops = 0;  ///< of the surface sampled, with sites on them
};

/// `count` sites for a remesh of `surface` (a 2-manifold, such as
/// cut_to_manifold's mesh), the features' sites and the pins within the
/// count: sample_sites_around the features' sites on their cut as `share`
/// says (more where chain sites crowd pieces too narrow for
/// them: sites_added_for_crowding), or sample_sites_for_topology without
/// features; then the pins; then the sites_near_features that
/// features.density asks for, where it is densest, off the boundary, half a
/// local spacing apart (add_sites_at_deviations). Deterministic.
/// \throw as sample_sites.
RemeshSites sample_remesh_sites(const RemeshSurface& surface, std::int64_t count, const FeatureSampling& features,
                                const ShortCreasePins& pins = {}, const SamplingOptions& options = {},
                                GivenSiteShare share = GivenSiteShare::half_cell);

}  // namespace geodual::remesh
