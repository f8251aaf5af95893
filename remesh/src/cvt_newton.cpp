#include "cvt_newton.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace geodual::remesh::detail {
namespace {

/// Conjugate-gradient iterations stop once the preconditioned residual has
/// shrunk by this factor, or after this many. Few iterations on purpose
/// (truncated Newton): the softest directions of H (rows of cells sliding
/// together) are the last CG resolves and where the surface Hessian is least
/// exact; after 10 iterations the step is smoother and rejected less often
/// (on four scans at 5K and 20K sites, Qavg after 10 steps +0.000 to +0.005
/// over 200 iterations, with 11-12 diagrams instead of 11-14).
constexpr double kRelativeResidual = 1e-3;
constexpr int kMaximumIterations = 10;

Eigen::Vector3d face_normal(const TriangleMesh& mesh, Index face) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(face, 0)).transpose();
  const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(face, 1)).transpose();
  const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(face, 2)).transpose();
  return (b - a).cross(c - a);
}

/// The integrals over a boundary of (x - a)(x - a)^T, (x - b)(x - b)^T and
/// (x - a)(x - b)^T ds, exact for straight segments: on a segment from p to
/// q of length L, with u = p - a, v = q - a, u' = p - b, v' = q - b, the last
/// is L (u u'^T / 3 + (u v'^T + v u'^T) / 6 + v v'^T / 3).
struct SecondMoments {
  Eigen::Matrix3d aa = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d bb = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d ab = Eigen::Matrix3d::Zero();
};

SecondMoments second_moments(const CvtBoundary& boundary, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const std::span<const Eigen::Vector3d> points = boundary.points;
  const std::size_t stride = boundary.separate_segments ? 2 : 1;
  SecondMoments sums;
  auto add = [](Eigen::Matrix3d& sum, double length, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                const Eigen::Vector3d& u2, const Eigen::Vector3d& v2) {
    sum += length * ((u * u2.transpose() + v * v2.transpose()) / 3 + (u * v2.transpose() + v * u2.transpose()) / 6);
  };
  for (std::size_t k = 1; k < points.size(); k += stride) {
    const Eigen::Vector3d& p = points[k - 1];
    const Eigen::Vector3d& q = points[k];
    const double length = (q - p).norm();
    const Eigen::Vector3d u = p - a, v = q - a, u2 = p - b, v2 = q - b;
    add(sums.aa, length, u, v, u, v);
    add(sums.bb, length, u2, v2, u2, v2);
    add(sums.ab, length, u, v, u2, v2);
  }
  return sums;
}

/// A matrix of 2x2 blocks, one block row per unknown site, in compressed
/// rows with the block columns in increasing order.
struct BlockRows {
  std::vector<Index> begin;  ///< per block row, its first block; one more at the end
  std::vector<Index> column;
  std::vector<Eigen::Matrix2d> block;

  /// The block at (row, column), which must be in the pattern.
  Eigen::Matrix2d& at(Index row, Index col) {
    const auto first = column.begin() + begin[row], last = column.begin() + begin[row + 1];
    return block[static_cast<std::size_t>(std::lower_bound(first, last, col) - column.begin())];
  }
  /// out = this x, each row summed over its columns in increasing order.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
    for (Index row = 0; row + 1 < static_cast<Index>(begin.size()); ++row) {
      double first = 0, second = 0;
      for (Index b = begin[row]; b < begin[row + 1]; ++b) {
        const Eigen::Matrix2d& m = block[static_cast<std::size_t>(b)];
        const Index col = column[static_cast<std::size_t>(b)];
        first += m(0, 0) * x[2 * col];
        first += m(0, 1) * x[2 * col + 1];
        second += m(1, 0) * x[2 * col];
        second += m(1, 1) * x[2 * col + 1];
      }
      out[2 * row] = first;
      out[2 * row + 1] = second;
    }
  }
};

/// One boundary's terms of the Hessian in its sites' frames (cvt_newton.hpp):
/// the blocks at (i, i), (j, j) and (i, j); unused where it adds nothing.
struct BoundaryBlocks {
  bool used = false;
  Eigen::Matrix2d ii, jj, ij;
};

/// Every boundary's blocks, on all threads. `unknown`: per site, its unknown's
/// index, or -1 for a site that stays.
std::vector<BoundaryBlocks> boundary_blocks(const CvtCells& cells, std::span<const CvtBoundary> boundaries,
                                            std::span<const Index> unknown) {
  const auto& frame = cells.frame;
  const auto& position = cells.position;
  std::vector<BoundaryBlocks> blocks(boundaries.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boundaries.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        const CvtBoundary& boundary = boundaries[b];
                        const Index i = boundary.i, j = boundary.j;
                        if (i < 0 || j < 0 || i == j || (unknown[i] < 0 && unknown[j] < 0)) continue;
                        const double separation = (position[i] - position[j]).norm();
                        if (!(separation > 0)) continue;
                        const double weight = 2 * boundary.density / separation;
                        const SecondMoments moments = second_moments(boundary, position[i], position[j]);
                        blocks[b] = {true, -weight * frame[i].transpose() * moments.aa * frame[i],
                                     -weight * frame[j].transpose() * moments.bb * frame[j],
                                     weight * frame[i].transpose() * moments.ab * frame[j]};
                      }
                    });
  return blocks;
}

/// H over the unknowns: Lloyd's term lloyd_scale[k] I on the diagonal plus
/// the boundaries' blocks, each entry summed in a fixed order (Lloyd's term,
/// then the boundaries in their order), so that it does not depend on the
/// threads.
BlockRows assemble_hessian(std::span<const Index> unknown, Index unknowns, const Eigen::VectorXd& lloyd_scale,
                           std::span<const CvtBoundary> boundaries, const std::vector<BoundaryBlocks>& blocks) {
  // The pattern: each unknown with itself and with the unknowns it shares a
  // boundary with, in increasing order, once however many boundaries they share.
  auto coupled = [&](std::size_t b) {
    return blocks[b].used && unknown[boundaries[b].i] >= 0 && unknown[boundaries[b].j] >= 0;
  };
  BlockRows hessian;
  hessian.begin.assign(static_cast<std::size_t>(unknowns) + 1, 0);
  for (Index k = 0; k < unknowns; ++k) hessian.begin[k + 1] = 1;
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (!coupled(b)) continue;
    ++hessian.begin[unknown[boundaries[b].i] + 1];
    ++hessian.begin[unknown[boundaries[b].j] + 1];
  }
  for (Index k = 0; k < unknowns; ++k) hessian.begin[k + 1] += hessian.begin[k];
  hessian.column.resize(static_cast<std::size_t>(hessian.begin[unknowns]));
  std::vector<Index> fill(hessian.begin.begin(), hessian.begin.end() - 1);
  for (Index k = 0; k < unknowns; ++k) hessian.column[fill[k]++] = k;
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (!coupled(b)) continue;
    const Index ki = unknown[boundaries[b].i], kj = unknown[boundaries[b].j];
    hessian.column[fill[ki]++] = kj;
    hessian.column[fill[kj]++] = ki;
  }
  Index kept = 0;
  for (Index k = 0; k < unknowns; ++k) {
    const auto first = hessian.column.begin() + hessian.begin[k], last = hessian.column.begin() + hessian.begin[k + 1];
    std::sort(first, last);
    hessian.begin[k] = kept;
    for (auto it = first, end = std::unique(first, last); it != end; ++it) hessian.column[kept++] = *it;
  }
  hessian.begin[unknowns] = kept;
  hessian.column.resize(static_cast<std::size_t>(kept));

  hessian.block.assign(static_cast<std::size_t>(kept), Eigen::Matrix2d::Zero());
  for (Index k = 0; k < unknowns; ++k) hessian.at(k, k) += lloyd_scale[k] * Eigen::Matrix2d::Identity();
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (!blocks[b].used) continue;
    const Index ki = unknown[boundaries[b].i], kj = unknown[boundaries[b].j];
    if (ki >= 0) hessian.at(ki, ki) += blocks[b].ii;
    if (kj >= 0) hessian.at(kj, kj) += blocks[b].jj;
    if (ki >= 0 && kj >= 0) {
      hessian.at(ki, kj) += blocks[b].ij;
      hessian.at(kj, ki) += blocks[b].ij.transpose();
    }
  }
  return hessian;
}

/// Solves (H + damping D) x = b, D = diag(scale) repeated per coordinate pair,
/// by conjugate gradients preconditioned with D (whose first iterate is
/// Lloyd's direction), stopping at a direction of negative curvature
/// (Steihaug 1983): far from a CVT H is indefinite, and the iterate reached
/// there is still a descent direction.
Eigen::VectorXd truncated_newton(const BlockRows& hessian, const Eigen::VectorXd& scale, const Eigen::VectorXd& b,
                                 double damping) {
  const Eigen::VectorXd lloyd = scale.replicate(1, 2).transpose().reshaped();  // per unknown
  const Eigen::VectorXd damped_diagonal = damping * lloyd;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  Eigen::VectorXd r = b;
  Eigen::VectorXd z = r.cwiseQuotient(lloyd);
  Eigen::VectorXd p = z;
  Eigen::VectorXd hp(b.size());
  double rz = r.dot(z);
  const double stop = kRelativeResidual * kRelativeResidual * rz;
  for (int iteration = 0; iteration < kMaximumIterations; ++iteration) {
    hessian.multiply(p, hp);
    hp += damped_diagonal.cwiseProduct(p);
    const double curvature = p.dot(hp);
    if (!(curvature > 0)) {
      if (iteration == 0) x = z;  // Lloyd's step
      break;
    }
    const double alpha = rz / curvature;
    x += alpha * p;
    r -= alpha * hp;
    z = r.cwiseQuotient(lloyd);
    const double next = r.dot(z);
    if (next < stop) break;
    p = z + (next / rz) * p;
    rz = next;
  }
  return x;
}

}  // namespace

std::vector<Eigen::Matrix<double, 3, 2>> tangent_frames(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                                        const voronoi::SurfaceTopology& topology) {
  std::vector<Eigen::Vector3d> normal(sites.size(), Eigen::Vector3d::Zero());
  std::vector<Index> vertex_site;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    if (sites[s].kind == SurfacePoint::Kind::face) {
      normal[s] = face_normal(mesh, sites[s].element);
      continue;
    }
    if (vertex_site.empty()) vertex_site.assign(static_cast<std::size_t>(mesh.vertices.rows()), -1);
    vertex_site[sites[s].element] = static_cast<Index>(s);
  }
  if (!vertex_site.empty()) {
    for (Index f = 0; f < mesh.faces.rows(); ++f) {
      if (topology.face_edges[f][0] < 0) continue;
      for (int c = 0; c < 3; ++c) {
        const Index s = vertex_site[mesh.faces(f, c)];
        if (s >= 0) normal[s] += face_normal(mesh, f);
      }
    }
  }
  std::vector<Eigen::Matrix<double, 3, 2>> frames(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const Eigen::Vector3d n = normal[s].norm() > 0 ? Eigen::Vector3d(normal[s].normalized()) : Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d u = n.unitOrthogonal();
    frames[s].col(0) = u;
    frames[s].col(1) = n.cross(u);
  }
  return frames;
}

std::vector<Eigen::Vector3d> cvt_newton_steps(const CvtCells& cells, std::span<const CvtBoundary> boundaries,
                                              const std::vector<bool>& movable, double damping, double max_step) {
  const std::size_t site_count = movable.size();
  // Unknowns: two tangent coordinates per movable site.
  std::vector<Index> unknown(site_count, -1);
  Index unknowns = 0;
  for (std::size_t s = 0; s < site_count; ++s) {
    if (movable[s]) unknown[s] = unknowns++;
  }
  std::vector<Eigen::Vector3d> steps(site_count, Eigen::Vector3d::Zero());
  if (unknowns == 0) return steps;

  const auto& frame = cells.frame;
  Eigen::VectorXd rhs(2 * unknowns);
  Eigen::VectorXd lloyd_scale(unknowns);  // 2 A_i (the weighted mass): Lloyd's Hessian
  for (std::size_t s = 0; s < site_count; ++s) {
    const Index k = unknown[s];
    if (k < 0) continue;
    lloyd_scale[k] = 2 * cells.mass[s];
    rhs.segment<2>(2 * k) = 2 * frame[s].transpose() * cells.moment[s];  // -g
  }
  const std::vector<BoundaryBlocks> blocks = boundary_blocks(cells, boundaries, unknown);
  const BlockRows hessian = assemble_hessian(unknown, unknowns, lloyd_scale, boundaries, blocks);
  const Eigen::VectorXd solution = truncated_newton(hessian, lloyd_scale, rhs, damping);
  for (std::size_t s = 0; s < site_count; ++s) {
    const Index k = unknown[s];
    if (k >= 0) steps[s] = frame[s] * solution.segment<2>(2 * k);
  }
  // A step is only trusted within a fraction of the cell's size: the
  // quadratic model of E holds near the sites, and its softest directions
  // (sliding whole rows of cells) are where the surface Hessian is least exact.
  for (std::size_t s = 0; s < site_count; ++s) {
    const double limit = max_step * std::sqrt(cells.area[s]);
    const double length = steps[s].norm();
    if (length > limit) steps[s] *= limit / length;
  }
  return steps;
}

}  // namespace geodual::remesh::detail
