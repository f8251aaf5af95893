#include "geodual/voronoi/voronoi_diagram.hpp"

#include "face_boundary.hpp"
#include "geodual/mesh/detail/progress_from_threads.hpp"
#include "geodual/mesh/detail/trim_heap.hpp"
#include "geodual/mesh/error.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <mutex>
#include <utility>

namespace geodual::voronoi {
namespace {

using detail::BoundaryGraph;
using detail::BoundaryNode;
using detail::BoundaryPiece;
using detail::EdgeCrossingStore;
using detail::FaceBoundaryTracer;
using detail::TracedChunk;

// Work is split into fixed chunks, independent of the number of threads, and
// merged in chunk order: the diagram is the same bits for any thread count,
// and the same as tracing the faces one by one in order.
constexpr Index faces_per_chunk = 256;
constexpr Index edges_per_chunk = 2048;

using Tracers = tbb::enumerable_thread_specific<FaceBoundaryTracer>;

Index chunk_count(Index items, Index per_chunk) { return (items + per_chunk - 1) / per_chunk; }

/// GeodesicOptions::progress during the extraction: asked with 1 (every face
/// is reached by now) on the calling thread only (see ProgressFromThreads),
/// every 64th time it comes here. Work stops at the next edge or face, and
/// stop_if_refused() throws geodual::Cancelled.
class CancelCheck {
 public:
  explicit CancelCheck(const std::function<bool(double)>& progress) : progress_(progress) {}

  /// False once refused.
  bool keep_going() {
    if (!progress_.asks() || ++calls_ % 64 != 0) return !progress_.refused();
    return progress_.keep_going(1.0);
  }

  void stop_if_refused() const {
    if (progress_.refused()) throw Cancelled("Voronoi diagram extraction cancelled");
  }

 private:
  ProgressFromThreads progress_;
  std::uint64_t calls_ = 0;  ///< on the calling thread only
};

/// Computes in parallel the crossings of every edge marked in `needed` that
/// `store` lacks, and appends them to it.
/// With `release_memory`, hands the merged chunks' memory back as it goes.
void compute_edge_crossings(const std::vector<std::uint8_t>& needed, Tracers& tracers, EdgeCrossingStore& store,
                            bool release_memory, CancelCheck& cancel) {
  struct Found {
    std::vector<Index> edges, counts;
    std::vector<detail::EdgeCrossing> crossings;
  };
  const Index num_edges = static_cast<Index>(needed.size());
  std::vector<Found> found(static_cast<std::size_t>(chunk_count(num_edges, edges_per_chunk)));
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t chunk) {
    FaceBoundaryTracer& tracer = tracers.local();
    Found& out = found[chunk];
    const Index begin = static_cast<Index>(chunk) * edges_per_chunk;
    const Index end = std::min(num_edges, begin + edges_per_chunk);
    for (Index e = begin; e < end; ++e) {
      if (!needed[e] || store.computed(e)) continue;
      if (!cancel.keep_going()) return;
      const std::size_t before = out.crossings.size();
      tracer.find_edge_crossings(e, out.crossings);
      out.edges.push_back(e);
      out.counts.push_back(static_cast<Index>(out.crossings.size() - before));
    }
    // Every chunk waits for the merge: without the slack of its growth.
    out.crossings.shrink_to_fit();
  });
  cancel.stop_if_refused();
  // Sized once (a doubling array would hold up to twice the crossings and
  // leave its outgrown copies behind); the chunks are freed as they are
  // merged, and their memory handed back now and then, so that the lists
  // and the store are not both held whole.
  std::size_t added = 0;
  for (const Found& chunk : found) added += chunk.crossings.size();
  store.crossings.reserve(store.crossings.size() + added);
  constexpr std::size_t kChunksBetweenTrims = 64;
  for (std::size_t c = 0; c < found.size(); ++c) {
    Found& chunk = found[c];
    if (release_memory && c % kChunksBetweenTrims == kChunksBetweenTrims - 1) trim_heap();
    Index next = static_cast<Index>(store.crossings.size());
    for (std::size_t i = 0; i < chunk.edges.size(); ++i) {
      store.set(chunk.edges[i], next, chunk.counts[i]);
      next += chunk.counts[i];
    }
    store.crossings.insert(store.crossings.end(), chunk.crossings.begin(), chunk.crossings.end());
    chunk = Found{};
  }
  if (release_memory) trim_heap();  // the chunks' lists, scattered through the heap
}

/// The merged graph under construction, and where each edge crossing's node is in it.
class GraphMerger {
 public:
  GraphMerger(const TriangleMesh& mesh, const GeodesicField& field, EdgeCrossingStore& store, BoundaryGraph& graph)
      : mesh_(mesh), field_(field), store_(store), graph_(graph) {}

  /// The crossings of `edge`, computed now (by `tracer`) if not yet; gives them
  /// nodes the first time an edge is asked for, as tracing one face after
  /// another in order would.
  std::span<const detail::EdgeCrossing> crossings(Index edge, FaceBoundaryTracer& tracer) {
    if (!store_.computed(edge)) {
      const auto first = static_cast<Index>(store_.crossings.size());
      tracer.find_edge_crossings(edge, store_.crossings);
      store_.set(edge, first, static_cast<Index>(store_.crossings.size()) - first);
    }
    give_nodes(edge);
    return store_.of(edge);
  }

  void give_nodes(Index edge) {
    const std::span<const detail::EdgeCrossing> along = store_.of(edge);
    if (along.empty()) return;
    const auto first = static_cast<Index>(along.data() - store_.crossings.data());
    node_of_crossing_.resize(store_.crossings.size(), -1);
    if (node_of_crossing_[first] >= 0) return;
    for (Index i = first; i < first + static_cast<Index>(along.size()); ++i) {
      node_of_crossing_[i] = static_cast<Index>(graph_.nodes.size());
      graph_.nodes.push_back(detail::edge_crossing_node(mesh_, field_, edge, store_.crossings[i]));
    }
  }

  /// Appends a chunk's graph: its nodes face by face after the nodes of the
  /// face's edge crossings met first there, then its pieces and points.
  void append(const TracedChunk& chunk, const GeodesicField& field) {
    const BoundaryGraph& part = chunk.graph;
    const Index vertex_site_offset = static_cast<Index>(graph_.vertex_sites.size());
    const Index point_offset = static_cast<Index>(graph_.points.size());
    node_of_local_.resize(part.nodes.size());
    Index local = 0;
    for (const TracedChunk::Face& face : chunk.faces) {
      for (const Index e : field.face_edges[face.face]) give_nodes(e);
      for (; local < face.node_end; ++local) {
        node_of_local_[local] = static_cast<Index>(graph_.nodes.size());
        BoundaryNode node = part.nodes[local];
        if (node.kind == BoundaryNode::Kind::voronoi_vertex) node.site_begin += vertex_site_offset;
        graph_.nodes.push_back(node);
      }
    }
    graph_.vertex_sites.insert(graph_.vertex_sites.end(), part.vertex_sites.begin(), part.vertex_sites.end());
    graph_.points.insert(graph_.points.end(), part.points.begin(), part.points.end());
    graph_.point_locations.insert(graph_.point_locations.end(), part.point_locations.begin(),
                                  part.point_locations.end());
    auto node_of = [&](Index reference) {
      return reference >= 0 ? node_of_local_[reference] : node_of_crossing_[detail::crossing_of_reference(reference)];
    };
    for (BoundaryPiece piece : part.pieces) {
      piece.from = node_of(piece.from);
      piece.to = node_of(piece.to);
      piece.point_begin += point_offset;
      piece.point_end += point_offset;
      graph_.pieces.push_back(piece);
    }
  }

 private:
  const TriangleMesh& mesh_;
  const GeodesicField& field_;
  EdgeCrossingStore& store_;
  BoundaryGraph& graph_;
  std::vector<Index> node_of_crossing_;  ///< per store crossing, -1 until given a node
  std::vector<Index> node_of_local_;     ///< scratch: per node of the chunk being appended
};

/// Adds a chunk's cell contributions, in order, and its statistics.
void add_contributions(const TracedChunk& chunk, VoronoiDiagram& diagram) {
  for (const detail::CellContribution& c : chunk.contributions) {
    diagram.cell_area[c.site] += c.area;
    diagram.cell_energy[c.site] += c.integrals.energy;
    diagram.cell_log_moment[c.site] += c.integrals.log_moment;
  }
  VoronoiStats& stats = diagram.stats;
  stats.boundary_faces += chunk.stats.boundary_faces;
  stats.refined_faces += chunk.stats.refined_faces;
  stats.unresolved_regions += chunk.stats.unresolved_regions;
  stats.max_vertex_residual = std::max(stats.max_vertex_residual, chunk.stats.max_vertex_residual);
  stats.max_area_mismatch = std::max(stats.max_area_mismatch, chunk.stats.max_area_mismatch);
}

/// Chains the per-face pieces into arcs: through every node where exactly two
/// pieces meet, stopping at Voronoi vertices and at the mesh boundary.
void chain_arcs(const BoundaryGraph& graph, VoronoiDiagram& diagram) {
  const Index num_nodes = static_cast<Index>(graph.nodes.size());
  const Index num_pieces = static_cast<Index>(graph.pieces.size());
  std::vector<Index> begin(num_nodes + 1, 0);
  for (const BoundaryPiece& piece : graph.pieces) {
    ++begin[piece.from + 1];
    ++begin[piece.to + 1];
  }
  for (Index n = 0; n < num_nodes; ++n) begin[n + 1] += begin[n];
  std::vector<Index> incident(begin.back());
  std::vector<Index> fill(begin.begin(), begin.end() - 1);
  for (Index p = 0; p < num_pieces; ++p) {
    incident[fill[graph.pieces[p].from]++] = p;
    incident[fill[graph.pieces[p].to]++] = p;
  }

  std::vector<Index> vertex_of_node(num_nodes, -1);
  for (Index n = 0; n < num_nodes; ++n) {
    const BoundaryNode& node = graph.nodes[n];
    if (node.kind != BoundaryNode::Kind::voronoi_vertex) continue;
    vertex_of_node[n] = static_cast<Index>(diagram.vertices.size());
    VoronoiVertex vertex;
    vertex.location = node.location;
    vertex.position = node.position;
    vertex.distance = node.distance;
    vertex.site_begin = static_cast<Index>(diagram.vertex_sites.size());
    vertex.degree = node.degree;
    diagram.vertex_sites.insert(diagram.vertex_sites.end(), graph.vertex_sites.begin() + node.site_begin,
                                graph.vertex_sites.begin() + node.site_begin + node.degree);
    diagram.vertices.push_back(vertex);
  }
  auto stops_at = [&](Index n) { return vertex_of_node[n] >= 0 || begin[n + 1] - begin[n] != 2; };

  // Each arc has its start node's point, then per piece the piece's points
  // and its end node's; there are no more arcs than pieces. Sized once: a
  // doubling array would leave its outgrown copies behind at the peak.
  const std::size_t most_points = graph.points.size() + 2 * static_cast<std::size_t>(num_pieces);
  diagram.points.reserve(most_points);
  diagram.point_locations.reserve(most_points);
  std::vector<std::uint8_t> used(num_pieces, 0);
  auto walk = [&](Index start, Index first_piece) {
    VoronoiArc arc;
    arc.start_vertex = vertex_of_node[start];
    arc.point_begin = static_cast<Index>(diagram.points.size());
    diagram.points.push_back(graph.nodes[start].position);
    diagram.point_locations.push_back(graph.nodes[start].location);
    Index node = start, piece_index = first_piece;
    bool first = true;
    while (true) {
      used[piece_index] = 1;
      const BoundaryPiece& piece = graph.pieces[piece_index];
      const bool forward = piece.from == node;
      if (first) {
        arc.left_site = forward ? piece.left : piece.right;
        arc.right_site = forward ? piece.right : piece.left;
        first = false;
      }
      if (forward) {
        for (Index i = piece.point_begin; i < piece.point_end; ++i) {
          diagram.points.push_back(graph.points[i]);
          diagram.point_locations.push_back(graph.point_locations[i]);
        }
      } else {
        for (Index i = piece.point_end; i-- > piece.point_begin;) {
          diagram.points.push_back(graph.points[i]);
          diagram.point_locations.push_back(graph.point_locations[i]);
        }
      }
      arc.length += piece.length;
      node = forward ? piece.to : piece.from;
      diagram.points.push_back(graph.nodes[node].position);
      diagram.point_locations.push_back(graph.nodes[node].location);
      if (stops_at(node)) {
        arc.end_vertex = vertex_of_node[node];
        break;
      }
      if (node == start) {
        arc.closed = true;
        break;
      }
      Index next = -1;
      for (Index i = begin[node]; i < begin[node + 1]; ++i) {
        if (!used[incident[i]]) next = incident[i];
      }
      if (next < 0) break;
      piece_index = next;
    }
    arc.point_end = static_cast<Index>(diagram.points.size());
    diagram.arcs.push_back(arc);
  };
  for (Index n = 0; n < num_nodes; ++n) {
    if (!stops_at(n)) continue;
    for (Index i = begin[n]; i < begin[n + 1]; ++i) {
      if (!used[incident[i]]) walk(n, incident[i]);
    }
  }
  // What is left are closed loops through crossings only: two cells, one
  // inside the other or around a handle.
  for (Index p = 0; p < num_pieces; ++p) {
    if (!used[p]) walk(graph.pieces[p].from, p);
  }
}

void collect_adjacency(VoronoiDiagram& diagram) {
  std::vector<CellAdjacency> pairs;
  pairs.reserve(diagram.arcs.size());
  for (const VoronoiArc& arc : diagram.arcs) {
    if (arc.left_site < 0 || arc.right_site < 0 || arc.left_site == arc.right_site) continue;
    pairs.push_back({std::min(arc.left_site, arc.right_site), std::max(arc.left_site, arc.right_site), arc.length, 1});
  }
  std::sort(pairs.begin(), pairs.end(), [](const CellAdjacency& a, const CellAdjacency& b) {
    return std::pair(a.site_a, a.site_b) < std::pair(b.site_a, b.site_b);
  });
  for (const CellAdjacency& pair : pairs) {
    if (!diagram.adjacency.empty() && diagram.adjacency.back().site_a == pair.site_a &&
        diagram.adjacency.back().site_b == pair.site_b) {
      diagram.adjacency.back().boundary_length += pair.boundary_length;
      diagram.adjacency.back().arc_count += 1;
    } else {
      diagram.adjacency.push_back(pair);
    }
  }
}

}  // namespace

VoronoiDiagram extract_voronoi(const TriangleMesh& mesh, GeodesicField field, const VoronoiOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  VoronoiDiagram diagram;
  diagram.field = std::move(field);
  const GeodesicField& f = diagram.field;
  const bool release_memory = options.geodesic.release_memory_between_phases;
  CancelCheck cancel(options.geodesic.progress);
  diagram.stats.geodesic_seconds = f.stats.total_seconds;
  diagram.cell_area.assign(f.sites.size(), 0.0);

  diagram.cell_energy.assign(f.sites.size(), 0.0);
  diagram.cell_log_moment.assign(f.sites.size(), Eigen::Vector3d::Zero());

  const std::vector<Eigen::Vector3d> site_normals = detail::site_normals(mesh, f);
  EdgeCrossingStore store(f.edge_length.size());
  Tracers tracers([&] { return FaceBoundaryTracer(mesh, f, options, store, site_normals); });
  BoundaryGraph graph;
  GraphMerger merger(mesh, f, store, graph);
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  const std::size_t num_edges = f.edge_length.size();

  // Faces that may hold a boundary (1), and the crossings of their edges.
  std::vector<std::uint8_t> traced(num_faces, 0);
  tbb::parallel_for(tbb::blocked_range<Index>(0, num_faces), [&](const tbb::blocked_range<Index>& range) {
    const FaceBoundaryTracer& tracer = tracers.local();
    for (Index face = range.begin(); face < range.end(); ++face) traced[face] = tracer.may_hold_boundary(face);
  });
  std::vector<std::uint8_t> needed(num_edges, 0);
  for (Index face = 0; face < num_faces; ++face) {
    if (!traced[face]) continue;
    for (const Index e : f.face_edges[face]) needed[e] = 1;
  }
  compute_edge_crossings(needed, tracers, store, release_memory, cancel);
  // Nearly every node of the graph is an edge crossing, found by now but for
  // the few of the faces next to these (2, below); the rest are Voronoi
  // vertices (two per cell) and the crossings inside refined faces, fewer
  // than three per cell; there are about as many pieces as nodes. Sized
  // up front: these are the extraction's largest arrays, and doubling one
  // briefly holds its old and new copies.
  const std::size_t expected_nodes = store.crossings.size() + store.crossings.size() / 8 + 6 * f.sites.size();
  graph.nodes.reserve(expected_nodes);
  graph.pieces.reserve(expected_nodes);
  for (Index face = 0; face < num_faces; ++face) {
    if (!traced[face]) continue;
    for (const Index e : f.face_edges[face]) merger.give_nodes(e);
  }
  // Then faces (2) next to an edge a boundary crosses whose other face is
  // traced; in face order, as a face marked here counts for later ones.
  FaceBoundaryTracer& serial_tracer = tracers.local();
  for (Index face = 0; face < num_faces; ++face) {
    if (traced[face] || f.face_edges[face][0] < 0) continue;
    if (!cancel.keep_going()) cancel.stop_if_refused();
    for (const Index e : f.face_edges[face]) {
      for (const Index neighbour : f.edge_faces[e]) {
        if (neighbour >= 0 && neighbour != face && traced[neighbour] && !merger.crossings(e, serial_tracer).empty()) {
          traced[face] = 2;
        }
      }
    }
  }
  for (Index face = 0; face < num_faces; ++face) {
    if (traced[face] != 2) continue;
    for (const Index e : f.face_edges[face]) needed[e] = 1;
  }
  compute_edge_crossings(needed, tracers, store, release_memory, cancel);
  std::vector<std::uint8_t>().swap(needed);

  // Trace the faces chunk by chunk in parallel; merge the chunks in order.
  struct Work {
    Index chunk = 0;
    TracedChunk traced;
  };
  // Never more chunks in flight than tokens, so a Work is always idle when the
  // first stage asks.
  const std::size_t live_chunks = 4 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  std::vector<Work> works(live_chunks);
  std::vector<Work*> idle;
  for (Work& work : works) idle.push_back(&work);
  std::mutex idle_mutex;
  Index next_chunk = 0;
  const Index num_chunks = chunk_count(num_faces, faces_per_chunk);
  tbb::parallel_pipeline(
      live_chunks,
      tbb::make_filter<void, Work*>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& control) -> Work* {
        if (next_chunk == num_chunks) {
          control.stop();
          return nullptr;
        }
        const std::lock_guard lock(idle_mutex);
        Work* work = idle.back();
        idle.pop_back();
        work->chunk = next_chunk++;
        return work;
      }) & tbb::make_filter<Work*, Work*>(tbb::filter_mode::parallel, [&](Work* work) {
        FaceBoundaryTracer& tracer = tracers.local();
        TracedChunk& out = work->traced;
        out.clear();
        const Index begin = work->chunk * faces_per_chunk;
        const Index end = std::min(num_faces, begin + faces_per_chunk);
        for (Index face = begin; face < end && cancel.keep_going(); ++face) {
          if (f.face_edges[face][0] < 0) continue;
          if (traced[face]) {
            tracer.trace_face(face, out);
          } else if (const Index site = f.nearest_site[mesh.faces(face, 0)]; site >= 0) {
            tracer.add_inner_face(face, site, out);
          }
        }
        return work;
      }) & tbb::make_filter<Work*, void>(tbb::filter_mode::serial_in_order, [&](Work* work) {
        if (cancel.keep_going()) merger.append(work->traced, f);
        add_contributions(work->traced, diagram);
        const std::lock_guard lock(idle_mutex);
        idle.push_back(work);
      }));

  cancel.stop_if_refused();
  // The graph holds the crossings' nodes now: the crossings, the tracers'
  // scratch and the face marks go before the arcs are built beside it.
  store = EdgeCrossingStore(0);
  tracers.clear();
  std::vector<std::uint8_t>().swap(traced);
  if (release_memory) trim_heap();
  chain_arcs(graph, diagram);
  graph = BoundaryGraph{};
  collect_adjacency(diagram);
  if (release_memory) trim_heap();  // the graph and the tracing's scratch
  diagram.stats.extraction_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return diagram;
}

VoronoiDiagram compute_voronoi(const GeodesicSurface& surface, std::span<const SurfacePoint> sites,
                               const VoronoiOptions& options) {
  return extract_voronoi(surface.mesh(), compute_geodesic_field(surface, sites, options.geodesic), options);
}

VoronoiDiagram compute_voronoi(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                               const VoronoiOptions& options) {
  return extract_voronoi(mesh, compute_geodesic_field(mesh, sites, options.geodesic), options);
}

}  // namespace geodual::voronoi
