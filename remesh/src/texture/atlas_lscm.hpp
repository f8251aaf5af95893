#pragma once
// Least-squares conformal maps (LSCM) of one chart, by CGAL's
// Surface_mesh_parameterization: the one source file that includes CGAL, so
// that the atlas's other parts compile fast.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geodual::remesh::detail {

/// The LSCM of a topological disk (CGAL's default: two boundary vertices far
/// apart held fixed): per vertex, its (u, v), with the triangles' orientation
/// kept (counter-clockwise stays counter-clockwise, v up). Empty where CGAL
/// refuses the surface or its linear system has no solution; flips and
/// overlaps are not checked here.
std::vector<Eigen::Vector2d> lscm_parameterisation(const std::vector<Eigen::Vector3d>& positions,
                                                   const std::vector<std::array<Index, 3>>& triangles);

}  // namespace geodual::remesh::detail
