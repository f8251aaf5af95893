// Farthest point sampling under an approximate geodesic metric.
//
// The graph, built per component:
//   nodes: the component's mesh vertices, M = 6 n + 32 candidate points spread
//          evenly by area (SamplingSurface::stratified_points: fewer gaps than
//          independent points, so fewer holes between the sites), and the
//          boundary sites already placed;
//   arcs:  every mesh edge; every point to the three corners of its face;
//          every pair of points closer than 1.6 sqrt(A / M) (3D) whose faces
//          are the same or share a vertex.
// Arc lengths are 3D distances. On a dense mesh paths run along mesh edges;
// on a coarse one from point to point inside and across faces, so the graph
// follows the surface whatever the ratio of sites to faces.
//
// The metric: distance fields grow from each site through the graph, a node
// taking the site of the neighbour that reached it, and the distance of a
// node from its site is estimated as
//     max(|x_node - x_site|, path / 2),
// the straight-line distance, unless the graph path that reached the node is
// more than twice as long: then the two are far apart on the surface however
// close in space (two sides of a thin part), and path / 2 keeps one site from
// claiming both. Plain graph path lengths overestimate by 5-15% along mesh
// edges, which lets sites come closer than intended; the straight line is
// the geodesic distance at the scale of the spacing, up to curvature.
//
// A search stops where it improves nothing, so a site's field only spreads
// through the region it is nearest to, along the surface: it cannot reach
// the far side of a thin part through nodes that other sites hold, however
// close that side is in space.
//
// Sites: the boundary sites are the first sources (with none, a candidate
// drawn at random is the first site); then, n times, the candidate
// farthest from all sites so far becomes a site (ties: the lower grid slot)
// and a Dijkstra search from it lowers the distances it improves, stopping
// where it improves none. The sites are candidates: face points, never
// vertices.

#include "common/point_grid.hpp"
#include "sampling/sampling_strategies.hpp"

#include <algorithm>
#include <functional>
#include <limits>

namespace geodual::remesh::detail {
namespace {

constexpr std::int64_t kCandidatesPerSite = 6;
constexpr std::int64_t kExtraCandidates = 32;
/// Link radius in units of the candidates' mean spacing sqrt(A / M).
constexpr double kLinkRadius = 1.6;
/// Graph paths longer than this many times the straight line set the distance.
constexpr double kMaxStretch = 2.0;
/// Candidates per block of the farthest-candidate search.
constexpr Index kBlock = 32;

struct Arc {
  Index a, b;
  float length;
};

bool faces_touch(const TriangleMesh& mesh, Index f, Index g) {
  if (f == g) return true;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (mesh.faces(f, i) == mesh.faces(g, j)) return true;
    }
  }
  return false;
}

using QueueEntry = std::pair<double, Index>;

}  // namespace

struct FarthestPointSampler::Impl {
  /// What the distance fields keep per node, together for locality.
  struct Node {
    Eigen::Vector3d position;
    double squared_distance;  ///< squared estimate of the distance to the nearest site
    double path_length;       ///< of the graph path from the node's site
    Index site;               ///< the node of the nearest site, -1 before any
  };

  const SamplingSurface& surface;
  const TriangleMesh& mesh;
  std::vector<Index> vertex_index;         ///< global vertex -> index in `positions`, -1 outside the component
  std::vector<Index> vertices;             ///< the component's vertices, by first use
  std::vector<SurfacePoint> points;        ///< candidates, then boundary sites
  std::vector<Eigen::Vector3d> positions;  ///< vertices, candidates, boundary sites
  /// Per node, its index in `positions`: nodes are numbered by the slots of
  /// a grid over the positions, so that neighbours in space are neighbours
  /// in memory.
  std::vector<Index> node_kind;
  Index num_vertices = 0;
  std::int64_t num_candidates = 0;
  std::vector<Arc> arcs;
  std::vector<Index> arc_begin;  ///< CSR of the graph
  std::vector<Index> arc_target;
  std::vector<float> arc_length;
  std::vector<Node> nodes;
  std::vector<QueueEntry> queue;  ///< Dijkstra, min-heap on squared distance
  /// Farthest-candidate search: nodes in blocks of kBlock, each with its best
  /// (farthest unchosen candidate) while not dirty; a max-heap of blocks whose
  /// keys are upper bounds of their best's squared distance.
  std::vector<std::uint8_t> closed;  ///< not a candidate, or already chosen
  std::vector<std::uint8_t> block_dirty;
  std::vector<Index> block_best;
  std::vector<QueueEntry> blocks;

  explicit Impl(const SamplingSurface& s)
      : surface(s), mesh(*s.mesh), vertex_index(static_cast<std::size_t>(s.mesh->num_vertices()), -1) {}

  /// What a node is: a vertex (< num_vertices), a candidate, a boundary site.
  Index kind_index(Index node) const { return node_kind[node]; }
  bool is_candidate(Index node) const {
    const Index i = kind_index(node);
    return i >= num_vertices && i < num_vertices + num_candidates;
  }
  const SurfacePoint& point_of(Index node) const { return points[kind_index(node) - num_vertices]; }
  void build_graph(const ComponentTask& task, Rng& rng);
  void grow_from(Index site);
  void sample(const ComponentTask& task, Rng& rng, std::vector<SurfacePoint>& out);
};

void FarthestPointSampler::Impl::build_graph(const ComponentTask& task, Rng& rng) {
  // The component's vertices, by first use.
  vertices.clear();
  const std::span<const Index> faces = surface.faces_of(task.component);
  for (const Index f : faces) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.faces(f, k);
      if (vertex_index[v] < 0) {
        vertex_index[v] = static_cast<Index>(vertices.size());
        vertices.push_back(v);
      }
    }
  }
  num_vertices = static_cast<Index>(vertices.size());

  points.clear();
  surface.stratified_points(task.component, num_candidates, rng, points);
  points.insert(points.end(), task.boundary_sites.begin(), task.boundary_sites.end());
  positions.resize(vertices.size() + points.size());
  for (Index v = 0; v < num_vertices; ++v) positions[v] = mesh.vertices.row(vertices[v]).transpose();
  for (std::size_t i = 0; i < points.size(); ++i) positions[vertices.size() + i] = site_position(mesh, points[i]);
  const double link_radius =
      kLinkRadius * std::sqrt(surface.component_area[task.component] / static_cast<double>(num_candidates));
  const PointGrid grid(positions, link_radius);
  const Index num_nodes = grid.size();
  node_kind.resize(static_cast<std::size_t>(num_nodes));
  std::vector<Index> node_of(static_cast<std::size_t>(num_nodes));
  for (Index node = 0; node < num_nodes; ++node) {
    node_kind[node] = grid.original(node);
    node_of[grid.original(node)] = node;
  }
  auto vertex_node = [&](Index v) { return node_of[vertex_index[v]]; };

  arcs.clear();
  for (const Index f : faces) {
    for (int k = 0; k < 3; ++k) {
      const Index a = vertex_node(mesh.faces(f, k)), b = vertex_node(mesh.faces(f, (k + 1) % 3));
      arcs.push_back(
          {std::min(a, b), std::max(a, b), static_cast<float>((grid.position(a) - grid.position(b)).norm())});
    }
  }
  std::sort(arcs.begin(), arcs.end(), [](const Arc& x, const Arc& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  arcs.erase(std::unique(arcs.begin(), arcs.end(), [](const Arc& x, const Arc& y) { return x.a == y.a && x.b == y.b; }),
             arcs.end());
  for (Index node = 0; node < num_nodes; ++node) {
    if (kind_index(node) < num_vertices) continue;
    const Index face = point_of(node).element;
    for (int k = 0; k < 3; ++k) {
      const Index corner = vertex_node(mesh.faces(face, k));
      arcs.push_back({corner, node, static_cast<float>((grid.position(corner) - grid.position(node)).norm())});
    }
    grid.for_each_near(node, [&](Index other, double d2) {
      if (other <= node || kind_index(other) < num_vertices) return;
      if (!faces_touch(mesh, face, point_of(other).element)) return;
      arcs.push_back({node, other, static_cast<float>(std::sqrt(d2))});
    });
  }
  for (const Index v : vertices) vertex_index[v] = -1;  // ready for the next component

  // Both directions of every arc, as CSR.
  arc_begin.assign(static_cast<std::size_t>(num_nodes) + 1, 0);
  for (const Arc& arc : arcs) {
    ++arc_begin[arc.a + 1];
    ++arc_begin[arc.b + 1];
  }
  for (Index i = 0; i < num_nodes; ++i) arc_begin[i + 1] += arc_begin[i];
  arc_target.resize(static_cast<std::size_t>(arc_begin.back()));
  arc_length.resize(arc_target.size());
  std::vector<Index> fill(arc_begin.begin(), arc_begin.end() - 1);
  for (const Arc& arc : arcs) {
    arc_target[fill[arc.a]] = arc.b;
    arc_length[fill[arc.a]++] = arc.length;
    arc_target[fill[arc.b]] = arc.a;
    arc_length[fill[arc.b]++] = arc.length;
  }
  arcs.clear();

  nodes.resize(static_cast<std::size_t>(num_nodes));
  for (Index node = 0; node < num_nodes; ++node) {
    nodes[node] = {grid.position(node), std::numeric_limits<double>::infinity(), 0.0, -1};
  }
  positions.clear();
}

void FarthestPointSampler::Impl::grow_from(Index site) {
  nodes[site].squared_distance = 0;
  nodes[site].path_length = 0;
  nodes[site].site = site;
  block_dirty[site / kBlock] = 1;
  queue.clear();
  queue.push_back({0.0, site});
  const auto later = std::greater<QueueEntry>();
  constexpr double kInverseStretch2 = 1 / (kMaxStretch * kMaxStretch);
  while (!queue.empty()) {
    std::pop_heap(queue.begin(), queue.end(), later);
    const auto [d2, node] = queue.back();
    queue.pop_back();
    const Node& from = nodes[node];
    if (d2 > from.squared_distance) continue;  // stale entry
    const Eigen::Vector3d& origin = nodes[from.site].position;
    for (Index i = arc_begin[node]; i < arc_begin[node + 1]; ++i) {
      Node& to = nodes[arc_target[i]];
      const double path = from.path_length + static_cast<double>(arc_length[i]);
      const double estimate = std::max((to.position - origin).squaredNorm(), path * path * kInverseStretch2);
      if (estimate < to.squared_distance) {
        to.squared_distance = estimate;
        to.path_length = path;
        to.site = from.site;
        block_dirty[arc_target[i] / kBlock] = 1;
        queue.push_back({estimate, arc_target[i]});
        std::push_heap(queue.begin(), queue.end(), later);
      }
    }
  }
}

void FarthestPointSampler::Impl::sample(const ComponentTask& task, Rng& rng, std::vector<SurfacePoint>& out) {
  const std::int64_t n = task.interior;
  if (n <= 0) return;
  num_candidates = kCandidatesPerSite * n + kExtraCandidates;
  build_graph(task, rng);
  const auto num_nodes = static_cast<Index>(nodes.size());
  const Index num_blocks = (num_nodes + kBlock - 1) / kBlock;
  closed.resize(static_cast<std::size_t>(num_nodes));
  for (Index node = 0; node < num_nodes; ++node) closed[node] = !is_candidate(node);
  block_dirty.assign(static_cast<std::size_t>(num_blocks), 1);
  block_best.assign(static_cast<std::size_t>(num_blocks), -1);

  std::int64_t picked = 0;
  auto choose = [&](Index node) {
    closed[node] = 1;
    out.push_back(point_of(node));
    ++picked;
    grow_from(node);
  };
  if (task.boundary_sites.empty()) {
    const auto drawn = std::min(static_cast<Index>(rng.uniform() * static_cast<double>(num_candidates)),
                                static_cast<Index>(num_candidates - 1));
    Index first = 0;
    while (kind_index(first) != num_vertices + drawn) ++first;
    choose(first);
  } else {
    for (Index node = 0; node < num_nodes; ++node) {
      if (kind_index(node) >= num_vertices + num_candidates) grow_from(node);
    }
  }

  // Max-heap of blocks on (key, -block). A popped block that is dirty gets
  // its best recomputed and goes back in; a clean one holds the farthest
  // candidate of all, since every other key bounds its block from above.
  auto before = [](const QueueEntry& x, const QueueEntry& y) {
    return x.first < y.first || (x.first == y.first && x.second > y.second);
  };
  blocks.clear();
  for (Index b = 0; b < num_blocks; ++b) blocks.push_back({std::numeric_limits<double>::infinity(), b});
  std::make_heap(blocks.begin(), blocks.end(), before);
  while (picked < n && !blocks.empty()) {
    std::pop_heap(blocks.begin(), blocks.end(), before);
    const auto [key, b] = blocks.back();
    blocks.pop_back();
    if (block_dirty[b]) {
      block_dirty[b] = 0;
      Index best = -1;
      const Index end = std::min(num_nodes, (b + 1) * kBlock);
      for (Index node = b * kBlock; node < end; ++node) {
        if (!closed[node] && (best < 0 || nodes[node].squared_distance > nodes[best].squared_distance)) best = node;
      }
      block_best[b] = best;
      if (best >= 0) {
        blocks.push_back({nodes[best].squared_distance, b});
        std::push_heap(blocks.begin(), blocks.end(), before);
      }
      continue;
    }
    // The block loses its best (and grow_from marks it dirty): it goes back
    // in with its old key, an upper bound.
    choose(block_best[b]);
    blocks.push_back({key, b});
    std::push_heap(blocks.begin(), blocks.end(), before);
  }
}

FarthestPointSampler::FarthestPointSampler(const SamplingSurface& surface) : impl_(std::make_unique<Impl>(surface)) {}
FarthestPointSampler::~FarthestPointSampler() = default;

void FarthestPointSampler::sample(const ComponentTask& task, Rng& rng, std::vector<SurfacePoint>& out) {
  impl_->sample(task, rng, out);
}

}  // namespace geodual::remesh::detail
