#include "geodual/remesh/angle_smoothing.hpp"

#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "geodual/mesh/triangle_shape.hpp"
#include "surface_walk.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

/// The faces round each vertex of a mesh (CSR).
struct FacesAround {
  std::vector<Index> begin;
  std::vector<Index> face;
  std::span<const Index> of(Index v) const {
    return {face.data() + begin[v], static_cast<std::size_t>(begin[v + 1] - begin[v])};
  }
};

FacesAround faces_around(const TriangleMesh& mesh) {
  FacesAround around;
  around.begin.assign(static_cast<std::size_t>(mesh.num_vertices()) + 1, 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) ++around.begin[mesh.faces(f, k) + 1];
  }
  for (Index v = 0; v < mesh.num_vertices(); ++v) around.begin[v + 1] += around.begin[v];
  around.face.resize(static_cast<std::size_t>(around.begin.back()));
  std::vector<Index> next(around.begin.begin(), around.begin.end() - 1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) around.face[next[mesh.faces(f, k)]++] = f;
  }
  return around;
}

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

  /// Points of the surface whose distance from the triangles at() watches.
  void watch(std::span<const Eigen::Vector3d> samples) {
    samples_ = samples;
    distance_.resize(samples.size());
    const Eigen::Vector3d x = mesh_.vertices.row(vertex_);
    for (std::size_t i = 0; i < samples.size(); ++i) distance_[i] = distance(samples[i], x);
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
  /// triangles than it was by more than `slack`.
  bool keeps_close(const Eigen::Vector3d& x, double slack) const {
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      if (distance(samples_[i], x) > distance_[i] + slack) return false;
    }
    return true;
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
  std::vector<double> distance_;  // per sample, before the move
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

/// The search for a vertex's best place (smooth_smallest_angles).
class VertexSearch {
 public:
  VertexSearch(const TriangleMesh& surface, const voronoi::SurfaceTopology& topology, const TriangleMesh& remesh,
               const FacesAround& around, const std::vector<SurfacePoint>& points, double bound, double max_move)
      : surface_(surface),
        topology_(topology),
        remesh_(remesh),
        around_(around),
        points_(points),
        bound_(bound),
        max_move_(max_move) {}

  Move best_move(Index v) {
    RingJudge judge(remesh_, around_.of(v), v, bound_);
    const Eigen::Vector3d start_position = remesh_.vertices.row(v);
    const SurfacePoint origin = points_[static_cast<std::size_t>(v)];
    Move move{origin, start_position, 0, 0};
    // The frame of the face the vertex lies on, and the scale of its edges.
    const Eigen::Vector3d a = surface_.vertices.row(surface_.faces(origin.element, 0));
    const Eigen::Vector3d b = surface_.vertices.row(surface_.faces(origin.element, 1));
    const Eigen::Vector3d c = surface_.vertices.row(surface_.faces(origin.element, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    if (!(normal.norm() > 0) || !normal.allFinite()) return move;
    const Eigen::Vector3d u = (b - a).normalized(), w = normal.normalized().cross(u);
    double edge = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    int ends = 0;
    for (const Index f : around_.of(v)) {
      for (int k = 0; k < 3; ++k) {
        if (remesh_.faces(f, k) == v) continue;
        const Eigen::Vector3d end = remesh_.vertices.row(remesh_.faces(f, k));
        edge += (end - start_position).norm();
        centroid += end;
        ++ends;
      }
    }
    if (ends == 0) return move;
    edge /= ends;
    centroid /= ends;
    const double reach = max_move_ * edge;
    // The surface's corners and face centres under the triangles round the
    // vertex, wherever it moves within reach: no move may take the remesh
    // farther from any of them than 3 % of an edge (a vertex that
    // slides off a crease or a rim, within the surface, would cut it off).
    double radius = 0;
    for (const Index f : around_.of(v)) {
      for (int k = 0; k < 3; ++k) {
        radius = std::max(radius, (Eigen::Vector3d(remesh_.vertices.row(remesh_.faces(f, k))) - start_position).norm());
      }
    }
    gather_samples(origin.element, start_position, radius + reach);
    judge.watch(samples_);
    const Ring start = judge.at(start_position);
    move.min_angle_before = move.min_angle = start.min_angle;
    if (start.folded) return move;
    const double slack = 0.03 * edge;
    // Whether the vertex walked by `trial` (in the frame) does better than
    // the best so far, which it then becomes.
    const auto improves = [&](const Eigen::Vector2d& trial) {
      const double length = trial.norm();
      if (length > reach) return false;
      const SurfacePoint point =
          detail::walk_on_surface(surface_, topology_, origin, trial.x() * u + trial.y() * w, length);
      const Eigen::Vector3d position = point.position(surface_);
      const Ring ring = judge.at(position);
      if (ring.folded || !(ring.min_angle > move.min_angle) || ring.min_q < start.min_q ||
          ring.angles_below > start.angles_below || !judge.keeps_close(position, slack)) {
        return false;
      }
      move = {point, position, start.min_angle, ring.min_angle};
      return true;
    };
    // First towards the centroid of its neighbours (Laplacian smoothing,
    // which a compass search can miss where two angles are smallest
    // together): the whole way, half or a quarter of it.
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();
    const Eigen::Vector2d towards((centroid - start_position).dot(u), (centroid - start_position).dot(w));
    for (const double fraction : {1.0, 0.5, 0.25}) {
      if (improves(fraction * towards)) offset = fraction * towards;
    }
    // Then a compass search: the best of eight steps is taken while one
    // improves, and the step halves when none does (at most 64 rounds of
    // trials: a guard, far above what a search takes).
    constexpr double kDiagonal = 0.70710678118654752;
    constexpr std::array<std::array<double, 2>, 8> kDirections{{{1, 0},
                                                                {-1, 0},
                                                                {0, 1},
                                                                {0, -1},
                                                                {kDiagonal, kDiagonal},
                                                                {-kDiagonal, kDiagonal},
                                                                {kDiagonal, -kDiagonal},
                                                                {-kDiagonal, -kDiagonal}}};
    double step = edge / 8;
    for (int tries = 0; step >= edge / 256 && tries < 64; ++tries) {
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
    return move;
  }

 private:
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
  const FacesAround& around_;
  const std::vector<SurfacePoint>& points_;
  double bound_;
  double max_move_;
  // Scratch of gather_samples.
  std::vector<Eigen::Vector3d> samples_;
  std::vector<Index> queue_;
  IndexHashSet reached_, corners_;
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
  if (points.size() != static_cast<std::size_t>(remesh.num_vertices())) {
    throw UsageError("angle smoothing: " + std::to_string(points.size()) + " points for a remesh of " +
                     std::to_string(remesh.num_vertices()) + " vertices");
  }
  const auto start_time = std::chrono::steady_clock::now();
  AngleSmoothingResult result;
  result.min_angle_before = result.min_angle_after = smallest_angle(remesh) / kRadiansPerDegree;
  const double bound = options.min_angle * kRadiansPerDegree;
  const auto finish = [&] {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return result;
  };
  if (remesh.num_faces() == 0 || !(result.min_angle_before < options.min_angle)) return finish();

  const FacesAround around = faces_around(remesh);
  const std::vector<std::uint8_t> on_remesh_boundary = build_mesh_topology(remesh).vertex_on_boundary;
  const auto movable = [&](Index v) {
    const auto i = static_cast<std::size_t>(v);
    const SurfacePoint& point = points[i];
    const bool at_vertex = point.kind == SurfacePoint::Kind::vertex ||
                           (point.barycentric.array() == 0).count() >= 2;  // a face point at one of its corners
    return !(i < fixed.size() && fixed[i]) && !on_remesh_boundary[i] && !at_vertex &&
           !detail::on_surface_boundary(topology, point);
  };
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
      for (const Index g : around.of(chosen_vertex)) {
        for (int k = 0; k < 3; ++k) stuck[static_cast<std::size_t>(remesh.faces(g, k))] = 0;
      }
    }
    if (!any_moved) break;
  }
  result.vertices_moved = std::count(moved.begin(), moved.end(), std::uint8_t{1});
  result.min_angle_after = smallest_angle(remesh) / kRadiansPerDegree;
  return finish();
}

}  // namespace geodual::remesh
