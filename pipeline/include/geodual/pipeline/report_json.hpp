#pragma once
// JSON forms of the reports, shared by the CLI's --json outputs and by
// embedding code. Keys are the reports' field names; a value that has no
// meaning (a genus of a non-manifold mesh) is null.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace geodual::pipeline {

/// vertices, faces, edges, components, boundary_loops, boundary_edges,
/// nonmanifold_edges, nonmanifold_vertices, degenerate_faces, duplicate_faces,
/// duplicate_vertices, unreferenced_vertices, bbox_min, bbox_max,
/// bbox_diagonal, euler_characteristic, genus (integer or null), oriented.
nlohmann::ordered_json mesh_report_json(const MeshReport& report);

/// format, encoding, file_bytes, polygons_split, welded_corners, notes.
nlohmann::ordered_json read_info_json(const io::ReadInfo& info);

/// The vertex attributes present, one entry each with its type, e.g.
/// ["colors rgb uchar", "normals float", "quality float"]; empty when none.
std::vector<std::string> attribute_list(const VertexAttributes& attributes);

}  // namespace geodual::pipeline
