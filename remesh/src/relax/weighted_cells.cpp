#include "relax/weighted_cells.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace geodual::remesh::detail {
namespace {

/// The gradient of the linear interpolant of `density` on face f (a vector in
/// its plane), sum_c rho_c grad(lambda_c) with grad(lambda_c) =
/// n x (p_{c+2} - p_{c+1}) / |n|^2, and the face's unnormalised normal n
/// (|n| = twice its area).
std::pair<Eigen::Vector3d, Eigen::Vector3d> face_gradient(const TriangleMesh& mesh, Index f,
                                                          std::span<const double> density) {
  Eigen::Vector3d p[3];
  for (int c = 0; c < 3; ++c) p[c] = mesh.vertices.row(mesh.faces(f, c)).transpose();
  const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
  const double n2 = n.squaredNorm();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  if (!(n2 > 0)) return {gradient, n};
  // grad(lambda_0) = -grad(lambda_1) - grad(lambda_2): differences to corner
  // 0, exactly zero for a constant density.
  const double rho0 = density[mesh.faces(f, 0)];
  for (int c = 1; c < 3; ++c) {
    gradient += (density[mesh.faces(f, c)] - rho0) * n.cross(p[(c + 2) % 3] - p[(c + 1) % 3]) / n2;
  }
  return {gradient, n};
}

}  // namespace

double WeightedCells::total_energy() const { return std::accumulate(energy.begin(), energy.end(), 0.0); }

WeightedCells weighted_cells(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                             const voronoi::VoronoiDiagram& diagram, std::span<const double> density) {
  const std::size_t n = sites.size();
  WeightedCells cells;
  if (density.empty()) {
    cells.mass = diagram.cell_area;
    cells.moment = diagram.cell_log_moment;
    cells.energy = diagram.cell_energy;
    cells.site_density.assign(n, 1.0);
    return cells;
  }
  // rho and its surface gradient at each site: in the site's face, or for a
  // vertex site the area-weighted mean over the faces around it, projected
  // on the plane normal to their area-weighted normal (the tangent plane of
  // cell_log_moment).
  std::vector<double> rho(n, 0.0);
  std::vector<Eigen::Vector3d> gradient(n, Eigen::Vector3d::Zero());
  std::vector<Index> vertex_site;
  for (std::size_t s = 0; s < n; ++s) {
    const SurfacePoint& site = sites[s];
    if (site.kind == SurfacePoint::Kind::face) {
      const double rho0 = density[mesh.faces(site.element, 0)];
      rho[s] = rho0 + site.barycentric[1] * (density[mesh.faces(site.element, 1)] - rho0) +
               site.barycentric[2] * (density[mesh.faces(site.element, 2)] - rho0);
      gradient[s] = face_gradient(mesh, site.element, density).first;
      continue;
    }
    rho[s] = density[site.element];
    if (vertex_site.empty()) vertex_site.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
    vertex_site[site.element] = static_cast<Index>(s);
  }
  if (!vertex_site.empty()) {
    std::vector<double> weight(n, 0.0);
    std::vector<Eigen::Vector3d> normal(n, Eigen::Vector3d::Zero());
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (diagram.field.face_edges[f][0] < 0) continue;
      for (int c = 0; c < 3; ++c) {
        const Index s = vertex_site[mesh.faces(f, c)];
        if (s < 0) continue;
        const auto [g, face_normal] = face_gradient(mesh, f, density);
        const double twice_area = face_normal.norm();
        gradient[s] += twice_area * g;
        weight[s] += twice_area;
        normal[s] += face_normal;
      }
    }
    for (std::size_t s = 0; s < n; ++s) {
      if (sites[s].kind != SurfacePoint::Kind::vertex) continue;
      if (!(weight[s] > 0) || !(normal[s].norm() > 0)) {
        gradient[s].setZero();
        continue;
      }
      const Eigen::Vector3d unit = normal[s].normalized();
      gradient[s] /= weight[s];
      gradient[s] -= unit.dot(gradient[s]) * unit;
    }
  }
  cells.mass.resize(n);
  cells.moment.resize(n);
  cells.energy.resize(n);
  cells.site_density = rho;
  for (std::size_t s = 0; s < n; ++s) {
    const double area = diagram.cell_area[s], energy = diagram.cell_energy[s];
    const Eigen::Vector3d& m = diagram.cell_log_moment[s];
    Eigen::Vector3d g = gradient[s];
    // rho linear over the cell changes by at most rho_s / 2 within the
    // radius R of the disk with the cell's area and energy (E = pi R^4 / 2).
    if (area > 0 && energy > 0) {
      const double radius = std::sqrt(2 * energy / area);
      const double cap = 0.5 * rho[s] / radius;
      if (g.norm() > cap) g *= cap / g.norm();
    } else {
      g.setZero();
    }
    // (The cap keeps the mass near rho_s A; the floor only guards odd cells.)
    cells.mass[s] = std::max(rho[s] * area + g.dot(m), 0.5 * rho[s] * area);
    cells.moment[s] = rho[s] * m + 0.5 * energy * g;
    cells.energy[s] = rho[s] * energy + (area > 0 ? 2 * energy / area * g.dot(m) : 0.0);
  }
  return cells;
}

}  // namespace geodual::remesh::detail
