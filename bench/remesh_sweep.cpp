// remesh_sweep: robustness sweep. Remeshes every mesh of the repository's data
// and every generated hard case (bench/hard_cases.hpp) at several site counts
// with the pipeline's default options, each run in a forked child (a crash or
// a signal is reported, not fatal), and prints one table.
//
//   build/bench/remesh_sweep [--sites 500,2000,20000] [--only NAME,...] [--time-limit S]
//                            [--lloyd K] [--sharp-angle DEG] [--continuation-angle DEG] [--samples N]
//                            [--repo DIR] [--list] [MESH...]
//
//   --sites A,B,...   site counts (default 500,2000,20000)
//   --only NAME,...   run only these meshes (names as --list prints them)
//   --time-limit S    wall-clock limit of one run in seconds (default 600)
//   --lloyd K         Lloyd iterations (default: the pipeline's)
//   --sharp-angle DEG the features kept (FeatureSamplingOptions::sharp_angle; default: the pipeline's, 0: none)
//   --continuation-angle DEG  their continuation (FeatureSamplingOptions::continuation_angle; default: the pipeline's)
//   --samples N       statistics samples per side (default 100000)
//   --repo DIR        repository root holding tests/data and examples/data (default .)
//   --list            print the mesh names (and the generated ones' faces and topology) and exit
//   MESH...           extra mesh files, named by their file name
//
// Meshes: tests/data/*.ply, examples/data/bunny.ply (skipped when it is the
// same file as tests/data/bunny.ply), the hard cases, then MESH....
// Columns: result (ok, the signal, or the error's first 60 characters; the
// full messages follow the table), wall time of the child, its peak memory,
// Qmin, Qavg, two-sided Hausdorff in % of the input's bounding-box diagonal;
// connected pieces, Euler characteristic and boundary loops of the surface
// remeshed (the input cut to a manifold, less its disabled scrap faces) and
// of the remesh ("a->b" where they differ); topology kept (every piece's χ
// and loop count equal, the remesh's piece found through its sites); and the
// area dropped (faces the manifold cut disabled, in % of the input's area);
// the sharp chains kept, or "dropped" where the weld along them failed and
// the remesh is the one without them.

#include "bench_support.hpp"
#include "hard_cases.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace geodual::bench {
namespace {

struct Options {
  std::vector<std::int64_t> site_counts = {500, 2000, 20000};
  std::vector<std::string> only;
  unsigned time_limit_seconds = 600;
  std::optional<int> lloyd;
  std::optional<double> sharp_angle;
  std::optional<double> continuation_angle;
  std::int64_t samples = 100000;
  std::filesystem::path repo = ".";
  bool list = false;
  std::vector<std::filesystem::path> extra_meshes;
};

/// One input of the sweep: a file or a generated hard case.
struct SweepMesh {
  std::string name;
  std::filesystem::path path;              ///< empty for a hard case
  std::function<TriangleMesh()> generate;  ///< hard cases only
};

/// Topology of a mesh: the total Euler characteristic and boundary loops,
/// and the same per component of the surface remeshed.
struct Topology {
  std::int64_t euler_characteristic = 0;
  std::int64_t boundary_loops = 0;
  std::int64_t components = 0;
};

/// What one successful run measured (trivially copyable: sent from the child).
struct RunFigures {
  std::int64_t input_faces = 0;
  std::int64_t remesh_vertices = 0;
  std::int64_t sites_added = 0;
  std::int64_t peak_rss = 0;
  double q_min = 0, q_avg = 0, hausdorff_pct = 0;
  Topology surface, remesh;
  std::int64_t components_differing = 0;  ///< components of the surface whose χ or loops the remesh changed
  std::int64_t dropped_faces = 0;
  double dropped_area_pct = 0;
  std::int64_t creases = 0;      ///< sharp chains kept in the remesh
  bool creases_dropped = false;  ///< the weld failed: the remesh without them
  /// The weld failed at places: the remesh without the creases near them.
  std::int64_t creases_dropped_near = 0;
};

Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--sites") {
      options.site_counts = parse_integer_list(arg, value(), 1, 100'000'000);
    } else if (arg == "--only") {
      const std::string names = value();
      for (const std::string_view name : split_commas(names)) options.only.emplace_back(name);
    } else if (arg == "--time-limit") {
      options.time_limit_seconds = static_cast<unsigned>(parse_integer(arg, value(), 1, 1'000'000));
    } else if (arg == "--lloyd") {
      options.lloyd = static_cast<int>(parse_integer(arg, value(), 0, 10'000));
    } else if (arg == "--sharp-angle") {
      options.sharp_angle = parse_number(arg, value());
      if (!(*options.sharp_angle >= 0 && *options.sharp_angle <= 180))
        throw UsageError(arg + " takes 0 to 180 degrees");
    } else if (arg == "--continuation-angle") {
      options.continuation_angle = parse_number(arg, value());
      if (!(*options.continuation_angle >= 0 && *options.continuation_angle <= 180))
        throw UsageError(arg + " takes 0 to 180 degrees");
    } else if (arg == "--samples") {
      options.samples = parse_integer(arg, value(), 0, quality::max_samples_per_side);
    } else if (arg == "--repo") {
      options.repo = value();
    } else if (arg == "--list") {
      options.list = true;
    } else if (arg == "--help" || arg == "-h") {
      std::cout << "usage: remesh_sweep [--sites 500,2000,20000] [--only NAME,...] [--time-limit S] [--lloyd K]"
                   " [--sharp-angle DEG] [--continuation-angle DEG] [--samples N] [--repo DIR] [--list] [MESH...]\n";
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      options.extra_meshes.emplace_back(arg);
    }
  }
  return options;
}

bool same_file_contents(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  if (std::filesystem::file_size(a, error) != std::filesystem::file_size(b, error) || error) return false;
  std::ifstream in_a(a, std::ios::binary), in_b(b, std::ios::binary);
  return std::equal(std::istreambuf_iterator<char>(in_a), std::istreambuf_iterator<char>(),
                    std::istreambuf_iterator<char>(in_b), std::istreambuf_iterator<char>());
}

/// Every mesh of the sweep in order; `only` filters by name (unknown names are an error).
std::vector<SweepMesh> sweep_meshes(const Options& options) {
  std::vector<SweepMesh> meshes;
  const std::filesystem::path data = options.repo / "tests" / "data";
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(data, error)) {
    if (entry.path().extension() == ".ply") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) meshes.push_back({file.stem().string(), file, {}});
  const std::filesystem::path example = options.repo / "examples" / "data" / "bunny.ply";
  if (std::filesystem::exists(example) && !same_file_contents(example, data / "bunny.ply")) {
    meshes.push_back({"examples/bunny", example, {}});
  }
  for (const HardCase& hard_case : hard_cases()) meshes.push_back({hard_case.name, {}, hard_case.build});
  for (const auto& file : options.extra_meshes) meshes.push_back({file.filename().string(), file, {}});

  if (options.only.empty()) return meshes;
  std::vector<SweepMesh> chosen;
  for (const std::string& name : options.only) {
    const auto it = std::find_if(meshes.begin(), meshes.end(), [&](const SweepMesh& m) { return m.name == name; });
    if (it == meshes.end()) throw UsageError("--only: no mesh named '" + name + "' (see --list)");
    chosen.push_back(*it);
  }
  return chosen;
}

/// The faces of `mesh` given by `faces` (all vertices kept: analyze_mesh counts referenced ones only).
TriangleMesh with_faces(const TriangleMesh& mesh, const std::vector<Index>& faces) {
  TriangleMesh part;
  part.vertices = mesh.vertices;
  part.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    part.faces.row(static_cast<Eigen::Index>(i)) = mesh.faces.row(faces[i]);
  return part;
}

Topology topology_of(const TriangleMesh& mesh) {
  if (mesh.num_faces() == 0) return {};
  const MeshReport report = analyze_mesh(mesh);
  return {report.euler_characteristic, report.boundary_loops, report.components};
}

/// Compares the surface remeshed with the remesh, in total and per component:
/// `site_component[i]` is the surface component of remesh vertex i.
void compare_topology(const TriangleMesh& surface, const TriangleMesh& remesh,
                      const std::vector<Index>& surface_component, Index components,
                      const std::vector<Index>& site_component, RunFigures& figures) {
  std::vector<std::vector<Index>> surface_faces(static_cast<std::size_t>(components));
  std::vector<std::vector<Index>> remesh_faces(static_cast<std::size_t>(components));
  std::vector<Index> all_surface_faces;
  for (Index f = 0; f < surface.num_faces(); ++f) {
    if (!is_proper_face(surface, f)) continue;
    all_surface_faces.push_back(f);
    surface_faces[static_cast<std::size_t>(surface_component[static_cast<std::size_t>(surface.faces(f, 0))])].push_back(
        f);
  }
  std::int64_t unplaced = 0;  // remesh faces whose first corner lies on no component
  for (Index f = 0; f < remesh.num_faces(); ++f) {
    const Index component = site_component[static_cast<std::size_t>(remesh.faces(f, 0))];
    if (component < 0) {
      ++unplaced;
      continue;
    }
    remesh_faces[static_cast<std::size_t>(component)].push_back(f);
  }
  figures.surface = topology_of(with_faces(surface, all_surface_faces));
  figures.remesh = topology_of(remesh);
  figures.components_differing = unplaced > 0 ? 1 : 0;
  for (std::size_t c = 0; c < surface_faces.size(); ++c) {
    const Topology before = topology_of(with_faces(surface, surface_faces[c]));
    const Topology after = topology_of(with_faces(remesh, remesh_faces[c]));
    if (before.euler_characteristic != after.euler_characteristic || before.boundary_loops != after.boundary_loops ||
        after.components != 1) {
      ++figures.components_differing;
    }
  }
}

/// Everything the sweep reads from a pipeline result, in one place.
RunFigures figures_of(const pipeline::RemeshPipelineResult& result) {
  const TriangleMesh& input = result.input.mesh;
  const TriangleMesh& surface = result.surface.mesh;  // same faces as the input, vertices split
  const TriangleMesh& remesh = result.remesh.mesh;    // vertex i is result.remesh.sites[i] unless welded
  RunFigures figures;
  figures.input_faces = input.num_faces();
  figures.remesh_vertices = remesh.num_vertices();
  figures.sites_added = result.remesh.sites_added;
  if (result.statistics) {
    figures.q_min = result.statistics->candidate.q_min;
    figures.q_avg = result.statistics->candidate.q_avg;
    figures.hausdorff_pct = result.statistics->hausdorff_pct;
  }

  figures.creases = result.features_dropped_reason.empty() ? result.features.sharp_chains : 0;
  figures.creases_dropped = !result.features_dropped_reason.empty();
  figures.creases_dropped_near = static_cast<std::int64_t>(result.features_dropped_near.size());
  figures.dropped_faces = result.dropped.faces;
  figures.dropped_area_pct = result.dropped.area_pct;

  const MeshTopology surface_topology = build_mesh_topology(surface);
  const std::vector<Index>& surface_component = surface_topology.vertex_component;
  const Index components = surface_topology.num_components();
  // Per remesh vertex, the surface component of its site. Sites at vertices
  // of the surface cut along its features name that cut's vertices.
  const std::vector<Index>& cut_vertex = result.feature_cut.original_vertex;
  const std::vector<Index>& vertex_of_site = result.remesh.vertex_of_site;
  std::vector<Index> vertex_component(static_cast<std::size_t>(remesh.num_vertices()), -1);
  for (std::size_t s = 0; s < result.remesh.sites.size(); ++s) {
    const SurfacePoint& site = result.remesh.sites[s];
    const bool at_vertex = site.kind == SurfacePoint::Kind::vertex;
    const Index elements = at_vertex
                               ? (cut_vertex.empty() ? surface.num_vertices() : static_cast<Index>(cut_vertex.size()))
                               : surface.num_faces();
    if (site.element < 0 || site.element >= elements) continue;
    const Index vertex = at_vertex
                             ? (cut_vertex.empty() ? site.element : cut_vertex[static_cast<std::size_t>(site.element)])
                             : surface.faces(site.element, 0);
    const std::size_t v = vertex_of_site.empty() ? s : static_cast<std::size_t>(vertex_of_site[s]);
    vertex_component[v] = surface_component[static_cast<std::size_t>(vertex)];
  }
  compare_topology(surface, remesh, surface_component, components, vertex_component, figures);
  return figures;
}

/// The run's figures, and why its creases were dropped, all or near places (empty: none was).
struct RunOutcome {
  RunFigures figures;
  std::string creases_dropped_reason;
};

RunOutcome remesh_once(const SweepMesh& mesh, std::int64_t sites, const Options& options) {
  reset_peak_rss();
  io::LoadedMesh loaded;
  if (mesh.generate) {
    loaded.mesh = mesh.generate();
  } else {
    loaded = io::read_mesh(mesh.path);
  }
  pipeline::RemeshPipelineOptions pipeline_options;
  pipeline_options.sites = sites;
  pipeline_options.quality.samples_per_side = options.samples;
  if (options.lloyd) pipeline_options.remesh.lloyd.iterations = *options.lloyd;
  if (options.sharp_angle) pipeline_options.features.sampling.sharp_angle = *options.sharp_angle;
  if (options.continuation_angle) pipeline_options.features.sampling.continuation_angle = *options.continuation_angle;
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(std::move(loaded), pipeline_options);
  RunFigures figures = figures_of(result);
  figures.peak_rss = peak_rss_bytes().value_or(0);
  return {figures, result.features_dropped_reason.empty() ? result.features_partly_dropped_reason
                                                          : result.features_dropped_reason};
}

std::string first_characters(const std::string& text, std::size_t count) {
  std::string line = text.substr(0, text.find('\n'));
  if (line.size() <= count) return line;
  return line.substr(0, count - 3) + "...";
}

std::string arrow(std::int64_t before, std::int64_t after) {
  return before == after ? std::to_string(before) : std::to_string(before) + "->" + std::to_string(after);
}

int run_sweep(const Options& options) {
  const std::vector<SweepMesh> meshes = sweep_meshes(options);
  if (options.list) {
    // Names, and what the generated cases are made of (analyze_mesh's figures).
    TextTable list({{"mesh", TextTable::Align::left},
                    {"file", TextTable::Align::left},
                    {"faces"},
                    {"components"},
                    {"loops"},
                    {"chi"},
                    {"nm edges"},
                    {"nm vertices"},
                    {"duplicates"}});
    for (const SweepMesh& mesh : meshes) {
      if (!mesh.generate) {
        list.add_row({mesh.name, mesh.path.string()});
        continue;
      }
      const MeshReport report = analyze_mesh(mesh.generate());
      list.add_row({mesh.name, "(generated)", grouped(report.faces), grouped(report.components),
                    grouped(report.boundary_loops), grouped(report.euler_characteristic),
                    grouped(report.nonmanifold_edges), grouped(report.nonmanifold_vertices),
                    grouped(report.duplicate_faces)});
    }
    list.print(std::cout);
    return 0;
  }
  if (meshes.empty()) throw UsageError("no meshes (run from the repository root or give --repo)");

  TextTable table({{"mesh", TextTable::Align::left},
                   {"faces"},
                   {"sites"},
                   {"added"},
                   {"result", TextTable::Align::left},
                   {"time s"},
                   {"peak MiB"},
                   {"Qmin"},
                   {"Qavg"},
                   {"H %"},
                   {"pieces"},
                   {"chi"},
                   {"loops"},
                   {"topology", TextTable::Align::left},
                   {"dropped %"},
                   {"creases"}});
  std::vector<std::string> failures, creases_dropped;
  std::cout << "machine: " << cpu_model() << ", load " << load_average() << "\n\n";
  for (const SweepMesh& mesh : meshes) {
    for (const std::int64_t sites : options.site_counts) {
      std::cerr << "remesh_sweep: " << mesh.name << " at " << sites << " sites\n";
      ChildLimits limits;
      limits.time_limit_seconds = options.time_limit_seconds;
      const auto start = Clock::now();
      const ChildOutcome outcome = run_in_child(limits, [&] {
        const RunOutcome run = remesh_once(mesh, sites, options);
        ByteWriter out;
        out.put(run.figures);
        out.put_string(run.creases_dropped_reason);
        return out.bytes();
      });
      const std::string seconds = fixed(seconds_since(start), 1);
      if (outcome.status != ChildOutcome::Status::ok) {
        failures.push_back(mesh.name + " at " + std::to_string(sites) + " sites: " + outcome.message);
        table.add_row({mesh.name, "-", grouped(sites), "-", first_characters(outcome.message, 60), seconds,
                       mebibytes(outcome.child_max_rss_bytes), "-", "-", "-", "-", "-", "-", "-", "-", "-"});
        continue;
      }
      ByteReader in(outcome.payload);
      const auto r = in.get<RunFigures>();
      if (r.creases_dropped || r.creases_dropped_near > 0) {
        creases_dropped.push_back(mesh.name + " at " + std::to_string(sites) + " sites" +
                                  (r.creases_dropped ? ""
                                                     : ", near " + std::to_string(r.creases_dropped_near) +
                                                           (r.creases_dropped_near == 1 ? " place" : " places")) +
                                  ": " + in.get_string());
      }
      std::string topology = "yes";
      if (r.components_differing > 0) {
        topology =
            "no (" + std::to_string(r.components_differing) + " of " + std::to_string(r.surface.components) + ")";
      }
      table.add_row(
          {mesh.name, grouped(r.input_faces), grouped(sites), grouped(r.sites_added), "ok", seconds,
           mebibytes(r.peak_rss), fixed(r.q_min, 3), fixed(r.q_avg, 3), fixed(r.hausdorff_pct, 3),
           arrow(r.surface.components, r.remesh.components),
           arrow(r.surface.euler_characteristic, r.remesh.euler_characteristic),
           arrow(r.surface.boundary_loops, r.remesh.boundary_loops), topology,
           fixed(r.dropped_area_pct, 2) + (r.dropped_faces > 0 ? " (" + grouped(r.dropped_faces) + " f)" : ""),
           r.creases_dropped            ? "dropped"
           : r.creases_dropped_near > 0 ? grouped(r.creases) + " (" + grouped(r.creases_dropped_near) + " out)"
                                        : grouped(r.creases)});
    }
  }
  table.print(std::cout);
  if (!failures.empty()) {
    std::cout << "\nfailures:\n";
    for (const std::string& failure : failures) std::cout << "- " << failure << '\n';
  }
  if (!creases_dropped.empty()) {
    std::cout << "\ncreases dropped:\n";
    for (const std::string& why : creases_dropped) std::cout << "- " << why << '\n';
  }
  return 0;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  using namespace geodual::bench;
  return run_main("remesh_sweep", [&] { return run_sweep(parse_options(argc, argv)); });
}
