#pragma once
// Sites for the command line: drawn at random, or read from a site file.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace geodual {

/// `count` vertices drawn uniformly from those used by a face with three
/// distinct corners, at pairwise distinct positions; the same for the same
/// mesh, count and seed on every platform. Throws geodual::UsageError if the
/// mesh has fewer such vertices.
std::vector<SurfacePoint> random_vertex_sites(const TriangleMesh& mesh, std::int64_t count, std::uint64_t seed);

/// Reads a site file: one site per line, either a vertex index alone or
/// `f FACE U V W` (a face index and barycentric coordinates). Blank lines and
/// lines starting with '#' are skipped. Errors name the file and line.
std::vector<SurfacePoint> read_site_file(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace geodual
