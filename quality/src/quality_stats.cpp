// compare_meshes: two-sided Hausdorff and RMS distance between two meshes by
// exact point-to-surface distances (nearest triangle found through a CGAL AABB
// tree) from every referenced vertex and from area-uniform samples of each
// side. The only translation unit of the library that includes CGAL.

#include "geodual/quality/quality_stats.hpp"

#include "geodual/mesh/detail/morton_code.hpp"
#include "geodual/mesh/detail/progress_from_threads.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/random.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace geodual::quality {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

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

/// Squared distance from p to triangle abc: the Voronoi region of its
/// vertices, edges and face that holds p decides which one is nearest
/// (Ericson, Real-Time Collision Detection, 5.1.5); a handful of dot products.
double squared_distance_to_triangle(const Point& point, const Triangle& triangle) {
  const Eigen::Vector3d p(point.x(), point.y(), point.z());
  const Eigen::Vector3d a(triangle[0].x(), triangle[0].y(), triangle[0].z());
  const Eigen::Vector3d b(triangle[1].x(), triangle[1].y(), triangle[1].z());
  const Eigen::Vector3d c(triangle[2].x(), triangle[2].y(), triangle[2].z());
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();  // vertex a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();  // edge ab
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {  // edge bc
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  }
  // Inside the face: the distance to its plane, |ap . n| / |n|, which keeps
  // its accuracy on needles (the barycentric point a + v ab + w ac does not).
  const Eigen::Vector3d normal = ab.cross(ac);
  const double normal2 = normal.squaredNorm();
  if (!(normal2 > 0)) {
    // So thin that the area underflows: the nearest point is on an edge.
    const auto segment = [&p](const Eigen::Vector3d& s, const Eigen::Vector3d& e) {
      const Eigen::Vector3d d = e - s;
      const double t = d.squaredNorm() > 0 ? std::clamp((p - s).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      return (p - (s + t * d)).squaredNorm();
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
  }
  const double height = ap.dot(normal);
  return height * height / normal2;
}

/// Traversal traits for the exact squared distance from a point to the
/// triangles of an AABB tree: children are visited nearest box first, and a
/// box no nearer than the best triangle so far is skipped. It starts from the
/// distance to a given triangle (the previous query's nearest, for queries
/// in spatial order) instead of the tree's k-d tree hint (costly for points
/// far from the surface). The result is the minimum over the triangles, so
/// it depends on the query alone, not on the start, the order of queries or
/// the thread.
class NearestTriangle {
 public:
  /// `first`: the tree's first triangle, to number the primitives from.
  NearestTriangle(TriangleIterator first, double start_squared, std::size_t start_triangle)
      : first_(first), best_(start_squared), best_triangle_(start_triangle) {}

  using Node = CGAL::AABB_node<CGAL::AABB_traits<Kernel, Primitive>>;
  using Priority = double;  ///< higher first: minus the squared distance to the box

  bool go_further() const { return true; }

  void intersection(const Point& query, const Primitive& primitive) {
    const double d2 = squared_distance_to_triangle(query, primitive.datum());
    if (d2 < best_) {
      best_ = d2;
      best_triangle_ = static_cast<std::size_t>(primitive.id() - first_);
    }
  }

  bool do_intersect(const Point& query, const Node& node) const { return box_distance(query, node) < best_; }

  std::pair<bool, Priority> do_intersect_with_priority(const Point& query, const Node& node) const {
    const double d2 = box_distance(query, node);
    return {d2 < best_, -d2};
  }

  double squared_distance() const { return best_; }
  std::size_t nearest_triangle() const { return best_triangle_; }

 private:
  static double box_distance(const Point& q, const Node& node) {
    const CGAL::Bbox_3& box = node.bbox();
    double d2 = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double below = box.min(axis) - q[axis];
      const double above = q[axis] - box.max(axis);
      const double gap = std::max({below, above, 0.0});
      d2 += gap * gap;
    }
    return d2;
  }

  TriangleIterator first_;
  double best_;
  std::size_t best_triangle_;
};

/// CGAL's median split of the tree build, asking `progress` first at every
/// node of at least 4096 triangles, so that a cancel ends a build of millions
/// of triangles within milliseconds (by Cancelled, thrown through the build).
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
  Tree::AABB_traits::Split_primitives split_;
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
      total += area;
      cumulative_area_.push_back(total);
    }
    if (triangles_.empty()) throw Error("every face has zero area");
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      if (referenced[v]) {
        vertices_.emplace_back(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
      }
    }
    tree_.insert(triangles_.begin(), triangles_.end());
    // Built now, not lazily on the first query, so that the queries only read.
    tree_.custom_build(tree_.traits().compute_bbox_object(), CancellableSplit(tree_, progress));
    bbox_ = tree_.bbox();
  }
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;

  std::int64_t vertex_count() const { return static_cast<std::int64_t>(vertices_.size()); }
  const Point& vertex(std::int64_t i) const { return vertices_[static_cast<std::size_t>(i)]; }

  /// Sample number `i` of stream `stream`: a face chosen with probability
  /// proportional to its area, then a uniform point in it
  /// ((1 - sqrt(r1)) a + sqrt(r1) (1 - r2) b + sqrt(r1) r2 c).
  Point sample(std::uint64_t stream, std::int64_t i) const {
    const auto counter = 3 * static_cast<std::uint64_t>(i);
    const double target = uniform(stream, counter) * cumulative_area_.back();
    const auto found = std::upper_bound(cumulative_area_.begin(), cumulative_area_.end(), target);
    const auto face =
        std::min<std::ptrdiff_t>(found - cumulative_area_.begin(), static_cast<std::ptrdiff_t>(triangles_.size()) - 1);
    const Triangle& t = triangles_[static_cast<std::size_t>(face)];
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
    near = nearest.nearest_triangle();
    return nearest.squared_distance();
  }

  /// The corners of its bounding box.
  const CGAL::Bbox_3& bbox() const { return bbox_; }

 private:
  std::vector<Triangle> triangles_;
  std::vector<double> cumulative_area_;
  std::vector<Point> vertices_;
  Tree tree_;
  CGAL::Bbox_3 bbox_;
};

struct OneSided {
  double max_squared = 0.0;
  double sum_squared = 0.0;
  std::int64_t count = 0;
};

/// Distances from `from`'s vertices and `samples` area-uniform samples of it
/// to `to`. Fixed blocks of points, each summed in order, then the blocks
/// summed in order: the same bits for any number of threads. The points of
/// a run of blocks are queried in Morton order, each search bounded from the
/// start by the previous point's nearest triangle, which is near: a few
/// times fewer boxes visited, and the same distances. Every block of queries
/// asks `progress`; a cancel stops every thread at its next block.
OneSided measure(const Surface& from, const Surface& to, std::int64_t samples, std::uint64_t stream,
                 ProgressCheck& progress) {
  constexpr std::int64_t block = 4096;
  constexpr std::int64_t blocks_per_run = 16;
  const std::int64_t vertices = from.vertex_count();
  const std::int64_t count = vertices + samples;
  const auto blocks = static_cast<std::size_t>((count + block - 1) / block);
  const auto runs = (blocks + blocks_per_run - 1) / blocks_per_run;
  std::vector<double> block_max(blocks, 0.0);
  std::vector<double> block_sum(blocks, 0.0);
  const CGAL::Bbox_3& box = to.bbox();
  const double extent = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  const double cells_per_unit = extent > 0 ? 1048575.0 / extent : 0.0;  // 2^20 - 1 cells along the longest side
  auto cell = [&](double x, double low) {
    return static_cast<std::uint64_t>(std::clamp((x - low) * cells_per_unit, 0.0, 2097151.0));
  };
  std::atomic<std::int64_t> measured{0};
  const auto keep_going = [&] {
    return progress.keep_going(static_cast<double>(measured.load(std::memory_order_relaxed)) /
                               static_cast<double>(count));
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<Point> points;
    std::vector<std::pair<std::uint64_t, std::int32_t>> order;
    std::vector<double> squared;
    for (std::size_t run = range.begin(); run != range.end(); ++run) {
      if (!keep_going()) return;  // before drawing the run's points
      const std::int64_t first = static_cast<std::int64_t>(run) * block * blocks_per_run;
      const std::int64_t last = std::min(first + block * blocks_per_run, count);
      const auto size = static_cast<std::size_t>(last - first);
      points.resize(size);
      order.resize(size);
      squared.resize(size);
      for (std::size_t k = 0; k < size; ++k) {
        const std::int64_t i = first + static_cast<std::int64_t>(k);
        const Point p = i < vertices ? from.vertex(i) : from.sample(stream, i - vertices);
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
      }
      for (std::int64_t b = first / block; b * block < last; ++b) {
        double max_squared = 0.0;
        double sum_squared = 0.0;
        for (std::int64_t i = b * block; i < std::min((b + 1) * block, last); ++i) {
          const double d2 = squared[static_cast<std::size_t>(i - first)];
          max_squared = std::max(max_squared, d2);
          sum_squared += d2;
        }
        block_max[static_cast<std::size_t>(b)] = max_squared;
        block_sum[static_cast<std::size_t>(b)] = sum_squared;
      }
    }
  });
  progress.check(1.0);
  OneSided result;
  result.count = count;
  for (std::size_t b = 0; b < blocks; ++b) {
    result.max_squared = std::max(result.max_squared, block_max[b]);
    result.sum_squared += block_sum[b];
  }
  return result;
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

}  // namespace

QualityReport compare_meshes(const TriangleMesh& reference, const TriangleMesh& candidate,
                             const QualityOptions& options) {
  if (options.samples_per_side < 0 || options.samples_per_side > max_samples_per_side) {
    throw Error("compare_meshes: samples_per_side is " + std::to_string(options.samples_per_side) + "; give 0 to " +
                std::to_string(max_samples_per_side));
  }
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
    progress.phase(0.2, 0.4);
    const OneSided forward =
        measure(reference_surface, candidate_surface, options.samples_per_side, splitmix64_mix(stream), progress);
    progress.phase(0.6, 0.4);
    const OneSided backward =
        measure(candidate_surface, reference_surface, options.samples_per_side, splitmix64_mix(stream + 1), progress);
    report.hausdorff_reference_to_candidate = std::sqrt(forward.max_squared);
    report.hausdorff_candidate_to_reference = std::sqrt(backward.max_squared);
    report.hausdorff = std::max(report.hausdorff_reference_to_candidate, report.hausdorff_candidate_to_reference);
    report.rms =
        std::sqrt((forward.sum_squared + backward.sum_squared) / static_cast<double>(forward.count + backward.count));
    report.reference_samples = forward.count;
    report.candidate_samples = backward.count;
  }

  // A reference with a face of non-zero area has a positive area and diagonal.
  const double diagonal = report.reference.bbox_diagonal;
  report.hausdorff_pct = 100.0 * report.hausdorff / diagonal;
  report.rms_pct = 100.0 * report.rms / diagonal;
  report.area_change_pct = 100.0 * (report.candidate.area - report.reference.area) / report.reference.area;
  if (report.reference.volume != 0.0) {
    report.volume_change_pct =
        100.0 * (report.candidate.volume - report.reference.volume) / std::abs(report.reference.volume);
  }
  return report;
}

}  // namespace geodual::quality
