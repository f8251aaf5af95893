#include "geodual/remesh/curvature_density.hpp"

#include "common/vertex_fields.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

Eigen::Vector3d corner(const TriangleMesh& mesh, Index f, int c) {
  return mesh.vertices.row(mesh.faces(f, c)).transpose();
}

/// |k1| + |k2| per vertex: sum over its edges of |dihedral angle| * length,
/// over twice its area. Boundary and non-manifold edges add nothing.
std::vector<double> total_curvature(const TriangleMesh& mesh, const std::vector<std::array<Index, 3>>& sides,
                                    const std::vector<double>& area) {
  std::vector<double> bend(area.size(), 0.0);
  auto normal = [&](Index f) {
    return Eigen::Vector3d((corner(mesh, f, 1) - corner(mesh, f, 0)).cross(corner(mesh, f, 2) - corner(mesh, f, 0)));
  };
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j][0] == sides[i][0] && sides[j][1] == sides[i][1]) ++j;
    if (j - i == 2) {
      const Eigen::Vector3d n0 = normal(sides[i][2]), n1 = normal(sides[i + 1][2]);
      const double angle = std::atan2(n0.cross(n1).norm(), n0.dot(n1));  // in [0, pi]
      const double length = (mesh.vertices.row(sides[i][0]) - mesh.vertices.row(sides[i][1])).norm();
      if (std::isfinite(angle)) {
        bend[sides[i][0]] += angle * length;
        bend[sides[i][1]] += angle * length;
      }
    }
    i = j;
  }
  std::vector<double> k(area.size(), 0.0);
  for (std::size_t v = 0; v < k.size(); ++v) {
    if (area[v] > 0) k[v] = bend[v] / (2 * area[v]);
  }
  return k;
}

}  // namespace

double uniform_spacing(const TriangleMesh& mesh, std::int64_t sites) {
  double area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    area += face_area(mesh, f);
  }
  return sites > 0 ? std::sqrt(2 * area / (std::sqrt(3.0) * static_cast<double>(sites))) : 0.0;
}

void check_options(const CurvatureDensityOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("curvature_density: " + what);
  };
  require(options.strength >= 0 && std::isfinite(options.strength),
          "strength must be a finite number >= 0, got " + std::to_string(options.strength));
  require(options.spacing > 0 && std::isfinite(options.spacing),
          "spacing must be a finite number > 0, got " + std::to_string(options.spacing));
  require(options.max_ratio >= 1 && std::isfinite(options.max_ratio),
          "max_ratio must be a finite number >= 1, got " + std::to_string(options.max_ratio));
}

std::vector<double> curvature_density(const TriangleMesh& mesh, const CurvatureDensityOptions& options) {
  check_options(options);
  std::vector<double> density(static_cast<std::size_t>(mesh.num_vertices()), 1.0);
  if (options.strength == 0 || options.max_ratio == 1) return density;

  const std::vector<double> area = detail::vertex_areas(mesh);
  const std::vector<std::array<Index, 3>> sides = detail::edge_sides(mesh);
  const double edge = detail::mean_edge_length(mesh, sides);
  if (!(edge > 0)) return density;
  const int passes = detail::smoothing_passes(options.spacing, edge);  // over one spacing

  std::vector<double> k = total_curvature(mesh, sides, area);
  detail::smooth(k, sides, area, passes);
  for (std::size_t v = 0; v < density.size(); ++v) {
    const double scaled = options.spacing * k[v];
    density[v] = std::min(options.max_ratio, 1 + options.strength * scaled * scaled);
  }
  detail::smooth(density, sides, area, passes);
  return density;
}

}  // namespace geodual::remesh
