#include "geodual/voronoi/geodesic_field.hpp"

#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"
#include "prepared_surface.hpp"
#include "site_groups.hpp"
#include "window_vtp.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

namespace geodual::voronoi {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string site_name(std::size_t i) { return "site " + std::to_string(i); }

/// The vertices of the smallest element holding a site (its vertex, the edge
/// or the face it lies inside), increasing, -1 for the rest.
std::array<Index, 3> carrier(const TriangleMesh& mesh, const SurfacePoint& site) {
  std::array<Index, 3> vertices = {-1, -1, -1};
  if (site.kind == SurfacePoint::Kind::vertex) {
    vertices[0] = site.element;
    return vertices;
  }
  int n = 0;
  for (int c = 0; c < 3; ++c) {
    if (site.barycentric[c] > 0) vertices[static_cast<std::size_t>(n++)] = mesh.faces(site.element, c);
  }
  std::sort(vertices.begin(), vertices.begin() + n);
  return vertices;
}

/// Checks every site and brings it to a canonical form: a face point with two
/// zero barycentric coordinates becomes a vertex site.
std::vector<SurfacePoint> validated_sites(const TriangleMesh& mesh, const detail::PropagationMesh& pm,
                                          const std::vector<Index>& new_face, const std::vector<Index>& new_vertex,
                                          std::span<const SurfacePoint> sites) {
  std::vector<SurfacePoint> result(sites.begin(), sites.end());
  for (std::size_t i = 0; i < result.size(); ++i) {
    SurfacePoint& site = result[i];
    if (site.kind == SurfacePoint::Kind::vertex) {
      if (site.element < 0 || site.element >= mesh.num_vertices()) {
        throw Error(site_name(i) + ": vertex index " + std::to_string(site.element) + " is out of range [0, " +
                    std::to_string(mesh.num_vertices()) + ")");
      }
    } else {
      if (site.element < 0 || site.element >= mesh.num_faces()) {
        throw Error(site_name(i) + ": face index " + std::to_string(site.element) + " is out of range [0, " +
                    std::to_string(mesh.num_faces()) + ")");
      }
      Eigen::Vector3d& b = site.barycentric;
      if (!b.allFinite() || b.minCoeff() < -1e-12 || std::abs(b.sum() - 1) > 1e-9) {
        throw Error(site_name(i) + ": barycentric coordinates (" + std::to_string(b[0]) + ", " + std::to_string(b[1]) +
                    ", " + std::to_string(b[2]) + ") must be non-negative and sum to 1");
      }
      for (int c = 0; c < 3; ++c) b[c] = b[c] < 1e-14 ? 0.0 : b[c];
      b /= b.sum();
      const Index local_face = new_face[site.element];
      if (!pm.included(local_face)) {
        throw Error(site_name(i) + ": face " + std::to_string(site.element) +
                    " repeats a vertex index and takes no part in the surface");
      }
      int nonzero = 0, corner = 0;
      for (int c = 0; c < 3; ++c) {
        if (b[c] > 0) ++nonzero, corner = c;
      }
      if (nonzero == 1) {
        site = SurfacePoint::at_vertex(mesh.faces(site.element, corner));
      } else if (!has_area_from_lengths(pm.face_lengths(pm.face_records[local_face]))) {
        throw Error(site_name(i) + ": face " + std::to_string(site.element) +
                    " has zero area; place the site on a neighbouring face");
      }
    }
    if (site.kind == SurfacePoint::Kind::vertex && pm.vertex_face[new_vertex[site.element]] < 0) {
      throw Error(site_name(i) + ": vertex " + std::to_string(site.element) + " is used by no triangle");
    }
  }
  // Two sites at the same point would have no cell between them. The same
  // position is the same point only on the same vertex, edge or face: two
  // sides of a cut (a slit, a crease cut open) meet in space but not on the
  // surface.
  std::vector<std::size_t> order(result.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<Eigen::Vector3d> positions(result.size());
  std::vector<std::array<Index, 3>> carriers(result.size());
  for (std::size_t i = 0; i < result.size(); ++i) {
    positions[i] = result[i].position(mesh);
    carriers[i] = carrier(mesh, result[i]);
  }
  auto less = [&](std::size_t a, std::size_t b) {
    const Eigen::Vector3d &p = positions[a], &q = positions[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return carriers[a] != carriers[b] ? carriers[a] < carriers[b] : a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (positions[order[i]] == positions[order[i - 1]] && carriers[order[i]] == carriers[order[i - 1]]) {
      throw Error(site_name(std::min(order[i], order[i - 1])) + " and " + site_name(std::max(order[i], order[i - 1])) +
                  " are at the same point");
    }
  }
  return result;
}

/// The inverse of a permutation of 0 .. n-1.
std::vector<Index> inverse(const std::vector<Index>& permutation) {
  std::vector<Index> inverse(permutation.size());
  for (std::size_t i = 0; i < permutation.size(); ++i) inverse[permutation[i]] = static_cast<Index>(i);
  return inverse;
}

/// Renumbers per-vertex values in place: value v goes to old_vertex[v]
/// (following each cycle of the permutation; no second array at the peak).
template <class... Values>
void to_caller_numbering(const std::vector<Index>& old_vertex, std::vector<Values>&... values) {
  std::vector<bool> placed(old_vertex.size(), false);
  for (std::size_t start = 0; start < old_vertex.size(); ++start) {
    if (placed[start]) continue;
    // Carry start's values round its cycle: each lands where it belongs and
    // picks up the values that were there.
    auto carried = std::make_tuple(values[start]...);
    for (std::size_t to = static_cast<std::size_t>(old_vertex[start]);; to = static_cast<std::size_t>(old_vertex[to])) {
      placed[to] = true;
      std::apply([&](auto&... carry) { (std::swap(carry, values[to]), ...); }, carried);
      if (to == start) break;
    }
  }
}

/// Runs window-VTP from the sites (in the propagation's numbering) and fills
/// the field's per-face results in the caller's numbering, its per-vertex
/// ones still in the propagation's. Returns the windows; the rest of the
/// propagation's state is freed.
detail::WindowStore propagate_at_once(const detail::PropagationMesh& pm, const detail::LocalityOrder& order,
                                      const std::vector<SurfacePoint>& local_sites, const GeodesicOptions& options,
                                      GeodesicField& field) {
  const auto start = Clock::now();
  detail::WindowVtp vtp(pm, options);
  vtp.add_sites(local_sites);
  vtp.run();
  field.stats = vtp.stats();
  field.stats.propagation_seconds = seconds_since(start);

  const std::vector<bool> valid = vtp.valid_faces();
  field.valid_face.resize(order.old_face.size());
  for (std::size_t f = 0; f < order.old_face.size(); ++f) field.valid_face[order.old_face[f]] = valid[f];
  field.face_point_sources = vtp.point_sources();
  for (FacePointSource& source : field.face_point_sources) source.face = order.old_face[source.face];
  field.distance = vtp.distances();  // still in the propagation's numbering
  field.nearest_site = vtp.labels();
  std::stable_sort(field.face_point_sources.begin(), field.face_point_sources.end(),
                   [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  return vtp.take_windows();
}

/// The merge takes the edges in chunks of this many (in every group alike).
constexpr Index kMergeChunk = 8192;

/// One group's windows on the edges of one chunk.
struct GroupChunk {
  /// The edges holding windows, increasing; edge_end[i] is where the windows
  /// of edges[i] end in `windows` (each edge's sorted along it).
  std::vector<Index> edges;
  std::vector<Index> edge_end;
  std::vector<detail::Window> windows;  ///< Window::source indexes GroupResult::sources
};

/// What a group hands to the merge once its propagation is over.
struct GroupResult {
  std::vector<GroupChunk> chunks;  ///< by chunk of edges (freed as the merge writes them)
  std::vector<detail::WindowSource> sources;
  std::vector<FacePointSource> point_sources;
  GeodesicStats stats;
};

/// Walks the groups' windows in one chunk of edges, in increasing edge
/// order: for each edge, the groups holding windows there.
class GroupCursor {
 public:
  GroupCursor(const std::vector<GroupResult>& groups, Index chunk)
      : groups_(groups), chunk_(static_cast<std::size_t>(chunk)), at_(groups.size(), 0) {}
  /// Calls visit(g, windows of g on e) for each group holding windows on e,
  /// in group order, and returns how many did; e must not decrease.
  template <class Visit>
  int visit(Index e, Visit&& visit) {
    int holders = 0;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const GroupChunk& chunk = groups_[g].chunks[chunk_];
      std::size_t& i = at_[g];
      while (i < chunk.edges.size() && chunk.edges[i] < e) ++i;
      if (i == chunk.edges.size() || chunk.edges[i] != e) continue;
      const Index begin = i > 0 ? chunk.edge_end[i - 1] : 0;
      visit(g, std::span<const detail::Window>(chunk.windows.data() + begin,
                                               static_cast<std::size_t>(chunk.edge_end[i] - begin)));
      ++holders;
    }
    return holders;
  }

 private:
  const std::vector<GroupResult>& groups_;
  std::size_t chunk_;
  std::vector<std::size_t> at_;
};

/// Per edge, the lower envelope of the groups' windows, in group order (the
/// store's MMP trimming, ties to the earlier group): the same for any thread
/// count. Edges a group freed hold none: that group's site is strictly
/// nearest on both their faces (WindowVtp::away_from_other_groups), where
/// every other group's windows are longer. Then RWR over the merged field as
/// window-VTP ends it (every face inactive): a face is redundant where its
/// corners and every window on its edges have one site (Definition 3.1), and
/// the windows of edges whose faces are all redundant go (unless
/// `remove_redundant_windows` is false). Fills the field's
/// windows and returns per face (propagation numbering) whether it is valid.
/// Two passes over the edges (count, then write in place), so that the
/// merged windows are never held twice.
std::vector<bool> merge_group_windows(const detail::PropagationMesh& pm, std::vector<GroupResult>& groups,
                                      const std::vector<std::uint8_t>& freed, const std::vector<Index>& label,
                                      bool remove_redundant_windows, bool release_memory, GeodesicField& field) {
  const Index num_edges = pm.num_edges();
  constexpr Index kChunk = kMergeChunk;
  const Index num_chunks = (num_edges + kChunk - 1) / kChunk;
  constexpr Index kNoSite = detail::WindowStore::kNoSite, kMixedSites = detail::WindowStore::kMixedSites;
  tbb::enumerable_thread_specific<detail::WindowStore> scratch([] { return detail::WindowStore(1, false); });
  tbb::enumerable_thread_specific<std::vector<detail::WindowStore::Piece>> pieces;
  // Calls emit(window) for each merged window of edge e, in order.
  auto merge_edge = [&](GroupCursor& cursor, Index e, auto&& emit) {
    if (freed[static_cast<std::size_t>(e)] != 0) {
      cursor.visit(e, [](std::size_t, std::span<const detail::Window>) {});
      return;
    }
    std::array<std::pair<std::size_t, std::span<const detail::Window>>, 8> held;
    int holders = 0, extra = 0;
    cursor.visit(e, [&](std::size_t g, std::span<const detail::Window> windows) {
      if (holders < static_cast<int>(held.size()))
        held[static_cast<std::size_t>(holders++)] = {g, windows};
      else
        ++extra;  // more than 8 groups on one edge: merged below with a fresh walk
    });
    if (holders == 1) {  // as the group left it
      const GroupResult& group = groups[held[0].first];
      for (const detail::Window& w : held[0].second) emit(w, group.sources[w.source]);
      return;
    }
    if (holders == 0) return;
    detail::WindowStore& store = scratch.local();
    std::vector<detail::WindowStore::Piece>& created = pieces.local();
    const double length = pm.edge_length(e);
    auto insert = [&](std::size_t g, std::span<const detail::Window> windows) {
      for (const detail::Window& w : windows) {
        const detail::WindowSource& source = groups[g].sources[w.source];
        detail::Window copy = w;
        copy.source = store.add_source(source.sigma, source.site);
        created.clear();
        store.insert(0, copy, source, length, created);
      }
    };
    if (extra == 0) {
      for (int i = 0; i < holders; ++i)
        insert(held[static_cast<std::size_t>(i)].first, held[static_cast<std::size_t>(i)].second);
    } else {
      GroupCursor again(groups, e / kChunk);
      again.visit(e, insert);
    }
    for (const detail::Window& w : store.on_edge(0)) emit(w, store.source_of(w));
    store.clear_edge(0);
    store.clear_sources();
  };

  // Pass 1: how many windows each edge keeps (counted in window_begin[e + 1],
  // summed below), and whether any is of a site other than its end v0's
  // nearest (a face is redundant only where all its corners have one site:
  // then v0's of each of its edges).
  field.window_begin.assign(static_cast<std::size_t>(num_edges) + 1, 0);
  std::vector<std::uint8_t> foreign_windows(static_cast<std::size_t>(num_edges), 0);
  tbb::parallel_for(Index{0}, num_chunks, [&](Index c) {
    const Index first_edge = c * kChunk, end_edge = std::min(num_edges, first_edge + kChunk);
    GroupCursor cursor(groups, c);
    for (Index e = first_edge; e < end_edge; ++e) {
      Index site = kNoSite;
      merge_edge(cursor, e, [&](const detail::Window&, const detail::WindowSource& source) {
        ++field.window_begin[static_cast<std::size_t>(e) + 1];
        site = site == kNoSite || site == source.site ? source.site : kMixedSites;
      });
      if (site != kNoSite) foreign_windows[static_cast<std::size_t>(e)] = site != label[pm.edge_vertices(e)[0]];
    }
  });

  // Redundant faces, and the edges between them.
  const Index num_faces = pm.num_faces();
  std::vector<std::uint8_t> redundant(static_cast<std::size_t>(num_faces), 0);
  tbb::parallel_for(Index{0}, num_faces, [&](Index f) {
    if (!pm.included(f)) return;
    const Index site = label[pm.vertex(f, 0)];
    if (site < 0 || label[pm.vertex(f, 1)] != site || label[pm.vertex(f, 2)] != site) return;
    for (const Index e : pm.face_edges(f)) {
      if (foreign_windows[static_cast<std::size_t>(e)] != 0) return;
    }
    redundant[static_cast<std::size_t>(f)] = 1;
  });
  foreign_windows = std::vector<std::uint8_t>();
  for (Index e = 0; e < num_edges; ++e) {
    const std::array<Index, 2> faces = pm.edge_faces[e];
    const bool dropped = remove_redundant_windows && (faces[0] < 0 || redundant[faces[0]] != 0) &&
                         (faces[1] < 0 || redundant[faces[1]] != 0);
    field.window_begin[e + 1] = field.window_begin[e] + (dropped ? 0 : field.window_begin[e + 1]);
  }

  // Pass 2: the windows, in place, a wave of chunks at a time: each wave's
  // part of the array is touched (made resident) only as the groups' windows
  // of those chunks go, so that the two are not held whole at once.
  field.windows.reserve(static_cast<std::size_t>(field.window_begin[num_edges]));
  constexpr Index kWave = 16;
  for (Index wave = 0; wave < num_chunks; wave += kWave) {
    const Index wave_end = std::min(num_chunks, wave + kWave);
    field.windows.resize(static_cast<std::size_t>(field.window_begin[std::min(num_edges, wave_end * kChunk)]));
    tbb::parallel_for(wave, wave_end, [&](Index c) {
      const Index first_edge = c * kChunk, end_edge = std::min(num_edges, first_edge + kChunk);
      GroupCursor cursor(groups, c);
      for (Index e = first_edge; e < end_edge; ++e) {
        if (field.window_begin[e] == field.window_begin[e + 1]) continue;  // none kept
        Index out = field.window_begin[e];
        merge_edge(cursor, e, [&](const detail::Window& w, const detail::WindowSource& source) {
          field.windows[static_cast<std::size_t>(out++)] = {w.b0,       w.b1,         w.source_x,
                                                            w.source_y, source.sigma, source.site};
        });
      }
      for (GroupResult& group : groups) group.chunks[static_cast<std::size_t>(c)] = GroupChunk();
    });
    // The groups' chunks just freed lie in the heap (their threads' arenas)
    // while the merged windows take fresh pages: hand them back, or the two
    // would be resident together.
    if (release_memory) trim_heap();
  }
  std::vector<bool> valid(static_cast<std::size_t>(num_faces), false);
  for (Index f = 0; f < num_faces; ++f) {
    valid[f] = pm.included(f) && label[pm.vertex(f, 0)] >= 0 && redundant[static_cast<std::size_t>(f)] == 0;
  }
  return valid;
}

/// Window-VTP in `num_groups` groups of sites at once (docs/algorithms.md,
/// "Parallel propagation"), merged into the field as propagate_at_once
/// leaves it, windows included.
void propagate_in_groups(const TriangleMesh& mesh, const detail::PropagationMesh& pm,
                         const detail::LocalityOrder& order, const std::vector<SurfacePoint>& local_sites,
                         int num_groups, const GeodesicOptions& options, GeodesicField& field) {
  const auto start = Clock::now();
  std::vector<Eigen::Vector3d> positions(field.sites.size());
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = field.sites[i].position(mesh);
  const std::vector<int> group_of = detail::partition_sites(positions, num_groups);
  const detail::SiteTree tree(positions, group_of);
  const std::vector<double> bound = detail::surface_path_upper_bound(pm, local_sites);

  const auto num_vertices = static_cast<std::size_t>(pm.num_vertices());
  field.distance.assign(num_vertices, std::numeric_limits<double>::infinity());
  field.nearest_site.assign(num_vertices, -1);
  std::vector<std::uint8_t> freed(static_cast<std::size_t>(pm.num_edges()), 0);
  std::vector<GroupResult> results(static_cast<std::size_t>(num_groups));
  // Progress: the groups done, and each running one's share of the faces.
  std::mutex mutex;  // guards the merged vertex arrays, `freed` and progress
  std::vector<double> group_progress(static_cast<std::size_t>(num_groups), 0.0);
  double reported = 0;

  auto run_group = [&](int g) {
    std::vector<SurfacePoint> sites;
    std::vector<Index> labels;
    for (std::size_t i = 0; i < local_sites.size(); ++i) {
      if (group_of[i] != g) continue;
      sites.push_back(local_sites[i]);
      labels.push_back(static_cast<Index>(i));
    }
    GeodesicOptions group_options = options;
    // A group's store is small; trimming the heap, which is process-wide,
    // would only hold up the other groups.
    group_options.release_memory_between_phases = false;
    if (options.progress) {
      group_options.progress = [&, g](double fraction) {
        const std::lock_guard lock(mutex);
        group_progress[static_cast<std::size_t>(g)] = std::min(1.0, fraction * num_groups);
        double sum = 0;
        for (const double p : group_progress) sum += p;
        reported = std::max(reported, std::min(1.0, sum / num_groups));
        return options.progress(reported);
      };
    }
    GroupResult& result = results[static_cast<std::size_t>(g)];
    // The propagation's state goes once its vertex distances are merged, and
    // the free blocks of its store once the windows are packed together,
    // before the windows are copied out: the copy is not held beside either.
    detail::WindowStore store = [&] {
      const detail::GroupLimits limits{bound, &tree, g, &mesh, order.old_vertex};
      detail::WindowVtp vtp(pm, group_options, &limits);
      vtp.add_sites(sites, labels);
      vtp.run();
      result.stats = vtp.stats();
      result.point_sources = vtp.point_sources();
      // Smallest distance, ties to the smaller site: the same in any order.
      const std::lock_guard lock(mutex);
      for (const Index v : vtp.reached()) {
        const double distance = vtp.distance(v);
        const Index label = vtp.label(v);
        if (distance < field.distance[v] || (distance == field.distance[v] && label < field.nearest_site[v])) {
          field.distance[v] = distance;
          field.nearest_site[v] = label;
        }
      }
      for (const Index e : vtp.freed_edges()) freed[static_cast<std::size_t>(e)] = 1;
      return vtp.take_windows();
    }();
    store.compact();
    {
      // Edge by edge (not WindowStore::drain, which sorts the edges by
      // address), each chunk sized first; only the edges holding windows are
      // read (a group holds windows on a few of the mesh's).
      const std::vector<Index> holding = store.edges_with_windows();
      result.chunks.resize(static_cast<std::size_t>((pm.num_edges() + kMergeChunk - 1) / kMergeChunk));
      for (std::size_t first = 0; first < holding.size();) {
        const Index c = holding[first] / kMergeChunk;
        std::size_t end = first, windows = 0;
        for (; end < holding.size() && holding[end] / kMergeChunk == c; ++end)
          windows += store.on_edge(holding[end]).size();
        GroupChunk& chunk = result.chunks[static_cast<std::size_t>(c)];
        chunk.edges.assign(holding.begin() + static_cast<std::ptrdiff_t>(first),
                           holding.begin() + static_cast<std::ptrdiff_t>(end));
        chunk.edge_end.reserve(end - first);
        chunk.windows.reserve(windows);
        for (const Index e : chunk.edges) {
          const std::span<const detail::Window> on_edge = store.on_edge(e);
          chunk.windows.insert(chunk.windows.end(), on_edge.begin(), on_edge.end());
          chunk.edge_end.push_back(static_cast<Index>(chunk.windows.size()));
        }
        first = end;
      }
      result.sources.resize(store.num_sources());
      for (std::size_t i = 0; i < store.num_sources(); ++i) {
        result.sources[i] = store.source(static_cast<std::uint32_t>(i));
      }
    }
  };
  tbb::parallel_for(0, num_groups, 1, [&](int g) {
    run_group(g);
    // The group's propagation state is freed now, in its thread's arena:
    // handed back, it is not resident beside the groups that follow.
    if (options.release_memory_between_phases) trim_heap();
  });

  const std::vector<bool> valid =
      merge_group_windows(pm, results, freed, field.nearest_site, options.remove_redundant_windows,
                          options.release_memory_between_phases, field);
  field.valid_face.resize(order.old_face.size());
  for (std::size_t f = 0; f < order.old_face.size(); ++f) field.valid_face[order.old_face[f]] = valid[f];

  GeodesicStats& stats = field.stats;
  for (GroupResult& result : results) {
    stats.windows_created += result.stats.windows_created;
    stats.peak_windows += result.stats.peak_windows;
    stats.peak_window_bytes += result.stats.peak_window_bytes;
    stats.vertices_popped += result.stats.vertices_popped;
    stats.pseudo_sources += result.stats.pseudo_sources;
    stats.faces_inactive += result.stats.faces_inactive;
    for (FacePointSource& source : result.point_sources) {
      source.face = order.old_face[source.face];
      field.face_point_sources.push_back(source);
    }
    result.point_sources = std::vector<FacePointSource>();
  }
  std::stable_sort(field.face_point_sources.begin(), field.face_point_sources.end(),
                   [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  stats.windows_stored = static_cast<std::int64_t>(field.windows.size());
  stats.propagation_seconds = seconds_since(start);
  if (options.progress && !options.progress(1.0)) throw Cancelled("geodesic computation cancelled");
}

/// The retained windows into the field, grouped by edge, emptying the store
/// as they go (see WindowStore::drain: the two copies would otherwise be the
/// peak of the whole computation).
void move_windows(detail::WindowStore& store, Index num_edges, GeodesicField& field) {
  constexpr int kRounds = 2;
  field.window_begin.assign(static_cast<std::size_t>(num_edges) + 1, 0);
  field.windows.reserve(static_cast<std::size_t>(store.live()));
  Index next_edge = 0;
  auto take = [&](Index edge, std::span<const detail::Window> windows) {
    for (; next_edge <= edge; ++next_edge) field.window_begin[next_edge] = static_cast<Index>(field.windows.size());
    for (const detail::Window& w : windows) {
      const detail::WindowSource& source = store.source_of(w);
      field.windows.push_back({w.b0, w.b1, w.source_x, w.source_y, source.sigma, source.site});
    }
  };
  store.drain(take, kRounds);
  for (; next_edge <= num_edges; ++next_edge) field.window_begin[next_edge] = static_cast<Index>(field.windows.size());
}

/// compute_geodesic_field on a prepared surface and its topology. For a
/// single field (`disposable`, holding `prepared`, and no topology yet), the
/// topology is made once propagation is over and the surface goes before
/// the windows are moved out: the peak is then what one field needs.
GeodesicField compute_field(const TriangleMesh& mesh, const detail::PreparedSurface& prepared,
                            std::shared_ptr<const SurfaceTopology> topology, std::span<const SurfacePoint> sites,
                            const GeodesicOptions& options, std::optional<detail::PreparedSurface>* disposable) {
  const auto start = Clock::now();
  // Propagation runs on the surface's copy renumbered for memory locality;
  // everything it returns is mapped back to the caller's numbering.
  const detail::PropagationMesh& pm = prepared.propagation;
  const detail::LocalityOrder& order = prepared.order;
  GeodesicField field;
  std::vector<SurfacePoint> local_sites;
  {
    // The maps from the caller's numbering, needed for the sites alone: made
    // for each field rather than held with the surface.
    const std::vector<Index> new_face = inverse(order.old_face), new_vertex = inverse(order.old_vertex);
    field.sites = validated_sites(mesh, pm, new_face, new_vertex, sites);
    local_sites = field.sites;
    for (SurfacePoint& site : local_sites) {
      site.element = site.kind == SurfacePoint::Kind::vertex ? new_vertex[site.element] : new_face[site.element];
    }
  }
  const double setup_seconds = seconds_since(start);
  // What the caller freed before (and the inverse maps) goes back too: the
  // groups propagate on worker threads, whose heaps cannot reuse this one's.
  if (options.release_memory_between_phases) trim_heap();

  const int num_groups = detail::site_group_count(local_sites.size(), options.site_groups);
  std::optional<detail::WindowStore> windows;
  if (num_groups == 1) {
    windows.emplace(propagate_at_once(pm, order, local_sites, options, field));
    windows->compact();
  } else {
    propagate_in_groups(mesh, pm, order, local_sites, num_groups, options, field);
  }
  to_caller_numbering(order.old_vertex, field.distance, field.nearest_site);
  field.stats.site_groups = num_groups;
  field.stats.setup_seconds = setup_seconds;
  const Index num_edges = pm.num_edges();
  if (disposable != nullptr) {
    detail::PreparedSurface& surface = **disposable;
    // What only propagation needed goes first.
    surface.propagation.vertex_face = std::vector<Index>();
    surface.propagation.fan_offsets = decltype(surface.propagation.fan_offsets)();
    surface.propagation.extra_fans = std::vector<std::array<Index, 2>>();
    surface.propagation.is_pseudo_source = std::vector<std::uint8_t>();
    if (!topology)
      topology = std::make_shared<const SurfaceTopology>(detail::caller_topology(surface.propagation, surface.order));
    disposable->reset();
  }
  field.topology = std::move(topology);
  field.edge_faces = field.topology->edge_faces;
  field.edge_length = field.topology->edge_length;
  field.face_edges = field.topology->face_edges;
  if (options.release_memory_between_phases) trim_heap();  // the propagation's state (and the surface given up)
  if (windows) move_windows(*windows, num_edges, field);
  field.stats.total_seconds = seconds_since(start);
  return field;
}

}  // namespace

GeodesicField compute_geodesic_field(const GeodesicSurface& surface, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options) {
  return compute_field(surface.mesh(), surface.prepared(), surface.topology(), sites, options, nullptr);
}

GeodesicField compute_geodesic_field(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                     const GeodesicOptions& options) {
  const auto start = Clock::now();
  std::optional<detail::PreparedSurface> prepared(detail::prepare_surface(mesh));
  const double preparation_seconds = seconds_since(start);
  if (options.release_memory_between_phases) trim_heap();  // the preparation's scratch
  GeodesicField field = compute_field(mesh, *prepared, nullptr, sites, options, &prepared);
  field.stats.setup_seconds += preparation_seconds;
  field.stats.total_seconds += preparation_seconds;
  return field;
}

PointDistance query(const GeodesicField& field, const TriangleMesh& mesh, const SurfacePoint& point) {
  if (point.kind == SurfacePoint::Kind::vertex) {
    return {field.distance.at(point.element), field.nearest_site.at(point.element)};
  }
  const Index f = point.element;
  PointDistance best{std::numeric_limits<double>::infinity(), -1};
  auto consider = [&](double d, Index site) {
    if (d < best.distance) best = {d, site};
  };
  // Through the face's corners (exact where the path passes a corner).
  const Eigen::Vector3d p = point.position(mesh);
  for (int c = 0; c < 3; ++c) {
    const Index v = mesh.faces(f, c);
    consider(field.distance[v] + (p - mesh.vertices.row(v).transpose()).norm(), field.nearest_site[v]);
  }
  if (field.face_edges[f][0] < 0) return best;
  // Point sources in the face or on its edges.
  const auto [first, last] =
      std::equal_range(field.face_point_sources.begin(), field.face_point_sources.end(), FacePointSource{f},
                       [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  for (auto it = first; it != last; ++it) {
    const Eigen::Vector3d q =
        SurfacePoint::in_face(f, it->barycentric[0], it->barycentric[1], it->barycentric[2]).position(mesh);
    consider(it->sigma + (q - p).norm(), it->site);
  }
  // Through the windows entering the face: lay the face out on each edge's
  // frame and look through the window's interval.
  for (int k = 0; k < 3; ++k) {
    const Index e = field.face_edges[f][k];
    const int side = field.edge_faces[e][0] == f ? 0 : 1;
    const auto [v0, v1] = field.edge_vertices(mesh, e);
    const Eigen::Vector3d a = mesh.vertices.row(v0).transpose(), b = mesh.vertices.row(v1).transpose();
    const double length = field.edge_length[e];
    if (!(length > 0)) continue;
    const Eigen::Vector3d axis = (b - a) / (b - a).norm();
    const Eigen::Vector3d r = p - a;
    const double x = r.dot(axis);
    const double y_abs = (r - x * axis).norm();
    const double y = side == 0 ? y_abs : -y_abs;  // the face lies on its side of the edge
    for (Index i = field.window_begin[e]; i < field.window_begin[e + 1]; ++i) {
      const EdgeWindow& w = field.windows[i];
      if ((w.source_y < 0) != (side == 0)) continue;  // leaves this face
      // Where the segment from the source to the point crosses the edge.
      const double t = -w.source_y / (y - w.source_y);
      const double crossing = w.source_x + (x - w.source_x) * t;
      if (crossing < w.b0 - 1e-12 * length || crossing > w.b1 + 1e-12 * length) continue;
      consider(w.sigma + std::hypot(x - w.source_x, y - w.source_y), w.site);
    }
  }
  return best;
}

}  // namespace geodual::voronoi
