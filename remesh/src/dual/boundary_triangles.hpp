#pragma once
// The dual's triangles along the mesh boundary, between the sites on it.
//
// The dual of a Voronoi diagram on a surface with boundary has a triangle
// for each Voronoi vertex only. Where the cell of a site off the boundary
// reaches the boundary between two consecutive sites on it, its edges to
// them are the dual's boundary, and the boundary stretch between the two
// sites is no edge of the dual: a crease cut open (feature_cut.hpp) is then
// not a chain of remesh edges. Across a strip narrower than the spacing the
// cells reach from one side to the other and meet at no Voronoi vertex at
// all, so the dual has no triangle there.
//
// Walking a boundary loop with the surface on its left, the cells it passes
// through are B, X_1 ... X_k, B' between consecutive sites B and B' on it;
// the polygon B B' X_k ... X_1 closes that stretch. Its triangles are the
// restricted Delaunay triangles of the boundary's Voronoi vertices (where an
// arc meets the boundary), the boundary stretch taken as an edge: across a
// strip, the zigzag between the sites of its two sides.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// The triangles (site indices, oriented as the mesh's faces) closing every
/// boundary stretch of `mesh` between consecutive sites on it that other
/// cells reach, at most `max_cells` of them, and whose polygon is simple: no
/// cell along it twice, no directed edge that `triangles` (the dual's so far)
/// already has. Stretches that do not qualify, and loops whose cells along
/// them cannot be told apart (through a vertex with several boundary edges
/// out of it, arcs ending at one point), are left as they are. Each polygon
/// is cut into triangles ear by ear, the ear whose smallest angle is largest
/// first (`positions`: the sites'), none with an angle below `min_angle`
/// degrees (a site off the boundary near its line, whose stretch a site on
/// the boundary there serves better, or two sites at one point) or an edge
/// longer than `max_reach` times the stretch (a cell from far off, where a
/// region has too few sites): those are left to the repair.
/// Deterministic.
std::vector<std::array<Index, 3>> boundary_triangles(const TriangleMesh& mesh, const voronoi::VoronoiDiagram& diagram,
                                                     std::span<const std::array<Index, 3>> triangles,
                                                     const VertexMatrix& positions, int max_cells = 4,
                                                     double min_angle = 10, double max_reach = 2);

}  // namespace geodual::remesh::detail
