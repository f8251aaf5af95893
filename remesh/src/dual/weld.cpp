#include "geodual/remesh/welded_dual.hpp"

#include "features/chain_points.hpp"

#include "geodual/mesh/detail/point_hash.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

namespace geodual::remesh {

using detail::point_on_edge;
using detail::site_key;
using detail::SiteKey;

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

namespace {

/// The weld's mesh in `welded`: the dual's vertices of twins (sites with one
/// key) merged into one, numbered in the order of their first site, without
/// the triangles that lose a corner and the folded pairs. Returns, per
/// vertex of welded.mesh, its first site.
std::vector<std::size_t> merge_twins(const TriangleMesh& dual, std::span<const SiteKey> keys, WeldedDual& welded) {
  const std::size_t n = keys.size();
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
  return site_of_vertex;
}

/// The cut surface's boundary edges and pieces, as build_mesh_topology(cut.mesh)
/// would give them, read from the outline of the surface it came from: an
/// edge of the cut is boundary where it copies a boundary or sharp edge of
/// the surface and no other face has the same two copies.
struct CutBoundary {
  struct Edge {
    Index p = -1, q = -1;  ///< vertices of cut.mesh, p < q
    Index face = -1;       ///< its one face, of positive area
  };
  std::vector<Edge> edges;          ///< sorted by (p, q)
  std::vector<Index> vertex_piece;  ///< per vertex of cut.mesh: faces joined through shared vertices
  Index piece_of_face(const TriangleMesh& mesh, Index f) const { return vertex_piece[mesh.faces(f, 0)]; }
};

CutBoundary cut_boundary(const FeatureSet& features, const FeatureCut& cut) {
  const TriangleMesh& mesh = cut.mesh;
  CutBoundary boundary;
  UnionFind pieces(static_cast<std::size_t>(mesh.num_vertices()));
  std::vector<std::array<Index, 3>> candidates;  // p, q, face
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index p = mesh.faces(f, k), q = mesh.faces(f, (k + 1) % 3);
      pieces.unite(p, q);
      const Index a = cut.original_vertex[p], b = cut.original_vertex[q];
      if (cut.surface.is_boundary_edge(a, b) || features.is_sharp(a, b)) {
        candidates.push_back({std::min(p, q), std::max(p, q), f});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  for (std::size_t i = 0; i < candidates.size();) {
    std::size_t j = i + 1;
    while (j < candidates.size() && candidates[j][0] == candidates[i][0] && candidates[j][1] == candidates[i][1]) ++j;
    const auto [p, q, face] = candidates[i];
    if (j == i + 1 && has_positive_area(mesh, face)) boundary.edges.push_back({p, q, face});
    i = j;
  }
  boundary.vertex_piece.resize(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) boundary.vertex_piece[v] = pieces.find(v);
  return boundary;
}

/// The point of the cut surface's boundary in `piece` nearest x, as a point
/// of the surface's edge, lattice-rounded like every edge site; within the
/// lattice's margin of an end, that end (the key of a site there). None
/// where the piece has no boundary.
std::optional<SurfacePoint> nearest_boundary_point(const TriangleMesh& surface, const FeatureCut& cut,
                                                   const CutBoundary& boundary, Index piece, const Eigen::Vector3d& x) {
  double best = std::numeric_limits<double>::infinity();
  std::optional<SurfacePoint> nearest;
  for (const auto& [p, q, f] : boundary.edges) {
    if (boundary.piece_of_face(cut.mesh, f) != piece) continue;
    const Eigen::Vector3d a = cut.mesh.vertices.row(p), b = cut.mesh.vertices.row(q);
    const Eigen::Vector3d d = b - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const double distance = (a + t * d - x).norm();
    if (distance < best) {
      best = distance;
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
  return nearest;
}

}  // namespace

WeldedDual weld_along_features(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                               const TriangleMesh& dual, std::span<const SurfacePoint> sites) {
  WeldedDual welded;
  const std::size_t n = sites.size();
  std::vector<SiteKey> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = site_key(surface, cut, sites[i]);
  const std::vector<std::size_t> site_of_vertex = merge_twins(dual, keys, welded);

  // Cracks: boundary edges of the weld with an end off the surface's boundary.
  const auto on_surface_boundary = [&](std::size_t site) {
    const SiteKey& key = keys[site];
    if (key.lo < 0) return false;
    if (key.lo == key.hi) return cut.surface.vertex_on_boundary[key.lo] != 0;
    return cut.surface.is_boundary_edge(key.lo, key.hi);
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
                                            : features.is_sharp(key.lo, key.hi) || on_surface_boundary(s));
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
  PointHash<std::size_t> site_grid(too_close > 0 ? too_close : 1.0);
  for (std::size_t s = 0; s < sites.size(); ++s) site_grid.insert(sites[s].position(cut.mesh), s);

  // The nearest point of the cut surface's boundary in the site's piece.
  const CutBoundary boundary = cut_boundary(features, cut);
  for (auto first = crack_neighbours.begin(); first != crack_neighbours.end();) {
    const std::size_t s = first->first;
    const auto last = std::find_if(first, crack_neighbours.end(), [&](const auto& pair) { return pair.first != s; });
    // The site's cell reaches the boundary between its two neighbours along
    // the crack: where they are on the boundary, it moves halfway between
    // them (to its nearest point there, it could land next to one of them).
    const bool between = last - first == 2 && on_cut_boundary(first->second) && on_cut_boundary((first + 1)->second);
    const Index piece = sites[s].kind == SurfacePoint::Kind::vertex
                            ? boundary.vertex_piece[static_cast<std::size_t>(sites[s].element)]
                            : boundary.piece_of_face(cut.mesh, sites[s].element);
    const Eigen::Vector3d x = between ? Eigen::Vector3d(0.5 * (sites[first->second].position(cut.mesh) +
                                                               sites[(first + 1)->second].position(cut.mesh)))
                                      : sites[s].position(cut.mesh);
    first = last;
    const std::optional<SurfacePoint> nearest = nearest_boundary_point(surface, cut, boundary, piece, x);
    if (!nearest) continue;
    const SiteKey key = site_key(surface, cut, *nearest);
    if (std::binary_search(held.begin(), held.end(), key)) continue;
    const Eigen::Vector3d target = nearest->position(cut.mesh);
    if (site_grid.any_within(target, too_close, [&](std::size_t other) { return other != s; })) {
      welded.doubling_sites.push_back(s);
      continue;
    }
    held.insert(std::upper_bound(held.begin(), held.end(), key), key);
    site_grid.insert(target, s);
    welded.site_moves.emplace_back(s, *nearest);
  }
  return welded;
}
}  // namespace geodual::remesh
