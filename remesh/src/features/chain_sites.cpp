#include "geodual/remesh/feature_cut.hpp"

#include "features/chain_points.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/vertex_copies.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

namespace geodual::remesh {
namespace {

using detail::ChainWalk;
using detail::point_on_edge;
using detail::site_key;
using detail::SiteKey;

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

/// A stretch of a chain between two arc lengths, split into `parts`.
struct Stretch {
  double from, to;
  int parts = 1;
  bool bends = false;  ///< no even parts of at least min_spacing keep to twice the chord error
};

/// The most parts of at least `spacing` a stretch of `length` splits into (16 at most).
int most_parts(double length, double spacing) {
  return spacing > 0 ? static_cast<int>(std::min(16.0, std::floor(length / spacing))) : 16;
}

/// Whether the chords of [from, to] split evenly into `parts` stay within `error` of the chain.
bool fits(const ChainWalk& walk, double from, double to, int parts, double error) {
  for (int k = 0; k < parts; ++k) {
    if (!walk.within(from + (to - from) * k / parts, from + (to - from) * (k + 1) / parts, error)) return false;
  }
  return true;
}

/// The stretch [from, to] of `walk`'s chain: where its chord leaves the
/// chain by more than the chord error, split evenly into the fewest parts
/// that keep to it (at most 16, no shorter than min_spacing), so that the
/// chain gets denser where it bends, there only; `bends` where the shortest
/// parts still leave it by more than twice the error.
Stretch split_stretch(const ChainWalk& walk, double from, double to, const FeatureSiteOptions& options) {
  Stretch stretch{from, to};
  if (!(options.max_chord_error > 0) || walk.within(from, to, options.max_chord_error)) return stretch;
  const int most = most_parts(to - from, options.min_spacing);
  int parts = std::min(most, 2);
  while (parts < most && !fits(walk, from, to, parts, options.max_chord_error)) ++parts;
  stretch.parts = std::max(parts, 1);
  stretch.bends = !fits(walk, from, to, stretch.parts, 2 * options.max_chord_error);
  return stretch;
}

/// The chain vertex strictly inside (from, to), at least `margin` from both,
/// farthest from the chord between the chain's points there; -1 where none.
std::ptrdiff_t farthest_vertex(const ChainWalk& walk, double from, double to, double margin) {
  const Eigen::Vector3d p = walk.point(from), d = walk.point(to) - p;
  const double dd = d.squaredNorm();
  std::ptrdiff_t farthest = -1;
  double largest = -1;
  const auto first = std::upper_bound(walk.at.begin(), walk.at.end(), from + margin);
  const auto last = std::lower_bound(first, walk.at.end(), to - margin);
  for (auto it = first; it < last; ++it) {
    const auto i = static_cast<std::size_t>(it - walk.at.begin());
    const Eigen::Vector3d x = walk.surface.vertices.row(walk.chain.vertices[i]).transpose() - p;
    const double t = dd > 0 ? std::clamp(x.dot(d) / dd, 0.0, 1.0) : 0.0;
    if (const double distance = (x - t * d).norm(); distance > largest) {
      largest = distance;
      farthest = static_cast<std::ptrdiff_t>(i);
    }
  }
  return farthest;
}

/// Appends to `stops` the points inside [from, to] that split it into parts
/// whose chords keep to `error`: the fewest even parts about `spacing` long
/// or shorter, down to `margin`, that do; where none do, the chain's own
/// vertex farthest from the chord is a point and each side is split alike
/// (Douglas and Peucker's simplification of the polyline, so that a chord
/// between two of its vertices leaves it by no more than the error). That
/// vertex is at least `margin` from either end, or a quarter of the part
/// where that is less, but never less than 0.6 `margin` (closer chain
/// points make slivers, and the weld takes points a fifth of a spacing apart
/// for one). Where no vertex is that far from the ends, the even parts.
void split_at_bends(const ChainWalk& walk, double from, double to, double spacing, double margin, double error,
                    std::vector<double>& stops) {
  const int parts = std::max(1, static_cast<int>(std::lround((to - from) / spacing)));
  const auto split_evenly = [&](int n) {
    for (int j = 1; j < n; ++j) stops.push_back(from + (to - from) * j / n);
  };
  for (int n = parts; n <= std::max(parts, most_parts(to - from, margin)); ++n) {
    if (fits(walk, from, to, n, error)) return split_evenly(n);
  }
  const double room = std::max(0.6 * margin, std::min(margin, (to - from) / 4));
  const std::ptrdiff_t vertex = farthest_vertex(walk, from, to, room);
  if (vertex < 0) return split_evenly(parts);
  const double bend = walk.at[static_cast<std::size_t>(vertex)];
  split_at_bends(walk, from, bend, spacing, margin, error, stops);
  stops.push_back(bend);
  split_at_bends(walk, bend, to, spacing, margin, error, stops);
}

/// Round a corner, the first site of every chain at one distance d: the
/// smallest of their spacings (a chain's length over its `segments`) and half
/// their lengths. In a wedge of angle theta between two chains, the corner's
/// cell meets the cells of the first sites at distances d1 <= d2 at a Voronoi
/// vertex only if d1 >= d2 cos(theta) (the bisectors must cross inside the
/// wedge); equal distances meet in any wedge. Half the length leaves room for
/// the chain's other end.
std::map<Index, double> corner_distances(const FeatureSet& features, std::span<const ChainWalk> walks,
                                         std::span<const std::int64_t> segments) {
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
  return corner_distance;
}

/// The stretch ends of `chain` (of `length`, in `segments` of `own`):
/// evenly round a closed chain; on an open one, from the corners' first
/// sites, evenly about `own` apart in between.
std::vector<double> stretch_ends(const FeatureChain& chain, double length, std::int64_t segments, double own,
                                 const std::map<Index, double>& corner_distance) {
  std::vector<double> ends;
  if (chain.closed) {
    for (std::int64_t k = 0; k <= segments; ++k) ends.push_back(own * static_cast<double>(k));
    return ends;
  }
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
  return ends;
}

/// The points of `walk`'s chain (the stretch `ends` of stretch_ends, about
/// `own` apart) where it bends beyond what even parts follow: split at its
/// own vertices (split_at_bends) from its corners, or round a closed chain
/// from its first vertex. The first site round a corner moves to the chain's
/// vertex nearest it within the tight spacing, if any: a vertex there is
/// where the chain bends, and a site beside it would cut the bend.
std::vector<double> stops_at_bends(const ChainWalk& walk, std::span<const double> ends, double own,
                                   const FeatureSiteOptions& options) {
  std::vector<double> stops;
  const auto split = [&](double from, double to) {
    split_at_bends(walk, from, to, own, options.tight_spacing, 2 * options.max_chord_error, stops);
  };
  if (walk.chain.closed) {
    stops.push_back(0);
    split(0, walk.length());
    return stops;
  }
  // The inner chain vertex nearest `at`, where one is within the tight spacing.
  const auto stop_near = [&](double at) {
    const auto upper = static_cast<std::size_t>(std::upper_bound(walk.at.begin(), walk.at.end(), at) - walk.at.begin());
    double nearest = at;
    for (std::size_t i = std::max<std::size_t>(1, upper) - 1; i <= std::min(upper, walk.at.size() - 2); ++i) {
      const double distance = std::abs(walk.at[i] - at);
      if (i > 0 && distance < options.tight_spacing && (nearest == at || distance < std::abs(nearest - at))) {
        nearest = walk.at[i];
      }
    }
    return nearest;
  };
  const double first = stop_near(ends[1]);
  double last = stop_near(ends[ends.size() - 2]);
  split(0, first);
  stops.push_back(first);
  if (last > first) {
    split(first, last);
    stops.push_back(last);
  } else {
    last = first;
  }
  split(last, walk.length());
  return stops;
}

/// The points of `walk`'s chain split into `stretches` (split_stretch): each
/// stretch that bends evenly into the fewest parts down to tight_spacing (0:
/// none closer) that keep to twice the chord error, if any; at a corner where the chain ends
/// `alone` (front, back), the stretch from it as closely as a tight one
/// after it. The points of tight stretches (parts shorter than min_spacing),
/// ends included, go to `dense` with their parts' length.
std::vector<double> stops_closer_evenly(const ChainWalk& walk, std::vector<Stretch> stretches,
                                        std::array<bool, 2> alone, const FeatureSiteOptions& options,
                                        std::vector<SpacedPoint>& dense) {
  std::vector<bool> tight(stretches.size(), false);
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    Stretch& stretch = stretches[k];
    if (!stretch.bends) continue;
    const double length = stretch.to - stretch.from;
    const int most = most_parts(length, options.min_spacing);
    const int most_tight = options.tight_spacing > 0 ? std::max(most, most_parts(length, options.tight_spacing)) : most;
    for (int n = stretch.parts + 1; n <= most_tight; ++n) {
      if (fits(walk, stretch.from, stretch.to, n, 2 * options.max_chord_error)) {
        stretch.parts = n;
        tight[k] = n > most;
        break;
      }
    }
  }
  if (!walk.chain.closed && stretches.size() >= 2) {
    for (const bool front : {true, false}) {
      const std::size_t end = front ? 0 : stretches.size() - 1, next = front ? 1 : stretches.size() - 2;
      if (tight[end] || !tight[next] || !alone[front ? 0 : 1]) continue;
      const double spacing = (stretches[next].to - stretches[next].from) / stretches[next].parts;
      const auto parts = static_cast<int>(std::llround((stretches[end].to - stretches[end].from) / spacing));
      if (parts > stretches[end].parts) stretches[end].parts = parts, tight[end] = true;
    }
  }
  std::vector<double> stops;
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    const auto [from, to, parts, bends] = stretches[k];
    if (k > 0) stops.push_back({from});
    for (int j = 1; j < parts; ++j) stops.push_back({from + (to - from) * j / parts});
    for (int j = 0; tight[k] && j <= parts; ++j)
      dense.push_back({walk.point(from + (to - from) * j / parts), (to - from) / parts});
  }
  if (walk.chain.closed) stops.push_back({0});
  return stops;
}

/// At a corner where an open chain ends alone (no wedge whose first sites
/// must sit at one distance), the part from the corner to its first point is
/// split as closely as the chain's points after it where those are closer
/// than min_spacing: the sites round the corner are as close as the chain's
/// there. `alone` at the chain's front and back.
void match_close_points_at_lone_ends(double length, std::array<bool, 2> alone, double min_spacing,
                                     std::vector<double>& stops) {
  if (stops.size() < 2) return;
  if (alone[0]) {
    const double gap = stops[1] - stops[0];
    const auto parts = static_cast<int>(std::llround(stops[0] / gap));
    if (gap < min_spacing && parts > 1) {
      std::vector<double> before;
      for (int j = 1; j < parts; ++j) before.push_back(stops[0] * j / parts);
      stops.insert(stops.begin(), before.begin(), before.end());
    }
  }
  if (alone[1]) {
    const std::size_t n = stops.size();
    const double gap = stops[n - 1] - stops[n - 2], last = stops[n - 1];
    const auto parts = static_cast<int>(std::llround((length - last) / gap));
    if (gap < min_spacing && parts > 1) {
      for (int j = 1; j < parts; ++j) stops.push_back({last + (length - last) * j / parts});
    }
  }
}

}  // namespace

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
  const std::map<Index, double> corner_distance = corner_distances(features, walks, segments);
  // Chain ends per vertex: a corner where one chain ends alone has no wedge
  // to keep the first sites' distances equal in.
  std::map<Index, int> ends_at;
  for (const FeatureChain& chain : features.chains) {
    if (chain.closed) continue;
    ++ends_at[chain.vertices.front()];
    ++ends_at[chain.vertices.back()];
  }
  std::vector<Stretch> stretches;
  std::vector<double> stops;
  for (std::size_t c = 0; c < walks.size(); ++c) {
    const FeatureChain& chain = features.chains[c];
    const ChainWalk& walk = walks[c];
    const double length = walk.length(), own = length / static_cast<double>(segments[c]);
    if (!(length > 0)) continue;
    const std::vector<double> ends = stretch_ends(chain, length, segments[c], own, corner_distance);
    stretches.clear();
    for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
      stretches.push_back(split_stretch(walk, ends[k], ends[k + 1], options));
    }
    const bool bends = std::any_of(stretches.begin(), stretches.end(), [](const Stretch& s) { return s.bends; });
    const std::array<bool, 2> alone = {!chain.closed && ends_at[chain.vertices.front()] == 1,
                                       !chain.closed && ends_at[chain.vertices.back()] == 1};
    if (bends && options.tight_spacing > 0 && options.split_at_bends) {
      stops = stops_at_bends(walk, ends, own, options);
      ++result.chains_split_at_bends;
      match_close_points_at_lone_ends(length, alone, options.min_spacing, stops);
      // The stops closer than min_spacing, with their distance to the nearer neighbour.
      for (std::size_t k = 0; k < stops.size(); ++k) {
        const double before = k > 0 ? stops[k - 1] : chain.closed ? stops.back() - length : 0.0;
        const double after = k + 1 < stops.size() ? stops[k + 1] : chain.closed ? stops.front() + length : length;
        const double gap = std::min(stops[k] - before, after - stops[k]);
        if (gap < options.min_spacing) result.dense_points.push_back({walk.point(stops[k]), gap});
      }
    } else {
      stops = stops_closer_evenly(walk, stretches, alone, options, result.dense_points);
    }
    // A point at a chain vertex too is a point of an edge beside it (a
    // vertex site stays where it is in the relaxation, and on the pulley's
    // bore its triangles came out with angles of 6 degrees).
    for (const double stop : stops) add(walk.key_at(stop));
  }
  return result;
}

std::vector<SurfacePoint> missing_twins(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut,
                                        std::span<const SurfacePoint> sites) {
  std::vector<SurfacePoint> missing;
  if (features.empty()) return missing;
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
    if (key.lo >= 0 && key.lo != key.hi && features.is_sharp(key.lo, key.hi)) held.push_back({key, site.element});
  }
  std::sort(held.begin(), held.end(), [](const auto& x, const auto& y) {
    return x.first < y.first || (x.first == y.first && x.second < y.second);
  });
  for (std::size_t i = 0; i < held.size();) {
    std::size_t j = i;
    while (j < held.size() && held[j].first == held[i].first) ++j;
    const SiteKey& key = held[i].first;
    for (const Index f :
         cut.surface.sharp_edge_faces[static_cast<std::size_t>(features.find_sharp_edge(key.lo, key.hi))]) {
      if (f < 0) continue;
      const bool has =
          std::any_of(held.begin() + static_cast<std::ptrdiff_t>(i), held.begin() + static_cast<std::ptrdiff_t>(j),
                      [&](const auto& h) { return h.second == f; });
      if (!has) missing.push_back(point_on_edge(surface, f, key.lo, key.hi, key.t));
    }
    i = j;
  }
  return missing;
}
}  // namespace geodual::remesh
