#pragma once
// Internal: checks every mesh passes on its way in (read_mesh) and out (the
// writers), whatever the format. They throw geodual::Error naming the file
// and the offending vertex or triangle (counted from 0).

#include "file_error.hpp"

#include "geodual/mesh/triangle_mesh.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

namespace geodual::io::detail {

/// Every triangle's indices name an existing vertex.
inline void check_face_indices(const std::filesystem::path& file, const TriangleMesh& mesh) {
  const Eigen::Index vertex_count = mesh.vertices.rows();
  const Index* index = mesh.faces.data();
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) {
    if (index[i] < 0 || index[i] >= vertex_count) {
      throw_file_error(file, "triangle ", i / 3, " refers to vertex ", index[i], ", but the mesh has ", vertex_count,
                       " vertices");
    }
  }
}

/// Every coordinate is a finite number (no NaN, no infinity).
inline void check_finite_coordinates(const std::filesystem::path& file, const TriangleMesh& mesh) {
  // A double is NaN or infinite exactly when all its exponent bits are set; this
  // integer test vectorises, so the whole matrix costs one pass at memory speed.
  constexpr std::uint64_t exponent_bits = 0x7ff0000000000000;
  const double* values = mesh.vertices.data();
  std::uint64_t any_non_finite = 0;
  for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) {
    any_non_finite |= (std::bit_cast<std::uint64_t>(values[i]) & exponent_bits) == exponent_bits;
  }
  if (any_non_finite == 0) {
    return;
  }
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      const double value = mesh.vertices(v, axis);
      if (!std::isfinite(value)) {
        throw_file_error(file, "vertex ", v, " (counting from 0) has a non-finite coordinate ", "xyz"[axis], " = ",
                         value);
      }
    }
  }
}

/// Vertex and triangle counts fit geodual's 32-bit indices.
inline void check_counts_fit_index(const std::filesystem::path& file, const TriangleMesh& mesh) {
  constexpr Eigen::Index max_count = std::numeric_limits<Index>::max();
  if (mesh.vertices.rows() > max_count || mesh.faces.rows() > max_count) {
    throw_file_error(file, "the mesh has ", mesh.vertices.rows(), " vertices and ", mesh.faces.rows(),
                     " triangles, more than geodual's 32-bit indices can address");
  }
}

}  // namespace geodual::io::detail
