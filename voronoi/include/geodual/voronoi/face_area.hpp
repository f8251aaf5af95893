#pragma once
// Which faces the geodesic engine gives an area. It lays each face out from
// its three edge lengths (Kahan's form of Heron's formula), so a needle whose
// height is below the rounding of its lengths is flat to it even where the
// cross product of two edges is not zero. compute_geodesic_field refuses a
// site inside a flat face; whoever places sites on faces uses this test.

#include "geodual/mesh/triangle_mesh.hpp"

namespace geodual::voronoi {

/// Whether face `face` (three distinct corners with finite coordinates
/// assumed) has positive area as the geodesic engine computes it.
bool has_geodesic_area(const TriangleMesh& mesh, Index face);

}  // namespace geodual::voronoi
