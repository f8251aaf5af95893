// geodual remesh MESH -o OUT (--sites N [--sampling S] [--seed S] | --site-file F)
//                     [--lloyd K] [--lloyd-tol T] [--json] [--preview OUT.png] [--max-repair-rounds K]
// The main job: a dense scan in, an isotropic mesh of about N vertices out,
// through the dual of the exact geodesic Voronoi diagram.

#include "command.hpp"
#include "site_source.hpp"
#include "text_table.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/quality_stats.hpp"
#include "geodual/remesh/remesh.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <string>

namespace geodual::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class RemeshCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command = *app.add_subcommand(
        "remesh", "Remesh a scan: the dual of the geodesic Voronoi diagram of N sites on it");
    command.footer(
        "Example:\n  geodual remesh scan.ply --sites 4000 -o remeshed.glb --preview remeshed.png\n"
        "Output by extension: .glb, .gltf (statistics in asset.extras), .ply, .obj.");
    command.add_option("MESH", mesh_path_, "Mesh file: .ply, .obj, .off, .stl, .gltf or .glb")->required();
    command.add_option("-o,--output", output_path_, "The remeshed surface: .glb, .gltf, .ply or .obj")->required();
    sites_.add_to(command);
    command.add_option("--lloyd", options_.lloyd.iterations,
                       "Lloyd iterations towards the geodesic centroids (0: the dual of the sampled sites)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    command.add_option("--lloyd-tol", options_.lloyd.tolerance,
                       "Stop Lloyd once an iteration lowers the CVT energy by less than this fraction")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    command.add_option("--max-repair-rounds", options_.max_repair_rounds,
                       "Rounds of adding sites where the dual fails before giving up")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    command.add_option("--preview", preview_path_, "Also render a picture of the result: .png");
    command.add_flag("--json", json_, "Print the statistics as one JSON object");
    return command;
  }

  int run() override {
    sites_.validate("remesh");
    io::refuse_to_overwrite_inputs(output_path_, {mesh_path_, sites_.file()});
    if (!preview_path_.empty()) io::refuse_to_overwrite_inputs(preview_path_, {mesh_path_, sites_.file()});
    const auto start = std::chrono::steady_clock::now();
    const io::LoadedMesh loaded = io::read_mesh(mesh_path_);
    // Sites are sampled on the surface that is remeshed: cut apart at
    // non-manifold edges and vertices (a no-op on a manifold).
    const remesh::ManifoldCut cut = remesh::cut_to_manifold(loaded.mesh);
    const TriangleMesh& mesh = cut.mesh;
    const double load_seconds = seconds_since(start);
    const auto sample_start = std::chrono::steady_clock::now();
    std::vector<SurfacePoint> sites = sites_.sites(mesh);
    const double sample_seconds = seconds_since(sample_start);
    const std::size_t given = sites.size();
    const remesh::RemeshResult result = remesh::remesh_from_sites(mesh, std::move(sites), options_);
    const remesh::TriangleQuality quality = remesh::triangle_quality(result.mesh);

    nlohmann::ordered_json json;
    json["mesh"] = mesh_path_;
    json["output"] = output_path_;
    json["input_vertices"] = loaded.mesh.num_vertices();
    json["input_faces"] = mesh.num_faces();
    json["vertices_split"] = cut.vertices_split;
    json["sampling"] = sites_.file().empty() ? nlohmann::ordered_json(sites_.sampling()) : nlohmann::ordered_json(nullptr);
    json["seed"] = sites_.seed();
    json["sites"] = given;
    json["lloyd_iterations"] = result.lloyd_iterations;
    json["energy_history"] = result.energy;
    json["sites_added"] = result.sites_added;
    json["repair_rounds"] = result.repair_rounds;
    json["vertices"] = result.mesh.num_vertices();
    json["faces"] = result.mesh.num_faces();
    json["euler_characteristic"] = quality.euler_characteristic;
    json["boundary_loops"] = quality.boundary_loops;
    json["q_min"] = quality.q_min;
    json["q_avg"] = quality.q_avg;
    json["theta_min_deg"] = quality.theta_min_deg;
    json["pct_angles_lt30"] = quality.pct_angles_lt30;
    json["load_s"] = load_seconds;
    json["sample_s"] = sample_seconds;
    json["geodesic_s"] = result.geodesic_seconds;
    json["diagram_s"] = result.diagram_seconds;
    json["lloyd_move_s"] = result.lloyd_seconds;
    json["dual_s"] = result.dual_seconds;
    const auto write_start = std::chrono::steady_clock::now();
    write_remesh(output_path_, result.mesh, json.dump());
    if (!preview_path_.empty()) write_mesh_preview(preview_path_, result.mesh);
    const double write_seconds = seconds_since(write_start);
    json["write_s"] = write_seconds;
    json["time_s"] = seconds_since(start);
    json["peak_memory_bytes"] = peak_memory_bytes();

    if (json_) {
      std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
      return 0;
    }
    KeyValueTable table;
    table.add("input", mesh_path_ + " (" + with_thousands(loaded.mesh.num_vertices()) + " vertices, " +
                           with_thousands(mesh.num_faces()) + " faces" +
                           (cut.vertices_split > 0 ? ", " + with_thousands(cut.vertices_split) +
                                                         " non-manifold vertices cut apart"
                                                   : std::string()) +
                           ")");
    table.add("sites", with_thousands(static_cast<std::int64_t>(given)) +
                           (sites_.file().empty() ? " (" + sites_.sampling() + ", seed " + std::to_string(sites_.seed()) + ")"
                                                  : " (" + sites_.file() + ")") +
                           (result.sites_added > 0 ? ", " + with_thousands(result.sites_added) + " added by repair" : ""));
    if (!result.energy.empty()) {
      table.add("lloyd", std::to_string(result.lloyd_iterations) + " iterations, CVT energy " +
                             significant(result.energy.front(), 4) + " -> " + significant(result.energy.back(), 4));
    }
    table.add("output", output_path_ + " (" + with_thousands(result.mesh.num_vertices()) + " vertices, " +
                            with_thousands(result.mesh.num_faces()) + " faces)");
    table.add("topology", "Euler characteristic " + std::to_string(quality.euler_characteristic) + ", " +
                              std::to_string(quality.boundary_loops) + " boundary loops, manifold");
    table.add("quality", "Qmin " + significant(quality.q_min, 3) + ", Qavg " + significant(quality.q_avg, 3) +
                             ", min angle " + significant(quality.theta_min_deg, 3) + " deg, " +
                             significant(quality.pct_angles_lt30, 3) + " % of angles < 30 deg");
    table.add("time", duration(seconds_since(start)) + " (load " + duration(load_seconds) + ", sample " +
                          duration(sample_seconds) + ", geodesics " + duration(result.geodesic_seconds) +
                          ", diagram " + duration(result.diagram_seconds) + ", lloyd steps " +
                          duration(result.lloyd_seconds) + ", dual " + duration(result.dual_seconds) +
                          ", write " + duration(write_seconds) + ")");
    table.add("peak memory", byte_size(static_cast<std::uintmax_t>(peak_memory_bytes())));
    if (!preview_path_.empty()) table.add("preview", preview_path_);
    table.print(std::cout);
    return 0;
  }

 private:
  std::string mesh_path_;
  std::string output_path_;
  SiteSource sites_;
  std::string preview_path_;
  remesh::RemeshOptions options_;
  bool json_ = false;
};

}  // namespace

std::unique_ptr<Command> make_remesh_command() { return std::make_unique<RemeshCommand>(); }

}  // namespace geodual::cli
