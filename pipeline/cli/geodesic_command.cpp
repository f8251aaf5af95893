// geodual geodesic MESH (--sites N [--sampling S] [--seed S] | --site-file F) [-o OUT]
//                        [--no-rwr] [--window-memory MIB] [--json]
// Exact geodesic distance from the nearest of several sites, at every vertex.

#include "command.hpp"
#include "geodesic_flags.hpp"
#include "progress_bar.hpp"
#include "site_source.hpp"
#include "text_table.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/field_output.hpp"
#include "geodual/pipeline/sites.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>

namespace geodual::cli {
namespace {

class GeodesicCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command =
        *app.add_subcommand("geodesic", "Exact geodesic distance to the nearest site at every vertex (window-VTP)");
    command.footer(
        "Example:\n  geodual geodesic scan.ply --sites 30 --seed 7 -o distance.ply\n"
        "Site file: one site per line, a vertex index, or 'f FACE U V W' (face and barycentric "
        "coordinates).");
    command.add_option("MESH", mesh_path_, "Mesh file: .ply, .obj, .off, .stl, .gltf or .glb")->required();
    sites_.add_to(command);
    command.add_option("-o,--output", output_path_,
                       "Write the mesh with the distance field: .ply (properties distance, site) or "
                       ".glb/.gltf (colour by site, _DISTANCE attribute)");
    geodesic_.add_to(command);
    command.add_flag("--json", json_, "Print the statistics as one JSON object");
    command.add_flag("-q,--quiet", quiet_, "No progress line on the terminal");
    return command;
  }

  int run() override {
    sites_.validate("geodesic");
    if (!output_path_.empty()) {
      io::require_output_path(output_path_, {".ply", ".glb", ".gltf"}, "a distance field");
      io::refuse_to_overwrite_inputs(output_path_, {mesh_path_, sites_.file()});
    }
    const io::LoadedMesh loaded = io::read_mesh(mesh_path_);
    require_computable_range(loaded.mesh, mesh_path_);
    const TriangleMesh& mesh = loaded.mesh;
    const std::vector<SurfacePoint> sites = sites_.sites(mesh);
    voronoi::GeodesicOptions options;
    geodesic_.apply(options);
    ProgressBar bar(quiet_);
    options.progress = [&](double fraction) { return bar.update("geodesics", fraction); };
    const voronoi::GeodesicField field = voronoi::compute_geodesic_field(mesh, sites, options);
    bar.finish();
    if (!output_path_.empty()) write_geodesic_field(output_path_, mesh, field);

    std::int64_t reached = 0;
    double max_distance = 0;
    for (const double d : field.distance) {
      if (std::isfinite(d)) {
        ++reached;
        max_distance = std::max(max_distance, d);
      }
    }
    const voronoi::GeodesicStats& s = field.stats;
    if (json_) {
      nlohmann::ordered_json json;
      json["mesh"] = mesh_path_;
      json["vertices"] = mesh.num_vertices();
      json["faces"] = mesh.num_faces();
      json["sites"] = sites.size();
      json["remove_redundant_windows"] = geodesic_.remove_redundant_windows();
      json["reached_vertices"] = reached;
      json["max_distance"] = max_distance;
      json["windows_created"] = s.windows_created;
      json["windows_stored"] = s.windows_stored;
      json["peak_windows"] = s.peak_windows;
      json["peak_window_bytes"] = s.peak_window_bytes;
      json["vertices_popped"] = s.vertices_popped;
      json["pseudo_sources"] = s.pseudo_sources;
      json["faces_inactive"] = s.faces_inactive;
      json["site_groups"] = s.site_groups;
      json["setup_s"] = s.setup_seconds;
      json["propagation_s"] = s.propagation_seconds;
      json["time_s"] = s.total_seconds;
      json["output"] = output_path_.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(output_path_);
      std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
      return 0;
    }
    KeyValueTable table;
    table.add("mesh", mesh_path_ + " (" + with_thousands(mesh.num_vertices()) + " vertices, " +
                          with_thousands(mesh.num_faces()) + " faces)");
    table.add("sites", with_thousands(static_cast<std::int64_t>(sites.size())));
    table.add("redundant window removal", geodesic_.remove_redundant_windows() ? "on" : "off");
    table.add("reached vertices", with_thousands(reached));
    table.add("max distance", significant(max_distance));
    table.add("windows created", with_thousands(s.windows_created));
    table.add("windows stored", with_thousands(s.windows_stored));
    table.add("peak windows", with_thousands(s.peak_windows) + " (" +
                                  byte_size(static_cast<std::uintmax_t>(s.peak_window_bytes)) + ")");
    table.add("vertices popped", with_thousands(s.vertices_popped));
    table.add("pseudo-sources", with_thousands(s.pseudo_sources));
    table.add("faces inactive", with_thousands(s.faces_inactive));
    table.add("site groups", std::to_string(s.site_groups));
    table.add("time", duration(s.total_seconds) + " (setup " + duration(s.setup_seconds) + ", propagation " +
                          duration(s.propagation_seconds) + ")");
    if (!output_path_.empty()) table.add("output", output_path_);
    table.print(std::cout);
    return 0;
  }

 private:
  std::string mesh_path_;
  SiteSource sites_{"random"};
  std::string output_path_;
  GeodesicFlags geodesic_;
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

std::unique_ptr<Command> make_geodesic_command() { return std::make_unique<GeodesicCommand>(); }

}  // namespace geodual::cli
