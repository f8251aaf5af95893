#pragma once
// What a mesh is made of and what is wrong with it: the defects scans carry
// (holes, non-manifold edges, unreferenced vertices, degenerate faces, ...).

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace geodual {

/// Counts follow the conventions of shared/data/meshes/MANIFEST.md, so that the
/// figures can be checked against it.
struct MeshReport {
  std::int64_t vertices = 0;  ///< as in the file, referenced or not
  std::int64_t faces = 0;     ///< as in the file
  /// Connected pieces of the referenced vertices, joined by edges: pieces that
  /// touch only at a pinch vertex count once.
  std::int64_t components = 0;
  /// Closed loops of boundary edges (edges with exactly one face); loops that
  /// touch at a pinch vertex are traced as one figure eight and count once.
  std::int64_t boundary_loops = 0;
  std::int64_t boundary_edges = 0;
  std::int64_t nonmanifold_edges = 0;  ///< edges with three or more faces
  /// Referenced vertices whose faces form several fans (faces around the
  /// vertex joined through shared edges); an end of a non-manifold edge alone
  /// does not make a vertex non-manifold.
  std::int64_t nonmanifold_vertices = 0;
  std::int64_t degenerate_faces = 0;                   ///< no area by has_positive_area (face_area.hpp)
  std::int64_t duplicate_faces = 0;                    ///< same vertex set as an earlier face
  std::int64_t duplicate_vertices = 0;                 ///< exactly the position of an earlier vertex
  std::int64_t unreferenced_vertices = 0;              ///< used by no face
  std::int64_t edges = 0;                              ///< distinct undirected edges
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  ///< over referenced vertices
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  double bbox_diagonal = 0.0;
  std::int64_t euler_characteristic = 0;  ///< V_referenced - E + F
  /// (2 C - B - chi) / 2, only where it means something: a non-empty
  /// orientable 2-manifold (no non-manifold edges or vertices; the faces can be
  /// oriented consistently, even if they are not stored so).
  std::optional<double> genus;
  bool oriented = true;  ///< no directed edge is used by two faces
};

/// Analyses the mesh as stored; never modifies it. Linear time; at most about
/// 26 bytes per face of working memory besides the mesh (for V = F / 2).
/// Throws geodual::Error if a face refers to a vertex that does not exist.
MeshReport analyze_mesh(const TriangleMesh& mesh);

}  // namespace geodual
