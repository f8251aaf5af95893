// compare_meshes: two-sided Hausdorff and RMS distance between two meshes by
// exact point-to-surface distances (nearest triangle found through a CGAL AABB
// tree) from every referenced vertex and from area-uniform samples of each
// side; feature_recall: distances from points along the reference's sharp
// edges to the candidate's edges (nearest segment, through a CGAL AABB tree of
// segments). The only translation unit of the library that includes CGAL.

#include "geodual/quality/quality_stats.hpp"

#include "geodual/mesh/coordinate_range.hpp"

#include "geodual/mesh/detail/morton_code.hpp"
#include "geodual/mesh/detail/nearest_primitive.hpp"
#include "geodual/mesh/detail/progress_from_threads.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/random.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/triangle_distance.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace geodual::quality {
namespace {

using aabb::Kernel;
using aabb::Point;
using aabb::Triangle;
using aabb::TrianglePrimitive;
using aabb::TriangleTree;
using Segment = Kernel::Segment_3;
using SegmentIterator = std::vector<Segment>::const_iterator;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentIterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

/// QualityOptions::progress, asked on the calling thread only (see
/// ProgressFromThreads). Each phase of compare_meshes covers a share of [0, 1].
class ProgressCheck {
 public:
  explicit ProgressCheck(const std::function<bool(double)>& callback) : progress_(callback) {}

  /// The next calls report within [from, from + share).
  void phase(double from, double share) {
    from_ = from;
    share_ = share;
  }

  /// Asks the callback with `done` of the current phase (on the calling
  /// thread; elsewhere it only reads the flag); false once cancelled.
  bool keep_going(double done) {
    if (!progress_.asks()) return !progress_.refused();
    // Never backwards, not even by the rounding of from + share at a phase's end.
    reported_ = std::max(reported_, from_ + share_ * std::clamp(done, 0.0, 1.0));
    return progress_.keep_going(reported_);
  }

  /// keep_going, throwing geodual::Cancelled when not.
  void check(double done) {
    if (!keep_going(done)) throw Cancelled("statistics cancelled");
  }

 private:
  ProgressFromThreads progress_;
  double reported_ = 0;  ///< the last fraction reported
  double from_ = 0.0;
  double share_ = 0.0;
};

/// Counter-based draws: value number `counter` of stream `stream`, so every
/// sample can be drawn on its own, in any order and on any thread.
double uniform(std::uint64_t stream, std::uint64_t counter) {
  return static_cast<double>(SplitMix64::nth(stream, counter) >> 11) * 0x1.0p-53;  // in [0, 1)
}

/// Squared distance from p to the triangle (geodual::squared_distance_to_triangle).
double squared_distance_to_triangle(const Point& point, const Triangle& triangle) {
  const auto eigen = [](const Point& q) { return Eigen::Vector3d(q.x(), q.y(), q.z()); };
  return geodual::squared_distance_to_triangle(eigen(point), eigen(triangle[0]), eigen(triangle[1]),
                                               eigen(triangle[2]));
}

/// Squared distance from p to the segment (geodual::squared_distance_to_segment).
double squared_distance_to_segment(const Point& point, const Segment& segment) {
  const auto eigen = [](const Point& q) { return Eigen::Vector3d(q.x(), q.y(), q.z()); };
  return geodual::squared_distance_to_segment(eigen(point), eigen(segment.source()), eigen(segment.target()));
}

using NearestTriangle = NearestPrimitive<Kernel, TrianglePrimitive, squared_distance_to_triangle>;
using NearestSegment = NearestPrimitive<Kernel, SegmentPrimitive, squared_distance_to_segment>;

/// CGAL's median split of the tree build, asking `progress` first at every
/// node of at least 4096 primitives, so that a cancel ends a build of millions
/// of primitives within milliseconds (by Cancelled, thrown through the build).
template <typename Tree>
class CancellableSplit {
 public:
  CancellableSplit(const Tree& tree, ProgressCheck& progress)
      : split_(tree.traits().split_primitives_object()), progress_(progress) {}

  template <typename PrimitiveIterator>
  void operator()(PrimitiveIterator first, PrimitiveIterator beyond, const CGAL::Bbox_3& box) const {
    if (beyond - first >= 4096) progress_.check(0.0);
    split_(first, beyond, box);
  }

 private:
  typename Tree::AABB_traits::Split_primitives split_;
  ProgressCheck& progress_;
};

/// One mesh as a surface to sample and to measure distances to: its faces of
/// non-zero area in an AABB tree, their cumulative areas, and its referenced
/// vertices. Building it asks `progress` (and throws Cancelled when refused).
class Surface {
 public:
  Surface(const TriangleMesh& mesh, ProgressCheck& progress) {
    std::vector<char> referenced(static_cast<std::size_t>(mesh.num_vertices()), 0);
    double total = 0.0;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      const Index a = mesh.faces(f, 0);
      const Index b = mesh.faces(f, 1);
      const Index c = mesh.faces(f, 2);
      referenced[a] = referenced[b] = referenced[c] = 1;
      const double area = face_area(mesh, f);
      if (!has_positive_area(mesh, f) || !(area > 0.0)) continue;  // degenerate: left out
      const Eigen::Vector3d p0 = mesh.vertices.row(a);
      const Eigen::Vector3d p1 = mesh.vertices.row(b);
      const Eigen::Vector3d p2 = mesh.vertices.row(c);
      triangles_.emplace_back(Point(p0.x(), p0.y(), p0.z()), Point(p1.x(), p1.y(), p1.z()),
                              Point(p2.x(), p2.y(), p2.z()));
      face_.push_back(f);
      total += area;
      cumulative_area_.push_back(total);
    }
    if (triangles_.empty()) throw Error("every face has zero area");
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      if (referenced[v]) {
        vertices_.emplace_back(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
        vertex_index_.push_back(v);
      }
    }
    tree_.insert(triangles_.begin(), triangles_.end());
    // Built now, not lazily on the first query, so that the queries only read.
    tree_.custom_build(tree_.traits().compute_bbox_object(), CancellableSplit<TriangleTree>(tree_, progress));
    bbox_ = tree_.bbox();
  }
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;

  std::int64_t vertex_count() const { return static_cast<std::int64_t>(vertices_.size()); }
  const Point& vertex(std::int64_t i) const { return vertices_[static_cast<std::size_t>(i)]; }
  /// The mesh's index of vertex(i), and the mesh's face that is triangle t.
  Index vertex_index(std::int64_t i) const { return vertex_index_[static_cast<std::size_t>(i)]; }
  Index face_index(std::size_t t) const { return face_[t]; }

  /// Sample number `i` of stream `stream`: a face chosen with probability
  /// proportional to its area, then a uniform point in it
  /// ((1 - sqrt(r1)) a + sqrt(r1) (1 - r2) b + sqrt(r1) r2 c). `triangle` is
  /// set to the face's triangle.
  Point sample(std::uint64_t stream, std::int64_t i, std::size_t& triangle) const {
    const auto counter = 3 * static_cast<std::uint64_t>(i);
    const double target = uniform(stream, counter) * cumulative_area_.back();
    const auto found = std::upper_bound(cumulative_area_.begin(), cumulative_area_.end(), target);
    const auto face =
        std::min<std::ptrdiff_t>(found - cumulative_area_.begin(), static_cast<std::ptrdiff_t>(triangles_.size()) - 1);
    triangle = static_cast<std::size_t>(face);
    const Triangle& t = triangles_[triangle];
    const double s = std::sqrt(uniform(stream, counter + 1));
    const double r = uniform(stream, counter + 2);
    const double wa = 1.0 - s;
    const double wb = s * (1.0 - r);
    const double wc = s * r;
    return Point(wa * t[0].x() + wb * t[1].x() + wc * t[2].x(), wa * t[0].y() + wb * t[1].y() + wc * t[2].y(),
                 wa * t[0].z() + wb * t[1].z() + wc * t[2].z());
  }

  /// Squared distance from p to the closest point of the surface; `near`,
  /// the index of a triangle close to p, bounds the search from the start,
  /// and is set to the nearest triangle.
  double squared_distance(const Point& p, std::size_t& near) const {
    NearestTriangle nearest(triangles_.cbegin(), squared_distance_to_triangle(p, triangles_[near]), near);
    tree_.traversal_with_priority(p, nearest);
    near = nearest.nearest_primitive();
    return nearest.squared_distance();
  }

  /// The corners of its bounding box.
  const CGAL::Bbox_3& bbox() const { return bbox_; }

 private:
  std::vector<Triangle> triangles_;
  std::vector<Index> face_;  ///< per triangle
  std::vector<double> cumulative_area_;
  std::vector<Point> vertices_;
  std::vector<Index> vertex_index_;  ///< per vertex
  TriangleTree tree_;
  CGAL::Bbox_3 bbox_;
};

struct OneSided {
  double max_squared = 0.0;
  Eigen::Vector3d farthest = Eigen::Vector3d::Zero();  ///< the first point measured at max_squared
  double sum_squared = 0.0;
  std::int64_t count = 0;
};

/// Per point measured (vertices first, then samples): where it lies on the
/// `from` side (the vertex of `from`'s mesh, or the face it was drawn on) and
/// the face of the `to` side nearest to it, and its squared distance.
struct MeasuredPoints {
  std::vector<Index> from_vertex;  ///< -1 for a sample
  std::vector<Index> from_face;    ///< -1 for a vertex
  std::vector<Index> to_face;
  std::vector<double> squared;
};

/// Distances from `from`'s vertices and `samples` area-uniform samples of it
/// to `to`. Fixed blocks of points, each summed in order, then the blocks
/// summed in order: the same bits for any number of threads. The points of
/// a run of blocks are queried in Morton order, each search bounded from the
/// start by the previous point's nearest triangle, which is near: a few
/// times fewer boxes visited, and the same distances. Every block of queries
/// asks `progress`; a cancel stops every thread at its next block.
OneSided measure(const Surface& from, const Surface& to, std::int64_t samples, std::uint64_t stream,
                 ProgressCheck& progress, MeasuredPoints* points_measured = nullptr) {
  constexpr std::int64_t block = 4096;
  constexpr std::int64_t blocks_per_run = 16;
  const std::int64_t vertices = from.vertex_count();
  const std::int64_t count = vertices + samples;
  const auto blocks = static_cast<std::size_t>((count + block - 1) / block);
  const auto runs = (blocks + blocks_per_run - 1) / blocks_per_run;
  std::vector<double> block_max(blocks, 0.0);
  std::vector<Point> block_farthest(blocks);
  std::vector<double> block_sum(blocks, 0.0);
  const CGAL::Bbox_3& box = to.bbox();
  const double extent = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  const double cells_per_unit = extent > 0 ? 1048575.0 / extent : 0.0;  // 2^20 - 1 cells along the longest side
  auto cell = [&](double x, double low) {
    return static_cast<std::uint64_t>(std::clamp((x - low) * cells_per_unit, 0.0, 2097151.0));
  };
  if (points_measured) {
    const auto size = static_cast<std::size_t>(count);
    points_measured->from_vertex.assign(size, -1);
    points_measured->from_face.assign(size, -1);
    points_measured->to_face.assign(size, -1);
    points_measured->squared.assign(size, 0.0);
  }
  std::atomic<std::int64_t> measured{0};
  const auto keep_going = [&] {
    return progress.keep_going(static_cast<double>(measured.load(std::memory_order_relaxed)) /
                               static_cast<double>(count));
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<Point> points;
    std::vector<std::size_t> drawn_on;  // per sample, its triangle of `from`
    std::vector<std::pair<std::uint64_t, std::int32_t>> order;
    std::vector<double> squared;
    for (std::size_t run = range.begin(); run != range.end(); ++run) {
      if (!keep_going()) return;  // before drawing the run's points
      const std::int64_t first = static_cast<std::int64_t>(run) * block * blocks_per_run;
      const std::int64_t last = std::min(first + block * blocks_per_run, count);
      const auto size = static_cast<std::size_t>(last - first);
      points.resize(size);
      drawn_on.resize(size);
      order.resize(size);
      squared.resize(size);
      for (std::size_t k = 0; k < size; ++k) {
        const std::int64_t i = first + static_cast<std::int64_t>(k);
        const Point p = i < vertices ? from.vertex(i) : from.sample(stream, i - vertices, drawn_on[k]);
        points[k] = p;
        order[k] = {morton_code(cell(p.x(), box.xmin()), cell(p.y(), box.ymin()), cell(p.z(), box.zmin())),
                    static_cast<std::int32_t>(k)};
      }
      std::sort(order.begin(), order.end());
      std::size_t near = 0;
      for (std::size_t j = 0; j < size; ++j) {
        if (j % block == 0) {
          if (!keep_going()) return;
          measured.fetch_add(std::min<std::int64_t>(block, static_cast<std::int64_t>(size - j)),
                             std::memory_order_relaxed);
        }
        const auto at = static_cast<std::size_t>(order[j].second);
        squared[at] = to.squared_distance(points[at], near);
        if (points_measured) {
          const auto i = static_cast<std::size_t>(first) + at;
          if (static_cast<std::int64_t>(i) < vertices) {
            points_measured->from_vertex[i] = from.vertex_index(static_cast<std::int64_t>(i));
          } else {
            points_measured->from_face[i] = from.face_index(drawn_on[at]);
          }
          points_measured->to_face[i] = to.face_index(near);
          points_measured->squared[i] = squared[at];
        }
      }
      for (std::int64_t b = first / block; b * block < last; ++b) {
        double max_squared = -1.0;
        double sum_squared = 0.0;
        Point farthest;
        for (std::int64_t i = b * block; i < std::min((b + 1) * block, last); ++i) {
          const double d2 = squared[static_cast<std::size_t>(i - first)];
          if (d2 > max_squared) max_squared = d2, farthest = points[static_cast<std::size_t>(i - first)];
          sum_squared += d2;
        }
        block_max[static_cast<std::size_t>(b)] = max_squared;
        block_farthest[static_cast<std::size_t>(b)] = farthest;
        block_sum[static_cast<std::size_t>(b)] = sum_squared;
      }
    }
  });
  progress.check(1.0);
  OneSided result;
  result.count = count;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (b == 0 || block_max[b] > result.max_squared) {
      result.max_squared = block_max[b];
      const Point& p = block_farthest[b];
      result.farthest = {p.x(), p.y(), p.z()};
    }
    result.sum_squared += block_sum[b];
  }
  return result;
}

/// Per vertex of `reference`, the largest distance measured at it: of the
/// vertex itself and of the reference's samples on its faces (`forward`, from
/// the reference), and of the candidate's points whose nearest face of the
/// reference is one of its faces (`backward`). In the order of the points: the
/// same whatever the threads.
std::vector<double> deviation_at_vertices(const TriangleMesh& reference, const MeasuredPoints& forward,
                                          const MeasuredPoints& backward) {
  std::vector<double> squared(static_cast<std::size_t>(reference.num_vertices()), 0.0);
  auto raise = [&](Index v, double d2) { squared[v] = std::max(squared[v], d2); };
  auto raise_face = [&](Index f, double d2) {
    for (int c = 0; c < 3; ++c) raise(reference.faces(f, c), d2);
  };
  for (std::size_t i = 0; i < forward.squared.size(); ++i) {
    if (forward.from_vertex[i] >= 0) {
      raise(forward.from_vertex[i], forward.squared[i]);
    } else {
      raise_face(forward.from_face[i], forward.squared[i]);
    }
  }
  for (std::size_t i = 0; i < backward.squared.size(); ++i) raise_face(backward.to_face[i], backward.squared[i]);
  for (double& d : squared) d = std::sqrt(d);
  return squared;
}

/// Runs `f`, prefixing the message of a geodual::Error with `which`.
template <typename F>
auto naming(const char* which, F&& f) {
  try {
    return f();
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& error) {
    throw Error(std::string(which) + ": " + error.what());
  }
}

/// The edges of a mesh (sides of faces joining two different vertices, each
/// once) as segments in an AABB tree, to measure distances to. Building it
/// asks `progress` (and throws Cancelled when refused).
class EdgeSegments {
 public:
  EdgeSegments(const TriangleMesh& mesh, ProgressCheck& progress) {
    {
      std::vector<std::array<Index, 2>> edges;
      edges.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
      for (Index f = 0; f < mesh.num_faces(); ++f) {
        for (int k = 0; k < 3; ++k) {
          const Index a = mesh.faces(f, k);
          const Index b = mesh.faces(f, (k + 1) % 3);
          if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
        }
      }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      if (edges.empty()) throw Error("no face has two different vertices, so there is no edge");
      progress.check(0.0);
      segments_.reserve(edges.size());
      const auto point = [&mesh](Index v) {
        return Point(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
      };
      for (const auto& [a, b] : edges) segments_.emplace_back(point(a), point(b));
    }
    tree_.insert(segments_.begin(), segments_.end());
    tree_.custom_build(tree_.traits().compute_bbox_object(), CancellableSplit<SegmentTree>(tree_, progress));
  }
  EdgeSegments(const EdgeSegments&) = delete;
  EdgeSegments& operator=(const EdgeSegments&) = delete;

  /// Squared distance from p to the nearest edge; `near` as in
  /// Surface::squared_distance.
  double squared_distance(const Point& p, std::size_t& near) const {
    NearestSegment nearest(segments_.cbegin(), squared_distance_to_segment(p, segments_[near]), near);
    tree_.traversal_with_priority(p, nearest);
    near = nearest.nearest_primitive();
    return nearest.squared_distance();
  }

 private:
  std::vector<Segment> segments_;
  SegmentTree tree_;
};

/// Throws Error for what triangle_quality refuses: no faces, an index out of
/// range, a non-finite coordinate.
void check_mesh(const TriangleMesh& mesh) {
  if (mesh.num_faces() == 0) throw Error("the mesh has no faces");
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.faces(f, k);
      if (v < 0 || v >= mesh.num_vertices()) {
        throw Error("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + ", but the mesh has " +
                    std::to_string(mesh.num_vertices()) + " vertices");
      }
    }
  }
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices.row(v).allFinite()) {
      throw Error("vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
}

void check_feature_options(const QualityOptions& options) {
  if (!(options.sharp_angle_deg > 0.0 && options.sharp_angle_deg <= 180.0)) {
    throw Error("feature recall: sharp_angle_deg is " + std::to_string(options.sharp_angle_deg) +
                "; give an angle in (0, 180] degrees");
  }
  if (!(options.feature_tolerance_pct > 0.0 && std::isfinite(options.feature_tolerance_pct))) {
    throw Error("feature recall: feature_tolerance_pct is " + std::to_string(options.feature_tolerance_pct) +
                "; give a positive percentage of the bounding-box diagonal");
  }
  if (!(options.long_crease_length >= 0.0 && std::isfinite(options.long_crease_length))) {
    throw Error("feature recall: long_crease_length is " + std::to_string(options.long_crease_length) +
                "; give a length of 0 (none) or more");
  }
}

/// The sharp chains (FeatureRecall): per sharp edge (a position in
/// `edges`), the chain it lies on, and per chain its length.
struct SharpChains {
  std::vector<std::size_t> chain_of_edge;
  std::vector<double> length;
};

SharpChains sharp_chains(const TriangleMesh& mesh, const MeshTopology& topology, const std::vector<Index>& edges) {
  // Per vertex, its sharp edges (positions in `edges`), in compressed rows.
  const auto vertex_count = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<std::size_t> first(vertex_count + 1, 0);
  for (const Index e : edges) {
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    ++first[static_cast<std::size_t>(a) + 1];
    ++first[static_cast<std::size_t>(b) + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) first[v + 1] += first[v];
  std::vector<std::size_t> incident(first[vertex_count]);
  {
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(edges[i])];
      incident[next[static_cast<std::size_t>(a)]++] = i;
      incident[next[static_cast<std::size_t>(b)]++] = i;
    }
  }
  const auto degree = [&](std::size_t v) { return first[v + 1] - first[v]; };

  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  SharpChains chains;
  chains.chain_of_edge.assign(edges.size(), none);
  // A new chain from vertex v along sharp edge i, on until a vertex with
  // other than two sharp edges, or back to an edge of the chain (a loop).
  const auto walk = [&](std::size_t v, std::size_t i) {
    const std::size_t chain = chains.length.size();
    double length = 0.0;
    while (chains.chain_of_edge[i] == none) {
      chains.chain_of_edge[i] = chain;
      const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(edges[i])];
      length += (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
      const auto w = static_cast<std::size_t>(static_cast<std::size_t>(a) == v ? b : a);
      if (degree(w) != 2) break;
      i = incident[first[w]] == i ? incident[first[w] + 1] : incident[first[w]];
      v = w;
    }
    chains.length.push_back(length);
  };
  for (std::size_t v = 0; v < vertex_count; ++v) {
    if (degree(v) == 2) continue;
    for (std::size_t k = first[v]; k < first[v + 1]; ++k) {
      if (chains.chain_of_edge[incident[k]] == none) walk(v, incident[k]);
    }
  }
  // What is left are loops, each through vertices of two sharp edges only.
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (chains.chain_of_edge[i] == none) {
      walk(static_cast<std::size_t>(topology.edge_vertices[static_cast<std::size_t>(edges[i])][0]), i);
    }
  }
  return chains;
}

/// The reference's sharp edges at options.sharp_angle_deg (their end
/// points), and per edge whether it lies on a crease at least
/// options.long_crease_length long; the chain counts go into `recall`.
struct ReferenceSharpEdges {
  std::vector<std::array<Eigen::Vector3d, 2>> ends;
  std::vector<char> on_long_crease;
};

ReferenceSharpEdges reference_sharp_edges(const TriangleMesh& reference, const QualityOptions& options,
                                          FeatureRecall& recall, ProgressCheck& progress) {
  ReferenceSharpEdges sharp;
  const MeshTopology topology = build_mesh_topology(reference);
  progress.check(0.7);
  const std::vector<Index> edges = sharp_edges(reference, topology, options.sharp_angle_deg);
  for (const Index e : edges) {
    const auto [a, b] = topology.edge_vertices[static_cast<std::size_t>(e)];
    sharp.ends.push_back({reference.vertices.row(a).transpose(), reference.vertices.row(b).transpose()});
  }
  const SharpChains chains = sharp_chains(reference, topology, edges);
  recall.chains = static_cast<std::int64_t>(chains.length.size());
  sharp.on_long_crease.assign(edges.size(), 0);
  if (options.long_crease_length > 0.0) {
    recall.long_crease_length = options.long_crease_length;
    for (const double length : chains.length) recall.long_chains += length >= options.long_crease_length;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      sharp.on_long_crease[i] = chains.length[chains.chain_of_edge[i]] >= options.long_crease_length;
      recall.long_edges += sharp.on_long_crease[i];
    }
  }
  return sharp;
}

/// Samples along the sharp edges: both ends of each and points at most
/// `spacing` apart between them. Returns the pieces per edge, with the
/// samples in all in `samples`. \throw Error beyond max_feature_samples.
std::vector<std::int64_t> sample_pieces(std::span<const std::array<Eigen::Vector3d, 2>> sharp, double spacing,
                                        const QualityOptions& options, std::int64_t& samples) {
  std::vector<std::int64_t> pieces(sharp.size());
  double total_pieces = 0.0;
  for (std::size_t i = 0; i < sharp.size(); ++i) {
    const double length = (sharp[i][1] - sharp[i][0]).norm();
    const double wanted = std::ceil(length / spacing);
    total_pieces += std::max(wanted, 1.0) + 1.0;
    if (!(total_pieces <= static_cast<double>(max_feature_samples))) {
      throw Error("feature recall: a tolerance of " + std::to_string(options.feature_tolerance_pct) +
                  " % of the diagonal needs more than " + std::to_string(max_feature_samples) +
                  " samples along the sharp edges; give a larger one");
    }
    pieces[i] = std::max<std::int64_t>(static_cast<std::int64_t>(wanted), 1);
  }
  samples = static_cast<std::int64_t>(total_pieces);
  return pieces;
}

/// The feature recall of checked meshes and options, within the progress
/// phase [from, from + share). `diagonal`: the reference's (referenced
/// vertices).
FeatureRecall measure_features(const TriangleMesh& reference, const TriangleMesh& candidate,
                               const QualityOptions& options, double diagonal, double from, double share,
                               ProgressCheck& progress) {
  FeatureRecall recall;
  recall.sharp_angle_deg = options.sharp_angle_deg;
  recall.tolerance = options.feature_tolerance_pct / 100.0 * diagonal;
  progress.phase(from, 0.3 * share);
  progress.check(0.0);
  // The topology is freed before the tree is built.
  const auto [sharp, on_long_crease] = reference_sharp_edges(reference, options, recall, progress);
  recall.edges = static_cast<std::int64_t>(sharp.size());
  progress.check(1.0);
  if (sharp.empty()) {
    progress.phase(from, share);
    progress.check(1.0);
    return recall;
  }

  const std::vector<std::int64_t> pieces = sample_pieces(sharp, recall.tolerance / 10.0, options, recall.samples);

  progress.phase(from + 0.3 * share, 0.2 * share);
  progress.check(0.0);
  const EdgeSegments candidate_edges = naming("candidate mesh", [&] { return EdgeSegments(candidate, progress); });

  // Fixed blocks of sharp edges, each summed in order, then the blocks summed
  // in order: the same bits for any number of threads.
  progress.phase(from + 0.5 * share, 0.5 * share);
  progress.check(0.0);
  constexpr std::size_t block = 64;
  const std::size_t blocks = (sharp.size() + block - 1) / block;
  std::vector<double> block_length(blocks, 0.0);
  std::vector<double> block_recalled(blocks, 0.0);
  std::vector<double> block_max_squared(blocks, 0.0);
  std::vector<double> block_long_length(blocks, 0.0);
  std::vector<double> block_long_recalled(blocks, 0.0);
  const double tolerance_squared = recall.tolerance * recall.tolerance;
  std::atomic<std::int64_t> measured{0};
  const auto keep_going = [&] {
    return progress.keep_going(static_cast<double>(measured.load(std::memory_order_relaxed)) /
                               static_cast<double>(recall.samples));
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks), [&](const tbb::blocked_range<std::size_t>& range) {
    std::int64_t unreported = 0;
    for (std::size_t b = range.begin(); b != range.end(); ++b) {
      double length = 0.0;
      double recalled = 0.0;
      double max_squared = 0.0;
      double long_length = 0.0;
      double long_recalled = 0.0;
      std::size_t near = 0;
      for (std::size_t i = b * block; i < std::min((b + 1) * block, sharp.size()); ++i) {
        const Eigen::Vector3d& a = sharp[i][0];
        const Eigen::Vector3d& z = sharp[i][1];
        const std::int64_t n = pieces[i];
        // Recalled halves of pieces: a piece counts one half for each recalled end.
        std::int64_t halves = 0;
        bool previous = false;
        for (std::int64_t k = 0; k <= n; ++k) {
          if (++unreported == 4096) {
            measured.fetch_add(unreported, std::memory_order_relaxed);
            unreported = 0;
            if (!keep_going()) return;
          }
          const Eigen::Vector3d p = k == n ? z : a + (static_cast<double>(k) / static_cast<double>(n)) * (z - a);
          const double d2 = candidate_edges.squared_distance(Point(p.x(), p.y(), p.z()), near);
          max_squared = std::max(max_squared, d2);
          const bool within = d2 <= tolerance_squared;
          if (k > 0) halves += static_cast<std::int64_t>(within) + static_cast<std::int64_t>(previous);
          previous = within;
        }
        // Summed like the lengths, so that all recalled gives exactly 100 %.
        const double edge_length = (z - a).norm();
        const double edge_recalled =
            halves == 2 * n ? edge_length : edge_length * static_cast<double>(halves) / static_cast<double>(2 * n);
        length += edge_length;
        recalled += edge_recalled;
        if (on_long_crease[i] != 0) {
          long_length += edge_length;
          long_recalled += edge_recalled;
        }
      }
      block_length[b] = length;
      block_recalled[b] = recalled;
      block_max_squared[b] = max_squared;
      block_long_length[b] = long_length;
      block_long_recalled[b] = long_recalled;
    }
  });
  progress.check(1.0);
  double recalled = 0.0;
  double long_recalled = 0.0;
  double max_squared = 0.0;
  for (std::size_t b = 0; b < blocks; ++b) {
    recall.length += block_length[b];
    recalled += block_recalled[b];
    recall.long_length += block_long_length[b];
    long_recalled += block_long_recalled[b];
    max_squared = std::max(max_squared, block_max_squared[b]);
  }
  recall.recall_pct = recall.length > 0 ? 100.0 * recalled / recall.length : 100.0;
  recall.long_recall_pct = recall.long_length > 0 ? 100.0 * long_recalled / recall.long_length : 100.0;
  recall.max_gap = std::sqrt(max_squared);
  recall.max_gap_pct = 100.0 * recall.max_gap / diagonal;
  return recall;
}

}  // namespace

QualityReport compare_meshes(const TriangleMesh& reference, const TriangleMesh& candidate,
                             const QualityOptions& options) {
  if (options.samples_per_side < 0 || options.samples_per_side > max_samples_per_side) {
    throw Error("compare_meshes: samples_per_side is " + std::to_string(options.samples_per_side) + "; give 0 to " +
                std::to_string(max_samples_per_side));
  }
  if (options.sharp_angle_deg != 0.0) check_feature_options(options);
  // Shares of the work in each phase, roughly as measured on meshes of a
  // million faces with a million samples per side.
  ProgressCheck progress(options.progress);
  QualityReport report;
  progress.phase(0.0, 0.05);
  progress.check(0.0);
  report.reference = naming("reference mesh", [&] { return triangle_quality(reference); });
  progress.phase(0.05, 0.05);
  progress.check(0.0);
  report.candidate = naming("candidate mesh", [&] { return triangle_quality(candidate); });

  {
    // One scope, so that the trees are freed before returning.
    progress.phase(0.1, 0.05);
    progress.check(0.0);
    const Surface reference_surface = naming("reference mesh", [&] { return Surface(reference, progress); });
    progress.phase(0.15, 0.05);
    progress.check(0.0);
    const Surface candidate_surface = naming("candidate mesh", [&] { return Surface(candidate, progress); });
    const std::uint64_t stream = splitmix64_mix(options.seed);
    std::optional<MeasuredPoints> forward_points, backward_points;
    if (options.deviation_at_vertices) forward_points.emplace(), backward_points.emplace();
    progress.phase(0.2, 0.38);
    const OneSided forward = measure(reference_surface, candidate_surface, options.samples_per_side,
                                     splitmix64_mix(stream), progress, forward_points ? &*forward_points : nullptr);
    progress.phase(0.58, 0.38);
    const OneSided backward =
        measure(candidate_surface, reference_surface, options.samples_per_side, splitmix64_mix(stream + 1), progress,
                backward_points ? &*backward_points : nullptr);
    if (options.deviation_at_vertices) {
      report.deviation_at_vertices = deviation_at_vertices(reference, *forward_points, *backward_points);
    }
    report.hausdorff_reference_to_candidate = std::sqrt(forward.max_squared);
    report.hausdorff_candidate_to_reference = std::sqrt(backward.max_squared);
    report.hausdorff = std::max(report.hausdorff_reference_to_candidate, report.hausdorff_candidate_to_reference);
    report.hausdorff_point = report.hausdorff_reference_to_candidate >= report.hausdorff_candidate_to_reference
                                 ? forward.farthest
                                 : backward.farthest;
    report.rms =
        std::sqrt((forward.sum_squared + backward.sum_squared) / static_cast<double>(forward.count + backward.count));
    report.reference_samples = forward.count;
    report.candidate_samples = backward.count;
  }

  // A reference with a face of non-zero area has a positive area and diagonal.
  const double diagonal = report.reference.bbox_diagonal;
  if (options.sharp_angle_deg != 0.0) {
    report.features = measure_features(reference, candidate, options, diagonal, 0.96, 0.04, progress);
  } else {
    progress.phase(0.96, 0.04);
    progress.check(1.0);
  }
  report.hausdorff_pct = 100.0 * report.hausdorff / diagonal;
  report.rms_pct = 100.0 * report.rms / diagonal;
  report.area_change_pct = 100.0 * (report.candidate.area - report.reference.area) / report.reference.area;
  if (report.reference.volume != 0.0) {
    report.volume_change_pct =
        100.0 * (report.candidate.volume - report.reference.volume) / std::abs(report.reference.volume);
  }
  return report;
}

FeatureRecall feature_recall(const TriangleMesh& reference, const TriangleMesh& candidate,
                             const QualityOptions& options) {
  check_feature_options(options);
  naming("reference mesh", [&] { check_mesh(reference); });
  naming("candidate mesh", [&] { check_mesh(candidate); });
  ProgressCheck progress(options.progress);
  return measure_features(reference, candidate, options, referenced_bounding_box(reference).diagonal(), 0.0, 1.0,
                          progress);
}

}  // namespace geodual::quality
