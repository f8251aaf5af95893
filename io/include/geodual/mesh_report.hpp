#pragma once
// What a mesh is made of and what is wrong with it: the defects scans carry
// (holes, non-manifold edges, unreferenced vertices, degenerate faces, ...).

#include "geodual/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace geodual {

struct MeshReport {
  std::int64_t vertices = 0;               ///< as in the file, referenced or not
  std::int64_t faces = 0;                  ///< as in the file
  std::int64_t components = 0;             ///< edge-connected components of the faces
  std::int64_t boundary_loops = 0;         ///< closed loops of edges with exactly one face
  std::int64_t boundary_edges = 0;
  std::int64_t nonmanifold_edges = 0;      ///< edges with three or more faces
  std::int64_t nonmanifold_vertices = 0;   ///< referenced vertices whose faces form several fans
  std::int64_t degenerate_faces = 0;       ///< a repeated index, or exactly zero area
  std::int64_t duplicate_faces = 0;        ///< same vertex set as an earlier face
  std::int64_t duplicate_vertices = 0;     ///< exactly the position of an earlier vertex
  std::int64_t unreferenced_vertices = 0;  ///< used by no face
  std::int64_t edges = 0;                  ///< distinct undirected edges
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  ///< over referenced vertices
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  double bbox_diagonal = 0.0;
  std::int64_t euler_characteristic = 0;   ///< V_referenced - E + F
  /// (2 C - B - chi) / 2, only where it means something: an orientable
  /// 2-manifold (no non-manifold edges or vertices, consistently oriented).
  std::optional<double> genus;
  bool oriented = true;                    ///< every interior edge used once in each direction
};

/// Analyses the mesh as stored; never modifies or rejects it.
MeshReport analyze_mesh(const TriangleMesh& mesh);

}  // namespace geodual
