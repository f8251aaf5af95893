#include "geodual/pipeline/report_json.hpp"

#include "geodual/pipeline/version.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/sample_sites.hpp"

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

nlohmann::ordered_json remesh_report_json(const RemeshPipelineResult& run, const RemeshPipelineOptions& options) {
  const quality::TriangleQuality quality =
      run.statistics ? run.statistics->candidate : quality::triangle_quality(run.remesh.mesh);
  nlohmann::ordered_json figures;
  figures["geodual_version"] = build_version();
  figures["input_vertices"] = run.input.mesh.num_vertices();
  figures["input_faces"] = run.input.mesh.num_faces();
  figures["vertices_split"] = run.surface.vertices_split;
  figures["dropped_faces"] = run.dropped.faces;
  figures["dropped_area_pct"] = run.dropped.area_pct;
  figures["sampling"] = !options.given_sites
                            ? nlohmann::ordered_json(remesh::sampling_strategy_name(options.sampling.strategy))
                            : nlohmann::ordered_json(nullptr);
  figures["seed"] = options.sampling.seed;
  figures["edge_length_target"] =
      options.edge_length > 0 ? nlohmann::ordered_json(options.edge_length) : nlohmann::ordered_json(nullptr);
  figures["faces_target"] = options.faces > 0 ? nlohmann::ordered_json(options.faces) : nlohmann::ordered_json(nullptr);
  figures["sites"] = static_cast<std::int64_t>(run.initial_sites.size()) - run.site_twins;
  figures["sites_added_for_topology"] = run.sites_added_for_topology;
  figures["sites_added_for_creases"] = run.sites_added_for_creases;
  figures["sites_added_for_creases_reason"] = run.sites_added_for_creases_reason.empty()
                                                  ? nlohmann::ordered_json(nullptr)
                                                  : nlohmann::ordered_json(run.sites_added_for_creases_reason);
  figures["sharp_angle_deg"] = options.features.sampling.sharp_angle;
  figures["continuation_angle_deg"] = options.features.sampling.continuation_angle;
  figures["feature_chains"] = run.features.sharp_chains;
  figures["feature_corners"] = run.features.corners.size();
  figures["feature_length"] = run.features.sharp_length;
  // None where no corner joins two features.
  const double narrowest_corner = remesh::narrowest_corner_angle(run.surface.mesh, run.features);
  figures["feature_narrowest_corner_deg"] =
      narrowest_corner < 360 ? nlohmann::ordered_json(narrowest_corner) : nlohmann::ordered_json(nullptr);
  figures["feature_sites"] = run.feature_sites;
  figures["feature_sites_tightened"] = run.feature_sites_tightened;
  figures["sites_added_near_features"] = run.sites_added_near_features;
  figures["crease_pins"] = run.crease_pins;
  figures["crease_segments"] = run.crease_segments.segments;
  figures["crease_segments_followed"] = run.crease_segments.edges;
  figures["crease_pins_reason"] =
      run.crease_pins_reason.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(run.crease_pins_reason);
  figures["features_dropped_reason"] = run.features_dropped_reason.empty()
                                           ? nlohmann::ordered_json(nullptr)
                                           : nlohmann::ordered_json(run.features_dropped_reason);
  figures["features_dropped_near"] = nlohmann::ordered_json::array();
  for (const Eigen::Vector3d& place : run.features_dropped_near) {
    figures["features_dropped_near"].push_back({place.x(), place.y(), place.z()});
  }
  figures["features_partly_dropped_reason"] = run.features_partly_dropped_reason.empty()
                                                  ? nlohmann::ordered_json(nullptr)
                                                  : nlohmann::ordered_json(run.features_partly_dropped_reason);
  figures["features_left_out"] = nlohmann::ordered_json::array();
  for (const pipeline::FeatureLeftOut& stretch : run.features_left_out) {
    figures["features_left_out"].push_back({{"edges", stretch.edges},
                                            {"length", stretch.length},
                                            {"place", {stretch.place.x(), stretch.place.y(), stretch.place.z()}}});
  }
  figures["cracks_closed"] = run.remesh.cracks_closed;
  figures["crack_triangles"] = run.remesh.crack_triangles;
  figures["input_euler_characteristic"] = run.input_report.euler_characteristic;
  figures["input_boundary_loops"] = run.input_report.boundary_loops;
  figures["surface_euler_characteristic"] = run.surface_euler_characteristic;
  figures["surface_boundary_loops"] = run.surface_boundary_loops;
  figures["lloyd_iterations"] = run.relaxation.iterations;
  figures["warm_start_iterations"] = run.relaxation.warm_start_iterations;
  figures["lloyd_diagrams"] = run.relaxation.diagrams;
  figures["energy_history"] = run.relaxation.energy;
  figures["sites_added"] = run.remesh.sites_added;
  figures["sites_left_out"] = run.remesh.sites_left_out;
  figures["repair_rounds"] = run.remesh.repair_rounds;
  figures["repair_problems"] = run.remesh.repair_problems;
  figures["smoothing_angle_deg"] = options.smoothing.smoothing_angle;
  figures["vertices_smoothed"] = run.smoothing.vertices_moved;
  figures["fit_deviations"] = options.smoothing.fit_deviations;
  figures["vertices_fitted"] = run.fitting.vertices_moved;
  figures["vertices"] = run.remesh.mesh.num_vertices();
  figures["faces"] = run.remesh.mesh.num_faces();
  figures["euler_characteristic"] = quality.euler_characteristic;
  figures["boundary_loops"] = quality.boundary_loops;
  figures["q_min"] = quality.q_min;
  figures["q_avg"] = quality.q_avg;
  figures["theta_min_deg"] = quality.theta_min_deg;
  figures["theta_min_avg_deg"] = quality.theta_min_avg_deg;
  figures["pct_angles_lt30"] = quality.pct_angles_lt30;
  figures["p30"] = quality.p30;
  figures["pct_valence6"] =
      quality.pct_valence6 ? nlohmann::ordered_json(*quality.pct_valence6) : nlohmann::ordered_json(nullptr);
  figures["max_error_pct"] =
      options.max_error_pct > 0 ? nlohmann::ordered_json(options.max_error_pct) : nlohmann::ordered_json(nullptr);
  figures["error_bound_met"] =
      options.max_error_pct > 0 ? nlohmann::ordered_json(run.error_bound_met) : nlohmann::ordered_json(nullptr);
  nlohmann::ordered_json error_rounds = nlohmann::ordered_json::array();
  for (const pipeline::ErrorRound& round : run.error_rounds) {
    error_rounds.push_back({{"sites", round.sites}, {"hausdorff_pct", round.hausdorff_pct}});
  }
  figures["error_rounds"] = error_rounds;
  // The texture atlas and what was baked onto it (null without --texture-size).
  if (run.atlas) {
    const remesh::TextureAtlas& atlas = *run.atlas;
    figures["texture"] = {{"size", options.texture_size},
                          {"atlas_vertices", atlas.source_vertex.size()},
                          {"charts", atlas.charts},
                          {"texture_used", atlas.texture_used},
                          {"mean_area_distortion", atlas.mean_area_distortion},
                          {"max_area_distortion", atlas.max_area_distortion},
                          {"mean_angle_distortion_deg", atlas.mean_angle_distortion},
                          {"max_angle_distortion_deg", atlas.max_angle_distortion},
                          {"texels_baked", run.textures.texels_baked},
                          {"base_color", !run.textures.base_color.empty()},
                          {"normal_map", !run.textures.normal_map.empty()}};
  } else {
    figures["texture"] = nullptr;
  }
  if (run.statistics) {
    figures["hausdorff_pct"] = run.statistics->hausdorff_pct;
    const Eigen::Vector3d& farthest = run.statistics->hausdorff_point;
    figures["hausdorff_at"] = {farthest.x(), farthest.y(), farthest.z()};
    figures["rms_pct"] = run.statistics->rms_pct;
    figures["area_change_pct"] = run.statistics->area_change_pct;
    // The feature recall (null where the statistics left it out).
    if (const std::optional<quality::FeatureRecall>& features = run.statistics->features) {
      figures["feature_recall_edges"] = features->edges;
      figures["feature_recall_length"] = features->length;
      figures["feature_recall_pct"] = features->recall_pct;
      figures["feature_max_gap_pct"] = features->max_gap_pct;
      figures["feature_long_crease_length"] = features->long_crease_length;
      figures["feature_long_creases"] = features->long_chains;
      figures["feature_long_length"] = features->long_length;
      figures["feature_long_recall_pct"] = features->long_recall_pct;
    } else {
      for (const char* key :
           {"feature_recall_edges", "feature_recall_length", "feature_recall_pct", "feature_max_gap_pct",
            "feature_long_crease_length", "feature_long_creases", "feature_long_length", "feature_long_recall_pct"}) {
        figures[key] = nullptr;
      }
    }
  }
  return figures;
}

}  // namespace geodual::pipeline
