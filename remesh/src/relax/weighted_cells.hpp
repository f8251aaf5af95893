#pragma once
// The Voronoi cells' integrals under a density rho (the weighted CVT energy
// F = sum_i int_cell rho(x) d(x, s_i)^2 dA), from the diagram's unweighted
// ones: the diagram gives, per cell, its area A, the first moment of the log
// map M = int log_s(x) dA and the energy E = int d^2 dA. With rho linear
// across the cell in the site's tangent plane, rho(x) ~ rho_s + g . log_s(x)
// (g: rho's surface gradient at the site),
//   mass    int rho dA         = rho_s A + g . M
//   moment  int rho log_s dA   = rho_s M + J g,          J = int log log^T dA
//   energy  int rho d^2 dA     = rho_s E + g . int d^2 log_s dA.
// J and the third moment are not in the diagram; for a cell of isotropic
// shape J = (E / 2) I, and a cell whose centroid is off its site by
// delta = M / A has int d^2 log ~ 2 E delta (first order in delta), so
//   moment ~ rho_s M + (E / 2) g,   energy ~ rho_s E + 2 (E / A) g . M.
// This energy's gradient with respect to the site is -2 times this moment to
// first order (the Voronoi partition is optimal for any rho > 0, so the
// boundary terms cancel as in the unweighted case): the weighted Lloyd step
// moment / mass and the energy the relaxation checks agree. The model is
// first order in rho's variation across a cell; g is capped so that it
// changes rho by at most half across the cell (curvature_density smooths
// rho over about a cell to keep within it). With no density, the diagram's
// integrals as they are.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace geodual::remesh::detail {

struct WeightedCells {
  std::vector<double> mass;             ///< int rho dA
  std::vector<Eigen::Vector3d> moment;  ///< int rho log_s dA, in the site's tangent plane as cell_log_moment
  std::vector<double> energy;           ///< int rho d^2 dA
  std::vector<double> site_density;     ///< rho at the site
  double total_energy() const;
};

/// `density`: one value per mesh vertex, linear inside faces; empty: 1.
WeightedCells weighted_cells(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                             const voronoi::VoronoiDiagram& diagram, std::span<const double> density);

}  // namespace geodual::remesh::detail
