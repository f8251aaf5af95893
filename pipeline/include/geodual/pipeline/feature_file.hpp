#pragma once
// Feature edges given by the user: read from a feature file, and checked
// against the mesh they belong to.

#include "geodual/mesh/triangle_mesh.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace geodual {

/// Reads a feature file: one polyline of the mesh's vertex indices per line,
/// `A B C ...` meaning the edges A-B, B-C, ... (0-based, as in the mesh
/// file). Blank lines and lines starting with '#' are skipped. \throw
/// geodual::Error naming the file and line for a word that is not an index,
/// an index out of range, a line with one index, or a pair of vertices that
/// share no face.
std::vector<std::array<Index, 2>> read_feature_file(const std::filesystem::path& path, const TriangleMesh& mesh);

/// \throw geodual::UsageError naming the first pair of `edges` that is not an
/// edge of `mesh` (two vertices of one face): "<what> A B: ...".
void require_edges_of(const TriangleMesh& mesh, const std::vector<std::array<Index, 2>>& edges,
                      const std::string& what);

}  // namespace geodual
