#pragma once
// Writing a geodesic distance field with the mesh it lives on.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <array>
#include <filesystem>

namespace geodual {

/// A colour per site index, well spread in hue, the same on every run;
/// grey for -1 (no site).
std::array<float, 3> site_color(Index site);

/// Writes the mesh with the field, by extension:
///  - .ply: per-vertex properties `distance` (double; inf where unreachable)
///    and `site` (int; -1 where unreachable);
///  - .glb / .gltf: COLOR_0 by nearest site and a `_DISTANCE` float attribute
///    (-1 where unreachable, glTF wants finite values).
/// Throws geodual::Error for other extensions.
void write_geodesic_field(const std::filesystem::path& path, const TriangleMesh& mesh,
                          const voronoi::GeodesicField& field);

}  // namespace geodual
