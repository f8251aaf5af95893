#include "boundary_corners.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <utility>

namespace geodual::remesh::detail {

LoopWalk::LoopWalk(const TriangleMesh& mesh, const BoundaryLoop& loop) : mesh_(mesh), loop_(loop) {
  start_.reserve(loop.edges.size());
  double at = 0;
  for (const BoundaryEdge& e : loop.edges) {
    start_.push_back(at);
    at += e.length;
  }
}

double LoopWalk::gap(double a, double b) const {
  const double along = std::abs(a - b);
  return closed() ? std::min(along, length() - along) : along;
}

std::size_t LoopWalk::locate(double at, double& fraction) const {
  if (closed()) {
    at = std::fmod(at, length());
    if (at < 0) at += length();
  } else {
    at = std::clamp(at, 0.0, length());
  }
  const auto after = std::upper_bound(start_.begin(), start_.end(), at);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(std::distance(start_.begin(), after) - 1, 0));
  const BoundaryEdge& e = loop_.edges[i];
  fraction = std::clamp((at - start_[i]) / e.length, 0.0, 1.0);
  return i;
}

Eigen::Vector3d LoopWalk::point(double at) const {
  double t = 0;
  const BoundaryEdge& e = loop_.edges[locate(at, t)];
  Eigen::Vector3d a = mesh_.vertices.row(mesh_.faces(e.face, e.corner));
  Eigen::Vector3d b = mesh_.vertices.row(mesh_.faces(e.face, (e.corner + 1) % 3));
  if (e.reversed) std::swap(a, b);
  return a + t * (b - a);
}

SurfacePoint LoopWalk::site(double at) const {
  double t = 0;
  const BoundaryEdge& e = loop_.edges[locate(at, t)];
  return point_on_face_edge(e.face, e.corner, e.reversed ? 1 - t : t);
}

std::vector<std::size_t> loop_corners(const LoopWalk& walk, double spacing, std::int64_t limit) {
  if (!walk.closed()) return {};
  const double r = std::min(spacing / 2, walk.length() / 6);
  std::vector<std::pair<double, std::size_t>> sharp;  // (-cosine, edge): the sharpest first once sorted
  for (std::size_t i = 0; i < walk.num_edges(); ++i) {
    const double at = walk.start(i);
    const Eigen::Vector3d v = walk.point(at);
    const Eigen::Vector3d before = walk.point(at - r) - v, after = walk.point(at + r) - v;
    const double cosine = before.dot(after) / (before.norm() * after.norm());
    if (cosine > kCornerCosine) sharp.emplace_back(-cosine, i);  // false for NaN (a chord of length 0)
  }
  std::sort(sharp.begin(), sharp.end());
  std::vector<std::size_t> corners;
  std::set<double> taken;  // arc lengths of the corners kept so far
  for (const auto& [cosine, i] : sharp) {
    if (static_cast<std::int64_t>(corners.size()) >= limit) break;
    const double at = walk.start(i);
    // The nearest kept corners either way round: the neighbours in arc
    // length, and across the loop's start the first and the last.
    const auto next = taken.lower_bound(at);
    bool near = false;
    if (next != taken.end()) near = near || walk.gap(*next, at) < 2 * r;
    if (next != taken.begin()) near = near || walk.gap(*std::prev(next), at) < 2 * r;
    if (!taken.empty()) near = near || walk.gap(*taken.begin(), at) < 2 * r || walk.gap(*taken.rbegin(), at) < 2 * r;
    if (near) continue;
    taken.insert(at);
    corners.push_back(i);
  }
  std::sort(corners.begin(), corners.end());
  return corners;
}

}  // namespace geodual::remesh::detail
