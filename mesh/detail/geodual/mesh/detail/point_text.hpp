#pragma once
// A point as error messages write it: "(x, y, z)", six significant digits.

#include <Eigen/Core>

#include <cstdio>
#include <string>

namespace geodual {

inline std::string point_text(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return text;
}

}  // namespace geodual
