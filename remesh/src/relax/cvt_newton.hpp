#pragma once
// A damped Newton step on the CVT energy E = sum_i int_{V_i} d(x, z_i)^2 dA
// (the Lloyd–Newton acceleration of Du & Emelianenko 2006; the Hessian as in
// Iri, Murota & Ohya 1984 and Liu et al., "On centroidal Voronoi
// tessellation — energy smoothness and fast computation", TOG 2009, §4).
//
// With M_i the cell's integral of the log map at z_i and A_i its area, the
// gradient is g_i = -2 M_i (a Lloyd step is -g_i / (2 A_i)). For two cells
// meeting along the boundary arc G_ij, moving z_j moves G_ij, and
//   d2E / dz_i dz_j = (2 / |z_i - z_j|) int_{G_ij} (x - z_i)(x - z_j)^T ds,
//   d2E / dz_i^2    = 2 A_i I - sum_j (2 / |z_i - z_j|) int_{G_ij} (x - z_i)(x - z_i)^T ds.
// These are the flat formulas; on the surface each site gets a 2D frame of
// its tangent plane and x - z is the chord, so the Hessian is approximate
// (exact on a plane) and the caller checks that a step lowers the energy.
// The step solves (H + damping D) d = -g with D = diag(2 A_i): damping 0 is
// Newton's step, a large damping a short Lloyd step. Away from a CVT, H is
// indefinite: the system is solved by conjugate gradients that stop at a
// direction of negative curvature (Steihaug 1983).
//
// Under a density rho (weighted_cells.hpp) A_i and M_i become the cell's
// rho-weighted mass and moment, and each boundary's terms are weighted by rho
// there (CvtBoundary::density; for the geodesic diagram the mean of its two
// sites' rho, which varies little across a cell).
//
// The same step serves the restricted Voronoi diagram of the warm start
// (restricted_voronoi.hpp), whose boundaries are straight segments, one per
// face crossed, and whose moments are int (x - z) dA taken into the tangent
// plane: there the formulas hold where the surface is flat across a cell.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_surface.hpp"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// What the Newton step needs of the cells, from a geodesic Voronoi diagram
/// or a restricted one (restricted_voronoi.hpp). Per site:
struct CvtCells {
  std::span<const Eigen::Vector3d> position;           ///< the site in space
  std::span<const Eigen::Matrix<double, 3, 2>> frame;  ///< its tangent plane (tangent_frames)
  std::span<const double> area;                        ///< its cell's area (bounds the step)
  std::span<const double> mass;                        ///< int rho dA
  std::span<const Eigen::Vector3d> moment;             ///< int rho (x - s) dA, taken into the tangent plane
};

/// The boundary between the cells of sites i and j, with the density along
/// it: a polyline, or separate segments given by their ends in pairs.
struct CvtBoundary {
  Index i = -1;
  Index j = -1;
  double density = 1;
  std::span<const Eigen::Vector3d> points;
  bool separate_segments = false;
};

/// Per site, an orthonormal basis of its tangent plane as the columns of a
/// 3x2 matrix: the plane of its face, or for a vertex site the plane normal to
/// the area-weighted normal of the faces around it (the planes in which the
/// diagram's log moments lie).
std::vector<Eigen::Matrix<double, 3, 2>> tangent_frames(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                        const voronoi::SurfaceTopology& topology);

/// The vectors cvt_newton_steps works in (the Hessian, its pattern),
/// kept from one call to the next: a relaxation's steps have about the same
/// sizes, and fresh ones each step cost page faults.
struct CvtNewtonBuffers {
  CvtNewtonBuffers();
  ~CvtNewtonBuffers();
  struct Vectors;
  std::unique_ptr<Vectors> vectors;
};

/// Per site, its step as a 3D vector in the site's tangent plane (zero for the
/// sites not movable), at most max_step * sqrt(cell area) long.
std::vector<Eigen::Vector3d> cvt_newton_steps(const CvtCells& cells, std::span<const CvtBoundary> boundaries,
                                              const std::vector<bool>& movable, double damping, double max_step,
                                              CvtNewtonBuffers& buffers);

}  // namespace geodual::remesh::detail
