#include "geodual/remesh/angle_smoothing.hpp"

#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/triangle_shape.hpp"
#include "sampling_grid.hpp"
#include "surface_walk.hpp"
#include "vertex_fields.hpp"

#include <Eigen/Geometry>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

/// The triangles round one vertex as it would be at another position: their
/// smallest angle and quality, and whether any turned over.
struct Ring {
  double min_angle = std::numbers::pi;
  double min_q = 1;
  int angles_below = 0;  ///< the bound's
  bool folded = false;
};

class RingJudge {
 public:
  RingJudge(const TriangleMesh& mesh, std::span<const Index> faces, Index vertex, double bound)
      : mesh_(mesh), faces_(faces), vertex_(vertex), bound_(bound) {
    normal_.reserve(faces.size());
    for (const Index f : faces) normal_.push_back(corners(f, mesh.vertices.row(vertex)).normal);
  }

  /// Points of the surface whose distance from the remesh the judge
  /// watches: from these triangles, or from the `others` (which stay where
  /// they are) where those are nearer.
  void watch(std::span<const Eigen::Vector3d> samples, std::span<const Index> others = {}) {
    samples_ = samples;
    distance_.resize(samples.size());
    beyond_.assign(samples.size(), std::numeric_limits<double>::infinity());
    const Eigen::Vector3d x = mesh_.vertices.row(vertex_);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      for (const Index f : others) {
        beyond_[i] =
            std::min(beyond_[i], squared_distance_to_triangle(samples[i], mesh_.vertices.row(mesh_.faces(f, 0)),
                                                              mesh_.vertices.row(mesh_.faces(f, 1)),
                                                              mesh_.vertices.row(mesh_.faces(f, 2))));
      }
      beyond_[i] = std::sqrt(beyond_[i]);
      distance_[i] = std::min(distance(samples[i], x), beyond_[i]);
    }
  }

  Ring at(const Eigen::Vector3d& x) const {
    Ring ring;
    for (std::size_t i = 0; i < faces_.size(); ++i) {
      const Corners c = corners(faces_[i], x);
      // Turned over: against its normal before the move, or flat.
      if (!(c.normal.dot(normal_[i]) > 0)) {
        ring.folded = true;
        return ring;
      }
      const TriangleShape shape = triangle_shape(c.p[0], c.p[1], c.p[2]);
      ring.min_angle = std::min(ring.min_angle, shape.min_angle());
      ring.min_q = std::min(ring.min_q, shape.q);
      ring.angles_below += static_cast<int>(
          std::count_if(shape.angles.begin(), shape.angles.end(), [&](double angle) { return angle < bound_; }));
    }
    return ring;
  }

  /// Whether, with the vertex at x, no watched point is farther from the
  /// remesh than it was by more than `slack`.
  bool keeps_close(const Eigen::Vector3d& x, double slack) const {
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      if (beyond_[i] <= distance_[i] + slack) continue;  // the other triangles keep it close
      if (distance(samples_[i], x) > distance_[i] + slack) return false;
    }
    return true;
  }

  /// The largest distance from the remesh, with the vertex at x, of the
  /// first `count` watched points, and which of them it is.
  std::pair<double, std::size_t> farthest(const Eigen::Vector3d& x, std::size_t count) const {
    std::pair<double, std::size_t> most{0.0, 0};
    for (std::size_t i = 0; i < count && i < samples_.size(); ++i) {
      const double d = std::min(distance(samples_[i], x), beyond_[i]);
      if (d > most.first) most = {d, i};
    }
    return most;
  }

  /// The mean quality of the triangles with the vertex at x.
  double mean_q(const Eigen::Vector3d& x) const {
    double sum = 0;
    for (const Index f : faces_) {
      const Corners c = corners(f, x);
      sum += triangle_shape(c.p[0], c.p[1], c.p[2]).q;
    }
    return faces_.empty() ? 1.0 : sum / static_cast<double>(faces_.size());
  }

 private:
  struct Corners {
    std::array<Eigen::Vector3d, 3> p;
    Eigen::Vector3d normal;
  };
  /// From point q to the triangles with the vertex at x.
  double distance(const Eigen::Vector3d& q, const Eigen::Vector3d& x) const {
    double squared = std::numeric_limits<double>::infinity();
    for (const Index f : faces_) {
      const Corners c = corners(f, x);
      squared = std::min(squared, squared_distance_to_triangle(q, c.p[0], c.p[1], c.p[2]));
    }
    return std::sqrt(squared);
  }
  Corners corners(Index f, const Eigen::Vector3d& x) const {
    Corners c;
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh_.faces(f, k);
      c.p[static_cast<std::size_t>(k)] = v == vertex_ ? x : Eigen::Vector3d(mesh_.vertices.row(v));
    }
    c.normal = (c.p[1] - c.p[0]).cross(c.p[2] - c.p[0]);
    return c;
  }

  const TriangleMesh& mesh_;
  std::span<const Index> faces_;
  Index vertex_;
  double bound_;
  std::vector<Eigen::Vector3d> normal_;
  std::span<const Eigen::Vector3d> samples_;
  std::vector<double> distance_;  // per sample, from the remesh before the move
  std::vector<double> beyond_;    // per sample, from the other triangles watched
};

double smallest_angle(const TriangleMesh& mesh, Index f) {
  return triangle_shape(mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)),
                        mesh.vertices.row(mesh.faces(f, 2)))
      .min_angle();
}

double smallest_angle(const TriangleMesh& mesh) {
  double smallest = std::numbers::pi;
  for (Index f = 0; f < mesh.num_faces(); ++f) smallest = std::min(smallest, smallest_angle(mesh, f));
  return smallest;
}

/// A vertex's best place: where on the surface, and the smallest angle of
/// its triangles there and where it is.
struct Move {
  SurfacePoint point;
  Eigen::Vector3d position;
  double min_angle_before = 0;
  double min_angle = 0;
  bool better() const { return min_angle > min_angle_before; }
};

/// The floors a move keeps to (smooth_largest_deviations): the least
/// smallest angle, worst Q and mean Q its triangles may end with.
struct QualityFloors {
  double min_angle = 0;  ///< radians
  double min_q = 0;
  double max_q_loss = 0;
};

/// The searches for a vertex's best place (smooth_smallest_angles,
/// smooth_largest_deviations).
class VertexSearch {
 public:
  VertexSearch(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology, const TriangleMesh& remesh,
               const detail::VertexFans& around, const std::vector<SurfacePoint>& points, double bound, double max_move)
      : surface_(surface),
        topology_(topology),
        remesh_(remesh),
        around_(around),
        points_(points),
        bound_(bound),
        max_move_(max_move) {}

  /// Where the smallest angle of v's triangles is largest.
  Move best_move(Index v) {
    const SurfacePoint origin = points_[static_cast<std::size_t>(v)];
    Move move{origin, remesh_.vertices.row(v), 0, 0};
    // The surface's corners and face centres under the triangles round the
    // vertex, wherever it moves within reach: no move may take the remesh
    // farther from any of them than 3 % of an edge (a vertex that
    // slides off a crease or a rim, within the surface, would cut it off).
    if (!prepare(v, -1)) return move;
    RingJudge judge(remesh_, around_.around(v), v, bound_);
    judge.watch(samples_);
    const Ring start = judge.at(start_);
    move.min_angle_before = move.min_angle = start.min_angle;
    if (start.folded) return move;
    const double slack = 0.03 * edge_;
    // Whether the vertex walked by `trial` (in the frame) does better than
    // the best so far, which it then becomes.
    const auto improves = [&](const Eigen::Vector2d& trial) {
      const std::optional<Move> at = walked(origin, trial);
      if (!at) return false;
      const Ring ring = judge.at(at->position);
      if (ring.folded || !(ring.min_angle > move.min_angle) || ring.min_q < start.min_q ||
          ring.angles_below > start.angles_below || !judge.keeps_close(at->position, slack)) {
        return false;
      }
      move = {at->point, at->position, start.min_angle, ring.min_angle};
      return true;
    };
    // First towards the centroid of its neighbours (Laplacian smoothing,
    // which a compass search can miss where two angles are smallest
    // together): the whole way, half or a quarter of it.
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();
    const Eigen::Vector2d towards = in_frame(centroid_);
    for (const double fraction : {1.0, 0.5, 0.25}) {
      if (improves(fraction * towards)) offset = fraction * towards;
    }
    compass_search(offset, improves, 256, 64);
    return move;
  }

  /// Where the largest distance of the surface's points within
  /// `reach_in_edges` mean edges of v from the remesh is least, within the
  /// floors; sets `before` and `after` to that distance. A move that does
  /// not lower it is none.
  std::optional<Move> least_deviation_move(Index v, double reach_in_edges, const QualityFloors& floors, double& before,
                                           double& after) {
    const SurfacePoint origin = points_[static_cast<std::size_t>(v)];
    std::optional<Move> move;
    before = after = 0;
    if (!prepare(v, reach_in_edges) || own_ == 0) return std::nullopt;
    RingJudge judge(remesh_, around_.around(v), v, bound_);
    judge.watch(samples_, second_ring(v));
    const Ring start = judge.at(start_);
    if (start.folded) return std::nullopt;
    const auto [deviation, worst] = judge.farthest(start_, own_);
    before = after = deviation;
    const double min_angle = std::min(start.min_angle, floors.min_angle);
    const double min_q = std::min(start.min_q, floors.min_q);
    const double min_mean_q = judge.mean_q(start_) - floors.max_q_loss;
    const double slack = 0.03 * edge_;
    const auto improves = [&](const Eigen::Vector2d& trial) {
      const std::optional<Move> at = walked(origin, trial);
      if (!at) return false;
      const Ring ring = judge.at(at->position);
      if (ring.folded || ring.min_angle < min_angle || ring.min_q < min_q || ring.angles_below > start.angles_below ||
          judge.mean_q(at->position) < min_mean_q) {
        return false;
      }
      const double reached = judge.farthest(at->position, own_).first;
      if (!(reached < after) || !judge.keeps_close(at->position, slack)) return false;
      after = reached;
      move = at;
      return true;
    };
    // First towards the farthest point (on the crease the remesh cuts off),
    // then the compass search.
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();
    const Eigen::Vector2d towards = in_frame(samples_[worst]);
    for (const double fraction : {1.0, 0.75, 0.5, 0.25}) {
      if (improves(fraction * towards)) {
        offset = fraction * towards;
        break;
      }
    }
    compass_search(offset, improves, 64, 24);
    return move;
  }

 private:
  /// The vertex's frame (the plane of the surface's face it lies on), its
  /// mean edge, centroid of its neighbours, reach, and the samples: with
  /// reach_in_edges < 0, those under its triangles wherever it moves within
  /// reach; otherwise those within that many mean edges of it, of which the
  /// first own_ are nearer to it than to any other vertex. False where the
  /// vertex has no edges or its face no area.
  bool prepare(Index v, double reach_in_edges) {
    start_ = remesh_.vertices.row(v);
    const SurfacePoint& origin = points_[static_cast<std::size_t>(v)];
    const Eigen::Vector3d a = surface_.vertices.row(surface_.faces(origin.element, 0));
    const Eigen::Vector3d b = surface_.vertices.row(surface_.faces(origin.element, 1));
    const Eigen::Vector3d c = surface_.vertices.row(surface_.faces(origin.element, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    if (!(normal.norm() > 0) || !normal.allFinite()) return false;
    u_ = (b - a).normalized();
    w_ = normal.normalized().cross(u_);
    double edge = 0, radius = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    int ends = 0;
    for (const Index f : around_.around(v)) {
      for (int k = 0; k < 3; ++k) {
        if (remesh_.faces(f, k) == v) continue;
        const Eigen::Vector3d end = remesh_.vertices.row(remesh_.faces(f, k));
        edge += (end - start_).norm();
        radius = std::max(radius, (end - start_).norm());
        centroid += end;
        ++ends;
      }
    }
    if (ends == 0) return false;
    edge_ = edge / ends;
    centroid_ = centroid / ends;
    reach_ = max_move_ * edge_;
    gather_samples(origin.element, start_, reach_in_edges < 0 ? radius + reach_ : reach_in_edges * edge_);
    if (reach_in_edges >= 0) {
      // Its own first: nearer to it than to its neighbours.
      const auto own_end = std::partition(samples_.begin(), samples_.end(), [&](const Eigen::Vector3d& q) {
        const double d = (q - start_).squaredNorm();
        for (const Index f : around_.around(v)) {
          for (int k = 0; k < 3; ++k) {
            if ((Eigen::Vector3d(remesh_.vertices.row(remesh_.faces(f, k))) - q).squaredNorm() < d) return false;
          }
        }
        return true;
      });
      own_ = static_cast<std::size_t>(own_end - samples_.begin());
    }
    return true;
  }

  /// The vertex walked on the surface from `origin` by `trial` (in its
  /// frame), where that is within reach; only the place is filled in.
  std::optional<Move> walked(const SurfacePoint& origin, const Eigen::Vector2d& trial) const {
    const double length = trial.norm();
    if (length > reach_) return std::nullopt;
    const SurfacePoint point =
        detail::walk_on_surface(surface_, topology_, origin, trial.x() * u_ + trial.y() * w_, length);
    return Move{point, point.position(surface_), 0, 0};
  }

  /// A point's offset from the vertex in its frame.
  Eigen::Vector2d in_frame(const Eigen::Vector3d& x) const { return {(x - start_).dot(u_), (x - start_).dot(w_)}; }

  /// The compass search from `offset`: the best of eight steps is taken
  /// while one improves, and the step halves when none does, from an eighth
  /// of an edge down to 1/`finest` of it (at most `max_rounds` rounds of
  /// trials: a guard, far above what a search takes).
  template <class Improves>
  void compass_search(Eigen::Vector2d offset, Improves& improves, double finest, int max_rounds) const {
    constexpr double kDiagonal = 0.70710678118654752;
    constexpr std::array<std::array<double, 2>, 8> kDirections{{{1, 0},
                                                                {-1, 0},
                                                                {0, 1},
                                                                {0, -1},
                                                                {kDiagonal, kDiagonal},
                                                                {-kDiagonal, kDiagonal},
                                                                {kDiagonal, -kDiagonal},
                                                                {-kDiagonal, -kDiagonal}}};
    double step = edge_ / 8;
    for (int tries = 0; step >= edge_ / finest && tries < max_rounds; ++tries) {
      Eigen::Vector2d best_offset = offset;
      for (const auto& [du, dw] : kDirections) {
        const Eigen::Vector2d trial = offset + step * Eigen::Vector2d(du, dw);
        if (improves(trial)) best_offset = trial;
      }
      if (best_offset != offset) {
        offset = best_offset;
      } else {
        step /= 2;
      }
    }
  }

  /// The triangles round v's neighbours that are not round v.
  std::span<const Index> second_ring(Index v) {
    second_ring_.clear();
    const auto ring = around_.around(v);
    for (const Index f : ring) {
      for (int k = 0; k < 3; ++k) {
        const Index w = remesh_.faces(f, k);
        if (w == v) continue;
        for (const Index g : around_.around(w)) {
          if (std::find(ring.begin(), ring.end(), g) == ring.end() &&
              std::find(second_ring_.begin(), second_ring_.end(), g) == second_ring_.end()) {
            second_ring_.push_back(g);
          }
        }
      }
    }
    return second_ring_;
  }

  /// samples_: the corners and centres of the surface's faces within
  /// `radius` of x, reached from `face` across its edges (at most
  /// kMaxFaces faces: a guard for surfaces far finer than the remesh).
  void gather_samples(Index face, const Eigen::Vector3d& x, double radius) {
    constexpr std::size_t kMaxFaces = 4096, kMaxSamples = 1024;
    samples_.clear();
    queue_.assign(1, face);
    reached_.clear();
    reached_.insert(face);
    corners_.clear();
    const auto within = [&](Index f) {
      for (int k = 0; k < 3; ++k) {
        if ((Eigen::Vector3d(surface_.vertices.row(surface_.faces(f, k))) - x).norm() <= radius) return true;
      }
      return false;
    };
    for (std::size_t next = 0; next < queue_.size() && queue_.size() < kMaxFaces; ++next) {
      const Index f = queue_[next];
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const Index corner = surface_.faces(f, k);
        centre += surface_.vertices.row(corner).transpose() / 3;
        if (corners_.insert(corner)) samples_.push_back(surface_.vertices.row(corner).transpose());
      }
      samples_.push_back(centre);
      for (const Index edge : topology_.face_edges[static_cast<std::size_t>(f)]) {
        if (edge < 0) continue;
        for (const Index g : topology_.edge_faces[static_cast<std::size_t>(edge)]) {
          if (g >= 0 && within(g) && reached_.insert(g)) queue_.push_back(g);
        }
      }
    }
    // Where the surface is much finer than the remesh, every k-th of them:
    // still several per triangle.
    if (samples_.size() > kMaxSamples) {
      const std::size_t every = (samples_.size() + kMaxSamples - 1) / kMaxSamples;
      std::size_t kept = 0;
      for (std::size_t i = 0; i < samples_.size(); i += every) samples_[kept++] = samples_[i];
      samples_.resize(kept);
    }
  }

  const TriangleMesh& surface_;
  const voronoi::SurfaceTopology& topology_;
  const TriangleMesh& remesh_;
  const detail::VertexFans& around_;
  const std::vector<SurfacePoint>& points_;
  double bound_;
  double max_move_;
  // What prepare() found for the vertex searched.
  Eigen::Vector3d start_, u_, w_, centroid_;
  double edge_ = 0, reach_ = 0;
  std::size_t own_ = 0;
  // Scratch of gather_samples and second_ring.
  std::vector<Eigen::Vector3d> samples_;
  std::vector<Index> queue_;
  IndexHashSet reached_, corners_;
  std::vector<Index> second_ring_;
};

/// Per vertex of `remesh`, whether a smoothing may move it (the contract of
/// smooth_smallest_angles).
std::vector<std::uint8_t> movable_vertices(const TriangleMesh& remesh, const voronoi::SurfaceTopology& topology,
                                           const std::vector<SurfacePoint>& points,
                                           std::span<const std::uint8_t> fixed) {
  const std::vector<std::uint8_t> on_remesh_boundary = build_mesh_topology(remesh).vertex_on_boundary;
  std::vector<std::uint8_t> movable(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& point = points[i];
    const bool at_vertex = point.kind == SurfacePoint::Kind::vertex ||
                           (point.barycentric.array() == 0).count() >= 2;  // a face point at one of its corners
    movable[i] = !(i < fixed.size() && fixed[i]) && !on_remesh_boundary[i] && !at_vertex &&
                 !detail::on_surface_boundary(topology, point);
  }
  return movable;
}

void check_points(const TriangleMesh& remesh, const std::vector<SurfacePoint>& points, const std::string& what) {
  if (points.size() != static_cast<std::size_t>(remesh.num_vertices())) {
    throw UsageError(what + ": " + std::to_string(points.size()) + " points for a remesh of " +
                     std::to_string(remesh.num_vertices()) + " vertices");
  }
}

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

AngleSmoothingResult smooth_smallest_angles(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology,
                                            TriangleMesh& remesh, std::vector<SurfacePoint>& points,
                                            std::span<const std::uint8_t> fixed, const AngleSmoothingOptions& options) {
  if (!(options.min_angle >= 0 && options.min_angle <= 60) || options.rounds < 0 ||
      !(options.max_move >= 0 && std::isfinite(options.max_move))) {
    throw UsageError("angle smoothing: min_angle " + std::to_string(options.min_angle) +
                     " must be in [0, 60], rounds " + std::to_string(options.rounds) + " >= 0 and max_move " +
                     std::to_string(options.max_move) + " finite and >= 0");
  }
  check_points(remesh, points, "angle smoothing");
  const auto start_time = std::chrono::steady_clock::now();
  AngleSmoothingResult result;
  result.min_angle_before = result.min_angle_after = smallest_angle(remesh) / kRadiansPerDegree;
  const double bound = options.min_angle * kRadiansPerDegree;
  const auto finish = [&] {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return result;
  };
  if (remesh.num_faces() == 0 || !(result.min_angle_before < options.min_angle)) return finish();

  const detail::VertexFans around = detail::vertex_fans(remesh);
  const std::vector<std::uint8_t> may_move = movable_vertices(remesh, topology, points, fixed);
  const auto movable = [&](Index v) { return may_move[static_cast<std::size_t>(v)] != 0; };
  VertexSearch search(surface, topology, remesh, around, points, bound, options.max_move);
  std::vector<std::pair<double, Index>> worst;  // the triangles below the bound: smallest angle, face
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(remesh.num_vertices()), 0);
  // Vertices whose search found no better place, as long as nothing round them moved.
  std::vector<std::uint8_t> stuck(static_cast<std::size_t>(remesh.num_vertices()), 0);
  for (int round = 0; round < options.rounds; ++round) {
    worst.clear();
    for (Index f = 0; f < remesh.num_faces(); ++f) {
      if (const double angle = smallest_angle(remesh, f); angle < bound) worst.emplace_back(angle, f);
    }
    std::sort(worst.begin(), worst.end());
    // Worst first: of a triangle's corners, the one whose best place gives
    // its triangles the largest smallest angle moves (the one that is out
    // of place, where its neighbours would only make up for it).
    bool any_moved = false;
    for (const auto& [angle, f] : worst) {
      if (!(smallest_angle(remesh, f) < bound)) continue;  // mended by a move before
      std::optional<Move> chosen;
      Index chosen_vertex = -1;
      for (int k = 0; k < 3; ++k) {
        const Index v = remesh.faces(f, k);
        if (!movable(v) || stuck[static_cast<std::size_t>(v)]) continue;
        const Move move = search.best_move(v);
        if (!move.better()) {
          stuck[static_cast<std::size_t>(v)] = 1;
        } else if (!chosen || move.min_angle > chosen->min_angle) {
          chosen = move;
          chosen_vertex = v;
        }
      }
      if (!chosen) continue;
      remesh.vertices.row(chosen_vertex) = chosen->position.transpose();
      points[static_cast<std::size_t>(chosen_vertex)] = chosen->point;
      moved[static_cast<std::size_t>(chosen_vertex)] = 1;
      any_moved = true;
      // Its neighbours' triangles changed: they may move again.
      for (const Index g : around.around(chosen_vertex)) {
        for (int k = 0; k < 3; ++k) stuck[static_cast<std::size_t>(remesh.faces(g, k))] = 0;
      }
    }
    if (!any_moved) break;
  }
  result.vertices_moved = std::count(moved.begin(), moved.end(), std::uint8_t{1});
  result.min_angle_after = smallest_angle(remesh) / kRadiansPerDegree;
  return finish();
}

DeviationSmoothingResult smooth_largest_deviations(const TriangleMesh& surface,
                                                   const voronoi::SurfaceTopology& topology, TriangleMesh& remesh,
                                                   std::vector<SurfacePoint>& points,
                                                   std::span<const std::uint8_t> fixed,
                                                   const DeviationSmoothingOptions& options) {
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
  DeviationSmoothingResult result;
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
