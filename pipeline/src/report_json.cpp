#include "geodual/pipeline/report_json.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace geodual::pipeline {
namespace {

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

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
  if (!report.genus) {
    json["genus"] = nullptr;
  } else if (*report.genus == std::round(*report.genus)) {
    json["genus"] = std::llround(*report.genus);  // 2, not 2.0
  } else {
    json["genus"] = *report.genus;
  }
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
