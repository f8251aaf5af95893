#include "geodual/remesh/angle_smoothing.hpp"

#include "post/vertex_search.hpp"

#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace geodual::remesh {

using detail::check_points;
using detail::kRadiansPerDegree;
using detail::movable_vertices;
using detail::Move;
using detail::smallest_angle;
using detail::VertexSearch;

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

}  // namespace geodual::remesh
