#pragma once
// Test support for the mesh suites: a mesh from literal vertices and faces.

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <initializer_list>

namespace geodual::test {

inline TriangleMesh make_mesh(std::initializer_list<std::array<double, 3>> vertices,
                              std::initializer_list<std::array<Index, 3>> faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  Index i = 0;
  for (const auto& v : vertices) mesh.vertices.row(i++) << v[0], v[1], v[2];
  i = 0;
  for (const auto& f : faces) mesh.faces.row(i++) << f[0], f[1], f[2];
  return mesh;
}

}  // namespace geodual::test
