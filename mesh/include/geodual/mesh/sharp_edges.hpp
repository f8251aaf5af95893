#pragma once
// Sharp edges: where the normals of an edge's two faces turn by a large
// angle (a crease of a machined part). Shared by the remesher's feature
// detection and the quality statistics' feature recall, so that both judge
// an edge the same way.

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <vector>

namespace geodual {

/// Whether face f runs the edge from a to b (a, then b, in its corner cycle):
/// two faces that run an edge the same way are misoriented.
bool face_runs_edge(const TriangleMesh& mesh, Index f, Index a, Index b);

/// The angle in degrees by which the unit normals of edge e's two faces turn
/// (0: flat, 180: folded flat back), the second face's normal taken flipped
/// when the two faces run the edge the same way (misoriented). NaN when the
/// edge does not have exactly two faces, or either face has no area.
double normal_turn_degrees(const TriangleMesh& mesh, const MeshTopology& topology, Index e);

/// The edges (indices into topology's edges, increasing) whose normals turn
/// by at least angle_degrees (> 0).
std::vector<Index> sharp_edges(const TriangleMesh& mesh, const MeshTopology& topology, double angle_degrees);

}  // namespace geodual
