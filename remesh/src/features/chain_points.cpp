#include "features/chain_points.hpp"

#include <cmath>
#include <utility>

namespace geodual::remesh::detail {

double lattice_parameter(double t) {
  return std::round(std::clamp(t, kLatticeMargin, 1 - kLatticeMargin) * kLattice) / kLattice;
}

SurfacePoint point_on_edge(const TriangleMesh& surface, Index f, Index a, Index b, double t) {
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (surface.faces(f, k) == a) barycentric[k] = 1 - t;
    if (surface.faces(f, k) == b) barycentric[k] = t;
  }
  return SurfacePoint::in_face(f, barycentric[0], barycentric[1], barycentric[2]);
}

SiteKey site_key(const TriangleMesh& surface, const FeatureCut& cut, const SurfacePoint& site) {
  if (site.kind == SurfacePoint::Kind::vertex) {
    const Index v = cut.original_vertex[static_cast<std::size_t>(site.element)];
    return {v, v, 0};
  }
  int zeros = 0, zero = -1, one = -1;
  for (int k = 0; k < 3; ++k) {
    if (site.barycentric[k] == 0) zeros++, zero = k;
    if (site.barycentric[k] == 1) one = k;
  }
  if (one >= 0) {
    const Index v = surface.faces(site.element, one);
    return {v, v, 0};
  }
  if (zeros != 1) return {};
  int i = (zero + 1) % 3, j = (zero + 2) % 3;
  if (surface.faces(site.element, i) > surface.faces(site.element, j)) std::swap(i, j);
  return {surface.faces(site.element, i), surface.faces(site.element, j), site.barycentric[j]};
}

ChainWalk::ChainWalk(const TriangleMesh& mesh, const FeatureChain& c)
    : surface(mesh), chain(c), at(c.vertices.size(), 0.0) {
  for (std::size_t i = 1; i < at.size(); ++i) {
    at[i] = at[i - 1] + (mesh.vertices.row(c.vertices[i]) - mesh.vertices.row(c.vertices[i - 1])).norm();
  }
}

std::size_t ChainWalk::locate(double s, double& t) const {
  const auto upper = std::upper_bound(at.begin(), at.end(), s);
  std::size_t i = upper == at.begin() ? 0 : static_cast<std::size_t>(upper - at.begin()) - 1;
  i = std::min(i, at.size() - 2);
  const double edge = at[i + 1] - at[i];
  t = edge > 0 ? std::clamp((s - at[i]) / edge, 0.0, 1.0) : 0.0;
  return i;
}

SiteKey ChainWalk::key_at(double s) const {
  double t = 0;
  const std::size_t i = locate(s, t);
  Index a = chain.vertices[i], b = chain.vertices[i + 1];
  if (a > b) {
    std::swap(a, b);
    t = 1 - t;
  }
  return {a, b, lattice_parameter(t)};
}

Eigen::Vector3d ChainWalk::point(double s) const {
  double t = 0;
  const std::size_t i = locate(s, t);
  return (1 - t) * surface.vertices.row(chain.vertices[i]).transpose() +
         t * surface.vertices.row(chain.vertices[i + 1]).transpose();
}

bool ChainWalk::within(double from, double to, double error) const {
  const Eigen::Vector3d p = point(from), q = point(to);
  const Eigen::Vector3d d = q - p;
  const double dd = d.squaredNorm();
  const auto first = std::upper_bound(at.begin(), at.end(), from), last = std::lower_bound(first, at.end(), to);
  for (auto it = first; it != last; ++it) {
    const std::size_t i = static_cast<std::size_t>(it - at.begin());
    const Eigen::Vector3d x = surface.vertices.row(chain.vertices[i]).transpose() - p;
    const double s = dd > 0 ? std::clamp(x.dot(d) / dd, 0.0, 1.0) : 0.0;
    if ((x - s * d).norm() > error) return false;
  }
  return true;
}

}  // namespace geodual::remesh::detail
