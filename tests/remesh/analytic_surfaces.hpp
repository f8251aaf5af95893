#pragma once
// Closed-form surfaces with known topology for the remesh tests.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geodual::test {

/// A TriangleMesh from lists of points and corner triples.
TriangleMesh mesh_from_lists(const std::vector<Eigen::Vector3d>& vertices,
                             const std::vector<std::array<Index, 3>>& faces);

/// The icosahedron split 1-to-4 `levels` times, vertices on the unit sphere
/// (genus 0, chi = 2).
TriangleMesh icosphere(int levels);
/// A torus (radii R > r) as an n x m periodic grid (genus 1, chi = 0),
/// centred at x = centre_x, axis along z.
TriangleMesh torus(double R, double r, int n, int m, double centre_x = 0);
/// Two tori side by side joined by a square tube through a k x k hole cut in
/// each (genus 2, chi = -2).
TriangleMesh double_torus(double R, double r, int n, int m, int k);
/// The unit disk as a polar grid: `rings` rings of `segments` quads around a
/// central fan (one boundary loop, chi = 1).
TriangleMesh disk(int rings, int segments);
/// The unit square [0, 1]^2 in z = 0 as an n x n grid of two triangles per
/// cell (diagonals from (i, j) to (i + 1, j + 1)); vertex (i, j) is j (n + 1) + i.
TriangleMesh unit_square(int n);
/// The unit square [0, 1]^2 in z = 0 as an n x n grid of two triangles per
/// cell (n even), slit along y = 1/2 from its left side to the centre: the
/// grid vertices there (but the centre) are doubled, those above the slit
/// using the copies. One boundary loop (chi = 1), which runs into the slit
/// along its lower side and back along its upper side, the two at the same
/// points.
TriangleMesh slit_square(int n);

}  // namespace geodual::test
