#include "dual/fault_places.hpp"

#include "geodual/mesh/detail/point_text.hpp"

#include <algorithm>
#include <cstddef>

namespace geodual::remesh {

std::vector<Eigen::Vector3d> fault_places(std::span<const Eigen::Vector3d> points, double spacing) {
  std::vector<Eigen::Vector3d> places;
  for (const Eigen::Vector3d& x : points) {
    if (std::none_of(places.begin(), places.end(),
                     [&](const Eigen::Vector3d& p) { return (p - x).norm() <= spacing; })) {
      places.push_back(x);
    }
  }
  return places;
}

std::string fault_places_text(const std::vector<Eigen::Vector3d>& places) {
  if (places.empty()) return {};
  std::string text =
      "; the faults lie " +
      (places.size() == 1 ? std::string("near ") : "at " + std::to_string(places.size()) + " places, near ");
  for (std::size_t i = 0; i < std::min<std::size_t>(places.size(), 3); ++i) {
    text += (i > 0 ? ", " : "") + point_text(places[i]);
  }
  return text + (places.size() > 3 ? ", ..." : "");
}

}  // namespace geodual::remesh
