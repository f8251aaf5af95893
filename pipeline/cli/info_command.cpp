// geodual info FILE [--json]: what a mesh file holds and what is wrong with it.

#include "command.hpp"
#include "option_checks.hpp"
#include "progress_bar.hpp"
#include "text_table.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/pipeline/report_json.hpp"
#include "geodual/remesh/feature_sampling.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>

namespace geodual::cli {
namespace {

std::string point(const Eigen::Vector3d& p) {
  return "(" + significant(p.x()) + ", " + significant(p.y()) + ", " + significant(p.z()) + ")";
}

class InfoCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command = *app.add_subcommand("info", "Read a mesh file and report its size, topology and defects");
    command.add_option("FILE", path_, "Mesh file: .ply, .obj, .off, .stl, .gltf or .glb")->required();
    command.add_flag("--json", json_, "Print one JSON object instead of a table");
    command.add_option("--preview", preview_path_, "Also render a picture of the mesh: .png");
    command
        .add_option("--sharp-angle", sharp_angle_,
                    "Report the sharp features a remesh with --sharp-angle would keep: creases where the normals "
                    "turn by at least this many degrees (0: none, the default here, since the cut and the detection "
                    "take several times the analysis; the remesh's default is 60)")
        ->capture_default_str()
        ->check(number_between(0, 180));
    command.add_option("--sites", sites_, "The remesh's site count, whose spacing sets the features' scale")
        ->capture_default_str()
        ->check(integer_between(4, 2147483647));
    command.footer("Example:\n  geodual info scan.ply --json\n  geodual info scan.ply --preview scan.png");
    return command;
  }

  int run() override {
    if (!preview_path_.empty()) {
      io::require_output_path(preview_path_, {".png"}, "a preview");
      io::refuse_to_overwrite_inputs(preview_path_, {path_});
    }
    const auto start = std::chrono::steady_clock::now();
    const io::LoadedMesh loaded = io::read_mesh(path_);
    require_computable_range(loaded.mesh, path_);
    const double read_seconds = seconds_since(start);
    stop_if_interrupted();
    const auto analysis_start = std::chrono::steady_clock::now();
    const MeshReport report = analyze_mesh(loaded.mesh);
    stop_if_interrupted();
    // The features on the surface a remesh sees (the input cut to a
    // manifold), as its sampling keeps them for the count: fewer where their
    // chains would take more than the count (FeatureSamplingOptions::max_share_narrow_regions).
    remesh::FeatureSet features;
    double narrowest_corner = 360;
    if (sharp_angle_ > 0 && report.faces > 0) {
      const TriangleMesh cut = remesh::cut_to_manifold(loaded.mesh).mesh;
      const remesh::RemeshSurface surface(cut);
      remesh::FeatureSamplingOptions options;
      options.sharp_angle = sharp_angle_;
      features = remesh::sample_features(surface, sites_, options).features;
      narrowest_corner = remesh::narrowest_corner_angle(cut, features);
    }
    const double analysis_seconds = seconds_since(analysis_start);
    stop_if_interrupted();
    if (!preview_path_.empty()) {
      write_mesh_preview(preview_path_, loaded.mesh, loaded.attributes.colors, still_wanted);
    }

    const std::vector<std::string> attributes = pipeline::attribute_list(loaded.attributes);
    if (json_) {
      print_json(loaded.info, attributes, report, features, narrowest_corner, read_seconds, analysis_seconds);
    } else {
      print_table(loaded.info, attributes, report, features, narrowest_corner, read_seconds, analysis_seconds);
    }
    return 0;
  }

 private:
  /// Ctrl-C: exit 3 before writing anything.
  static void stop_if_interrupted() {
    if (interrupted()) throw Cancelled("info cancelled");
  }

  static double short_crease_length(const remesh::FeatureSet& features) {
    double length = 0;
    for (const remesh::FeatureChain& crease : features.short_creases) length += crease.length;
    return length;
  }

  void print_json(const io::ReadInfo& info, const std::vector<std::string>& attributes, const MeshReport& report,
                  const remesh::FeatureSet& features, double narrowest_corner, double read_seconds,
                  double analysis_seconds) const {
    nlohmann::ordered_json json;
    json["file"] = path_;
    json.update(pipeline::read_info_json(info));
    json["attributes"] = attributes;
    json["read_seconds"] = read_seconds;
    json["analysis_seconds"] = analysis_seconds;
    json.update(pipeline::mesh_report_json(report));
    json["sharp_angle_deg"] = sharp_angle_;
    json["feature_chains"] = features.sharp_chains;
    json["feature_corners"] = features.corners.size();
    json["feature_length"] = features.sharp_length;
    json["feature_narrowest_corner_deg"] =
        narrowest_corner < 360 ? nlohmann::ordered_json(narrowest_corner) : nlohmann::ordered_json(nullptr);
    json["short_creases"] = features.short_creases.size();
    json["short_crease_length"] = short_crease_length(features);
    // Paths and notes need not be UTF-8: replace what is not rather than fail.
    std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
  }

  void print_table(const io::ReadInfo& info, const std::vector<std::string>& attributes, const MeshReport& report,
                   const remesh::FeatureSet& features, double narrowest_corner, double read_seconds,
                   double analysis_seconds) const {
    KeyValueTable table;
    table.add("file", path_);
    table.add("format",
              std::string(io::format_name(info.format)) + (info.encoding.empty() ? "" : ", " + info.encoding));
    table.add("file size", byte_size(info.file_bytes));
    const double megabytes_per_second = static_cast<double>(info.file_bytes) / 1e6 / read_seconds;
    table.add("read time", duration(read_seconds) + " (" + significant(megabytes_per_second, 3) + " MB/s)");
    if (info.polygons_split > 0) table.add("polygons split", with_thousands(info.polygons_split));
    if (info.welded_corners > 0) table.add("welded corners", with_thousands(info.welded_corners));
    for (const std::string& note : info.notes) table.add("note", note);
    table.add("vertex attributes", attributes.empty() ? "none" : comma_list(attributes));

    table.add("vertices", with_thousands(report.vertices));
    table.add("faces", with_thousands(report.faces));
    table.add("edges", with_thousands(report.edges));
    table.add("components", with_thousands(report.components));
    table.add("boundary loops", with_thousands(report.boundary_loops) + " (" + with_thousands(report.boundary_edges) +
                                    " boundary edges)");
    table.add("non-manifold edges", with_thousands(report.nonmanifold_edges));
    table.add("non-manifold vertices", with_thousands(report.nonmanifold_vertices));
    table.add("degenerate faces", with_thousands(report.degenerate_faces));
    table.add("duplicate faces", with_thousands(report.duplicate_faces));
    table.add("duplicate vertices", with_thousands(report.duplicate_vertices));
    table.add("unreferenced vertices", with_thousands(report.unreferenced_vertices));
    table.add("euler characteristic", with_thousands(report.euler_characteristic));
    table.add("genus", report.genus ? significant(*report.genus) : "not defined (not an orientable 2-manifold)");
    table.add("oriented", report.oriented ? "yes" : "no (some edge is used twice in one direction)");
    if (sharp_angle_ > 0) {
      table.add("sharp features", with_thousands(features.sharp_chains) + " chains, " +
                                      with_thousands(static_cast<std::int64_t>(features.corners.size())) +
                                      " corners, length " + significant(features.sharp_length) + " (" +
                                      significant(sharp_angle_, 3) + " deg at the scale of " + with_thousands(sites_) +
                                      " sites)");
      if (narrowest_corner < 360) {
        table.add("narrowest corner",
                  significant(narrowest_corner, 3) +
                      " deg between features (a remesh that keeps them has an angle about this small there)");
      }
      table.add("short creases", with_thousands(static_cast<std::int64_t>(features.short_creases.size())) +
                                     ", length " + significant(short_crease_length(features)) +
                                     " (sharp edges too short or weak at that scale to cut along: remesh "
                                     "--pin-creases follows them)");
    }
    table.add("bounding box", point(report.bbox_min) + " to " + point(report.bbox_max));
    table.add("bbox diagonal", significant(report.bbox_diagonal));
    table.add("analysis time", duration(analysis_seconds));
    table.print(std::cout);
  }

  std::string path_;
  bool json_ = false;
  std::string preview_path_;
  double sharp_angle_ = 0;
  std::int64_t sites_ = 4000;
};

}  // namespace

std::unique_ptr<Command> make_info_command() { return std::make_unique<InfoCommand>(); }

}  // namespace geodual::cli
