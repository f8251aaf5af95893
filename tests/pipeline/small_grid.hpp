#pragma once
// Small inputs shared by the pipeline's file-reading tests: a 3 x 3 grid of
// vertices in the plane and temporary text files.

#include "geodual/mesh/triangle_mesh.hpp"

#include <filesystem>
#include <fstream>
#include <string>

namespace geodual::test {

/// A 3 x 3 grid of vertices (8 triangles, diagonals a -> a + 4), plus one
/// vertex at (5, 5, 5) that no face uses when asked.
inline TriangleMesh small_grid(bool with_unreferenced_vertex) {
  TriangleMesh mesh;
  mesh.vertices.resize(with_unreferenced_vertex ? 10 : 9, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) mesh.vertices.row(j * 3 + i) << i, j, 0;
  }
  if (with_unreferenced_vertex) mesh.vertices.row(9) << 5, 5, 5;
  mesh.faces.resize(8, 3);
  int f = 0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const int a = j * 3 + i;
      mesh.faces.row(f++) << a, a + 1, a + 4;
      mesh.faces.row(f++) << a, a + 4, a + 3;
    }
  }
  return mesh;
}

/// Writes `text` to a file `name` in the temporary folder and returns its path.
inline std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("geodual_pipeline_test_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace geodual::test
