// remesh_bench: the whole remesh, stage by stage, with the peak memory of
// each run (one forked child per run, so runs do not share memory).
//
//   build/bench/remesh_bench [--sites 2000,4000] [--lloyd K] [--subdivided 1,2] [--subdivided-cache D]
//                            [--time-limit S] MESH...
//
// Stages: load (read the file), sample (random sites by area, on boundaries
// too), geodesics (window-VTP + RWR), diagram (Voronoi extraction), dual
// (dual Delaunay and its checks; repair rounds repeat geodesics, diagram and
// dual and are included in their columns; with --lloyd K, so are the K
// Lloyd iterations' diagrams), write (a .glb in a temporary
// folder).

#include "bench_support.hpp"
#include "subdivided_inputs.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace geodual::bench {
namespace {

struct Options {
  std::vector<std::int64_t> site_counts = {2000, 4000};
  int lloyd = 0;  ///< Lloyd iterations before the dual
  std::vector<int> subdivided_levels;
  std::filesystem::path subdivided_input = "examples/data/bunny.ply";
  std::filesystem::path cache;
  unsigned time_limit_seconds = 600;
  std::vector<std::filesystem::path> meshes;
};

struct Run {
  std::int64_t faces = 0, sites = 0, sites_added = 0, vertices_out = 0;
  double load = 0, sample = 0, geodesics = 0, diagram = 0, dual = 0, write = 0, total = 0;
  std::int64_t peak_rss = 0;
};

Options parse_options(int argc, char** argv) {
  Options options;
  options.cache = std::filesystem::path(argv[0]).parent_path() / "subdivided";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--sites") {
      options.site_counts = parse_integer_list(arg, value(), 4, 100'000'000);
    } else if (arg == "--subdivided") {
      for (const std::int64_t level : parse_integer_list(arg, value(), 1, 2)) {
        options.subdivided_levels.push_back(static_cast<int>(level));
      }
    } else if (arg == "--subdivided-cache") {
      options.cache = value();
    } else if (arg == "--lloyd") {
      options.lloyd = static_cast<int>(parse_integer(arg, value(), 0, 10'000));
    } else if (arg == "--time-limit") {
      options.time_limit_seconds = static_cast<unsigned>(parse_integer(arg, value(), 1, 1'000'000));
    } else if (arg == "--help" || arg == "-h") {
      std::cout << "usage: remesh_bench [--sites 2000,4000] [--lloyd K] [--subdivided 1,2] [--subdivided-cache D]"
                   " [--time-limit S] MESH...\n";
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      options.meshes.emplace_back(arg);
    }
  }
  if (options.meshes.empty() && options.subdivided_levels.empty()) throw UsageError("give at least one mesh");
  return options;
}

Run remesh_once(const std::filesystem::path& mesh_path, std::int64_t sites, int lloyd,
                const std::filesystem::path& output) {
  Run run;
  const auto start = Clock::now();
  const io::LoadedMesh loaded = io::read_mesh(mesh_path);
  run.load = seconds_since(start);
  run.faces = loaded.mesh.num_faces();
  auto stage = Clock::now();
  std::vector<SurfacePoint> points = remesh::sample_sites(loaded.mesh, sites);
  run.sample = seconds_since(stage);
  run.sites = sites;
  remesh::RemeshOptions remesh_options;
  remesh_options.lloyd.iterations = lloyd;
  const remesh::RemeshResult result = remesh::remesh_from_sites(loaded.mesh, std::move(points), remesh_options);
  run.geodesics = result.relaxation.geodesic_seconds + result.dual.geodesic_seconds;
  run.diagram = result.relaxation.diagram_seconds + result.dual.diagram_seconds;
  run.dual = result.dual.dual_seconds;
  run.sites_added = result.dual.sites_added;
  run.vertices_out = result.dual.mesh.num_vertices();
  stage = Clock::now();
  write_remesh(output, result.dual.mesh);
  run.write = seconds_since(stage);
  run.total = seconds_since(start);
  run.peak_rss = peak_rss_bytes().value_or(0);
  return run;
}

int run_benchmark(const Options& options) {
  std::vector<std::filesystem::path> meshes = options.meshes;
  for (const int level : options.subdivided_levels) {
    std::cerr << "remesh_bench: preparing " << options.subdivided_input.stem().string() << " subdivided " << level
              << "x (cached in " << options.cache.string() << ")\n";
    meshes.push_back(ensure_subdivided(options.subdivided_input, level, options.cache));
  }
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("remesh_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(scratch);

  TextTable table({{"mesh", TextTable::Align::left},
                   {"faces"},
                   {"sites"},
                   {"added"},
                   {"load s"},
                   {"sample s"},
                   {"geodesics s"},
                   {"diagram s"},
                   {"dual s"},
                   {"write s"},
                   {"total s"},
                   {"peak RSS MiB"}});
  std::cout << "machine: " << cpu_model() << ", load " << load_average() << "\n\n";
  for (const auto& mesh : meshes) {
    for (const std::int64_t sites : options.site_counts) {
      ChildLimits limits;
      limits.time_limit_seconds = options.time_limit_seconds;
      const ChildOutcome outcome = run_in_child(limits, [&] {
        const Run r = remesh_once(mesh, sites, options.lloyd, scratch / "out.glb");
        ByteWriter out;
        out.put(r);
        return out.bytes();
      });
      const std::string name = mesh.filename().string();
      if (outcome.status != ChildOutcome::Status::ok) {
        table.add_row({name, "-", grouped(sites), "-", "-", "-", "-", "-", "-", "-", outcome.message,
                       mebibytes(outcome.child_max_rss_bytes)});
        continue;
      }
      ByteReader in(outcome.payload);
      const Run r = in.get<Run>();
      table.add_row({name, grouped(r.faces), grouped(r.sites), grouped(r.sites_added), fixed(r.load, 2),
                     fixed(r.sample, 2), fixed(r.geodesics, 2), fixed(r.diagram, 2), fixed(r.dual, 2),
                     fixed(r.write, 2), fixed(r.total, 2), mebibytes(r.peak_rss)});
      std::cerr << "remesh_bench: " << name << " " << sites << " sites: " << fixed(r.total, 2) << " s\n";
    }
  }
  table.print(std::cout);
  std::filesystem::remove_all(scratch);
  return 0;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "remesh_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
