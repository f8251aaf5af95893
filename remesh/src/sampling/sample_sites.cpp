// sample_sites: shares the sites among components and boundary loops, places
// the boundary sites, lets the strategy place the interior ones, and makes
// sure no two sites coincide and none sits on a vertex.

#include "geodual/remesh/sample_sites.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "sampling/boundary_sites.hpp"
#include "sampling/sampling_strategies.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>

namespace geodual::remesh {
namespace {

using detail::BoundaryLoop;
using detail::proportional_split;
using detail::Rng;
using detail::SamplingSurface;

// Random streams of one seed: per component and purpose, plus one for repairs.
enum Purpose : std::uint64_t { interior_random = 1, interior_poisson = 2, interior_fps = 3, repair = 4 };
std::uint64_t stream(Index component, Purpose purpose) {
  return (static_cast<std::uint64_t>(component) + 1) << 8 | purpose;
}

std::string plural(std::int64_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

/// The sites every component with area needs: 3 per boundary loop (so that
/// the dual keeps it) and at least 4 (a tetrahedron, the smallest closed
/// remesh).
struct TopologyMinimum {
  std::int64_t needed = 0;           ///< every component its minimum
  std::int64_t needed_by_loops = 0;  ///< 3 per loop
  std::int64_t components = 0;       ///< with area
  std::int64_t loops = 0;
};

/// A component holding given sites needs only 3 per loop of its own.
std::int64_t component_minimum(std::int64_t loops, bool has_given) {
  return has_given ? 3 * loops : std::max<std::int64_t>(4, 3 * loops);
}

TopologyMinimum topology_minimum(const SamplingSurface& surface, const std::vector<std::int64_t>& loops_per_component,
                                 const std::vector<std::int64_t>& given_per_component) {
  TopologyMinimum minimum;
  for (Index c = 0; c < surface.num_components; ++c) {
    if (!(surface.component_area[c] > 0)) continue;
    ++minimum.components;
    minimum.loops += loops_per_component[c];
    minimum.needed += component_minimum(loops_per_component[c], given_per_component[c] > 0);
    minimum.needed_by_loops += 3 * loops_per_component[c];
  }
  return minimum;
}

/// Sites per component (0 for components without area).
std::vector<std::int64_t> sites_per_component(const SamplingSurface& surface,
                                              const std::vector<std::int64_t>& loops_per_component,
                                              const std::vector<std::int64_t>& given_per_component, std::int64_t count,
                                              GivenSiteShare given_share) {
  std::vector<Index> with_area;
  for (Index c = 0; c < surface.num_components; ++c) {
    if (surface.component_area[c] > 0) with_area.push_back(c);
  }
  std::vector<double> areas, held;
  std::vector<std::int64_t> minimum, loop_minimum;
  const TopologyMinimum total = topology_minimum(surface, loops_per_component, given_per_component);
  const std::int64_t needed = total.needed, needed_by_loops = total.needed_by_loops, num_loops = total.loops;
  const double share = given_share == GivenSiteShare::half_cell ? 0.5 : 0.0;  // of a cell, per given site
  for (const Index c : with_area) {
    areas.push_back(surface.component_area[c]);
    held.push_back(share * static_cast<double>(given_per_component[c]));
    loop_minimum.push_back(3 * loops_per_component[c]);
    minimum.push_back(component_minimum(loops_per_component[c], given_per_component[c] > 0));
  }
  if (count < needed_by_loops) {
    const std::string also =
        needed > needed_by_loops ? " (" + std::to_string(needed) + " to give every component at least 4 as well)" : "";
    throw UsageError("site count " + std::to_string(count) + " is too small for the mesh's " +
                     plural(num_loops, "boundary loop") + ": at least " + std::to_string(needed_by_loops) +
                     " sites are needed, 3 per loop" + also + "; or turn sites on the boundary off");
  }
  std::vector<std::int64_t> parts;
  if (count >= needed) {
    parts = proportional_split(areas, minimum, count, held);
  } else {
    // Too few for every component: each loop keeps its 3 sites; the rest
    // tops components up to their minimum, largest area first.
    parts = loop_minimum;
    std::int64_t rest = count - needed_by_loops;
    std::vector<std::size_t> by_area(with_area.size());
    std::iota(by_area.begin(), by_area.end(), std::size_t{0});
    std::stable_sort(by_area.begin(), by_area.end(), [&](std::size_t a, std::size_t b) { return areas[a] > areas[b]; });
    for (const std::size_t i : by_area) {
      const std::int64_t add = std::min(rest, minimum[i] - parts[i]);
      parts[i] += add;
      rest -= add;
    }
  }
  std::vector<std::int64_t> sites(static_cast<std::size_t>(surface.num_components), 0);
  for (std::size_t i = 0; i < with_area.size(); ++i) sites[with_area[i]] = parts[i];
  return sites;
}

/// Sites per loop of one component with `sites` sites in all: about one per
/// hexagonal spacing of boundary, at least 3 per loop, at most sites - 1 in
/// all (but never below 3 per loop).
std::vector<std::int64_t> sites_per_loop(const std::vector<const BoundaryLoop*>& loops, double area,
                                         std::int64_t sites) {
  const double spacing = detail::hexagonal_spacing(area, sites);
  std::vector<std::int64_t> parts;
  std::vector<double> lengths;
  std::int64_t sum = 0;
  for (const BoundaryLoop* loop : loops) {
    const double ratio = std::min(loop->length / spacing, static_cast<double>(sites));
    parts.push_back(std::max<std::int64_t>(3, std::llround(ratio)));
    lengths.push_back(loop->length);
    sum += parts.back();
  }
  const auto num_loops = static_cast<std::int64_t>(loops.size());
  const std::int64_t cap = std::max(3 * num_loops, sites - 1);
  if (sum <= cap) return parts;
  return proportional_split(lengths, std::vector<std::int64_t>(loops.size(), 3), cap);
}

/// Moves sites that sit exactly on a corner of their face or on another
/// site's position (the later one moves): interior sites to a new random
/// point of their face, boundary sites a little along their edge.
/// Sites before `first_movable` (placed by the caller) stay where they are,
/// whatever they coincide with.
void separate_coincident_sites(const TriangleMesh& mesh, std::vector<SurfacePoint>& sites, std::size_t first_movable,
                               std::uint64_t seed) {
  Rng rng(seed, stream(-1, repair));
  std::vector<Eigen::Vector3d> positions(sites.size());
  std::vector<std::size_t> order(sites.size());
  std::vector<std::size_t> bad;
  constexpr int kRounds = 64;
  for (int round = 0; round < kRounds; ++round) {
    bad.clear();
    for (std::size_t i = 0; i < sites.size(); ++i) {
      positions[i] = detail::site_position(mesh, sites[i]);
      if (i < first_movable) continue;
      for (int k = 0; k < 3; ++k) {
        if (positions[i] == mesh.vertices.row(mesh.faces(sites[i].element, k)).transpose()) {
          bad.push_back(i);
          break;
        }
      }
    }
    std::iota(order.begin(), order.end(), std::size_t{0});
    auto less = [&](std::size_t a, std::size_t b) {
      const Eigen::Vector3d &p = positions[a], &q = positions[b];
      if (p.x() != q.x()) return p.x() < q.x();
      if (p.y() != q.y()) return p.y() < q.y();
      if (p.z() != q.z()) return p.z() < q.z();
      return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < order.size(); ++i) {
      // Of two at one position, the later moves (the caller's twins stay).
      if (positions[order[i]] == positions[order[i - 1]] && order[i] >= first_movable) bad.push_back(order[i]);
    }
    if (bad.empty()) return;
    std::sort(bad.begin(), bad.end());
    bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
    for (const std::size_t i : bad) {
      SurfacePoint& site = sites[i];
      int zero = -1;
      for (int k = 0; k < 3; ++k) {
        if (site.barycentric[k] == 0) zero = k;
      }
      if (zero < 0) {
        site = detail::random_point_in_face(site.element, rng);
      } else {
        const int from = (zero + 1) % 3;  // the edge runs from corner zero + 1 to zero + 2
        const double t = site.barycentric[(zero + 2) % 3] + 0x1p-16 * (rng.uniform() - 0.5);
        site = detail::point_on_face_edge(site.element, from, t);
      }
    }
  }
  throw Error("sample_sites: could not place " + std::to_string(sites.size()) +
              " sites at distinct positions off the vertices (the faces are too small for their coordinates)");
}

/// Per boundary loop of `surface`, whether one of `sites` lies on it: on one
/// of its edges (a barycentric 0) or at one of its vertices.
std::vector<std::uint8_t> loops_holding(const TriangleMesh& mesh, const SamplingSurface& surface,
                                        std::span<const SurfacePoint> sites) {
  std::vector<std::uint8_t> holds(surface.boundary_loops.size(), 0);
  if (sites.empty()) return holds;
  std::vector<Index> loop_of_edge(3 * static_cast<std::size_t>(mesh.num_faces()), -1);
  std::vector<Index> loop_of_vertex(static_cast<std::size_t>(mesh.vertices.rows()), -1);
  for (std::size_t l = 0; l < surface.boundary_loops.size(); ++l) {
    for (const detail::BoundaryEdge& edge : surface.boundary_loops[l].edges) {
      loop_of_edge[3 * static_cast<std::size_t>(edge.face) + static_cast<std::size_t>(edge.corner)] =
          static_cast<Index>(l);
      for (const int k : {edge.corner, (edge.corner + 1) % 3}) {
        loop_of_vertex[mesh.faces(edge.face, k)] = static_cast<Index>(l);
      }
    }
  }
  for (const SurfacePoint& site : sites) {
    Index loop = -1;
    if (site.kind == SurfacePoint::Kind::vertex) {
      loop = loop_of_vertex[site.element];
    } else {
      for (int k = 0; k < 3 && loop < 0; ++k) {
        if (site.barycentric[k] == 1) loop = loop_of_vertex[mesh.faces(site.element, k)];
        if (site.barycentric[k] == 0) loop = loop_of_edge[3 * static_cast<std::size_t>(site.element) + (k + 1) % 3];
      }
    }
    if (loop >= 0) holds[static_cast<std::size_t>(loop)] = 1;
  }
  return holds;
}

/// sample_sites, with the count raised to the topology's minimum first when
/// `raise_for_topology`.
/// `topology`: the mesh's, or null to build it.
SampledSites sample(const TriangleMesh& mesh, const MeshTopology* topology, std::int64_t count,
                    const SamplingOptions& options, bool raise_for_topology, std::span<const SurfacePoint> given = {},
                    GivenSiteShare given_share = GivenSiteShare::none) {
  if (count < 4 && given.empty()) {
    throw UsageError("site count " + std::to_string(count) + " is too small: at least 4 sites are needed");
  }
  if (count > std::numeric_limits<Index>::max()) {
    throw UsageError("site count " + std::to_string(count) + " is too large: at most " +
                     std::to_string(std::numeric_limits<Index>::max()) + " sites");
  }
  if (count < 0) throw UsageError("site count " + std::to_string(count) + " is negative");
  const SamplingSurface surface = topology ? detail::build_sampling_surface(mesh, *topology, options.sites_on_boundary)
                                           : detail::build_sampling_surface(mesh, options.sites_on_boundary);
  if (std::none_of(surface.component_area.begin(), surface.component_area.end(), [](double a) { return a > 0; })) {
    throw Error(
        "sample_sites: the mesh has no face with positive area and three distinct corners: nowhere to put sites");
  }

  // The given sites, per component; the loops holding one are theirs.
  std::vector<std::int64_t> given_per_component(static_cast<std::size_t>(surface.num_components), 0);
  const std::vector<std::uint8_t> loop_given = loops_holding(mesh, surface, given);
  std::vector<Index> vertex_component;
  if (!given.empty()) {
    vertex_component.assign(static_cast<std::size_t>(mesh.vertices.rows()), -1);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (surface.face_component[f] < 0) continue;
      for (int k = 0; k < 3; ++k) vertex_component[mesh.faces(f, k)] = surface.face_component[f];
    }
  }
  const auto given_component = [&](const SurfacePoint& site) {
    return site.kind == SurfacePoint::Kind::face ? surface.face_component[site.element]
                                                 : vertex_component[site.element];
  };
  for (const SurfacePoint& site : given) {
    const Index c = given_component(site);
    if (c >= 0) ++given_per_component[c];
  }
  std::vector<std::vector<const BoundaryLoop*>> loops(static_cast<std::size_t>(surface.num_components));
  std::vector<std::int64_t> loops_per_component(loops.size(), 0);
  for (std::size_t l = 0; l < surface.boundary_loops.size(); ++l) {
    if (loop_given[l]) continue;
    const BoundaryLoop& loop = surface.boundary_loops[l];
    loops[loop.component].push_back(&loop);
    ++loops_per_component[loop.component];
  }
  SampledSites sampled;
  sampled.boundary_loops = static_cast<std::int64_t>(surface.boundary_loops.size());
  const TopologyMinimum minimum = topology_minimum(surface, loops_per_component, given_per_component);
  if (raise_for_topology && count < minimum.needed) {
    sampled.sites_added_for_topology = minimum.needed - count;
    sampled.topology_reason = "site count " + std::to_string(count) + " raised to " + std::to_string(minimum.needed) +
                              ": the surface's " + plural(minimum.components, "piece") +
                              (minimum.loops > 0 ? " and " + plural(minimum.loops, "boundary loop") : "") +
                              " need at least 4 sites per piece" + (minimum.loops > 0 ? " and 3 per loop" : "") +
                              ", or the remesh would lose pieces" + (minimum.loops > 0 ? " or holes" : "");
    count = minimum.needed;
    if (count > std::numeric_limits<Index>::max()) {
      throw UsageError(sampled.topology_reason + "; that is more than the " +
                       std::to_string(std::numeric_limits<Index>::max()) + " sites allowed");
    }
  }
  const std::vector<std::int64_t> sites =
      sites_per_component(surface, loops_per_component, given_per_component, count, given_share);

  // Per component, its given sites first in its boundary sites.
  std::vector<std::vector<SurfacePoint>> given_in(static_cast<std::size_t>(surface.num_components));
  for (const SurfacePoint& site : given) {
    const Index c = given_component(site);
    if (c >= 0) given_in[c].push_back(site);
  }
  std::vector<SurfacePoint> boundary_sites, interior_sites;
  boundary_sites.reserve(static_cast<std::size_t>(count) + given.size());
  interior_sites.reserve(static_cast<std::size_t>(count));
  std::optional<detail::FarthestPointSampler> fps;
  if (options.strategy == SamplingStrategy::fps) fps.emplace(surface);
  for (Index c = 0; c < surface.num_components; ++c) {
    if (sites[c] == 0) continue;
    // The component's boundary sites: the given ones, then those placed on its other loops.
    std::vector<SurfacePoint>& component_boundary = given_in[c];
    const std::size_t first_placed = component_boundary.size();
    if (!loops[c].empty()) {
      const std::vector<std::int64_t> per_loop = sites_per_loop(loops[c], surface.component_area[c], sites[c]);
      const double spacing = detail::hexagonal_spacing(surface.component_area[c], sites[c]);
      detail::place_boundary_sites(mesh, loops[c], per_loop, spacing, component_boundary);
    }
    boundary_sites.insert(boundary_sites.end(), component_boundary.begin() + static_cast<std::ptrdiff_t>(first_placed),
                          component_boundary.end());
    detail::ComponentTask task;
    task.component = c;
    task.boundary_sites = component_boundary;
    task.total = sites[c] + given_per_component[c];
    task.interior = task.total - static_cast<std::int64_t>(task.boundary_sites.size());
    switch (options.strategy) {
      case SamplingStrategy::random: {
        Rng rng(options.seed, stream(c, interior_random));
        detail::sample_interior_random(surface, task, rng, interior_sites);
        break;
      }
      case SamplingStrategy::poisson: {
        Rng rng(options.seed, stream(c, interior_poisson));
        detail::sample_interior_poisson(surface, task, rng, interior_sites);
        break;
      }
      case SamplingStrategy::fps: {
        Rng rng(options.seed, stream(c, interior_fps));
        fps->sample(task, rng, interior_sites);
        break;
      }
    }
  }
  // The given sites first, as given; then the others, boundary ones first.
  std::vector<SurfacePoint> result(given.begin(), given.end());
  result.insert(result.end(), boundary_sites.begin(), boundary_sites.end());
  result.insert(result.end(), interior_sites.begin(), interior_sites.end());
  if (static_cast<std::int64_t>(result.size()) != count + static_cast<std::int64_t>(given.size())) {
    throw Error("sample_sites: internal error: placed " + std::to_string(result.size()) + " sites instead of " +
                std::to_string(count + static_cast<std::int64_t>(given.size())));
  }
  separate_coincident_sites(mesh, result, given.size(), options.seed);
  sampled.sites = std::move(result);
  return sampled;
}

}  // namespace

std::vector<SurfacePoint> sample_sites(const TriangleMesh& mesh, std::int64_t count, const SamplingOptions& options) {
  return sample(mesh, nullptr, count, options, false).sites;
}

SampledSites sample_sites_for_topology(const TriangleMesh& mesh, std::int64_t count, const SamplingOptions& options) {
  return sample(mesh, nullptr, count, options, true);
}

SampledSites sample_sites_for_topology(const RemeshSurface& surface, std::int64_t count,
                                       const SamplingOptions& options) {
  return sample(surface.mesh(), &surface.topology(), count, options, true);
}

SampledSites sample_sites_around(const TriangleMesh& mesh, std::int64_t count,
                                 std::span<const SurfacePoint> boundary_sites, const SamplingOptions& options,
                                 GivenSiteShare given_share) {
  return sample(mesh, nullptr, count, options, true, boundary_sites, given_share);
}

SampledSites sample_sites_around(const RemeshSurface& surface, std::int64_t count,
                                 std::span<const SurfacePoint> boundary_sites, const SamplingOptions& options,
                                 GivenSiteShare given_share) {
  return sample(surface.mesh(), &surface.topology(), count, options, true, boundary_sites, given_share);
}

SamplingStrategy parse_sampling_strategy(std::string_view name) {
  if (name == "random") return SamplingStrategy::random;
  if (name == "poisson") return SamplingStrategy::poisson;
  if (name == "fps") return SamplingStrategy::fps;
  throw UsageError("unknown sampling strategy '" + std::string(name) + "': expected random, poisson or fps");
}

std::string sampling_strategy_name(SamplingStrategy strategy) {
  switch (strategy) {
    case SamplingStrategy::random: return "random";
    case SamplingStrategy::poisson: return "poisson";
    case SamplingStrategy::fps: return "fps";
  }
  throw UsageError("unknown sampling strategy value " + std::to_string(static_cast<int>(strategy)));
}

void require_a_site_on_every_piece(const TriangleMesh& surface, std::span<const SurfacePoint> sites) {
  require_a_site_on_every_piece(RemeshSurface(surface), sites);
}

void require_a_site_on_every_piece(const RemeshSurface& prepared, std::span<const SurfacePoint> sites) {
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  std::vector<std::uint8_t> has_site(static_cast<std::size_t>(topology.num_components()), 0);
  for (const SurfacePoint& site : sites) {
    const bool face = site.kind == SurfacePoint::Kind::face;
    const std::vector<Index>& component_of = face ? topology.face_component : topology.vertex_component;
    if (site.element < 0 || static_cast<std::size_t>(site.element) >= component_of.size()) continue;
    const Index piece = component_of[static_cast<std::size_t>(site.element)];
    if (piece >= 0) has_site[static_cast<std::size_t>(piece)] = 1;
  }
  // Pieces without area can take no site: they are left out of every remesh.
  std::vector<std::uint8_t> has_area(has_site.size(), 0);
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Index piece = topology.face_component[static_cast<std::size_t>(f)];
    if (piece >= 0 && has_positive_area(surface, f)) has_area[static_cast<std::size_t>(piece)] = 1;
  }
  std::int64_t missing = 0;
  Index first = -1;
  for (Index piece = 0; piece < topology.num_components(); ++piece) {
    if (has_site[static_cast<std::size_t>(piece)] || !has_area[static_cast<std::size_t>(piece)]) continue;
    if (missing++ == 0) first = piece;
  }
  if (missing == 0) return;
  const auto vertex =
      static_cast<Index>(std::find(topology.vertex_component.begin(), topology.vertex_component.end(), first) -
                         topology.vertex_component.begin());
  throw Error(std::to_string(missing) + " of " + std::to_string(topology.num_components()) +
              " pieces of the surface hold no site, so the remesh would leave them out (the first: the piece with "
              "vertex " +
              std::to_string(vertex) + ", " +
              std::to_string(topology.components[static_cast<std::size_t>(first)].faces) +
              " faces); give sites on every piece, or let geodual sample them");
}

}  // namespace geodual::remesh
