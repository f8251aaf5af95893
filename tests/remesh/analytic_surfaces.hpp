#pragma once
// Closed-form surfaces with known topology for the remesh tests.

#include "geodual/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace geodual::test {

/// A TriangleMesh from lists of points and corner triples.
TriangleMesh mesh_from_lists(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<Index, 3>>& faces);

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

}  // namespace geodual::test
