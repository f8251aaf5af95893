#include "geodual/remesh/remesh_sites.hpp"

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/remesh/error_density.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

/// The sites the pieces of the features' cut need beside their chain sites
/// so that each keeps the density of `count` sites over the whole surface:
/// sum over pieces of max(0, lambda A - g / 2), lambda = count / A_total, a
/// chain site standing for half a cell on its side (GivenSiteShare::half_cell).
/// Below `count` less the chain points, unless pieces too narrow for the half
/// cells of their chain sites (strips between creases lined on both sides)
/// take more than their area's share.
std::int64_t sites_for_the_density_asked(const RemeshSurface& cut, std::span<const SurfacePoint> chain_sites,
                                         std::int64_t count) {
  const MeshTopology& topology = cut.topology();
  const auto pieces = static_cast<std::size_t>(topology.num_components());
  std::vector<double> area(pieces, 0.0), half_cells(pieces, 0.0);
  double total_area = 0;
  for (Index f = 0; f < cut.mesh().num_faces(); ++f) {
    const Index piece = topology.face_component[static_cast<std::size_t>(f)];
    if (piece < 0) continue;
    const double a = face_area(cut.mesh(), f);
    area[static_cast<std::size_t>(piece)] += a;
    total_area += a;
  }
  for (const SurfacePoint& site : chain_sites) {
    const std::vector<Index>& piece_of =
        site.kind == SurfacePoint::Kind::face ? topology.face_component : topology.vertex_component;
    const Index piece = piece_of[static_cast<std::size_t>(site.element)];
    if (piece >= 0) half_cells[static_cast<std::size_t>(piece)] += 0.5;
  }
  const double density = static_cast<double>(count) / total_area;
  double needed = 0;
  for (std::size_t c = 0; c < pieces; ++c) needed += std::max(0.0, density * area[c] - half_cells[c]);
  return static_cast<std::int64_t>(std::ceil(needed));
}

}  // namespace

RemeshSites sample_remesh_sites(const RemeshSurface& surface, std::int64_t count, const FeatureSampling& features,
                                const ShortCreasePins& pins, const SamplingOptions& options, GivenSiteShare share) {
  // The surface the sites go on: with features, their cut, prepared here once.
  std::optional<RemeshSurface> cut;
  const RemeshSurface& sites_surface = features.empty() ? surface : cut.emplace(features.cut.mesh);
  const auto pinned = static_cast<std::int64_t>(pins.pins.size());
  RemeshSites result;
  std::int64_t beside_chains = std::max<std::int64_t>(0, count - features.sites.points - pinned);
  if (!features.empty()) {
    // Where chains crowd narrow pieces, the others would get fewer than their
    // share: the count grows so that they keep it, where that is more than a
    // tenth of the count (below, their density thins a little).
    constexpr double kMaxShortfall = 0.1;
    const std::int64_t needed = sites_for_the_density_asked(sites_surface, features.sites.sites, count);
    if (static_cast<double>(needed - beside_chains) > kMaxShortfall * static_cast<double>(count)) {
      const std::int64_t total = features.sites.points + pinned + needed;
      result.sites_added_for_crowding = total - count;
      result.crowding_reason = "site count " + std::to_string(count) + " raised to " + std::to_string(total) +
                               ": the " + std::to_string(features.sites.points) +
                               " sites on the creases crowd pieces too narrow for them, and the " +
                               std::to_string(beside_chains) + " left of the count would give the other pieces " +
                               std::to_string(needed - beside_chains) + " fewer than the spacing asks for";
      beside_chains = needed;
    }
  }
  SampledSites sampled = features.empty()
                             ? sample_sites_for_topology(surface, std::max<std::int64_t>(4, count - pinned), options)
                             : sample_sites_around(sites_surface, beside_chains, features.sites.sites, options, share);
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
