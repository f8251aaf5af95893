#pragma once
// The dual of a geodesic Voronoi diagram: one vertex per site at its surface
// position, one triangle per Voronoi vertex (degree k > 3: a fan of k - 2
// triangles from its smallest site index), oriented like the input.
//
// The dual is a faithful remesh only when the diagram has the closed-ball
// property: every cell a disk, two cells meeting along at most one arc.
// dual_delaunay checks the result against the input's topology, per
// connected component, and says where to add sites when it falls short.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace geodual::remesh {

/// What is wrong with a dual mesh, and where sites would help.
struct DualCheck {
  bool valid = true;
  /// One line per kind of problem found, for error messages.
  std::vector<std::string> problems;
  std::int64_t nonmanifold_edges = 0;     ///< dual edges with three or more triangles, or misoriented pairs
  std::int64_t nonmanifold_vertices = 0;  ///< sites whose triangles form several fans
  std::int64_t unused_sites = 0;          ///< sites that are no triangle's corner
  std::int64_t duplicate_triangles = 0;
  std::int64_t degenerate_triangles = 0;  ///< zero area
  std::int64_t split_arcs = 0;            ///< cell pairs meeting along more than one arc
  std::int64_t closed_arcs = 0;           ///< boundaries with no Voronoi vertex (a cell inside another)
  std::int64_t topology_mismatches = 0;   ///< components whose Euler characteristic or boundary loops differ
  /// Points where new sites restore the closed-ball property.
  std::vector<SurfacePoint> repair_sites;
  /// Sites that no added site can help and that are better left out: each
  /// cuts a corner off its one neighbour's cell (no Voronoi vertex).
  std::vector<Index> redundant_sites;
};

/// DualCheck::problems (or RepairedDual::repair_problems) as one line, "; " between them.
std::string problems_line(const std::vector<std::string>& problems);

struct DualMesh {
  TriangleMesh mesh;  ///< vertex i is site i
  DualCheck check;
};

struct DualOptions {
  /// Also close the dual along the mesh boundary: where cells of sites off
  /// the boundary reach it between two consecutive sites on it, triangles on
  /// those sites make the stretch between the two an edge (across a strip
  /// narrower than the spacing, the zigzag between its sides). What a cut
  /// along creases needs, whose sides are lined with sites (feature_cut.hpp).
  bool close_boundary_stretches = false;
};

/// Builds the dual triangle mesh of `diagram` (computed on `input`) and checks it.
DualMesh dual_delaunay(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                       const DualOptions& options = {});

}  // namespace geodual::remesh
