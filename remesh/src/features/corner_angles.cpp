#include "geodual/mesh/union_find.hpp"
#include "geodual/remesh/features.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace geodual::remesh {
namespace {

/// A face round a corner, and the face's corner (0, 1, 2) there.
struct FanFace {
  Index corner;
  Index face;
  int k;
};

/// The angle of face `f` at its corner k, in radians.
double face_angle(const TriangleMesh& mesh, Index f, int k) {
  const Eigen::Vector3d p = mesh.vertices.row(mesh.faces(f, k));
  const Eigen::Vector3d a = Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, (k + 1) % 3))) - p;
  const Eigen::Vector3d b = Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, (k + 2) % 3))) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

double narrowest_corner_angle(const TriangleMesh& surface, const FeatureSet& features) {
  if (features.corners.empty()) return 360;
  double narrowest = 2 * std::numbers::pi;
  std::vector<FanFace> fan;
  for (Index f = 0; f < surface.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = surface.faces(f, k);
      if (std::binary_search(features.corners.begin(), features.corners.end(), v)) fan.push_back({v, f, k});
    }
  }
  std::stable_sort(fan.begin(), fan.end(), [](const FanFace& a, const FanFace& b) { return a.corner < b.corner; });
  UnionFind sectors;
  std::vector<double> angle;
  // Whether the fan's faces fan[begin, end) have an edge from the corner that
  // no other face of the fan has: the corner is on the boundary.
  std::vector<Index> others;
  const auto on_boundary = [&](std::size_t begin, std::size_t end) {
    others.clear();
    for (std::size_t i = begin; i < end; ++i) {
      for (const int step : {1, 2}) others.push_back(surface.faces(fan[i].face, (fan[i].k + step) % 3));
    }
    std::sort(others.begin(), others.end());
    for (std::size_t i = 0; i < others.size();) {
      std::size_t j = i;
      while (j < others.size() && others[j] == others[i]) ++j;
      if (j - i == 1) return true;
      i = j;
    }
    return false;
  };
  for (std::size_t begin = 0, end = 0; begin < fan.size(); begin = end) {
    while (end < fan.size() && fan[end].corner == fan[begin].corner) ++end;
    const std::size_t size = end - begin;
    sectors.reset(size);
    // Two faces of the fan that share an edge from the corner are in one
    // sector unless the edge is sharp; an edge with one face is boundary.
    for (std::size_t i = 0; i < size; ++i) {
      const FanFace& a = fan[begin + i];
      for (const int step : {1, 2}) {
        const Index other = surface.faces(a.face, (a.k + step) % 3);
        if (features.is_sharp(a.corner, other)) continue;
        for (std::size_t j = i + 1; j < size; ++j) {
          const FanFace& b = fan[begin + j];
          const Index b_next = surface.faces(b.face, (b.k + 1) % 3), b_previous = surface.faces(b.face, (b.k + 2) % 3);
          if (b_next == other || b_previous == other) sectors.unite(static_cast<Index>(i), static_cast<Index>(j));
        }
      }
    }
    // One sector all round (a chain ending inside a face's fan, no boundary
    // edge there) lies between no two features: no bound.
    std::size_t sector_count = 0;
    for (std::size_t i = 0; i < size; ++i) sector_count += sectors.find(static_cast<Index>(i)) == static_cast<Index>(i);
    if (sector_count == 1 && !on_boundary(begin, end)) continue;
    angle.assign(size, 0.0);
    for (std::size_t i = 0; i < size; ++i) {
      angle[sectors.find(static_cast<Index>(i))] += face_angle(surface, fan[begin + i].face, fan[begin + i].k);
    }
    for (std::size_t i = 0; i < size; ++i) {
      if (sectors.find(static_cast<Index>(i)) == static_cast<Index>(i)) narrowest = std::min(narrowest, angle[i]);
    }
  }
  return narrowest * 180 / std::numbers::pi;
}

}  // namespace geodual::remesh
