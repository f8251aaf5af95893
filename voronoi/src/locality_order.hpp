#pragma once
// A renumbering of a mesh's faces and vertices for memory locality. Window
// propagation visits faces, edges and vertices wherever the wavefronts are;
// scans often store neighbouring triangles far apart, so each visit is a cache
// miss. Faces are sorted along a Morton (Z-order) curve through their
// centroids, vertices numbered in the order the sorted faces first use them,
// so that neighbours on the surface are mostly neighbours in memory.

#include "geodual/mesh/triangle_mesh.hpp"

#include <vector>

namespace geodual::voronoi::detail {

struct LocalityOrder {
  TriangleMesh mesh;                          ///< the renumbered copy (corner order of each face kept)
  std::vector<Index> new_face, old_face;      ///< old -> new and new -> old
  std::vector<Index> new_vertex, old_vertex;  ///< unreferenced vertices come last
};

LocalityOrder locality_order(const TriangleMesh& mesh);

}  // namespace geodual::voronoi::detail
