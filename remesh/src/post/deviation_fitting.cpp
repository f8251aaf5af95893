#include "geodual/remesh/deviation_fitting.hpp"

#include "common/point_grid.hpp"
#include "post/vertex_search.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/triangle_distance.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

using detail::check_points;
using detail::kRadiansPerDegree;
using detail::movable_vertices;
using detail::Move;
using detail::QualityFloors;
using detail::smallest_angle;
using detail::VertexSearch;

/// The one-sided distances from the remesh of the surface's vertices (those
/// of its faces: a scan's unreferenced vertices are not on it) and of its
/// face centres, where those vertices are fewer than eight per remesh vertex:
/// each sample is charged to its nearest remesh vertex and measured to its
/// triangles and to those of the next nearest vertex, both within `radius`.
/// After moves, only the samples they can have changed are measured again,
/// the same as measuring all.
class DeviationRanking {
 public:
  DeviationRanking(const TriangleMesh& surface, const TriangleMesh& remesh, const detail::VertexFans& around,
                   double radius)
      : surface_(surface), remesh_(remesh), around_(around), radius_(radius) {
    std::vector<std::uint8_t> referenced(static_cast<std::size_t>(surface.num_vertices()), 0);
    for (Index f = 0; f < surface.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) referenced[static_cast<std::size_t>(surface.faces(f, k))] = 1;
    }
    for (Index v = 0; v < surface.num_vertices(); ++v) {
      if (referenced[static_cast<std::size_t>(v)]) samples_.push_back(v);
    }
    if (static_cast<Index>(samples_.size()) < 8 * remesh.num_vertices()) {
      for (Index f = 0; f < surface.num_faces(); ++f) samples_.push_back(surface.num_vertices() + f);
    }
    nearest_.assign(samples_.size(), {-1, -1});
    deviation_.assign(samples_.size(), 0.0);
    std::vector<Index> all(samples_.size());
    std::iota(all.begin(), all.end(), Index{0});
    measure(all);
  }

  /// After the vertices `moved` moved: the samples charged to them or to
  /// their neighbours, or that they may have come within reach of (a sample
  /// within the radius of a vertex's new place is charged to a vertex within
  /// twice the radius of it), and those charged to none.
  void update(std::span<const Index> moved) {
    if (moved.empty()) return;
    const detail::PointGrid grid = vertex_grid();
    std::vector<std::uint8_t> changed(static_cast<std::size_t>(remesh_.num_vertices()), 0);
    for (const Index m : moved) {
      for (const Index f : around_.around(m)) {
        for (int k = 0; k < 3; ++k) changed[static_cast<std::size_t>(remesh_.faces(f, k))] = 1;
      }
      const Eigen::Vector3d at = remesh_.vertices.row(m);
      grid.for_each_within(at, 2 * radius_, [&](Index slot, double) { changed[grid.original(slot)] = 1; });
    }
    std::vector<Index> again;
    for (std::size_t i = 0; i < nearest_.size(); ++i) {
      const auto [first, second] = nearest_[i];
      if (first < 0 || changed[first] || (second >= 0 && changed[second])) again.push_back(static_cast<Index>(i));
    }
    measure(again, grid);
  }

  /// The largest distance of the samples from the remesh, to any of its
  /// triangles. A sample's measure bounds its distance from above (its
  /// triangles are some of the remesh's), so the samples are measured
  /// exactly from the largest bound down, until the next bound is below the
  /// largest distance found. Samples charged to no vertex are measured too.
  double largest_distance() const {
    const detail::PointGrid grid = vertex_grid();
    double longest_edge = 0;
    for (Index f = 0; f < remesh_.num_faces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        longest_edge = std::max(
            longest_edge,
            (remesh_.vertices.row(remesh_.faces(f, k)) - remesh_.vertices.row(remesh_.faces(f, (k + 1) % 3))).norm());
      }
    }
    std::vector<std::pair<double, Index>> bounds(nearest_.size());
    for (std::size_t i = 0; i < bounds.size(); ++i) {
      bounds[i] = {nearest_[i][0] >= 0 ? deviation_[i] : std::numeric_limits<double>::infinity(),
                   static_cast<Index>(i)};
    }
    std::make_heap(bounds.begin(), bounds.end());
    double largest = 0;
    while (!bounds.empty() && bounds.front().first > largest) {
      std::pop_heap(bounds.begin(), bounds.end());
      const auto [bound, i] = bounds.back();
      bounds.pop_back();
      largest = std::max(largest, distance_to_remesh(sample(i), bound, grid, longest_edge));
    }
    return largest;
  }

  /// Per remesh vertex, the largest distance of the samples charged to it.
  std::vector<double> per_vertex() const {
    std::vector<double> largest(static_cast<std::size_t>(remesh_.num_vertices()), 0.0);
    for (std::size_t i = 0; i < nearest_.size(); ++i) {
      if (const Index v = nearest_[i][0]; v >= 0) largest[v] = std::max(largest[v], deviation_[i]);
    }
    return largest;
  }

 private:
  detail::PointGrid vertex_grid() const {
    std::vector<Eigen::Vector3d> positions(static_cast<std::size_t>(remesh_.num_vertices()));
    for (Index v = 0; v < remesh_.num_vertices(); ++v) positions[static_cast<std::size_t>(v)] = remesh_.vertices.row(v);
    return detail::PointGrid(positions, radius_);
  }

  /// The distance of x from the remesh's triangles, at most `bound` (or
  /// infinite): a triangle within it of x has its corners within it and the
  /// longest edge, among the vertices `grid` holds.
  double distance_to_remesh(const Eigen::Vector3d& x, double bound, const detail::PointGrid& grid,
                            double longest_edge) const {
    const auto to_face = [&](Index f) {
      return squared_distance_to_triangle(x, remesh_.vertices.row(remesh_.faces(f, 0)),
                                          remesh_.vertices.row(remesh_.faces(f, 1)),
                                          remesh_.vertices.row(remesh_.faces(f, 2)));
    };
    double closest = std::numeric_limits<double>::infinity();
    if (!std::isfinite(bound)) {
      for (Index f = 0; f < remesh_.num_faces(); ++f) closest = std::min(closest, to_face(f));
      return std::sqrt(closest);
    }
    grid.for_each_within(x, bound + longest_edge, [&](Index slot, double) {
      for (const Index f : around_.around(grid.original(slot))) closest = std::min(closest, to_face(f));
    });
    return std::sqrt(closest);
  }

  /// The position of the k-th sample.
  Eigen::Vector3d sample(Index k) const {
    const Index i = samples_[static_cast<std::size_t>(k)];
    if (i < surface_.num_vertices()) return surface_.vertices.row(i);
    const Index f = i - surface_.num_vertices();
    return (surface_.vertices.row(surface_.faces(f, 0)) + surface_.vertices.row(surface_.faces(f, 1)) +
            surface_.vertices.row(surface_.faces(f, 2)))
               .transpose() /
           3;
  }

  void measure(std::span<const Index> samples) { measure(samples, vertex_grid()); }

  /// The two nearest vertices and the distance of each of `samples`, on all threads.
  void measure(std::span<const Index> samples, const detail::PointGrid& grid) {
    const auto count = static_cast<Index>(samples.size());
    tbb::parallel_for(tbb::blocked_range<Index>(0, count, 4096), [&](const tbb::blocked_range<Index>& range) {
      for (Index k = range.begin(); k != range.end(); ++k) {
        const auto i = static_cast<std::size_t>(samples[static_cast<std::size_t>(k)]);
        const Eigen::Vector3d x = sample(static_cast<Index>(i));
        std::array<Index, 2> nearest{-1, -1};
        std::array<double, 2> squared{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        grid.for_each_within(x, radius_, [&](Index slot, double d2) {
          const Index v = grid.original(slot);
          if (d2 < squared[0] || (d2 == squared[0] && v < nearest[0])) {
            nearest = {v, nearest[0]};
            squared = {d2, squared[0]};
          } else if (d2 < squared[1] || (d2 == squared[1] && v < nearest[1])) {
            nearest[1] = v;
            squared[1] = d2;
          }
        });
        nearest_[i] = nearest;
        deviation_[i] = 0;
        if (nearest[0] < 0) continue;
        double closest = std::numeric_limits<double>::infinity();
        for (const Index v : nearest) {
          if (v < 0) continue;
          for (const Index f : around_.around(v)) {
            closest = std::min(closest, squared_distance_to_triangle(x, remesh_.vertices.row(remesh_.faces(f, 0)),
                                                                     remesh_.vertices.row(remesh_.faces(f, 1)),
                                                                     remesh_.vertices.row(remesh_.faces(f, 2))));
          }
        }
        deviation_[i] = std::sqrt(closest);
      }
    });
  }

  const TriangleMesh& surface_;
  const TriangleMesh& remesh_;  // read as it is moved
  const detail::VertexFans& around_;
  double radius_;
  std::vector<Index> samples_;                 // a surface vertex v, or face f as num_vertices() + f (its centre)
  std::vector<std::array<Index, 2>> nearest_;  // per sample: its vertex, the next nearest (-1: none within the radius)
  std::vector<double> deviation_;
};

}  // namespace

DeviationFittingResult fit_deviations(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology,
                                      TriangleMesh& remesh, std::vector<SurfacePoint>& points,
                                      std::span<const std::uint8_t> fixed, const DeviationFittingOptions& options) {
  if (!(options.share >= 0 && options.share < 1) || options.rounds < 0 || !(options.reach > 0 && options.reach <= 2) ||
      !(options.min_angle >= 0 && options.min_angle <= 60) || !(options.max_q_loss >= 0 && options.max_q_loss <= 1) ||
      !(options.max_move >= 0 && std::isfinite(options.max_move))) {
    throw UsageError("deviation smoothing: share " + std::to_string(options.share) + " must be in [0, 1), rounds " +
                     std::to_string(options.rounds) + " >= 0, reach " + std::to_string(options.reach) +
                     " in (0, 2], min_angle " + std::to_string(options.min_angle) + " in [0, 60], max_q_loss " +
                     std::to_string(options.max_q_loss) + " in [0, 1] and max_move " +
                     std::to_string(options.max_move) + " finite and >= 0");
  }
  check_points(remesh, points, "deviation smoothing");
  const auto start_time = std::chrono::steady_clock::now();
  DeviationFittingResult result;
  const auto finish = [&] {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return result;
  };
  const double edge = detail::mean_edge_length(remesh, detail::edge_sides(remesh));
  if (!(edge > 0)) return finish();
  const detail::VertexFans around = detail::vertex_fans(remesh);
  DeviationRanking ranking(surface, remesh, around, edge);
  std::vector<double> deviation = ranking.per_vertex();
  result.deviation_before = result.deviation_after = ranking.largest_distance();
  if (options.share == 0 || options.rounds == 0 || options.max_move == 0) return finish();
  // The floors: the remesh's smallest angle (or the bound, if lower), and
  // the worst Q of the triangles with no angle below the bound, which the
  // angle smoothing (next in the pipeline) leaves as they are, so that the
  // remesh's Qmin at the end is not lowered (without such triangles, the
  // remesh's worst).
  const double bound = options.min_angle * kRadiansPerDegree;
  double smallest = std::numbers::pi, worst_q = 1, worst_kept_q = 1;
  bool any_kept = false;
  for (Index f = 0; f < remesh.num_faces(); ++f) {
    const TriangleShape shape =
        triangle_shape(remesh.vertices.row(remesh.faces(f, 0)), remesh.vertices.row(remesh.faces(f, 1)),
                       remesh.vertices.row(remesh.faces(f, 2)));
    smallest = std::min(smallest, shape.min_angle());
    worst_q = std::min(worst_q, shape.q);
    if (shape.min_angle() >= bound) {
      worst_kept_q = std::min(worst_kept_q, shape.q);
      any_kept = true;
    }
  }
  const QualityFloors floors{std::min(smallest, bound), any_kept ? worst_kept_q : worst_q, options.max_q_loss};
  const std::vector<std::uint8_t> movable = movable_vertices(remesh, topology, points, fixed);
  VertexSearch search(surface, topology, remesh, around, points, bound, options.max_move);
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(remesh.num_vertices()), 0);
  std::vector<std::pair<double, Index>>
      worst;                          // the vertices to move: their deviation (negated, largest first), vertex
  std::vector<Index> moved_in_round;  // since the ranking was last brought up to date
  for (int round = 0; round < options.rounds; ++round) {
    if (round > 0) {
      ranking.update(moved_in_round);
      moved_in_round.clear();
      deviation = ranking.per_vertex();
    }
    const double largest = *std::max_element(deviation.begin(), deviation.end());
    worst.clear();
    for (Index v = 0; v < remesh.num_vertices(); ++v) {
      const double d = deviation[static_cast<std::size_t>(v)];
      if (movable[static_cast<std::size_t>(v)] && d >= options.share * largest && d > 0) worst.emplace_back(-d, v);
    }
    std::sort(worst.begin(), worst.end());
    bool any_moved = false;
    for (const auto& [negated, v] : worst) {
      double before = 0, after = 0;
      const std::optional<Move> move = search.least_deviation_move(v, options.reach, floors, before, after);
      if (!move) continue;
      remesh.vertices.row(v) = move->position.transpose();
      points[static_cast<std::size_t>(v)] = move->point;
      moved[static_cast<std::size_t>(v)] = 1;
      moved_in_round.push_back(v);
      any_moved = true;
    }
    if (!any_moved) break;
  }
  ranking.update(moved_in_round);
  result.deviation_after = ranking.largest_distance();
  result.vertices_moved = std::count(moved.begin(), moved.end(), std::uint8_t{1});
  return finish();
}

}  // namespace geodual::remesh
