#pragma once
// Writing Voronoi diagrams and remeshes, and the pictures of them.

#include "geodual/io/gltf.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace geodual {

/// .glb / .gltf: the input mesh coloured by nearest site at its vertices
/// (COLOR_0) with a `_DISTANCE` attribute, the cell boundaries as a LINES
/// primitive ("voronoi_boundaries"), the sites as POINTS ("sites") and the
/// Voronoi vertices as POINTS ("voronoi_vertices"); `extras_json` (a JSON
/// object, or empty) goes to asset.extras. Throws geodual::Error for other
/// extensions.
void write_voronoi_diagram(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const voronoi::VoronoiDiagram& diagram, const std::string& extras_json = {});

/// A remeshed surface and its vertex attributes by extension: .ply, .obj,
/// .glb or .gltf (io::write_mesh; glTF with `extras_json` in asset.extras,
/// its triangles stored as `compression` says). A compression other than
/// none with a .ply or .obj path throws geodual::Error.
void write_remesh(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes = {},
                  const std::string& extras_json = {}, io::GltfCompression compression = io::GltfCompression::none);

/// A remesh's glTF file: `entry` alone, `extras_json` in asset.extras,
/// stored as `compression` says, geodual's version as the generator.
void write_remesh_gltf(const std::filesystem::path& path, io::GltfTriangleMesh entry, const std::string& extras_json,
                       io::GltfCompression compression);

/// Per vertex, the mean quality Q of its triangles mapped to a colour: red
/// (Q = 0) through yellow to green (Q = 1), sRGB-encoded as VertexAttributes::colors.
ColorMatrix quality_colors(const TriangleMesh& mesh);

/// A PNG picture of the input coloured by cell with the boundaries and sites.
/// `progress` as io::PreviewOptions::progress (false: Cancelled, nothing written).
void write_voronoi_preview(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const voronoi::VoronoiDiagram& diagram, const std::function<bool(double)>& progress = {});

/// A PNG picture of a mesh, shaded with its wireframe (coloured per vertex
/// when `colors`, sRGB-encoded as VertexAttributes::colors, has a row per
/// vertex; alpha is ignored) and `lines` (polylines, such as feature chains)
/// in dark red over it; `progress` as above.
void write_mesh_preview(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors = {},
                        const std::function<bool(double)>& progress = {},
                        std::span<const std::vector<Eigen::Vector3d>> lines = {});

/// The process's peak resident memory in bytes (0 where unknown).
std::int64_t peak_memory_bytes();

}  // namespace geodual
