#include "geodual/pipeline/report_json.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace geodual::pipeline {
namespace {

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::ordered_json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

/// A genus as 2, not 2.0; null where it means nothing.
nlohmann::ordered_json genus_json(const std::optional<double>& genus) {
  if (!genus) return nullptr;
  if (*genus == std::round(*genus)) return std::llround(*genus);
  return *genus;
}

}  // namespace

nlohmann::ordered_json mesh_report_json(const MeshReport& report) {
  nlohmann::ordered_json json;
  json["vertices"] = report.vertices;
  json["faces"] = report.faces;
  json["edges"] = report.edges;
  json["components"] = report.components;
  json["boundary_loops"] = report.boundary_loops;
  json["boundary_edges"] = report.boundary_edges;
  json["nonmanifold_edges"] = report.nonmanifold_edges;
  json["nonmanifold_vertices"] = report.nonmanifold_vertices;
  json["degenerate_faces"] = report.degenerate_faces;
  json["duplicate_faces"] = report.duplicate_faces;
  json["duplicate_vertices"] = report.duplicate_vertices;
  json["unreferenced_vertices"] = report.unreferenced_vertices;
  json["bbox_min"] = vector_json(report.bbox_min);
  json["bbox_max"] = vector_json(report.bbox_max);
  json["bbox_diagonal"] = report.bbox_diagonal;
  json["euler_characteristic"] = report.euler_characteristic;
  json["genus"] = genus_json(report.genus);
  json["oriented"] = report.oriented;
  return json;
}

std::vector<std::string> attribute_list(const VertexAttributes& attributes) {
  std::vector<std::string> list;
  if (attributes.colors.rows() > 0) {
    list.push_back(std::string("colors ") + (attributes.colors.cols() == 4 ? "rgba " : "rgb ") +
                   std::string(ply_type_name(attributes.color_type)));
  }
  if (attributes.normals.rows() > 0) list.push_back("normals " + std::string(ply_type_name(attributes.normal_type)));
  for (const VertexScalar& scalar : attributes.scalars) {
    list.push_back(scalar.name + " " + std::string(ply_type_name(scalar.type)));
  }
  return list;
}

nlohmann::ordered_json triangle_quality_json(const quality::TriangleQuality& q) {
  nlohmann::ordered_json json;
  json["vertices"] = q.vertices;
  json["faces"] = q.faces;
  json["degenerate_faces"] = q.degenerate_faces;
  json["q_min"] = q.q_min;
  json["q_avg"] = q.q_avg;
  json["theta_min_deg"] = q.theta_min_deg;
  json["theta_min_avg_deg"] = q.theta_min_avg_deg;
  json["pct_angles_lt30"] = q.pct_angles_lt30;
  json["p30"] = q.p30;
  json["valence_histogram"] = q.valence_histogram;
  json["interior_vertices"] = q.interior_vertices;
  json["pct_valence6"] = optional_json(q.pct_valence6);
  json["euler_characteristic"] = q.euler_characteristic;
  json["genus"] = genus_json(q.genus);
  json["components"] = q.components;
  json["boundary_loops"] = q.boundary_loops;
  json["nonmanifold_edges"] = q.nonmanifold_edges;
  json["bbox_diagonal"] = q.bbox_diagonal;
  json["area"] = q.area;
  json["volume"] = q.volume;
  return json;
}

nlohmann::ordered_json quality_report_json(const quality::QualityReport& report,
                                           const quality::QualityOptions& options) {
  nlohmann::ordered_json json = triangle_quality_json(report.candidate);
  json["hausdorff"] = report.hausdorff;
  json["rms"] = report.rms;
  json["hausdorff_pct"] = report.hausdorff_pct;
  json["rms_pct"] = report.rms_pct;
  const double diagonal = report.reference.bbox_diagonal;
  json["hausdorff_reference_to_candidate_pct"] = 100.0 * report.hausdorff_reference_to_candidate / diagonal;
  json["hausdorff_candidate_to_reference_pct"] = 100.0 * report.hausdorff_candidate_to_reference / diagonal;
  json["hausdorff_at"] = {report.hausdorff_point.x(), report.hausdorff_point.y(), report.hausdorff_point.z()};
  json["area_change_pct"] = report.area_change_pct;
  json["volume_change_pct"] = optional_json(report.volume_change_pct);
  const std::optional<quality::FeatureRecall>& features = report.features;
  json["sharp_angle_deg"] = options.sharp_angle_deg;
  json["feature_tolerance_pct"] = options.feature_tolerance_pct;
  json["feature_recall_edges"] = features ? nlohmann::ordered_json(features->edges) : nlohmann::ordered_json(nullptr);
  json["feature_recall_length"] = features ? nlohmann::ordered_json(features->length) : nlohmann::ordered_json(nullptr);
  json["feature_recall_pct"] =
      features ? nlohmann::ordered_json(features->recall_pct) : nlohmann::ordered_json(nullptr);
  json["feature_max_gap_pct"] =
      features ? nlohmann::ordered_json(features->max_gap_pct) : nlohmann::ordered_json(nullptr);
  json["samples_per_side"] = options.samples_per_side;
  json["seed"] = options.seed;
  json["reference_samples"] = report.reference_samples;
  json["candidate_samples"] = report.candidate_samples;
  json["reference_quality"] = triangle_quality_json(report.reference);
  return json;
}

nlohmann::ordered_json read_info_json(const io::ReadInfo& info) {
  nlohmann::ordered_json json;
  json["format"] = std::string(io::format_name(info.format));
  json["encoding"] = info.encoding;
  json["file_bytes"] = info.file_bytes;
  json["polygons_split"] = info.polygons_split;
  json["welded_corners"] = info.welded_corners;
  json["notes"] = info.notes;
  return json;
}

}  // namespace geodual::pipeline
