#include "common/vertex_fields.hpp"

#include "geodual/mesh/face_area.hpp"

#include <algorithm>
#include <cmath>

namespace geodual::remesh::detail {
namespace {

/// Calls f(u, v) once per edge of the sorted sides.
template <class F>
void for_each_edge(const std::vector<std::array<Index, 3>>& sides, F f) {
  for (std::size_t i = 0; i < sides.size(); ++i) {
    if (i > 0 && sides[i][0] == sides[i - 1][0] && sides[i][1] == sides[i - 1][1]) continue;
    f(sides[i][0], sides[i][1]);
  }
}

}  // namespace

std::vector<double> vertex_areas(const TriangleMesh& mesh) {
  std::vector<double> area(static_cast<std::size_t>(mesh.num_vertices()), 0.0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    const double third = face_area(mesh, f) / 3;
    for (int c = 0; c < 3; ++c) area[mesh.faces(f, c)] += third;
  }
  return area;
}

std::vector<std::array<Index, 3>> edge_sides(const TriangleMesh& mesh) {
  std::vector<std::array<Index, 3>> sides;
  sides.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index u = mesh.faces(f, c), v = mesh.faces(f, (c + 1) % 3);
      sides.push_back({std::min(u, v), std::max(u, v), f});
    }
  }
  std::sort(sides.begin(), sides.end());
  return sides;
}

double mean_edge_length(const TriangleMesh& mesh, const std::vector<std::array<Index, 3>>& sides) {
  double sum = 0;
  for (const auto& side : sides) sum += (mesh.vertices.row(side[0]) - mesh.vertices.row(side[1])).norm();
  return sides.empty() ? 0.0 : sum / static_cast<double>(sides.size());
}

int smoothing_passes(double length, double mean_edge) {
  constexpr double kMaxPasses = 400;
  if (!(mean_edge > 0)) return 1;
  return static_cast<int>(std::clamp(std::ceil(std::pow(length / mean_edge, 2)), 1.0, kMaxPasses));
}

void smooth(std::vector<double>& value, const std::vector<std::array<Index, 3>>& sides, const std::vector<double>& area,
            int passes) {
  std::vector<double> sum(value.size()), weight(value.size());
  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t v = 0; v < value.size(); ++v) {
      sum[v] = area[v] * value[v];
      weight[v] = area[v];
    }
    for_each_edge(sides, [&](Index u, Index v) {
      sum[u] += area[v] * value[v];
      weight[u] += area[v];
      sum[v] += area[u] * value[u];
      weight[v] += area[u];
    });
    for (std::size_t v = 0; v < value.size(); ++v) {
      if (weight[v] > 0) value[v] = sum[v] / weight[v];
    }
  }
}

void dilate(std::vector<double>& value, const std::vector<std::array<Index, 3>>& sides, int passes) {
  std::vector<double> next;
  for (int pass = 0; pass < passes; ++pass) {
    next = value;
    for_each_edge(sides, [&](Index u, Index v) {
      next[u] = std::max(next[u], value[v]);
      next[v] = std::max(next[v], value[u]);
    });
    std::swap(value, next);
  }
}

}  // namespace geodual::remesh::detail
