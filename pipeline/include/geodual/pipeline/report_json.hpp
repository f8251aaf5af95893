#pragma once
// JSON forms of the reports, shared by the CLI's --json outputs and by
// embedding code. Keys are the reports' field names; a value that has no
// meaning (a genus of a non-manifold mesh) is null.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace geodual::pipeline {

/// vertices, faces, edges, components, boundary_loops, boundary_edges,
/// nonmanifold_edges, nonmanifold_vertices, degenerate_faces, duplicate_faces,
/// duplicate_vertices, unreferenced_vertices, bbox_min, bbox_max,
/// bbox_diagonal, euler_characteristic, genus (integer or null), oriented.
nlohmann::ordered_json mesh_report_json(const MeshReport& report);

/// The figures of one mesh under the keys `geodual stats --json` prints:
/// vertices, faces, degenerate_faces, q_min, q_avg, theta_min_deg,
/// theta_min_avg_deg, pct_angles_lt30, p30, valence_histogram,
/// interior_vertices, pct_valence6 (or null), euler_characteristic, genus
/// (integer or null), components, boundary_loops, nonmanifold_edges,
/// bbox_diagonal, area, volume.
nlohmann::ordered_json triangle_quality_json(const quality::TriangleQuality& quality);

/// `geodual stats --json` less the paths and times: the candidate's figures
/// (triangle_quality_json), hausdorff, rms, hausdorff_pct, rms_pct,
/// hausdorff_reference_to_candidate_pct, hausdorff_candidate_to_reference_pct,
/// area_change_pct, volume_change_pct (or null), sharp_angle_deg,
/// feature_tolerance_pct, feature_recall_edges, feature_recall_length,
/// feature_recall_pct, feature_max_gap_pct (null without feature recall),
/// samples_per_side, seed, reference_samples, candidate_samples and
/// reference_quality (triangle_quality_json of the reference). `options` are
/// those the report was made with.
nlohmann::ordered_json quality_report_json(const quality::QualityReport& report,
                                           const quality::QualityOptions& options);

/// What a remesh is, under the keys of `geodual remesh --json` less the
/// paths, times and memory: the same bytes for the same input, options and
/// seed (the CLI writes them into a glTF output's extras; Python returns
/// them as `report`). docs/formats.md lists the keys.
nlohmann::ordered_json remesh_report_json(const RemeshPipelineResult& run, const RemeshPipelineOptions& options);

/// format, encoding, file_bytes, polygons_split, welded_corners, notes.
nlohmann::ordered_json read_info_json(const io::ReadInfo& info);

/// The vertex attributes present, one entry each with its type, e.g.
/// ["colors rgb uchar", "normals float", "quality float"]; empty when none.
std::vector<std::string> attribute_list(const VertexAttributes& attributes);

}  // namespace geodual::pipeline
