#include "locality_order.hpp"

#include "geodual/mesh/detail/morton_code.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace geodual::voronoi::detail {

namespace {

/// The vertex numbering that goes with a face order: old_vertex (new ->
/// old) and new_vertex, vertices in the order the faces first use them, then
/// the unreferenced ones.
void number_vertices(const TriangleMesh& mesh, const std::vector<Index>& old_face, std::vector<Index>& new_vertex,
                     std::vector<Index>& old_vertex) {
  const Index num_vertices = mesh.num_vertices();
  new_vertex.assign(static_cast<std::size_t>(num_vertices), -1);
  old_vertex.clear();
  old_vertex.reserve(static_cast<std::size_t>(num_vertices));
  for (const Index f : old_face) {
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.faces(f, c);
      if (new_vertex[v] < 0) {
        new_vertex[v] = static_cast<Index>(old_vertex.size());
        old_vertex.push_back(v);
      }
    }
  }
  for (Index v = 0; v < num_vertices; ++v) {
    if (new_vertex[v] < 0) {
      new_vertex[v] = static_cast<Index>(old_vertex.size());
      old_vertex.push_back(v);
    }
  }
}

}  // namespace

LocalityOrder locality_order(const TriangleMesh& mesh) {
  const Index num_vertices = mesh.num_vertices();
  const Index num_faces = mesh.num_faces();
  LocalityOrder order;

  // Morton codes of the face centroids in the bounding box of the mesh.
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::RowVector3d hi = -lo;
  for (Index v = 0; v < num_vertices; ++v) {
    lo = lo.cwiseMin(mesh.vertices.row(v));
    hi = hi.cwiseMax(mesh.vertices.row(v));
  }
  const double extent = num_vertices > 0 ? (hi - lo).maxCoeff() : 0.0;
  constexpr double kCells = (1 << 21) - 1;
  const double scale = extent > 0 && std::isfinite(extent) ? kCells / extent : 0.0;
  std::vector<std::uint64_t> code(static_cast<std::size_t>(num_faces));
  tbb::parallel_for(Index{0}, num_faces, [&](Index f) {
    const Eigen::RowVector3d c = (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
                                  mesh.vertices.row(mesh.faces(f, 2))) /
                                 3.0;
    std::array<std::uint64_t, 3> cell;
    for (int axis = 0; axis < 3; ++axis) {
      const double q = (c[axis] - lo[axis]) * scale;
      cell[axis] = static_cast<std::uint64_t>(q > 0 ? std::min(q, kCells) : 0.0);  // also for NaN
    }
    code[f] = morton_code(cell[0], cell[1], cell[2]);
  });
  order.old_face.resize(static_cast<std::size_t>(num_faces));
  std::iota(order.old_face.begin(), order.old_face.end(), Index{0});
  // A total order (ties by index): the same result on any number of threads.
  tbb::parallel_sort(order.old_face.begin(), order.old_face.end(),
                     [&](Index a, Index b) { return code[a] != code[b] ? code[a] < code[b] : a < b; });
  order.new_face.resize(static_cast<std::size_t>(num_faces));
  for (Index f = 0; f < num_faces; ++f) order.new_face[order.old_face[f]] = f;

  number_vertices(mesh, order.old_face, order.new_vertex, order.old_vertex);

  order.mesh.vertices.resize(num_vertices, 3);
  tbb::parallel_for(Index{0}, num_vertices,
                    [&](Index v) { order.mesh.vertices.row(v) = mesh.vertices.row(order.old_vertex[v]); });
  order.mesh.faces.resize(num_faces, 3);
  tbb::parallel_for(Index{0}, num_faces, [&](Index f) {
    for (int c = 0; c < 3; ++c) order.mesh.faces(f, c) = order.new_vertex[mesh.faces(order.old_face[f], c)];
  });
  return order;
}

}  // namespace geodual::voronoi::detail
