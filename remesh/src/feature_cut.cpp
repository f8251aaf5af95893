#include "geodual/remesh/feature_cut.hpp"

#include "crack_fill.hpp"

#include "chain_points.hpp"
#include "fault_places.hpp"

#include "geodual/mesh/detail/point_grid.hpp"
#include "geodual/mesh/detail/point_text.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"
#include "geodual/mesh/vertex_copies.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <tuple>

namespace geodual::remesh {
namespace {

using detail::ChainWalk;
using detail::point_on_edge;
using detail::site_key;
using detail::SiteKey;

bool is_sharp(const FeatureSet& features, Index a, Index b) {
  const std::array<Index, 2> key = {std::min(a, b), std::max(a, b)};
  return std::binary_search(features.sharp_edges.begin(), features.sharp_edges.end(), key);
}

/// Appends to `out` the point `key` on each face of its edge (at each copy
/// of its vertex), unless `held` (sorted) has it already; then holds it.
void add_twins(const TriangleMesh& surface, const MeshTopology& topology, const VertexCopies& copies,
               const SiteKey& key, std::vector<SiteKey>& held, std::vector<SurfacePoint>& out) {
  if (key.lo < 0) return;
  if (std::binary_search(held.begin(), held.end(), key)) return;
  if (key.lo == key.hi) {
    for (const Index copy : copies.of(key.lo)) out.push_back(SurfacePoint::at_vertex(copy));
  } else {
    const Index edge = topology.find_edge(key.lo, key.hi);
    if (edge < 0) return;
    for (const Index f : topology.edge_faces(edge)) out.push_back(point_on_edge(surface, f, key.lo, key.hi, key.t));
  }
  held.insert(std::upper_bound(held.begin(), held.end(), key), key);
}

/// Per surface vertex, its copies in cut.mesh that faces use.
VertexCopies used_vertex_copies(const FeatureCut& cut, Index num_vertices) {
  std::vector<std::uint8_t> used(cut.original_vertex.size(), 0);
  for (Index f = 0; f < cut.mesh.num_faces(); ++f) {
    if (has_repeated_corner(cut.mesh, f)) continue;
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(cut.mesh.faces(f, k))] = 1;
  }
  return group_vertex_copies(cut.original_vertex, num_vertices, used);
}

}  // namespace

FeatureCut cut_along_features(const TriangleMesh& surface, const FeatureSet& features) {
  return cut_along_features(RemeshSurface(surface), features);
}

FeatureCut cut_along_features(const RemeshSurface& prepared, const FeatureSet& features) {
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  const Index num_faces = surface.num_faces(), num_vertices = static_cast<Index>(surface.vertices.rows());
  // Corners at one vertex stay together across every edge with two faces
  // that is not sharp: one class per sector between the chains.
  UnionFind sector(static_cast<std::size_t>(3 * num_faces));
  const auto corner_at = [&](Index f, Index v) {
    for (int k = 0; k < 3; ++k) {
      if (surface.faces(f, k) == v) return 3 * f + k;
    }
    return Index{-1};
  };
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    if (faces.size() != 2 || is_sharp(features, a, b)) continue;
    for (const Index v : {a, b}) sector.unite(corner_at(faces[0], v), corner_at(faces[1], v));
  }
  FeatureCut cut;
  cut.mesh.faces = surface.faces;
  std::vector<Index> vertex_of_sector(static_cast<std::size_t>(3 * num_faces), -1);
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(num_vertices), 0);
  std::vector<Index> extra;
  for (Index f = 0; f < num_faces; ++f) {
    if (has_repeated_corner(surface, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index root = sector.find(3 * f + k), v = surface.faces(f, k);
      if (vertex_of_sector[root] < 0) {
        if (!taken[v]) {
          taken[v] = 1;
          vertex_of_sector[root] = v;
        } else {
          vertex_of_sector[root] = num_vertices + static_cast<Index>(extra.size());
          extra.push_back(v);
        }
      }
      cut.mesh.faces(f, k) = vertex_of_sector[root];
    }
  }
  cut.mesh.vertices.resize(num_vertices + static_cast<Index>(extra.size()), 3);
  cut.mesh.vertices.topRows(num_vertices) = surface.vertices;
  cut.original_vertex.resize(static_cast<std::size_t>(num_vertices) + extra.size());
  std::iota(cut.original_vertex.begin(), cut.original_vertex.begin() + num_vertices, Index{0});
  for (std::size_t i = 0; i < extra.size(); ++i) {
    cut.mesh.vertices.row(num_vertices + static_cast<Index>(i)) = surface.vertices.row(extra[i]);
    cut.original_vertex[static_cast<std::size_t>(num_vertices) + i] = extra[i];
  }
  return cut;
}

FeatureSites feature_sites(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                           const FeatureSiteOptions& options) {
  return feature_sites(RemeshSurface(surface), features, cut, options);
}

FeatureSites feature_sites(const RemeshSurface& prepared, const FeatureSet& features, const FeatureCut& cut,
                           const FeatureSiteOptions& options) {
  if (!(options.spacing > 0)) throw UsageError("feature_sites: the spacing must be positive");
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  const VertexCopies copies = used_vertex_copies(cut, static_cast<Index>(surface.vertices.rows()));
  FeatureSites result;
  std::vector<SiteKey> held;
  const auto add = [&](const SiteKey& key) {
    const std::size_t before = held.size();
    add_twins(surface, topology, copies, key, held, result.sites);
    if (held.size() > before) ++result.points;
  };
  for (const Index v : features.corners) add({v, v, 0});
  // Each chain's own spacing: even, about options.spacing.
  std::vector<ChainWalk> walks;
  std::vector<std::int64_t> segments;
  for (const FeatureChain& chain : features.chains) {
    const ChainWalk& walk = walks.emplace_back(surface, chain);
    segments.push_back(std::max<std::int64_t>(chain.closed ? 3 : 1, std::llround(walk.length() / options.spacing)));
  }
  // Round a corner, the first site of every chain at one distance d: the
  // smallest of their spacings and half their lengths. In a wedge of angle
  // theta between two chains, the corner's cell meets the cells of the first
  // sites at distances d1 <= d2 at a Voronoi vertex only if d1 >= d2 cos(theta)
  // (the bisectors must cross inside the wedge); equal distances meet in any
  // wedge. Half the length leaves room for the chain's other end.
  std::map<Index, double> corner_distance;
  for (std::size_t c = 0; c < walks.size(); ++c) {
    const FeatureChain& chain = features.chains[c];
    if (chain.closed) continue;
    const double own = std::min(walks[c].length() / static_cast<double>(segments[c]), 0.5 * walks[c].length());
    for (const Index end : {chain.vertices.front(), chain.vertices.back()}) {
      const auto [it, inserted] = corner_distance.try_emplace(end, own);
      if (!inserted) it->second = std::min(it->second, own);
    }
  }
  // A stretch whose chord leaves the chain by more than the chord error is
  // split evenly into the fewest parts that keep to it (at most 16, no
  // shorter than min_spacing): the chain gets denser where it bends, there
  // only. Where the shortest parts still leave it by more than twice the
  // error, parts down to tight_spacing, if some number of them keeps to
  // twice the error.
  struct Stretch {
    double from, to;
    int parts = 1;
    bool tight = false;  ///< its parts are shorter than min_spacing
  };
  const auto most_parts = [](double length, double spacing) {
    return spacing > 0 ? static_cast<int>(std::min(16.0, std::floor(length / spacing))) : 16;
  };
  const auto fits = [](const ChainWalk& walk, double from, double to, int parts, double error) {
    for (int k = 0; k < parts; ++k) {
      if (!walk.within(from + (to - from) * k / parts, from + (to - from) * (k + 1) / parts, error)) return false;
    }
    return true;
  };
  const auto split = [&](const ChainWalk& walk, double from, double to) {
    Stretch stretch{from, to};
    if (!(options.max_chord_error > 0) || walk.within(from, to, options.max_chord_error)) return stretch;
    const int most = most_parts(to - from, options.min_spacing);
    const int most_tight =
        std::max(most, most_parts(to - from, options.tight_spacing > 0 ? options.tight_spacing : options.min_spacing));
    int parts = std::min(most, 2);
    while (parts < most && !fits(walk, from, to, parts, options.max_chord_error)) ++parts;
    parts = std::max(parts, 1);
    if (!fits(walk, from, to, parts, 2 * options.max_chord_error)) {
      // Closer parts only where some number of them keeps to twice the error
      // (a smooth bend): a chain that wiggles at the input's scale (a scan's
      // noise) would not keep to it at any spacing the tight one allows.
      int tight = parts + 1;
      while (tight <= most_tight && !fits(walk, from, to, tight, 2 * options.max_chord_error)) ++tight;
      if (tight <= most_tight) parts = tight;
    }
    stretch.parts = parts;
    stretch.tight = parts > most;
    return stretch;
  };
  // Chain ends per vertex: a corner where one chain ends alone has no wedge
  // to keep the first sites' distances equal in.
  std::map<Index, int> ends_at;
  for (const FeatureChain& chain : features.chains) {
    if (chain.closed) continue;
    ++ends_at[chain.vertices.front()];
    ++ends_at[chain.vertices.back()];
  }
  std::vector<double> at;
  std::vector<Stretch> stretches;
  for (std::size_t c = 0; c < walks.size(); ++c) {
    const FeatureChain& chain = features.chains[c];
    const double length = walks[c].length(), own = length / static_cast<double>(segments[c]);
    if (!(length > 0)) continue;
    // The stretch ends: evenly round a closed chain; on an open one, from the
    // corners' first sites, evenly about `own` apart in between.
    std::vector<double> ends;
    if (chain.closed) {
      for (std::int64_t k = 0; k <= segments[c]; ++k) ends.push_back(own * static_cast<double>(k));
    } else {
      const double first = corner_distance.at(chain.vertices.front());
      const double last = length - corner_distance.at(chain.vertices.back());
      ends.push_back(0);
      if (last - first < 0.25 * std::min(first, length - last)) {
        ends.push_back(0.5 * (first + last));
      } else {
        const auto gaps = std::max<std::int64_t>(1, std::llround((last - first) / own));
        for (std::int64_t k = 0; k <= gaps; ++k) {
          ends.push_back(first + (last - first) * static_cast<double>(k) / static_cast<double>(gaps));
        }
      }
      ends.push_back(length);
    }
    stretches.clear();
    for (std::size_t k = 0; k + 1 < ends.size(); ++k) stretches.push_back(split(walks[c], ends[k], ends[k + 1]));
    // At a corner where this chain ends alone, the stretch from it takes the
    // spacing of a tight stretch after it: the sites round the corner are as
    // close as the chain's there.
    if (!chain.closed && stretches.size() >= 2) {
      for (const bool front : {true, false}) {
        Stretch& end = front ? stretches.front() : stretches.back();
        const Stretch& next = front ? stretches[1] : stretches[stretches.size() - 2];
        if (end.tight || !next.tight || ends_at[front ? chain.vertices.front() : chain.vertices.back()] > 1) continue;
        const double spacing = (next.to - next.from) / next.parts;
        const auto parts = static_cast<int>(std::llround((end.to - end.from) / spacing));
        if (parts > end.parts) end.parts = parts, end.tight = true;
      }
    }
    at.clear();
    for (std::size_t k = 0; k < stretches.size(); ++k) {
      const auto [from, to, parts, tight] = stretches[k];
      if (k > 0) at.push_back(from);
      for (int j = 1; j < parts; ++j) at.push_back(from + (to - from) * j / parts);
      if (tight) {  // the stretch's points, ends included
        for (int j = 0; j <= parts; ++j) {
          result.dense_points.push_back({walks[c].point(from + (to - from) * j / parts), (to - from) / parts});
        }
      }
    }
    if (chain.closed) at.push_back(0);  // the closing end is a site too (the open ends are corners)
    for (const double s : at) add(walks[c].key_at(s));
  }
  return result;
}

std::vector<SurfacePoint> missing_twins(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                                        std::span<const SurfacePoint> sites) {
  std::vector<SurfacePoint> missing;
  if (features.empty()) return missing;
  const MeshTopology topology = build_mesh_topology(surface);
  // Sites at a vertex the cut split: every copy needs one.
  const VertexCopies copies = used_vertex_copies(cut, static_cast<Index>(surface.vertices.rows()));
  std::vector<Index> at_vertex_held;    // cut vertices holding a site
  std::vector<Index> at_vertex_wanted;  // surface vertices with more than one copy holding one
  for (const SurfacePoint& site : sites) {
    const SiteKey key = site_key(surface, cut, site);
    if (key.lo < 0 || key.lo != key.hi || copies.of(key.lo).size() < 2) continue;
    at_vertex_wanted.push_back(key.lo);
    if (site.kind == SurfacePoint::Kind::vertex) {
      at_vertex_held.push_back(site.element);
    } else {
      for (int k = 0; k < 3; ++k) {
        if (site.barycentric[k] == 1) at_vertex_held.push_back(cut.mesh.faces(site.element, k));
      }
    }
  }
  std::sort(at_vertex_held.begin(), at_vertex_held.end());
  std::sort(at_vertex_wanted.begin(), at_vertex_wanted.end());
  at_vertex_wanted.erase(std::unique(at_vertex_wanted.begin(), at_vertex_wanted.end()), at_vertex_wanted.end());
  for (const Index v : at_vertex_wanted) {
    for (const Index copy : copies.of(v)) {
      if (!std::binary_search(at_vertex_held.begin(), at_vertex_held.end(), copy)) {
        missing.push_back(SurfacePoint::at_vertex(copy));
      }
    }
  }
  // Per sharp-edge point held: the faces holding it.
  std::vector<std::pair<SiteKey, Index>> held;
  for (const SurfacePoint& site : sites) {
    if (site.kind != SurfacePoint::Kind::face) continue;
    const SiteKey key = site_key(surface, cut, site);
    if (key.lo >= 0 && key.lo != key.hi && is_sharp(features, key.lo, key.hi)) held.push_back({key, site.element});
  }
  std::sort(held.begin(), held.end(), [](const auto& x, const auto& y) {
    return x.first < y.first || (x.first == y.first && x.second < y.second);
  });
  for (std::size_t i = 0; i < held.size();) {
    std::size_t j = i;
    while (j < held.size() && held[j].first == held[i].first) ++j;
    const SiteKey& key = held[i].first;
    for (const Index f : topology.edge_faces(topology.find_edge(key.lo, key.hi))) {
      const bool has =
          std::any_of(held.begin() + static_cast<std::ptrdiff_t>(i), held.begin() + static_cast<std::ptrdiff_t>(j),
                      [&](const auto& h) { return h.second == f; });
      if (!has) missing.push_back(point_on_edge(surface, f, key.lo, key.hi, key.t));
    }
    i = j;
  }
  return missing;
}

namespace {

/// Removes the pairs of faces on the same three vertices with opposite
/// orientations, returning how many: where the cells round the end of a
/// chain or a narrow wedge reach the same three sites from both sides, the
/// weld makes a triangle and its mirror image, a flap of no area folded onto
/// itself. Without both, the edges they shared keep the triangles of the
/// surface on either side.
std::int64_t remove_folded_pairs(TriangleMesh& mesh) {
  const Index num_faces = mesh.num_faces();
  // Per face: its corners sorted and whether sorting them took an odd permutation.
  std::vector<std::pair<std::array<Index, 3>, bool>> key(static_cast<std::size_t>(num_faces));
  for (Index f = 0; f < num_faces; ++f) {
    std::array<Index, 3> c{mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
    bool odd = false;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2 - i; ++j) {
        if (c[j] > c[j + 1]) {
          std::swap(c[j], c[j + 1]);
          odd = !odd;
        }
      }
    }
    key[static_cast<std::size_t>(f)] = {c, odd};
  }
  std::vector<Index> order(static_cast<std::size_t>(num_faces));
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(),
            [&](Index a, Index b) { return key[a] < key[b] || (key[a] == key[b] && a < b); });
  std::vector<std::uint8_t> removed(static_cast<std::size_t>(num_faces), 0);
  std::int64_t pairs = 0;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j < order.size() && key[order[j]].first == key[order[i]].first) ++j;
    // Within one vertex triple: the even ones first, then the odd ones; pair them off in order.
    std::size_t even = i, odd = i;
    while (odd < j && !key[order[odd]].second) ++odd;
    for (std::size_t k = odd; even < odd && k < j; ++even, ++k) {
      removed[order[even]] = removed[order[k]] = 1;
      ++pairs;
    }
    i = j;
  }
  if (pairs == 0) return 0;
  Index kept = 0;
  for (Index f = 0; f < num_faces; ++f) {
    if (!removed[f]) mesh.faces.row(kept++) = mesh.faces.row(f);
  }
  mesh.faces.conservativeResize(kept, 3);
  return pairs;
}

}  // namespace

WeldedDual weld_along_features(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                               const TriangleMesh& dual, std::span<const SurfacePoint> sites) {
  WeldedDual welded;
  const std::size_t n = sites.size();
  std::vector<SiteKey> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = site_key(surface, cut, sites[i]);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  // Vertices numbered in the order of their first site.
  std::vector<std::size_t> first_of(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    first_of[i] = (k > 0 && keys[i].lo >= 0 && keys[i] == keys[order[k - 1]]) ? first_of[order[k - 1]] : i;
  }
  welded.vertex_of_site.assign(n, -1);
  std::vector<std::size_t> site_of_vertex;
  for (std::size_t i = 0; i < n; ++i) {
    if (first_of[i] == i) {
      welded.vertex_of_site[i] = static_cast<Index>(site_of_vertex.size());
      site_of_vertex.push_back(i);
    }
  }
  for (std::size_t i = 0; i < n; ++i) welded.vertex_of_site[i] = welded.vertex_of_site[first_of[i]];
  welded.mesh.vertices.resize(static_cast<Index>(site_of_vertex.size()), 3);
  for (std::size_t v = 0; v < site_of_vertex.size(); ++v) {
    welded.mesh.vertices.row(static_cast<Index>(v)) = dual.vertices.row(static_cast<Index>(site_of_vertex[v]));
  }
  welded.mesh.faces.resize(dual.num_faces(), 3);
  Index kept = 0;
  for (Index f = 0; f < dual.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) welded.mesh.faces(kept, k) = welded.vertex_of_site[dual.faces(f, k)];
    if (!has_repeated_corner(welded.mesh, kept)) ++kept;
  }
  welded.mesh.faces.conservativeResize(kept, 3);
  welded.folded_pairs = remove_folded_pairs(welded.mesh);
  if (welded.folded_pairs > 0) {
    std::vector<std::uint8_t> used(site_of_vertex.size(), 0);
    for (Index f = 0; f < welded.mesh.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(welded.mesh.faces(f, k))] = 1;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!used[static_cast<std::size_t>(welded.vertex_of_site[i])]) welded.unused_sites.push_back(i);
    }
  }

  // Cracks: boundary edges of the weld with an end off the surface's boundary.
  const MeshTopology surface_topology = build_mesh_topology(surface);
  const auto on_surface_boundary = [&](std::size_t site) {
    const SiteKey& key = keys[site];
    if (key.lo < 0) return false;
    if (key.lo == key.hi) return surface_topology.vertex_on_boundary[key.lo] != 0;
    const Index edge = surface_topology.find_edge(key.lo, key.hi);
    return edge >= 0 && surface_topology.is_boundary_edge(edge);
  };
  // Surface vertices on a chain: the cut split them, or a chain ends there
  // in the open (the tip of a slit, one copy).
  std::vector<std::uint8_t> on_chain(static_cast<std::size_t>(surface.vertices.rows()), 0);
  for (const auto& [a, b] : features.sharp_edges) on_chain[a] = on_chain[b] = 1;
  const MeshTopology topology = build_mesh_topology(welded.mesh);
  // Twins that made a triangle or an edge in two pieces: not a remesh.
  for (Index e = 0; e < topology.num_edges(); ++e) welded.nonmanifold_edges += topology.is_manifold_edge(e) ? 0 : 1;
  const auto on_cut_boundary = [&](std::size_t s) {
    const SiteKey& key = keys[s];
    return key.lo >= 0 && (key.lo == key.hi ? on_chain[key.lo] || on_surface_boundary(s)
                                            : is_sharp(features, key.lo, key.hi) || on_surface_boundary(s));
  };
  // The ends of cracked edges inside a piece of the cut surface (not on any
  // of its boundaries) need a site on the boundary; each with the other ends
  // of its cracked edges.
  std::vector<std::pair<std::size_t, std::size_t>> crack_neighbours;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    const std::size_t sa = site_of_vertex[a], sb = site_of_vertex[b];
    if (on_surface_boundary(sa) && on_surface_boundary(sb)) continue;
    ++welded.cracked_edges;
    welded.crack_vertices.insert(welded.crack_vertices.end(), {a, b});
    if (!on_cut_boundary(sa)) crack_neighbours.emplace_back(sa, sb);
    if (!on_cut_boundary(sb)) crack_neighbours.emplace_back(sb, sa);
  }
  if (welded.cracked_edges == 0) return welded;
  std::sort(crack_neighbours.begin(), crack_neighbours.end());
  std::vector<SiteKey> held;  // a move onto a point a site holds would make two sites one
  for (const SiteKey& key : keys) {
    if (key.lo >= 0) held.push_back(key);
  }
  std::sort(held.begin(), held.end());
  // Nor onto a point all but at a site (a thousandth of the spacing, the
  // welded remesh's mean edge, away): two vertices there would make a needle
  // (ogre at 5,000 sites: a boundary site and a site moved 5.4e-7 from it).
  // The site there serves the crack: the one that would move goes.
  double edge_length_sum = 0;
  for (const auto& [a, b] : topology.edge_vertices) {
    edge_length_sum += (welded.mesh.vertices.row(a) - welded.mesh.vertices.row(b)).norm();
  }
  const double too_close =
      topology.num_edges() > 0 ? 1e-3 * edge_length_sum / static_cast<double>(topology.num_edges()) : 0.0;
  PointGrid<std::size_t> site_grid(too_close > 0 ? too_close : 1.0);
  for (std::size_t s = 0; s < sites.size(); ++s) site_grid.insert(sites[s].position(cut.mesh), s);

  // The nearest point of the cut surface's boundary in the site's piece.
  const MeshTopology cut_topology = build_mesh_topology(cut.mesh);
  std::vector<Index> boundary_edges;
  for (Index e = 0; e < cut_topology.num_edges(); ++e) {
    if (cut_topology.is_boundary_edge(e) && has_positive_area(cut.mesh, cut_topology.edge_faces(e)[0])) {
      boundary_edges.push_back(e);
    }
  }
  for (auto first = crack_neighbours.begin(); first != crack_neighbours.end();) {
    const std::size_t s = first->first;
    const auto last = std::find_if(first, crack_neighbours.end(), [&](const auto& pair) { return pair.first != s; });
    // The site's cell reaches the boundary between its two neighbours along
    // the crack: where they are on the boundary, it moves halfway between
    // them (to its nearest point there, it could land next to one of them).
    const bool between = last - first == 2 && on_cut_boundary(first->second) && on_cut_boundary((first + 1)->second);
    const Index piece = sites[s].kind == SurfacePoint::Kind::vertex
                            ? cut_topology.vertex_component[static_cast<std::size_t>(sites[s].element)]
                            : cut_topology.face_component[static_cast<std::size_t>(sites[s].element)];
    const Eigen::Vector3d x = between ? Eigen::Vector3d(0.5 * (sites[first->second].position(cut.mesh) +
                                                               sites[(first + 1)->second].position(cut.mesh)))
                                      : sites[s].position(cut.mesh);
    first = last;
    double best = std::numeric_limits<double>::infinity();
    SurfacePoint nearest;
    for (const Index e : boundary_edges) {
      const Index f = cut_topology.edge_faces(e)[0];
      if (cut_topology.face_component[static_cast<std::size_t>(f)] != piece) continue;
      const auto [p, q] = cut_topology.edge_vertices[static_cast<std::size_t>(e)];
      const Eigen::Vector3d a = cut.mesh.vertices.row(p), b = cut.mesh.vertices.row(q);
      const Eigen::Vector3d d = b - a;
      const double t = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const double distance = (a + t * d - x).norm();
      if (distance < best) {
        best = distance;
        // As a point of the surface's edge, lattice-rounded like every edge
        // site; within the lattice's margin of an end, that end (the key of
        // a site there, which `held` may have).
        Index lo = cut.original_vertex[p], hi = cut.original_vertex[q];
        double along = t;
        if (lo > hi) std::swap(lo, hi), along = 1 - t;
        if (t < detail::kLatticeMargin || t > 1 - detail::kLatticeMargin) {
          nearest = SurfacePoint::at_vertex(t < detail::kLatticeMargin ? p : q);
        } else {
          nearest = point_on_edge(surface, f, lo, hi, detail::lattice_parameter(along));
        }
      }
    }
    if (!(best < std::numeric_limits<double>::infinity())) continue;
    const SiteKey key = site_key(surface, cut, nearest);
    if (std::binary_search(held.begin(), held.end(), key)) continue;
    const Eigen::Vector3d target = nearest.position(cut.mesh);
    if (site_grid.any_within(target, too_close, [&](std::size_t other) { return other != s; })) {
      welded.doubling_sites.push_back(s);
      continue;
    }
    held.insert(std::upper_bound(held.begin(), held.end(), key), key);
    site_grid.insert(target, s);
    welded.site_moves.emplace_back(s, nearest);
  }
  return welded;
}

namespace {

/// Chain points closer than this many spacings are one point (doubled_chain_points).
constexpr double kDoubledPoint = 0.2;

/// Per site, whether it doubles a point on a chain: it lies on a sharp edge
/// or a vertex of one, within `tolerance` of a corner or of a site there with
/// another key and a lower index (a twin shares its key and is no double).
/// The dual's repair keeps its points apart only on one piece, and the two
/// sheets of a cut are two: each may get a point a hair from the other's, or
/// from a chain site, which welded makes a triangle with a side of almost
/// nothing. Corners are never doubles.
std::vector<std::uint8_t> doubled_chain_points(const TriangleMesh& surface, const FeatureSet& features,
                                               const FeatureCut& cut, std::span<const SurfacePoint> sites,
                                               double tolerance) {
  std::vector<std::uint8_t> on_chain(static_cast<std::size_t>(surface.vertices.rows()), 0);
  for (const auto& [a, b] : features.sharp_edges) on_chain[a] = on_chain[b] = 1;
  std::vector<std::uint8_t> doubled(sites.size(), 0);
  PointGrid<SiteKey> grid(tolerance);  // the chain points held, by key
  std::vector<SiteKey> keys(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) keys[i] = site_key(surface, cut, sites[i]);
  for (const bool corners : {true, false}) {
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const SiteKey& key = keys[i];
      if (key.lo < 0) continue;
      const bool corner =
          key.lo == key.hi && std::binary_search(features.corners.begin(), features.corners.end(), key.lo);
      const bool chain_point = key.lo == key.hi ? on_chain[key.lo] != 0 : is_sharp(features, key.lo, key.hi);
      if (corner != corners || !chain_point) continue;
      const Eigen::Vector3d x = sites[i].position(cut.mesh);
      if (!corner && grid.any_within(x, tolerance, [&](const SiteKey& other) { return !(other == key); })) {
        doubled[i] = 1;
        continue;
      }
      grid.insert(x, key);
    }
  }
  return doubled;
}

/// `sites` less those `marked`.
std::vector<SurfacePoint> sites_not_marked(std::span<const SurfacePoint> sites,
                                           const std::vector<std::uint8_t>& marked) {
  std::vector<SurfacePoint> kept;
  kept.reserve(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (!marked[i]) kept.push_back(sites[i]);
  }
  return kept;
}

/// The first piece of `surface` (cut along the features) that the welded
/// remesh does not keep: `what` describes it for an error message ("" when it
/// keeps them all), `sites` are where it went wrong. A piece is kept when its
/// sites are the vertices of one piece of the remesh, which holds no other
/// piece's sites and has the same Euler characteristic and boundary loops.
/// (Each piece of the cut is checked on its own before the weld, but only
/// those holding sites: a piece of the cut whose sites were all left out
/// would go missing unseen.)
struct PieceNotKept {
  std::string what;
  /// Indices of the sites that went astray: those of the piece away from the
  /// remesh piece most of them are on, or another piece's on that one (none
  /// where only the counts differ).
  std::vector<std::size_t> sites;
};
PieceNotKept first_piece_not_kept(const TriangleMesh& surface, const FeatureCut& cut,
                                  std::span<const SurfacePoint> sites, const WeldedDual& welded) {
  const MeshTopology pieces = build_mesh_topology(surface);
  const MeshTopology remeshed = build_mesh_topology(welded.mesh);
  std::vector<std::uint8_t> has_area(pieces.components.size(), 0);
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Index piece = pieces.face_component[f];
    if (piece >= 0 && has_positive_area(surface, f)) has_area[piece] = 1;
  }
  // Per site, its piece of the surface and of the remesh (-1: none).
  std::vector<Index> piece_of(sites.size(), -1), made_of(sites.size(), -1);
  // Per piece of the surface, the piece of the remesh its sites are on (-1:
  // none, -2: several, or a site on none); per piece of the remesh, the
  // surface's piece whose sites it holds (-2: several).
  std::vector<Index> remeshed_of(pieces.components.size(), -1);
  std::vector<Index> surface_of(remeshed.components.size(), -1);
  std::vector<Index> first_vertex(pieces.components.size(), -1);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const SurfacePoint& site = sites[s];
    const Index piece = site.kind == SurfacePoint::Kind::vertex
                            ? pieces.vertex_component[cut.original_vertex[static_cast<std::size_t>(site.element)]]
                            : pieces.face_component[site.element];
    const Index vertex = welded.vertex_of_site[s];
    const Index made = vertex >= 0 ? remeshed.vertex_component[vertex] : -1;
    piece_of[s] = piece;
    made_of[s] = made;
    if (piece < 0) continue;
    Index& mine = remeshed_of[piece];
    if (made < 0 || (mine >= 0 && mine != made)) {
      mine = -2;
    } else if (mine == -1) {
      mine = made;
    }
    if (made >= 0) surface_of[made] = surface_of[made] == -1 || surface_of[made] == piece ? piece : -2;
  }
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Index piece = pieces.face_component[f];
    if (piece >= 0 && first_vertex[piece] < 0) first_vertex[piece] = surface.faces(f, 0);
  }
  auto counts = [](const ComponentCounts& c) {
    return "Euler characteristic " + std::to_string(c.euler_characteristic()) + ", " +
           std::to_string(c.boundary_loops) + (c.boundary_loops == 1 ? " boundary loop" : " boundary loops");
  };
  for (std::size_t piece = 0; piece < pieces.components.size(); ++piece) {
    if (!has_area[piece]) continue;
    const ComponentCounts& expected = pieces.components[piece];
    const Index made = remeshed_of[piece];
    PieceNotKept lost;
    const auto piece_index = static_cast<Index>(piece);
    if (made == -1) {
      lost.what = "no vertex";
    } else if (made == -2) {
      lost.what = "its sites on several pieces, or on none";
      std::vector<std::int64_t> on(remeshed.components.size(), 0);
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (piece_of[s] == piece_index && made_of[s] >= 0) ++on[made_of[s]];
      }
      const auto most = static_cast<Index>(std::max_element(on.begin(), on.end()) - on.begin());
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (piece_of[s] == piece_index && made_of[s] != most) lost.sites.push_back(s);
      }
    } else if (surface_of[made] != piece_index) {
      lost.what = "a piece shared with another";
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (made_of[s] == made && piece_of[s] != piece_index) lost.sites.push_back(s);
      }
    } else if (remeshed.components[made].euler_characteristic() != expected.euler_characteristic() ||
               remeshed.components[made].boundary_loops != expected.boundary_loops) {
      lost.what = counts(remeshed.components[made]);
    } else {
      continue;
    }
    lost.what = "the piece with input vertex " + std::to_string(first_vertex[piece]) + " (" +
                std::to_string(expected.faces) + " faces, " + counts(expected) + "; in the remesh: " + lost.what + ")";
    return lost;
  }
  return {};
}

/// The positions of `sites` (on `mesh`) whose index is in `which`: for
/// DualRepairError's places.
template <typename Indices>
std::vector<Eigen::Vector3d> positions(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                       const Indices& which) {
  std::vector<Eigen::Vector3d> points;
  for (const auto i : which) points.push_back(sites[static_cast<std::size_t>(i)].position(mesh));
  return points;
}

/// The weld's failure: `what`, where (fault_places of `points` a `spacing`
/// apart) and the remedy.
DualRepairError weld_error(const std::string& what, std::span<const Eigen::Vector3d> points, double spacing,
                           const std::string& remedy = "") {
  std::vector<Eigen::Vector3d> places = fault_places(points, spacing);
  const std::string message = "the remesh " + what + fault_places_text(places) + remedy;
  return DualRepairError(message, std::move(places));
}

}  // namespace

RepairedDual welded_dual_with_repair(const voronoi::GeodesicSurface& cut_surface, const TriangleMesh& surface,
                                     const FeatureSet& features, const FeatureCut& cut, std::vector<SurfacePoint> sites,
                                     voronoi::VoronoiDiagram diagram, const RepairOptions& options) {
  RepairedDual result;
  std::int64_t sites_added = 0, sites_left_out = 0;
  int repair_rounds = 0;  // of the rounds before the last
  int leave_out_rounds = 0;
  std::vector<std::string> repair_problems;
  double geodesic_seconds = 0, diagram_seconds = 0, dual_seconds = 0;
  constexpr const char* kRemedy = "; try more sites, or a larger sharp angle";
  // The next round's diagram, of `sites`.
  const auto recompute = [&] {
    diagram = voronoi::compute_voronoi(cut_surface, sites, options.voronoi);
    geodesic_seconds += diagram.stats.geodesic_seconds;
    diagram_seconds += diagram.stats.extraction_seconds;
  };
  for (int round = 0;; ++round) {
    RepairOptions within = options;  // with the sites still allowed
    if (options.max_sites_added > 0) {
      within.max_sites_added = std::max<std::int64_t>(1, options.max_sites_added - sites_added);
    }
    result = dual_with_repair(cut_surface, std::move(sites), std::move(diagram), within);
    sites_added += result.sites_added;
    sites_left_out += result.sites_left_out;
    repair_problems.insert(repair_problems.end(), result.repair_problems.begin(), result.repair_problems.end());
    geodesic_seconds += result.geodesic_seconds;
    diagram_seconds += result.diagram_seconds;
    dual_seconds += result.dual_seconds;
    // Points the repair doubled on a chain go, the points they doubled get
    // their twins, and the diagram is computed again.
    const double spacing = result.diagram.mean_spacing();
    const std::vector<std::uint8_t> doubled =
        doubled_chain_points(surface, features, cut, result.sites, kDoubledPoint * spacing);
    if (const auto count = std::count(doubled.begin(), doubled.end(), 1); count > 0) {
      if (round >= options.max_rounds) {
        std::vector<std::size_t> doubles;
        for (std::size_t i = 0; i < doubled.size(); ++i) {
          if (doubled[i]) doubles.push_back(i);
        }
        throw weld_error("welded along the sharp features doubles " + std::to_string(count) +
                             " points on its creases after " + std::to_string(round) + " rounds",
                         positions(cut.mesh, result.sites, doubles), spacing);
      }
      sites = sites_not_marked(result.sites, doubled);
      // The points they doubled serve both sheets: their twins come now.
      const std::vector<SurfacePoint> twins = missing_twins(surface, features, cut, sites);
      sites.insert(sites.end(), twins.begin(), twins.end());
      sites_added += static_cast<std::int64_t>(twins.size());
      sites_left_out += count;
      repair_rounds += result.repair_rounds + 1;
      repair_problems.push_back(std::to_string(count) +
                                " repair sites doubling points on the sharp features (left out)");
      recompute();
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    WeldedDual welded = weld_along_features(surface, features, cut, result.mesh, result.sites);
    if (welded.nonmanifold_edges > 0) {
      const MeshTopology topology = build_mesh_topology(welded.mesh);
      std::vector<Eigen::Vector3d> ends;
      for (Index e = 0; e < topology.num_edges(); ++e) {
        if (!topology.is_manifold_edge(e)) ends.push_back(welded.mesh.vertices.row(topology.edge_vertices[e][0]));
      }
      throw weld_error("welded along the sharp features has " + std::to_string(welded.nonmanifold_edges) +
                           " edges with three or more triangles",
                       ends, spacing);
    }
    if (!welded.unused_sites.empty() || !welded.doubling_sites.empty()) {
      // Sites whose triangles all folded away, or that would close a crack
      // all but on another site: left out, the diagram computed again, twice
      // at most (where folds keep coming, the weld will not close).
      const std::size_t left_out = welded.unused_sites.size() + welded.doubling_sites.size();
      if (round >= options.max_rounds || ++leave_out_rounds > 2) {
        std::vector<Eigen::Vector3d> points = positions(cut.mesh, result.sites, welded.unused_sites);
        const std::vector<Eigen::Vector3d> doubling = positions(cut.mesh, result.sites, welded.doubling_sites);
        points.insert(points.end(), doubling.begin(), doubling.end());
        throw weld_error("welded along the sharp features leaves " + std::to_string(left_out) +
                             " sites in no triangle or on another after " + std::to_string(round) + " rounds",
                         points, spacing);
      }
      std::vector<std::uint8_t> unused(result.sites.size(), 0);
      for (const std::size_t site : welded.unused_sites) unused[site] = 1;
      for (const std::size_t site : welded.doubling_sites) unused[site] = 1;
      sites = sites_not_marked(result.sites, unused);
      sites_left_out += static_cast<std::int64_t>(left_out);
      repair_rounds += result.repair_rounds + 1;
      if (!welded.unused_sites.empty()) {
        repair_problems.push_back(std::to_string(welded.unused_sites.size()) +
                                  " sites in no triangle once welded (left out)");
      }
      if (!welded.doubling_sites.empty()) {
        repair_problems.push_back(std::to_string(welded.doubling_sites.size()) +
                                  " sites that would close a crack all but on another site (left out)");
      }
      dual_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      recompute();
      continue;
    }
    // The weld as the remesh: every triangle of positive area (each piece's
    // dual has only such; welded, three sites on one straight stretch of a
    // chain could still make one flat) and every piece of the surface kept.
    const auto accept = [&] {
      for (Index f = 0; f < welded.mesh.num_faces(); ++f) {
        if (has_positive_area(welded.mesh, f)) continue;
        const Eigen::Vector3d corner = welded.mesh.vertices.row(welded.mesh.faces(f, 0));
        throw DualRepairError(
            "the remesh welded along the sharp features has a triangle of zero area, at " + point_text(corner),
            {corner});
      }
      if (const PieceNotKept lost = first_piece_not_kept(surface, cut, result.sites, welded); !lost.what.empty()) {
        throw weld_error("welded along the sharp features does not keep " + lost.what,
                         positions(cut.mesh, std::span<const SurfacePoint>(result.sites), lost.sites), spacing,
                         kRemedy);
      }
      result.mesh = std::move(welded.mesh);
      result.vertex_of_site = std::move(welded.vertex_of_site);
    };
    std::vector<std::pair<std::size_t, SurfacePoint>> moved_from;  // to undo the moves
    for (const auto& [site, point] : welded.site_moves) {
      moved_from.emplace_back(site, result.sites[site]);
      result.sites[site] = point;
    }
    const std::vector<SurfacePoint> more = missing_twins(surface, features, cut, result.sites);
    if (welded.cracked_edges == 0 && more.empty()) {
      accept();
      break;
    }
    dual_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (round >= options.max_rounds || (more.empty() && welded.site_moves.empty())) {
      // The last resort: the cracks are holes of a few edges on the sites as
      // they are; closed with triangles on their vertices, the weld is a
      // remesh of the surface, the connectivity there not the dual's.
      for (const auto& [site, point] : moved_from) result.sites[site] = point;
      if (const std::optional<CrackFill> fill = close_cracks(welded.mesh, welded.crack_vertices)) {
        accept();
        result.cracks_closed = fill->holes;
        result.crack_triangles = fill->triangles;
        repair_problems.push_back(std::to_string(welded.cracked_edges) +
                                  " edges of the welded remesh leaving the sharp features after " +
                                  std::to_string(round) + " rounds, closed with " + std::to_string(fill->triangles) +
                                  " triangles on their vertices");
        break;
      }
      std::vector<Eigen::Vector3d> ends;
      for (const Index v : welded.crack_vertices) ends.push_back(welded.mesh.vertices.row(v));
      throw weld_error("does not close along the sharp features after " + std::to_string(round) +
                           " rounds: " + std::to_string(welded.cracked_edges) +
                           " edges of its boundary leave the surface's creases and boundary",
                       ends, spacing, kRemedy);
    }
    sites = std::move(result.sites);
    sites_added += static_cast<std::int64_t>(more.size());
    repair_rounds += result.repair_rounds + 1;
    if (options.max_sites_added > 0 && sites_added > options.max_sites_added) {
      std::vector<Eigen::Vector3d> twins;
      for (const SurfacePoint& twin : more) twins.push_back(twin.position(cut.mesh));
      throw weld_error("welded along the sharp features would add " + std::to_string(sites_added) + " sites in " +
                           std::to_string(round + 1) + " rounds, more than the " +
                           std::to_string(options.max_sites_added) + " allowed: its creases are finer than the spacing",
                       twins, spacing, kRemedy);
    }
    if (!more.empty()) {
      repair_problems.push_back(std::to_string(more.size()) + " points of the sharp features without their twin sites");
    }
    if (welded.cracked_edges > 0) {
      repair_problems.push_back(std::to_string(welded.cracked_edges) +
                                " edges of the welded remesh leaving the sharp features");
    }
    sites.insert(sites.end(), more.begin(), more.end());
    recompute();
  }
  result.sites_added = sites_added;
  result.sites_left_out = sites_left_out;
  result.repair_rounds += repair_rounds;
  result.repair_problems = std::move(repair_problems);
  result.geodesic_seconds = geodesic_seconds;
  result.diagram_seconds = diagram_seconds;
  result.dual_seconds = dual_seconds;
  return result;
}

}  // namespace geodual::remesh
