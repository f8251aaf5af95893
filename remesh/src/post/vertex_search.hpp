#pragma once
// The search for a remesh vertex's best place on the surface, shared by the
// angle smoothing (angle_smoothing.hpp: where the smallest angle of its
// triangles is largest) and the deviation fitting (deviation_fitting.hpp:
// where the surface's farthest points round it come nearest, within quality
// floors). A vertex moves along the surface by straightest geodesics from
// where it is; see docs/algorithms.md#angle-smoothing.

#include "common/surface_walk.hpp"
#include "common/vertex_fields.hpp"

#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/triangle_shape.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace geodual::remesh::detail {

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
  /// they are) where those are nearer; with `first` (the remesh's vertices
  /// before a smoothing's first move), at most `allowance` farther than from
  /// these triangles as they were then, so that moves one after the other
  /// cannot each take a point a little farther away.
  void watch(std::span<const Eigen::Vector3d> samples, std::span<const Index> others = {},
             const VertexMatrix* first = nullptr, double allowance = 0) {
    samples_ = samples;
    distance_.resize(samples.size());
    beyond_.assign(samples.size(), std::numeric_limits<double>::infinity());
    const Eigen::Vector3d x = mesh_.vertices.row(vertex_);
    const auto now = [&](Index v) -> Eigen::Vector3d { return mesh_.vertices.row(v); };
    for (std::size_t i = 0; i < samples.size(); ++i) {
      beyond_[i] = distance_to_faces(samples[i], others, now);
      distance_[i] = std::min(distance(samples[i], x), beyond_[i]);
      if (first) {
        const auto then = [&](Index v) -> Eigen::Vector3d { return first->row(v); };
        distance_[i] = std::min(distance_[i], distance_to_faces(samples[i], faces_, then) + allowance);
      }
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
    return distance_to_faces(q, faces_, [&](Index v) -> Eigen::Vector3d {
      return v == vertex_ ? x : Eigen::Vector3d(mesh_.vertices.row(v));
    });
  }
  /// From point q to `faces` of the mesh, each vertex v at position(v) (infinite where there are none).
  template <class Position>
  double distance_to_faces(const Eigen::Vector3d& q, std::span<const Index> faces, const Position& position) const {
    double squared = std::numeric_limits<double>::infinity();
    for (const Index f : faces) {
      squared =
          std::min(squared, squared_distance_to_triangle(q, position(mesh_.faces(f, 0)), position(mesh_.faces(f, 1)),
                                                         position(mesh_.faces(f, 2))));
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

/// The smallest angle of triangle f of `mesh`, and of all its triangles (radians).
double smallest_angle(const TriangleMesh& mesh, Index f);
double smallest_angle(const TriangleMesh& mesh);

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
               const VertexFans& around, const std::vector<SurfacePoint>& points, double bound, double max_move)
      : surface_(surface),
        topology_(topology),
        remesh_(remesh),
        first_(remesh.vertices),
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
    // farther from any of them than 3 % of an edge, nor all the moves
    // together than 6 % (a vertex that slides off a crease or a rim, within
    // the surface, would cut it off; so would the corners round a hollow's
    // bottom, moving out of it a little at a time).
    if (!prepare(v, -1)) return move;
    RingJudge judge(remesh_, around_.around(v), v, bound_);
    const double slack = 0.03 * edge_;
    judge.watch(samples_, {}, &first_, slack);
    const Ring start = judge.at(start_);
    move.min_angle_before = move.min_angle = start.min_angle;
    if (start.folded) return move;
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
    const SurfacePoint point = walk_on_surface(surface_, topology_, origin, trial.x() * u_ + trial.y() * w_, length);
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
  const VertexMatrix first_;  // remesh_.vertices before the first move (best_move's judge)
  const VertexFans& around_;
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
                                           std::span<const std::uint8_t> fixed);

/// \throw UsageError unless `points` has one point per vertex of `remesh`.
void check_points(const TriangleMesh& remesh, const std::vector<SurfacePoint>& points, const std::string& what);

}  // namespace geodual::remesh::detail
