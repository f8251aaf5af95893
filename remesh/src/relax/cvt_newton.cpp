#include "relax/cvt_newton.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
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

/// Each entry (r, c) of a segment's term is L ((u_r u'_c + v_r v'_c) / 3 +
/// (u_r v'_c + v_r u'_c) / 6), in that order of operations, summed over the
/// segments in order. The entries go two at a time (the divisions bound the
/// loop), and aa and bb, symmetric to the bit (the same products, each sum
/// commuted), are summed on their upper triangles only.
SecondMoments second_moments(const CvtBoundary& boundary, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  using Pair = Eigen::Array2d;
  const std::span<const Eigen::Vector3d> points = boundary.points;
  const std::size_t stride = boundary.separate_segments ? 2 : 1;
  auto term = [](double length, const Pair& ur, const Pair& vr, const Pair& u2c, const Pair& v2c) -> Pair {
    return length * ((ur * u2c + vr * v2c) / 3 + (ur * v2c + vr * u2c) / 6);
  };
  auto both = [](double x) { return Pair(x, x); };
  // aa and bb: (0, 1) (1, 1) | (0, 2) (1, 2) | (0, 0) (2, 2); ab: rows 0 and 1
  // of each column, row 2 of columns 0 and 1, then (2, 2).
  Pair aa1 = Pair::Zero(), aa2 = Pair::Zero(), aa_diagonal = Pair::Zero();
  Pair bb1 = Pair::Zero(), bb2 = Pair::Zero(), bb_diagonal = Pair::Zero();
  Pair ab0 = Pair::Zero(), ab1 = Pair::Zero(), ab2 = Pair::Zero(), ab_row2 = Pair::Zero();
  double ab22 = 0;
  for (std::size_t k = 1; k < points.size(); k += stride) {
    const Eigen::Vector3d& p = points[k - 1];
    const Eigen::Vector3d& q = points[k];
    const double length = (q - p).norm();
    const Eigen::Vector3d u = p - a, v = q - a, u2 = p - b, v2 = q - b;
    const Pair u01(u[0], u[1]), v01(v[0], v[1]), u02(u[0], u[2]), v02(v[0], v[2]);
    const Pair u201(u2[0], u2[1]), v201(v2[0], v2[1]), u202(u2[0], u2[2]), v202(v2[0], v2[2]);
    aa1 += term(length, u01, v01, both(u[1]), both(v[1]));
    aa2 += term(length, u01, v01, both(u[2]), both(v[2]));
    aa_diagonal += term(length, u02, v02, u02, v02);
    bb1 += term(length, u201, v201, both(u2[1]), both(v2[1]));
    bb2 += term(length, u201, v201, both(u2[2]), both(v2[2]));
    bb_diagonal += term(length, u202, v202, u202, v202);
    ab0 += term(length, u01, v01, both(u2[0]), both(v2[0]));
    ab1 += term(length, u01, v01, both(u2[1]), both(v2[1]));
    ab2 += term(length, u01, v01, both(u2[2]), both(v2[2]));
    ab_row2 += term(length, both(u[2]), both(v[2]), u201, v201);
    ab22 += length * ((u[2] * u2[2] + v[2] * v2[2]) / 3 + (u[2] * v2[2] + v[2] * u2[2]) / 6);
  }
  SecondMoments sums;
  sums.aa << aa_diagonal[0], aa1[0], aa2[0], aa1[0], aa1[1], aa2[1], aa2[0], aa2[1], aa_diagonal[1];
  sums.bb << bb_diagonal[0], bb1[0], bb2[0], bb1[0], bb1[1], bb2[1], bb2[0], bb2[1], bb_diagonal[1];
  sums.ab << ab0[0], ab1[0], ab2[0], ab0[1], ab1[1], ab2[1], ab_row2[0], ab_row2[1], ab22;
  return sums;
}

/// A matrix of 2x2 blocks, one block row per unknown site, in compressed
/// rows with the block columns in increasing order.
struct BlockRows {
  std::vector<Index> begin;  ///< per block row, its first block; one more at the end
  std::vector<Index> column;
  std::vector<Eigen::Matrix2d> block;

  /// The block at (row, column), which must be in the pattern (looked for
  /// from the row's first: its few columns are quicker scanned than halved).
  Eigen::Matrix2d& at(Index row, Index col) {
    const auto first = column.begin() + begin[row], last = column.begin() + begin[row + 1];
    return block[static_cast<std::size_t>(std::find(first, last, col) - column.begin())];
  }
  /// out = this x + diagonal .* x, each row summed over its columns in
  /// increasing order (its two entries as a pair), then its diagonal term
  /// added. Four rows go at once, so that four sums are in flight while each
  /// waits on its last addition (the loop is bound by their latency).
  void multiply(const Eigen::VectorXd& x, const Eigen::VectorXd& diagonal, Eigen::VectorXd& out) const {
    using Pair = Eigen::Array2d;
    auto add = [&](Pair& sum, Index b) {
      const Eigen::Matrix2d& m = block[static_cast<std::size_t>(b)];
      const Index col = column[static_cast<std::size_t>(b)];
      sum += m.col(0).array() * x[2 * col];
      sum += m.col(1).array() * x[2 * col + 1];
    };
    auto store = [&](Index row, const Pair& sum) {
      out[2 * row] = sum[0] + diagonal[2 * row] * x[2 * row];
      out[2 * row + 1] = sum[1] + diagonal[2 * row + 1] * x[2 * row + 1];
    };
    constexpr Index kRowsAtOnce = 4;
    const Index rows = static_cast<Index>(begin.size()) - 1;
    Index row = 0;
    for (; row + kRowsAtOnce <= rows; row += kRowsAtOnce) {
      std::array<Pair, kRowsAtOnce> sum;
      sum.fill(Pair::Zero());
      Index shortest = begin[row + 1] - begin[row];
      for (Index k = 1; k < kRowsAtOnce; ++k) shortest = std::min(shortest, begin[row + k + 1] - begin[row + k]);
      for (Index n = 0; n < shortest; ++n) {
        for (Index k = 0; k < kRowsAtOnce; ++k) add(sum[k], begin[row + k] + n);
      }
      for (Index k = 0; k < kRowsAtOnce; ++k) {
        for (Index b = begin[row + k] + shortest; b < begin[row + k + 1]; ++b) add(sum[k], b);
        store(row + k, sum[k]);
      }
    }
    for (; row < rows; ++row) {
      Pair sum = Pair::Zero();
      for (Index b = begin[row]; b < begin[row + 1]; ++b) add(sum, b);
      store(row, sum);
    }
  }
};

/// One boundary's terms of the Hessian in its sites' frames (cvt_newton.hpp):
/// the blocks at (i, i), (j, j) and (i, j).
struct BoundaryBlocks {
  Eigen::Matrix2d ii, jj, ij;
};

}  // namespace

/// What one call leaves for the next (cvt_newton.hpp).
struct CvtNewtonBuffers::Vectors {
  std::vector<Index> unknown;
  std::vector<BoundaryBlocks> blocks;
  /// Per boundary, the unknowns of its sites i and j (-1 for a site that
  /// stays), or -1 and -1 where it adds nothing: apart from the blocks, so
  /// that the serial passes over the boundaries read little.
  std::vector<std::array<Index, 2>> ends;
  std::vector<Index> incident_begin, incident, fill, sorted;
  BlockRows hessian;
};

namespace {

/// Every boundary's blocks and ends, on all threads. `unknown`: per site, its
/// unknown's index, or -1 for a site that stays.
void boundary_blocks(const CvtCells& cells, std::span<const CvtBoundary> boundaries, std::span<const Index> unknown,
                     CvtNewtonBuffers::Vectors& buffers) {
  const auto& frame = cells.frame;
  const auto& position = cells.position;
  std::vector<BoundaryBlocks>& blocks = buffers.blocks;
  std::vector<std::array<Index, 2>>& ends = buffers.ends;
  blocks.resize(boundaries.size());
  ends.resize(boundaries.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boundaries.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        ends[b] = {-1, -1};
                        const CvtBoundary& boundary = boundaries[b];
                        const Index i = boundary.i, j = boundary.j;
                        if (i < 0 || j < 0 || i == j || (unknown[i] < 0 && unknown[j] < 0)) continue;
                        const double separation = (position[i] - position[j]).norm();
                        if (!(separation > 0)) continue;
                        const double weight = 2 * boundary.density / separation;
                        const SecondMoments moments = second_moments(boundary, position[i], position[j]);
                        ends[b] = {unknown[i], unknown[j]};
                        blocks[b] = {-weight * frame[i].transpose() * moments.aa * frame[i],
                                     -weight * frame[j].transpose() * moments.bb * frame[j],
                                     weight * frame[i].transpose() * moments.ab * frame[j]};
                      }
                    });
}

/// H over the unknowns: Lloyd's term lloyd_scale[k] I on the diagonal plus
/// the boundaries' blocks, each entry summed in a fixed order (Lloyd's term,
/// then the boundaries in their order), so that it does not depend on the
/// threads. Each block row is built on its own from the boundaries at its
/// unknown, listed in their order: the rows go on all threads.
void assemble_hessian(Index unknowns, const Eigen::VectorXd& lloyd_scale, CvtNewtonBuffers::Vectors& buffers) {
  const std::vector<BoundaryBlocks>& blocks = buffers.blocks;
  const std::vector<std::array<Index, 2>>& ends = buffers.ends;
  // Per unknown, the boundaries with blocks at it, in their order.
  std::vector<Index>& incident_begin = buffers.incident_begin;
  incident_begin.assign(static_cast<std::size_t>(unknowns) + 1, 0);
  for (const auto& [ki, kj] : ends) {
    if (ki >= 0) ++incident_begin[ki + 1];
    if (kj >= 0) ++incident_begin[kj + 1];
  }
  for (Index k = 0; k < unknowns; ++k) incident_begin[k + 1] += incident_begin[k];
  std::vector<Index>& incident = buffers.incident;
  incident.resize(static_cast<std::size_t>(incident_begin[unknowns]));
  {
    std::vector<Index>& fill = buffers.fill;
    fill.assign(incident_begin.begin(), incident_begin.end() - 1);
    for (std::size_t b = 0; b < ends.size(); ++b) {
      const auto [ki, kj] = ends[b];
      if (ki >= 0) incident[fill[ki]++] = static_cast<Index>(b);
      if (kj >= 0) incident[fill[kj]++] = static_cast<Index>(b);
    }
  }
  // The other unknown of boundary b at unknown k, or -1.
  auto other = [&](Index b, Index k) {
    const auto [ki, kj] = ends[static_cast<std::size_t>(b)];
    return ki == k ? kj : ki;
  };

  // The pattern: each unknown with itself and with the unknowns it shares a
  // boundary with, in increasing order, once however many boundaries they
  // share. Row k's columns are first sorted in its own room (1 + its
  // boundaries, at incident_begin[k] + k), then packed.
  std::vector<Index>& sorted = buffers.sorted;
  sorted.resize(incident.size() + static_cast<std::size_t>(unknowns));
  BlockRows& hessian = buffers.hessian;
  hessian.begin.assign(static_cast<std::size_t>(unknowns) + 1, 0);
  tbb::parallel_for(tbb::blocked_range<Index>(0, unknowns, 256), [&](const tbb::blocked_range<Index>& range) {
    for (Index k = range.begin(); k != range.end(); ++k) {
      const auto first = sorted.begin() + incident_begin[k] + k;
      auto last = first;
      *last++ = k;
      for (Index n = incident_begin[k]; n < incident_begin[k + 1]; ++n) {
        const Index m = other(incident[static_cast<std::size_t>(n)], k);
        if (m >= 0) *last++ = m;
      }
      std::sort(first, last);
      hessian.begin[k + 1] = static_cast<Index>(std::unique(first, last) - first);
    }
  });
  for (Index k = 0; k < unknowns; ++k) hessian.begin[k + 1] += hessian.begin[k];
  hessian.column.resize(static_cast<std::size_t>(hessian.begin[unknowns]));
  hessian.block.resize(hessian.column.size());
  tbb::parallel_for(tbb::blocked_range<Index>(0, unknowns, 256), [&](const tbb::blocked_range<Index>& range) {
    for (Index k = range.begin(); k != range.end(); ++k) {
      const auto first = sorted.begin() + incident_begin[k] + k;
      std::copy(first, first + (hessian.begin[k + 1] - hessian.begin[k]), hessian.column.begin() + hessian.begin[k]);
      for (Index b = hessian.begin[k]; b < hessian.begin[k + 1]; ++b) {
        hessian.block[static_cast<std::size_t>(b)] = Eigen::Matrix2d::Zero();
      }
      Eigen::Matrix2d& diagonal = hessian.at(k, k);
      diagonal += lloyd_scale[k] * Eigen::Matrix2d::Identity();
      for (Index n = incident_begin[k]; n < incident_begin[k + 1]; ++n) {
        const Index b = incident[static_cast<std::size_t>(n)];
        const BoundaryBlocks& terms = blocks[static_cast<std::size_t>(b)];
        const Index m = other(b, k);
        if (ends[static_cast<std::size_t>(b)][0] == k) {
          diagonal += terms.ii;
          if (m >= 0) hessian.at(k, m) += terms.ij;
        } else {
          diagonal += terms.jj;
          if (m >= 0) hessian.at(k, m) += terms.ij.transpose();
        }
      }
    }
  });
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
    hessian.multiply(p, damped_diagonal, hp);
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
  // Per site, on all threads: a face site's normal is its own; a vertex
  // site's is summed below over the faces in their order.
  std::vector<Eigen::Vector3d> normal(sites.size());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, sites.size(), 512), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t s = range.begin(); s != range.end(); ++s) {
          normal[s] =
              sites[s].kind == SurfacePoint::Kind::face ? face_normal(mesh, sites[s].element) : Eigen::Vector3d::Zero();
        }
      });
  std::vector<Index> vertex_site;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    if (sites[s].kind == SurfacePoint::Kind::face) continue;
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sites.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s) {
                        const Eigen::Vector3d n =
                            normal[s].norm() > 0 ? Eigen::Vector3d(normal[s].normalized()) : Eigen::Vector3d::UnitZ();
                        const Eigen::Vector3d u = n.unitOrthogonal();
                        frames[s].col(0) = u;
                        frames[s].col(1) = n.cross(u);
                      }
                    });
  return frames;
}

CvtNewtonBuffers::CvtNewtonBuffers() : vectors(std::make_unique<Vectors>()) {}

CvtNewtonBuffers::~CvtNewtonBuffers() = default;

std::vector<Eigen::Vector3d> cvt_newton_steps(const CvtCells& cells, std::span<const CvtBoundary> boundaries,
                                              const std::vector<bool>& movable, double damping, double max_step,
                                              CvtNewtonBuffers& buffers) {
  CvtNewtonBuffers::Vectors& room = *buffers.vectors;
  const std::size_t site_count = movable.size();
  // Unknowns: two tangent coordinates per movable site.
  std::vector<Index>& unknown = room.unknown;
  unknown.assign(site_count, -1);
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
  boundary_blocks(cells, boundaries, unknown, room);
  assemble_hessian(unknowns, lloyd_scale, room);
  const Eigen::VectorXd solution = truncated_newton(room.hessian, lloyd_scale, rhs, damping);
  // A step is only trusted within a fraction of the cell's size: the
  // quadratic model of E holds near the sites, and its softest directions
  // (sliding whole rows of cells) are where the surface Hessian is least exact.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, site_count, 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s) {
                        const Index k = unknown[s];
                        if (k >= 0) steps[s] = frame[s] * solution.segment<2>(2 * k);
                        const double limit = max_step * std::sqrt(cells.area[s]);
                        const double length = steps[s].norm();
                        if (length > limit) steps[s] *= limit / length;
                      }
                    });
  return steps;
}

}  // namespace geodual::remesh::detail
