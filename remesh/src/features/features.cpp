#include "geodual/remesh/features.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/sorted_edges.hpp"
#include "geodual/mesh/union_find.hpp"
#include "geodual/remesh/curvature_density.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace geodual::remesh {

Index FeatureSet::find_sharp_edge(Index a, Index b) const { return find_sorted_edge(sharp_edges, a, b); }

bool FeatureSet::is_sharp(Index a, Index b) const { return find_sharp_edge(a, b) >= 0; }
namespace {

/// The graph of feature edges: per vertex, its edges (CSR over `edges`).
struct FeatureGraph {
  std::vector<std::array<Index, 2>> edges;
  std::vector<std::uint8_t> edge_on_boundary;
  std::vector<Index> begin;      // per vertex + 1
  std::vector<Index> incidence;  // edge indices
  std::span<const Index> edges_at(Index v) const {
    return {incidence.data() + begin[v], incidence.data() + begin[v + 1]};
  }
  Index degree(Index v) const { return begin[v + 1] - begin[v]; }
  Index other_end(Index e, Index v) const { return edges[e][0] == v ? edges[e][1] : edges[e][0]; }
};

FeatureGraph build_graph(Index num_vertices, std::vector<std::array<Index, 2>> edges,
                         std::vector<std::uint8_t> on_boundary) {
  FeatureGraph graph;
  graph.edges = std::move(edges);
  graph.edge_on_boundary = std::move(on_boundary);
  graph.begin.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const auto& [a, b] : graph.edges) {
    ++graph.begin[a + 1];
    ++graph.begin[b + 1];
  }
  for (Index v = 0; v < num_vertices; ++v) graph.begin[v + 1] += graph.begin[v];
  graph.incidence.resize(2 * graph.edges.size());
  std::vector<Index> next(graph.begin.begin(), graph.begin.end() - 1);
  for (Index e = 0; e < static_cast<Index>(graph.edges.size()); ++e) {
    for (const Index v : graph.edges[e]) graph.incidence[next[v]++] = e;
  }
  return graph;
}

double edge_length(const TriangleMesh& mesh, Index a, Index b) {
  return (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
}

/// The angle in degrees between the directions a -> v and v -> b (0: straight on).
double turn_degrees(const TriangleMesh& mesh, Index a, Index v, Index b) {
  const Eigen::Vector3d in = mesh.vertices.row(v) - mesh.vertices.row(a);
  const Eigen::Vector3d out = mesh.vertices.row(b) - mesh.vertices.row(v);
  return std::atan2(in.cross(out).norm(), in.dot(out)) * 180 / std::numbers::pi;
}

/// Sharp edges that stay sharp at `scale` (FeatureOptions::scale): the faces
/// with a corner within that distance of the edge, on each side, reached
/// across edges with two faces that are not sharp, must not join up, and their
/// area-weighted normals must turn by at least `angle` degrees. The faces
/// round both ends are always within reach, so that where the input's edges
/// are longer than the scale, the faces round a lone noisy edge still join.
/// With max_spread > 0, every face's normal must also lie within max_spread
/// degrees of its side's mean: both sides are smooth at that scale. The
/// `walls` part the sides as the sharp edges do, without being judged.
std::vector<Index> sharp_at_scale(const TriangleMesh& mesh, const MeshTopology& topology,
                                  const std::vector<Index>& sharp, double angle, double scale, double max_spread = 0,
                                  const std::vector<Index>& walls = {}) {
  const Index num_faces = mesh.num_faces();
  std::vector<std::uint8_t> is_sharp(static_cast<std::size_t>(topology.num_edges()), 0);
  for (const Index e : sharp) is_sharp[e] = 1;
  for (const Index e : walls) is_sharp[e] = 1;
  std::vector<Eigen::Vector3d> normal(static_cast<std::size_t>(num_faces));
  for (Index f = 0; f < num_faces; ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    normal[f] = (b - a).cross(c - a);  // twice the area times the unit normal
  }
  constexpr std::size_t kMaxFaces = 1 << 14;  // per side: beyond this, the region is judged as reached so far
  std::vector<std::int64_t> seen(static_cast<std::size_t>(num_faces), -1);
  std::vector<Index> queue;
  std::vector<Index> kept;
  const double min_cos = std::cos(angle * std::numbers::pi / 180);
  const double spread_cos = std::cos(max_spread * std::numbers::pi / 180);
  for (std::size_t i = 0; i < sharp.size(); ++i) {
    const Index e = sharp[i];
    const auto faces = topology.edge_faces(e);
    const Eigen::Vector3d start = mesh.vertices.row(topology.edge_vertices[e][0]);
    const Eigen::Vector3d along = Eigen::Vector3d(mesh.vertices.row(topology.edge_vertices[e][1])) - start;
    const auto within_scale = [&](Index f) {  // a corner of f within `scale` of the edge
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d x = mesh.vertices.row(mesh.faces(f, k));
        const double t =
            along.squaredNorm() > 0 ? std::clamp((x - start).dot(along) / along.squaredNorm(), 0.0, 1.0) : 0.0;
        if ((start + t * along - x).squaredNorm() <= scale * scale) return true;
      }
      return false;
    };
    // Region growing from each side; stamp 2 i + side marks the faces reached.
    Eigen::Vector3d mean[2];
    bool joined = false, smooth = true;
    for (int side = 0; side < 2 && !joined && smooth; ++side) {
      const std::int64_t stamp = 2 * static_cast<std::int64_t>(i) + side;
      mean[side] = Eigen::Vector3d::Zero();
      queue.assign(1, faces[side]);
      seen[faces[side]] = stamp;
      for (std::size_t head = 0; head < queue.size() && queue.size() < kMaxFaces; ++head) {
        const Index f = queue[head];
        mean[side] += normal[f];
        for (const Index edge : topology.face_edges[f]) {
          if (is_sharp[edge] || topology.edge_faces(edge).size() != 2) continue;
          for (const Index g : topology.edge_faces(edge)) {
            if (seen[g] == stamp || !within_scale(g)) continue;
            if (side == 1 && seen[g] == stamp - 1) joined = true;  // side 0 reached it: one region
            seen[g] = stamp;
            queue.push_back(g);
          }
        }
      }
      if (max_spread > 0 && mean[side].norm() > 0) {
        const Eigen::Vector3d axis = mean[side].normalized();
        smooth = std::all_of(queue.begin(), queue.end(),
                             [&](Index f) { return !(normal[f].dot(axis) < spread_cos * normal[f].norm()); });
      }
    }
    if (joined || !smooth) continue;
    // Faces that run the edge the same way are misoriented: one side's normals count flipped.
    const auto [a, b] = topology.edge_vertices[e];
    if (face_runs_edge(mesh, faces[0], a, b) == face_runs_edge(mesh, faces[1], a, b)) mean[1] = -mean[1];
    if (mean[0].norm() > 0 && mean[1].norm() > 0 && mean[0].normalized().dot(mean[1].normalized()) > min_cos) continue;
    kept.push_back(e);
  }
  return kept;
}

/// Faces whose normals turn by less than this many degrees across an edge
/// lie in one plane: a machined part's flat face cut into triangles, or a
/// faceted side's quad (float coordinates turn them by far less).
constexpr double kCoplanarAngle = 0.05;

/// A surface is machined, made of planar facets, where at least this share
/// of its area lies on facets of two faces or more.
constexpr double kMachinedFacetShare = 0.5;

/// A surface's planar facets: the faces joined across edges that turn by
/// less than kCoplanarAngle. A CAD part's flat faces and a faceted side's
/// quads are such facets; a scan has few faces coplanar with a neighbour
/// (under a tenth of its area).
struct PlanarFacets {
  std::vector<double> turn;     ///< per edge, in degrees (NaN but between two faces with area)
  std::vector<Index> facet_of;  ///< per face: its facet, a face's index
  std::vector<double> area;     ///< per facet (at its index)
  bool machined = false;        ///< kMachinedFacetShare of the area or more on facets of two faces or more
};

PlanarFacets planar_facets(const TriangleMesh& mesh, const MeshTopology& topology) {
  const Index num_faces = mesh.num_faces();
  const auto size = static_cast<std::size_t>(num_faces);
  PlanarFacets planar;
  planar.turn.resize(static_cast<std::size_t>(topology.num_edges()));
  UnionFind facets(size);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    planar.turn[e] = normal_turn_degrees(mesh, topology, e);
    if (planar.turn[e] < kCoplanarAngle) facets.unite(topology.edge_faces(e)[0], topology.edge_faces(e)[1]);
  }
  planar.facet_of.resize(size);
  planar.area.assign(size, 0.0);
  std::vector<Index> faces_in(size, 0);
  for (Index f = 0; f < num_faces; ++f) {
    const Index facet = planar.facet_of[f] = facets.find(f);
    planar.area[facet] += face_area(mesh, f);
    faces_in[facet] += 1;
  }
  double total = 0, on_facets = 0;
  for (std::size_t f = 0; f < size; ++f) {
    total += planar.area[f];
    if (faces_in[f] >= 2) on_facets += planar.area[f];
  }
  planar.machined = on_facets >= kMachinedFacetShare * total;
  return planar;
}

/// On a machined surface, the edges where the normals turn by `angle`
/// degrees or more between two planar facets, each at least a remesh
/// triangle in area (sqrt(3) scale^2, the scale being half the spacing): the
/// folds between a CAD part's flat faces are creases however weak. A scan
/// split into coplanar quadruples is machined too, but its facets are
/// smaller than a remesh triangle unless the remesh is about as fine as the
/// scan was.
std::vector<Index> folds_between_facets(const MeshTopology& topology, const PlanarFacets& planar, double angle,
                                        double scale) {
  std::vector<Index> folds;
  if (!planar.machined) return folds;
  const double min_area = std::sqrt(3.0) * scale * scale;
  const auto wide = [&](Index f) { return planar.area[planar.facet_of[f]] >= min_area; };
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    if (planar.turn[e] >= angle && wide(faces[0]) && wide(faces[1])) folds.push_back(e);
  }
  return folds;
}

/// Corners and chains of a feature graph (FeatureSet's, with the edge
/// indices of each chain).
struct Chains {
  std::vector<Index> corners;
  std::vector<FeatureChain> chains;
  std::vector<std::vector<Index>> chain_edges;
};

Chains walk_chains(const TriangleMesh& surface, const FeatureGraph& graph, double corner_angle) {
  const Index num_vertices = static_cast<Index>(graph.begin.size()) - 1;
  Chains result;
  // Corners: ends and junctions (degree other than 2), and sharp turns.
  std::vector<std::uint8_t> corner(static_cast<std::size_t>(num_vertices), 0);
  for (Index v = 0; v < num_vertices; ++v) {
    const Index degree = graph.degree(v);
    if (degree == 0) continue;
    if (degree != 2) {
      corner[v] = 1;
    } else {
      const auto at = graph.edges_at(v);
      corner[v] = turn_degrees(surface, graph.other_end(at[0], v), v, graph.other_end(at[1], v)) >= corner_angle;
    }
    if (corner[v]) result.corners.push_back(v);
  }
  // Chains: walks from each corner along each of its edges to the next
  // corner; what is left are closed loops without one. Sharp chains first.
  std::vector<std::uint8_t> walked(graph.edges.size(), 0);
  auto walk = [&](Index start, Index first_edge) {
    FeatureChain chain;
    std::vector<Index> edges;
    chain.on_boundary = graph.edge_on_boundary[first_edge] != 0;
    chain.vertices.push_back(start);
    Index v = start, e = first_edge;
    while (true) {
      walked[e] = 1;
      edges.push_back(e);
      const Index next = graph.other_end(e, v);
      chain.length += edge_length(surface, v, next);
      chain.vertices.push_back(next);
      v = next;
      if (corner[v] || v == start) break;
      const auto at = graph.edges_at(v);  // degree 2, no corner: go on along its other edge
      e = at[0] == e ? at[1] : at[0];
      if (walked[e]) break;
    }
    // A loop through one corner is an open chain from that corner back to it.
    chain.closed = chain.vertices.front() == chain.vertices.back() && !corner[chain.vertices.front()];
    result.chains.push_back(std::move(chain));
    result.chain_edges.push_back(std::move(edges));
  };
  for (const int boundary : {0, 1}) {
    for (const Index v : result.corners) {
      for (const Index e : graph.edges_at(v)) {
        if (!walked[e] && graph.edge_on_boundary[e] == boundary) walk(v, e);
      }
    }
    for (Index e = 0; e < static_cast<Index>(graph.edges.size()); ++e) {
      if (!walked[e] && graph.edge_on_boundary[e] == boundary) walk(graph.edges[e][0], e);
    }
  }
  return result;
}

/// An edge whose faces turn by less than this many degrees is no fold (a
/// planar quad's diagonal, rounding).
constexpr double kFoldAngle = 1;

/// The sharp edges (indices into topology's edges, `sharp`) that border a
/// narrow region: the regions are the faces joined across edges with two
/// faces that are not sharp, and a region's width is twice its area over the
/// length of its border (sharp and boundary edges), the width of a strip or
/// the radius of a disc. A region is narrow below `min_width`, and below
/// `min_rough_width` where it is rough (FeatureOptions::smooth_region_angle):
/// a sliver boxed in by a scan's noisy creases has no room for a cell of its
/// own, where a machined part's thin wall or engraved stroke, smooth or
/// faceted between its creases, is kept down to a fraction of the spacing.
/// On a `machined` surface no region is rough: its folds are the part's
/// shape, not a scan's noise.
std::vector<std::uint8_t> borders_of_narrow_regions(const TriangleMesh& mesh, const MeshTopology& topology,
                                                    const std::vector<std::uint8_t>& is_sharp,
                                                    const FeatureOptions& options, bool machined) {
  const Index num_faces = mesh.num_faces();
  UnionFind regions(static_cast<std::size_t>(num_faces));
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    if (faces.size() == 2 && !is_sharp[e]) regions.unite(faces[0], faces[1]);
  }
  const auto size = static_cast<std::size_t>(num_faces);
  std::vector<double> area(size, 0.0), border(size, 0.0);
  // Per region (at its root face): whether an edge turns by smooth_angle or
  // more; its folds (edges that turn by kFoldAngle or more), counted up to
  // two, the first one's direction, and whether the others are parallel to it.
  std::vector<std::uint8_t> steep(size, 0), folds(size, 0), parallel(size, 1);
  std::vector<Eigen::Vector3d> fold_direction(size);
  const double parallel_cosine = std::cos(options.parallel_fold_angle * std::numbers::pi / 180);
  for (Index f = 0; f < num_faces; ++f) area[regions.find(f)] += face_area(mesh, f);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const auto faces = topology.edge_faces(e);
    const auto [a, b] = topology.edge_vertices[e];
    if (!is_sharp[e] && faces.size() == 2) {
      const Index region = regions.find(faces[0]);
      const double turn = normal_turn_degrees(mesh, topology, e);
      if (turn < kFoldAngle) continue;
      // NaN (a face without area) counts as steep, and as a fold parallel to none.
      if (!(turn < options.smooth_region_angle)) steep[region] = 1;
      const Eigen::Vector3d direction = (mesh.vertices.row(b) - mesh.vertices.row(a)).transpose().normalized();
      if (folds[region] == 0) fold_direction[region] = direction;
      if (!(std::abs(direction.dot(fold_direction[region])) >= parallel_cosine) || std::isnan(turn)) {
        parallel[region] = 0;
      }
      folds[region] = static_cast<std::uint8_t>(std::min(folds[region] + 1, 2));
      continue;
    }
    const double length = edge_length(mesh, a, b);
    for (const Index f : faces) border[regions.find(f)] += length;
  }
  // Rough: steep somewhere, unless its folds are two or more parallel lines
  // (a faceted prism's or cylinder's side: ruled, developable).
  const auto rough = [&](Index region) {
    return !machined && steep[region] && !(options.parallel_fold_angle > 0 && folds[region] >= 2 && parallel[region]);
  };
  std::vector<std::uint8_t> drop(is_sharp.size(), 0);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!is_sharp[e]) continue;
    for (const Index f : topology.edge_faces(e)) {
      const Index region = regions.find(f);
      const double min_width =
          rough(region) ? std::max(options.min_region_width, options.min_rough_region_width) : options.min_region_width;
      if (2 * area[region] < min_width * border[region]) drop[e] = 1;
    }
  }
  return drop;
}

/// The edges that continue the creases `sharp` at options.continuation_angle
/// (FeatureOptions): reached from them along a path of such edges, each
/// smooth-sided at the scale.
std::vector<Index> continuations(const TriangleMesh& mesh, const MeshTopology& topology,
                                 const std::vector<Index>& sharp, const FeatureOptions& options) {
  std::vector<Index> weaker = sharp_edges(mesh, topology, options.continuation_angle);
  if (options.scale > 0) {
    weaker = sharp_at_scale(mesh, topology, weaker, options.continuation_angle, options.scale,
                            options.continuation_max_spread);
  }
  std::vector<std::uint8_t> is_sharp(static_cast<std::size_t>(topology.num_edges()), 0);
  for (const Index e : sharp) is_sharp[e] = 1;
  std::vector<Index> candidates;
  std::vector<std::array<Index, 2>> pairs;
  for (const Index e : weaker) {
    if (is_sharp[e]) continue;
    candidates.push_back(e);
    pairs.push_back(topology.edge_vertices[e]);
  }
  const auto num_vertices = static_cast<Index>(mesh.vertices.rows());
  const FeatureGraph graph =
      build_graph(num_vertices, std::move(pairs), std::vector<std::uint8_t>(candidates.size(), 0));
  // Breadth first from the creases' vertices over the candidates.
  std::vector<std::uint8_t> reached(static_cast<std::size_t>(num_vertices), 0), taken(candidates.size(), 0);
  std::vector<Index> queue;
  for (const Index e : sharp) {
    for (const Index v : topology.edge_vertices[e]) {
      if (!reached[v]) reached[v] = 1, queue.push_back(v);
    }
  }
  std::vector<Index> continued;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Index v = queue[head];
    for (const Index i : graph.edges_at(v)) {
      if (taken[i]) continue;
      taken[i] = 1;
      continued.push_back(candidates[i]);
      const Index w = graph.other_end(i, v);
      if (!reached[w]) reached[w] = 1, queue.push_back(w);
    }
  }
  return continued;
}

}  // namespace

FeatureOptions remesh_feature_options(const TriangleMesh& surface, std::int64_t sites, double sharp_angle,
                                      double min_length, double continuation_angle) {
  const double spacing = uniform_spacing(surface, sites);
  return {.sharp_angle = sharp_angle,
          .continuation_angle = continuation_angle,
          .scale = 0.5 * spacing,
          .min_chain_length = min_length * spacing,
          .min_dangling_chain_length = 2 * spacing,
          .min_region_width = 0.1 * spacing,
          .min_rough_region_width = 0.5 * spacing};
}

FeatureSet detect_features(const TriangleMesh& surface, const FeatureOptions& options) {
  if (!(options.sharp_angle > 0) && options.given_edges.empty()) return {};
  return detect_features(RemeshSurface(surface), options);
}

FeatureSet detect_features(const RemeshSurface& prepared, const FeatureOptions& options) {
  FeatureSet features;
  if (!(options.sharp_angle > 0) && options.given_edges.empty()) return features;
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  std::vector<Index> sharp, sharp_alone;  // the latter judged on their two faces alone
  std::optional<PlanarFacets> facets;     // made once, where a filter below asks
  const auto planar = [&]() -> const PlanarFacets& {
    if (!facets) facets = planar_facets(surface, topology);
    return *facets;
  };
  if (options.sharp_angle > 0) {
    sharp = sharp_alone = sharp_edges(surface, topology, options.sharp_angle);
    if (options.scale > 0) {
      std::vector<Index> walls;  // where the two sides part, as at the sharp edges
      if (options.facet_folds_part_sides && !sharp.empty() && options.continuation_angle > 0 &&
          options.continuation_angle < options.sharp_angle) {
        walls = folds_between_facets(topology, planar(), options.continuation_angle, options.scale);
      }
      sharp = sharp_at_scale(surface, topology, sharp, options.sharp_angle, options.scale, 0, walls);
    }
    if (options.continuation_angle > 0 && options.continuation_angle < options.sharp_angle && !sharp.empty()) {
      const std::vector<Index> continued = continuations(surface, topology, sharp, options);
      sharp.insert(sharp.end(), continued.begin(), continued.end());
    }
  }
  // The given edges join them, marked as kept whatever the filters below say.
  std::vector<std::uint8_t> given(static_cast<std::size_t>(topology.num_edges()), 0);
  for (const auto& [a, b] : options.given_edges) {
    const Index e = topology.find_edge(a, b);
    if (e >= 0 && topology.edge_faces(e).size() == 2) given[e] = 1;
  }
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (given[e]) sharp.push_back(e);
  }
  std::sort(sharp.begin(), sharp.end());
  sharp.erase(std::unique(sharp.begin(), sharp.end()), sharp.end());
  if (!options.excluded_edges.empty()) {
    std::vector<std::uint8_t> excluded(static_cast<std::size_t>(topology.num_edges()), 0);
    for (const auto& [a, b] : options.excluded_edges) {
      if (const Index e = topology.find_edge(a, b); e >= 0) excluded[e] = 1;
    }
    std::erase_if(sharp, [&](Index e) { return excluded[e] != 0; });
  }
  const Index num_vertices = static_cast<Index>(surface.vertices.rows());

  // Chains shorter than min_chain_length go, and then the chains round
  // regions narrower than min_region_width, until none is left: the chains
  // they ended at may join up into longer ones.
  std::vector<std::array<Index, 2>> edges;
  std::vector<std::uint8_t> is_sharp(static_cast<std::size_t>(topology.num_edges()), 0);
  for (const Index e : sharp) is_sharp[e] = 1;
  while (!sharp.empty()) {
    edges.clear();
    for (const Index e : sharp) edges.push_back(topology.edge_vertices[e]);
    const FeatureGraph graph = build_graph(num_vertices, edges, std::vector<std::uint8_t>(edges.size(), 0));
    const Chains chains = walk_chains(surface, graph, options.corner_angle);
    std::vector<std::uint8_t> drop(sharp.size(), 0);
    bool dropped = false;
    // A lone edge whose ends are on no other sharp edge and off the boundary
    // cannot be cut open (its faces still share both ends): it goes too.
    const auto lone_end = [&](Index v) { return graph.degree(v) == 1 && !topology.vertex_on_boundary[v]; };
    for (std::size_t c = 0; c < chains.chains.size(); ++c) {
      const FeatureChain& chain = chains.chains[c];
      const bool lone =
          chain.vertices.size() == 2 && lone_end(chain.vertices.front()) && lone_end(chain.vertices.back());
      const bool dangling = lone_end(chain.vertices.front()) || lone_end(chain.vertices.back());
      const double min_length =
          dangling ? std::max(options.min_chain_length, options.min_dangling_chain_length) : options.min_chain_length;
      if (chain.length >= min_length && !lone) continue;
      for (const Index e : chains.chain_edges[c]) {
        if (given[sharp[e]] && !lone) continue;
        drop[e] = 1;
        dropped = true;
      }
    }
    if (!dropped && std::max(options.min_region_width, options.min_rough_region_width) > 0) {
      const bool machined = options.machined_regions_smooth &&
                            options.min_rough_region_width > options.min_region_width && planar().machined;
      const std::vector<std::uint8_t> narrow =
          borders_of_narrow_regions(surface, topology, is_sharp, options, machined);
      for (std::size_t i = 0; i < sharp.size(); ++i) {
        if (!narrow[sharp[i]] || given[sharp[i]]) continue;
        drop[i] = 1;
        dropped = true;
      }
    }
    if (!dropped) break;
    std::vector<Index> kept;
    for (std::size_t i = 0; i < sharp.size(); ++i) {
      if (drop[i]) {
        is_sharp[sharp[i]] = 0;
      } else {
        kept.push_back(sharp[i]);
      }
    }
    sharp = std::move(kept);
  }
  if (!sharp_alone.empty()) {
    // What the filters dropped.
    std::vector<std::array<Index, 2>> dropped;
    for (const Index e : sharp_alone) {
      if (!is_sharp[e]) dropped.push_back(topology.edge_vertices[e]);
    }
    const auto count = dropped.size();
    const FeatureGraph graph = build_graph(num_vertices, std::move(dropped), std::vector<std::uint8_t>(count, 0));
    features.short_creases = walk_chains(surface, graph, options.corner_angle).chains;
  }
  if (sharp.empty()) return features;
  features.sharp_edges = edges;  // in edge order: sorted by vertex pair
  std::vector<std::uint8_t> touched(static_cast<std::size_t>(num_vertices), 0);
  for (const auto& [a, b] : edges) {
    touched[a] = touched[b] = 1;
    features.sharp_length += edge_length(surface, a, b);
  }

  // The boundary loops that the chains run into join the graph.
  std::vector<std::uint8_t> on_boundary(edges.size(), 0);
  std::vector<std::uint8_t> loop_touched(static_cast<std::size_t>(topology.num_boundary_loops), 0);
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const Index loop = topology.edge_boundary_loop[e];
    if (loop < 0) continue;
    const auto [a, b] = topology.edge_vertices[e];
    if (touched[a] || touched[b]) loop_touched[loop] = 1;
  }
  for (Index e = 0; e < topology.num_edges(); ++e) {
    const Index loop = topology.edge_boundary_loop[e];
    if (loop < 0 || !loop_touched[loop]) continue;
    edges.push_back(topology.edge_vertices[e]);
    on_boundary.push_back(1);
  }
  const FeatureGraph graph = build_graph(num_vertices, std::move(edges), std::move(on_boundary));
  Chains chains = walk_chains(surface, graph, options.corner_angle);
  features.corners = std::move(chains.corners);
  features.chains = std::move(chains.chains);
  for (const FeatureChain& chain : features.chains) features.sharp_chains += chain.on_boundary ? 0 : 1;
  return features;
}

}  // namespace geodual::remesh
