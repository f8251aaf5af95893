// geodual geodesic MESH (--sites N [--seed S] | --site-file F) [-o OUT]
//                        [--no-rwr] [--window-memory MIB] [--json]
// Exact geodesic distance from the nearest of several sites, at every vertex.

#include "command.hpp"
#include "progress_bar.hpp"
#include "text_table.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
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
    CLI::App& command = *app.add_subcommand(
        "geodesic", "Exact geodesic distance to the nearest site at every vertex (window-VTP)");
    command.footer(
        "Example:\n  geodual geodesic scan.ply --sites 30 --seed 7 -o distance.ply\n"
        "Site file: one site per line, a vertex index, or 'f FACE U V W' (face and barycentric "
        "coordinates).");
    command.add_option("MESH", mesh_path_, "Mesh file: .ply, .obj, .off, .stl, .gltf or .glb")->required();
    CLI::Option* sites = command.add_option("--sites", site_count_, "Number of random vertex sites");
    CLI::Option* site_file = command.add_option("--site-file", site_file_, "Read the sites from this file");
    sites->excludes(site_file);
    site_file->excludes(sites);
    command.add_option("--seed", seed_, "Seed for the random sites")->capture_default_str();
    command.add_option("-o,--output", output_path_,
                       "Write the mesh with the distance field: .ply (properties distance, site) or "
                       ".glb/.gltf (colour by site, _DISTANCE attribute)");
    command.add_flag("--no-rwr", no_rwr_, "Keep every window (no Redundant Window Removal), as MMP does");
    command.add_option("--window-memory", window_memory_mib_, "Stop with an error beyond this many MiB of windows")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    command.add_flag("--json", json_, "Print the statistics as one JSON object");
    command.add_flag("-q,--quiet", quiet_, "No progress line on the terminal");
    return command;
  }

  int run() override {
    if (site_file_.empty() && site_count_ <= 0) {
      throw UsageError("geodesic: give --sites N (N >= 1) or --site-file FILE");
    }
    if (!output_path_.empty()) {
      io::require_output_path(output_path_, {".ply", ".glb", ".gltf"}, "a distance field");
      io::refuse_to_overwrite_inputs(output_path_, {mesh_path_, site_file_});
    }
    const io::LoadedMesh loaded = io::read_mesh(mesh_path_);
    const TriangleMesh& mesh = loaded.mesh;
    const std::vector<SurfacePoint> sites = site_file_.empty()
                                                ? random_vertex_sites(mesh, site_count_, seed_)
                                                : read_site_file(site_file_, mesh);
    voronoi::GeodesicOptions options;
    options.remove_redundant_windows = !no_rwr_;
    options.window_memory_limit_bytes = static_cast<std::size_t>(window_memory_mib_) << 20;
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
      json["remove_redundant_windows"] = !no_rwr_;
      json["reached_vertices"] = reached;
      json["max_distance"] = max_distance;
      json["windows_created"] = s.windows_created;
      json["windows_stored"] = s.windows_stored;
      json["peak_windows"] = s.peak_windows;
      json["peak_window_bytes"] = s.peak_window_bytes;
      json["vertices_popped"] = s.vertices_popped;
      json["pseudo_sources"] = s.pseudo_sources;
      json["faces_inactive"] = s.faces_inactive;
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
    table.add("redundant window removal", no_rwr_ ? "off" : "on");
    table.add("reached vertices", with_thousands(reached));
    table.add("max distance", significant(max_distance));
    table.add("windows created", with_thousands(s.windows_created));
    table.add("windows stored", with_thousands(s.windows_stored));
    table.add("peak windows", with_thousands(s.peak_windows) + " (" + byte_size(static_cast<std::uintmax_t>(s.peak_window_bytes)) + ")");
    table.add("vertices popped", with_thousands(s.vertices_popped));
    table.add("pseudo-sources", with_thousands(s.pseudo_sources));
    table.add("faces inactive", with_thousands(s.faces_inactive));
    table.add("time", duration(s.total_seconds) + " (setup " + duration(s.setup_seconds) + ", propagation " +
                          duration(s.propagation_seconds) + ")");
    if (!output_path_.empty()) table.add("output", output_path_);
    table.print(std::cout);
    return 0;
  }

 private:
  std::string mesh_path_;
  std::int64_t site_count_ = 0;
  std::string site_file_;
  std::uint64_t seed_ = 1;
  std::string output_path_;
  bool no_rwr_ = false;
  std::int64_t window_memory_mib_ = 8192;
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

std::unique_ptr<Command> make_geodesic_command() { return std::make_unique<GeodesicCommand>(); }

}  // namespace geodual::cli
