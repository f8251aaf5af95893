#include "geodual/remesh/remesh_sites.hpp"

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/error_density.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace geodual::remesh {

RemeshSites sample_remesh_sites(const RemeshSurface& surface, std::int64_t count, const FeatureSampling& features,
                                const ShortCreasePins& pins, const SamplingOptions& options, GivenSiteShare share) {
  // The surface the sites go on: with features, their cut, prepared here once.
  std::optional<RemeshSurface> cut;
  const RemeshSurface& sites_surface = features.empty() ? surface : cut.emplace(features.cut.mesh);
  const auto pinned = static_cast<std::int64_t>(pins.pins.size());
  SampledSites sampled =
      features.empty()
          ? sample_sites_for_topology(surface, std::max<std::int64_t>(4, count - pinned), options)
          : sample_sites_around(sites_surface, std::max<std::int64_t>(0, count - features.sites.points - pinned),
                                features.sites.sites, options, share);
  RemeshSites result;
  result.sites = std::move(sampled.sites);
  result.first_pin = static_cast<std::int64_t>(result.sites.size());
  result.pins = pinned;
  result.sites.insert(result.sites.end(), pins.pins.begin(), pins.pins.end());
  result.sites_added_for_topology = sampled.sites_added_for_topology;
  result.topology_reason = std::move(sampled.topology_reason);
  result.boundary_loops = sampled.boundary_loops;
  if (features.density.empty()) return result;
  // The sites the density asks for beyond the count, where it is densest,
  // off the boundary (the chains' sides, lined with sites already).
  std::vector<double> excess(features.density.size());
  for (std::size_t v = 0; v < excess.size(); ++v) {
    excess[v] = sites_surface.topology().vertex_on_boundary[v] != 0 ? 0.0 : features.density[v] - 1;
  }
  const std::size_t before = result.sites.size();
  result.sites = add_sites_at_deviations(sites_surface.mesh(), result.sites, excess, features.density,
                                         features.density_spacing, features.sites_near_features);
  result.sites_added_near_features = static_cast<std::int64_t>(result.sites.size() - before);
  return result;
}

}  // namespace geodual::remesh
