#pragma once
// The shared currency between geodual's modules: an indexed triangle mesh as
// two row-major Eigen matrices, the convention libigl made familiar.
//
// Vertex order and count are the file's: unreferenced vertices stay, nothing
// is welded or reordered unless a reader says so (STL, which has no indices).

#include <Eigen/Core>

#include <cstdint>

namespace geodual {

using Index = std::int32_t;

/// N x 3 vertex positions, one row per vertex.
using VertexMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// M x 3 vertex indices, one row per triangle, counter-clockwise seen from outside.
using FaceMatrix = Eigen::Matrix<Index, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct TriangleMesh {
  VertexMatrix vertices;
  FaceMatrix faces;

  Index num_vertices() const { return static_cast<Index>(vertices.rows()); }
  Index num_faces() const { return static_cast<Index>(faces.rows()); }
};

}  // namespace geodual
