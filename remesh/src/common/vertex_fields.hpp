#pragma once
// Fields of one value per mesh vertex, and their smoothing over the edges:
// what the densities of the weighted CVT (curvature_density.hpp,
// error_density.hpp) are built with. Faces with a repeated corner take no part.

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <vector>

namespace geodual::remesh::detail {

/// Per vertex, a third of the area of the faces around it.
std::vector<double> vertex_areas(const TriangleMesh& mesh);

/// The undirected edges (low, high, face), sorted: an edge's faces are adjacent.
std::vector<std::array<Index, 3>> edge_sides(const TriangleMesh& mesh);

/// The mean length of the face sides (an edge between two faces counts
/// twice); 0 without sides.
double mean_edge_length(const TriangleMesh& mesh, const std::vector<std::array<Index, 3>>& sides);

/// The averaging passes that smooth over about `length`: one pass diffuses
/// over about one mesh edge, n passes over sqrt(n) edges. At least 1, at most 400.
int smoothing_passes(double length, double mean_edge);

/// `passes` Jacobi sweeps of area-weighted one-ring averaging; vertices
/// without area keep their value.
void smooth(std::vector<double>& value, const std::vector<std::array<Index, 3>>& sides, const std::vector<double>& area,
            int passes);

/// `passes` sweeps of one-ring maxima: each value spreads `passes` edges.
void dilate(std::vector<double>& value, const std::vector<std::array<Index, 3>>& sides, int passes);

}  // namespace geodual::remesh::detail
