// geodual voronoi MESH (--sites N [--sampling S] [--seed S] | --site-file F)
//                       -o OUT.glb [--json] [--preview OUT.png]
// The exact geodesic Voronoi diagram of sites on a mesh.

#include "command.hpp"
#include "geodesic_flags.hpp"
#include "option_checks.hpp"
#include "progress_bar.hpp"
#include "site_source.hpp"
#include "text_table.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <string>

namespace geodual::cli {
namespace {

nlohmann::ordered_json point_json(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

class VoronoiCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command = *app.add_subcommand("voronoi", "The exact geodesic Voronoi diagram of sites on a mesh");
    command.footer(
        "Example:\n  geodual voronoi scan.ply --sites 200 --seed 3 -o cells.glb --preview cells.png\n"
        "The .glb holds the mesh coloured by cell, the cell boundaries (LINES) and the sites (POINTS).");
    command.add_option("MESH", mesh_path_, "Mesh file: .ply, .obj, .off, .stl, .gltf or .glb")->required();
    sites_.add_to(command);
    command.add_option("-o,--output", output_path_, "Write the diagram: .glb or .gltf")->required();
    command.add_option("--preview", preview_path_, "Also render a picture of the diagram: .png");
    command
        .add_option("--boundary-tolerance,--tolerance", options_.boundary_tolerance,
                    "Largest distance between a traced boundary and the exact one, as a fraction of the "
                    "bounding-box diagonal (--tolerance: the old name, kept for one release)")
        ->capture_default_str()
        ->check(finite_positive());
    geodesic_.add_to(command);
    command.add_flag("--json", json_, "Print cells, Voronoi vertices and timings as one JSON object");
    command.add_flag("-q,--quiet", quiet_, "No progress line on the terminal");
    return command;
  }

  int run() override {
    sites_.validate("voronoi");
    io::require_output_path(output_path_, {".glb", ".gltf"}, "a Voronoi diagram");
    io::refuse_to_overwrite_inputs(output_path_, {mesh_path_, sites_.file()});
    if (!preview_path_.empty()) {
      io::require_output_path(preview_path_, {".png"}, "a preview");
      io::refuse_to_overwrite_inputs(preview_path_, {mesh_path_, sites_.file()});
    }
    const auto start = std::chrono::steady_clock::now();
    const io::LoadedMesh loaded = io::read_mesh(mesh_path_);
    require_computable_range(loaded.mesh, mesh_path_);
    const TriangleMesh& mesh = loaded.mesh;
    const double load_seconds = seconds_since(start);
    const auto sample_start = std::chrono::steady_clock::now();
    const std::vector<SurfacePoint> sites = sites_.sites(mesh);
    const double sample_seconds = seconds_since(sample_start);
    ProgressBar bar(quiet_);
    voronoi::VoronoiOptions options = options_;
    geodesic_.apply(options.geodesic);
    options.geodesic.progress = [&](double fraction) { return bar.update("geodesics", fraction); };
    const voronoi::VoronoiDiagram diagram = voronoi::compute_voronoi(mesh, sites, options);
    bar.finish();
    const auto write_start = std::chrono::steady_clock::now();
    // The picture first: it is the part Ctrl-C can stop, and then nothing is written.
    if (!preview_path_.empty()) write_voronoi_preview(preview_path_, mesh, diagram, still_wanted);
    write_voronoi_diagram(output_path_, mesh, diagram);
    const double write_seconds = seconds_since(write_start);
    double boundary_length = 0;
    for (const voronoi::VoronoiArc& arc : diagram.arcs) boundary_length += arc.length;
    const voronoi::VoronoiStats& s = diagram.stats;

    if (json_) {
      nlohmann::ordered_json json;
      json["mesh"] = mesh_path_;
      json["output"] = output_path_;
      json["sites"] = sites.size();
      json["voronoi_vertex_count"] = diagram.vertices.size();
      json["arc_count"] = diagram.arcs.size();
      json["total_boundary_length"] = boundary_length;
      json["boundary_faces"] = s.boundary_faces;
      json["refined_faces"] = s.refined_faces;
      json["unresolved_regions"] = s.unresolved_regions;
      json["max_vertex_residual"] = s.max_vertex_residual;
      json["load_s"] = load_seconds;
      json["sample_s"] = sample_seconds;
      json["geodesic_s"] = s.geodesic_seconds;
      json["diagram_s"] = s.extraction_seconds;
      json["write_s"] = write_seconds;
      json["time_s"] = seconds_since(start);
      json["peak_memory_bytes"] = peak_memory_bytes();
      nlohmann::ordered_json cells = nlohmann::ordered_json::array();
      for (std::size_t i = 0; i < sites.size(); ++i) {
        nlohmann::ordered_json cell;
        cell["site"] = i;
        cell["position"] = point_json(sites[i].position(mesh));
        cell["area"] = diagram.cell_area[i];
        cells.push_back(std::move(cell));
      }
      for (const voronoi::CellAdjacency& pair : diagram.adjacency) {
        cells[static_cast<std::size_t>(pair.site_a)]["neighbours"].push_back(pair.site_b);
        cells[static_cast<std::size_t>(pair.site_b)]["neighbours"].push_back(pair.site_a);
      }
      json["cells"] = std::move(cells);
      nlohmann::ordered_json vertices = nlohmann::ordered_json::array();
      for (const voronoi::VoronoiVertex& vertex : diagram.vertices) {
        nlohmann::ordered_json v;
        v["position"] = point_json(vertex.position);
        v["face"] = vertex.location.element;
        v["barycentric"] = {vertex.location.barycentric[0], vertex.location.barycentric[1],
                            vertex.location.barycentric[2]};
        v["distance"] = vertex.distance;
        const auto around = diagram.sites_of(vertex);
        v["sites"] = std::vector<Index>(around.begin(), around.end());
        vertices.push_back(std::move(v));
      }
      json["voronoi_vertices"] = std::move(vertices);
      std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
      return 0;
    }
    KeyValueTable table;
    table.add("mesh", mesh_path_ + " (" + with_thousands(mesh.num_vertices()) + " vertices, " +
                          with_thousands(mesh.num_faces()) + " faces)");
    table.add("sites",
              with_thousands(static_cast<std::int64_t>(sites.size())) +
                  (sites_.file().empty() ? " (" + sites_.sampling() + ", seed " + std::to_string(sites_.seed()) + ")"
                                         : " (" + sites_.file() + ")"));
    table.add("voronoi vertices", with_thousands(static_cast<std::int64_t>(diagram.vertices.size())));
    table.add("boundary arcs", with_thousands(static_cast<std::int64_t>(diagram.arcs.size())) + ", total length " +
                                   significant(boundary_length));
    table.add("boundary faces",
              with_thousands(s.boundary_faces) + " (" + with_thousands(s.refined_faces) + " refined)");
    table.add("time", duration(seconds_since(start)) + " (load " + duration(load_seconds) + ", sample " +
                          duration(sample_seconds) + ", geodesics " + duration(s.geodesic_seconds) + ", diagram " +
                          duration(s.extraction_seconds) + ", write " + duration(write_seconds) + ")");
    table.add("peak memory", byte_size(static_cast<std::uintmax_t>(peak_memory_bytes())));
    table.add("output", output_path_);
    if (!preview_path_.empty()) table.add("preview", preview_path_);
    table.print(std::cout);
    return 0;
  }

 private:
  std::string mesh_path_;
  SiteSource sites_{"random"};  // a diagram of independent sites, as the benchmarks draw them
  std::string output_path_;
  std::string preview_path_;
  voronoi::VoronoiOptions options_;
  GeodesicFlags geodesic_;
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

std::unique_ptr<Command> make_voronoi_command() { return std::make_unique<VoronoiCommand>(); }

}  // namespace geodual::cli
