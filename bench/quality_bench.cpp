// quality_bench: geodual's remesh side by side with CGAL's isotropic
// remeshing at the same vertex count, with the quality figures of
// shared/DESIGN.md for all of them (issue 5, deliverable 4).
//
//   build/bench/quality_bench [--sites 5000,20000] [--lloyd K] [--lloyd-tol T] [--warm-start W]
//                             [--plain-lloyd] [--adapt S] [--no-cgal]
//                             [--cgal-iterations N] [--cgal-border keep|protect]
//                             [--tolerance PCT] [--max-runs R] [--samples S]
//                             [--time-limit S] [MESH...]
//
// Default meshes: tests/data/{bunny,armadillo_86k,fertility}.ply
// (run from the repository root). For each mesh (read once, by the parent
// process) and each site count n, every run below is a forked child, so its
// peak RSS is its own (plus the input the parent had already read):
//
//   geodual        geodual::pipeline::run_remesh_pipeline, n sites sampled as
//                  the pipeline does by default (blue noise, seed 1), no Lloyd
//                  relaxation.
//   geodual+Lloyd  the same sites, K Lloyd iterations with the default
//                  (Newton-accelerated) steps (default 10; fewer when the
//                  energy stalls below --lloyd-tol), after at most W
//                  warm-start steps on the restricted Voronoi diagram
//                  (default: LloydOptions' default; 0: none).
//   geodual+plain  with --plain-lloyd: the same, plain (over-relaxed) Lloyd
//                  steps.
//   geodual+adapt  with --adapt S: the Lloyd row's run with curvature-adapted
//                  sizing (RemeshOptions::curvature_adaptation = S, a
//                  weighted CVT; see remesh/curvature_density.hpp).
//   CGAL           (not with --no-cgal) CGAL::Polygon_mesh_processing::isotropic_remeshing of a
//                  Surface_mesh built from the input, number_of_iterations N
//                  (default 3), with a target edge length L searched so that
//                  its vertex count is within --tolerance % (default 3) of the
//                  geodual+Lloyd row's (of the geodual row if that failed).
//
// The search for L: EdgeLengthSearch (cgal_remeshing.hpp), at most
// --max-runs runs; if none lands within the tolerance, the closest L is run
// once more and reported with its miss.
//
// Borders: "keep" (the default) leaves CGAL's own handling: border edges are
// constrained, so they are split and collapsed along the border but never
// flipped, and their vertices are not smoothed; the holes stay. "protect"
// follows CGAL's isotropic_remeshing example: border edges are first split to
// at most L (split_long_edges), then protect_constraints keeps them as they
// are (the input's own border vertices stay).
//
// Timing: wall and CPU seconds of the remesh itself (for geodual: sampling,
// Lloyd and the dual, from the mesh in memory; for CGAL: building the
// Surface_mesh, remeshing, and reading it back), not of the statistics. Peak
// RSS is measured before the statistics too.
//
// Quality: geodual::quality::compare_meshes(input, output) for every row
// (10^6 area-uniform samples per side plus all vertices for the distances;
// --samples changes it). Hausdorff and RMS are in % of the input's bounding
// box diagonal.
//
// CGAL needs a valid polygon mesh: faces with a repeated vertex index are
// left out, unreferenced vertices are dropped, and an input whose faces
// cannot all be added (non-manifold edges or vertices, inconsistent
// orientation) is reported as such in the CGAL row.

#include "bench_support.hpp"
#include "cgal_remeshing.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace geodual::bench {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

enum class BorderMode { keep, protect };

struct Options {
  std::vector<std::int64_t> site_counts = {5000, 20000};
  int lloyd = 10;
  double lloyd_tolerance = remesh::LloydOptions{}.tolerance;
  int warm_start = remesh::LloydOptions{}.warm_start_iterations;
  bool plain_lloyd = false;  ///< also a row with plain Lloyd steps
  double adapt = 0;          ///< > 0: also a row with curvature-adapted sizing of this strength
  bool cgal = true;          ///< the CGAL row
  unsigned cgal_iterations = 3;
  BorderMode border = BorderMode::keep;
  double tolerance_pct = 3.0;
  int max_runs = 8;
  std::int64_t samples = quality::QualityOptions{}.samples_per_side;
  unsigned time_limit_seconds = 1800;
  std::vector<std::filesystem::path> meshes;
};

/// The figures of one row, sent back from a child (trivially copyable).
struct Figures {
  std::int64_t vertices = 0, faces = 0, euler_characteristic = 0, boundary_loops = 0, nonmanifold_edges = 0;
  double q_min = 0, q_avg = 0, theta_min_deg = 0, theta_min_avg_deg = 0, pct_angles_lt30 = 0, p30 = 0;
  double pct_valence6 = std::numeric_limits<double>::quiet_NaN();
  double hausdorff_pct = std::numeric_limits<double>::quiet_NaN();
  double rms_pct = std::numeric_limits<double>::quiet_NaN();
};

/// What one run reports: the method's vertex count, cost, and (when asked
/// for) the quality of its output and of the input.
struct RunResult {
  std::int64_t vertices = 0;  ///< of the output
  double seconds = 0, cpu_seconds = 0;
  std::int64_t peak_rss = 0;
  std::int64_t sites_added = 0;
  int lloyd_iterations = 0;
  int warm_start_iterations = 0;
  bool has_figures = false;
  Figures output;
  Figures input;  ///< the reference side of compare_meshes, distances NaN
};

Figures figures_of(const quality::TriangleQuality& q) {
  Figures f;
  f.vertices = q.vertices;
  f.faces = q.faces;
  f.euler_characteristic = q.euler_characteristic;
  f.boundary_loops = q.boundary_loops;
  f.nonmanifold_edges = q.nonmanifold_edges;
  f.q_min = q.q_min;
  f.q_avg = q.q_avg;
  f.theta_min_deg = q.theta_min_deg;
  f.theta_min_avg_deg = q.theta_min_avg_deg;
  f.pct_angles_lt30 = q.pct_angles_lt30;
  f.p30 = q.p30;
  if (q.pct_valence6) f.pct_valence6 = *q.pct_valence6;
  return f;
}

void add_figures(RunResult& run, const TriangleMesh& input, const TriangleMesh& output, const Options& options) {
  quality::QualityOptions quality;
  quality.samples_per_side = options.samples;
  const quality::QualityReport report = quality::compare_meshes(input, output, quality);
  run.output = figures_of(report.candidate);
  run.output.hausdorff_pct = report.hausdorff_pct;
  run.output.rms_pct = report.rms_pct;
  run.input = figures_of(report.reference);
  run.has_figures = true;
}

std::vector<std::byte> to_bytes(const RunResult& run) {
  ByteWriter out;
  out.put(run);
  return out.bytes();
}

RunResult from_bytes(const std::vector<std::byte>& bytes) {
  ByteReader in(bytes);
  return in.get<RunResult>();
}

// ---------------------------------------------------------------------------
// geodual

RunResult run_geodual(const io::LoadedMesh& input, std::int64_t sites, int lloyd, bool newton, double adapt,
                      const Options& options) {
  pipeline::RemeshPipelineOptions pipeline_options;
  pipeline_options.sites = sites;
  pipeline_options.remesh.lloyd.iterations = lloyd;
  pipeline_options.remesh.lloyd.newton = newton;
  pipeline_options.remesh.curvature_adaptation = adapt;
  pipeline_options.remesh.lloyd.tolerance = options.lloyd_tolerance;
  pipeline_options.remesh.lloyd.warm_start_iterations = options.warm_start;
  pipeline_options.statistics = false;  // measured below, the same way for every row
  RunResult run;
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  const pipeline::RemeshPipelineResult result = pipeline::run_remesh_pipeline(input, pipeline_options);
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = result.remesh.mesh.num_vertices();
  run.sites_added = result.remesh.sites_added;
  run.lloyd_iterations = result.relaxation.iterations;
  run.warm_start_iterations = result.relaxation.warm_start_iterations;
  add_figures(run, input.mesh, result.remesh.mesh, options);
  return run;
}

// ---------------------------------------------------------------------------
// CGAL

/// One CGAL remesh with target edge length `length`; figures only when asked
/// for, or when the vertex count lands within the tolerance of `target`.
RunResult run_cgal(const TriangleMesh& input, double length, std::int64_t target, bool force_figures,
                   const Options& options) {
  RunResult run;
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  CgalMesh mesh = to_cgal(input);
  if (options.border == BorderMode::protect) {
    // CGAL's example: border edges no longer than L, then kept as they are.
    std::vector<CgalMesh::Halfedge_index> border;
    PMP::border_halfedges(mesh.faces(), mesh, std::back_inserter(border));
    std::vector<CgalMesh::Edge_index> border_edges;
    for (const auto h : border) border_edges.push_back(mesh.edge(h));
    PMP::split_long_edges(border_edges, length, mesh);
  }
  PMP::isotropic_remeshing(mesh.faces(), length, mesh,
                           CGAL::parameters::number_of_iterations(options.cgal_iterations)
                               .protect_constraints(options.border == BorderMode::protect));
  const TriangleMesh output = from_cgal(mesh);
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = output.num_vertices();
  const double miss = 100.0 * std::abs(static_cast<double>(run.vertices - target)) / static_cast<double>(target);
  if (force_figures || miss <= options.tolerance_pct) add_figures(run, input, output, options);
  return run;
}

struct CgalSearch {
  std::optional<RunResult> result;    ///< the run reported (with figures)
  double length = 0;                  ///< its target edge length
  int runs = 0;                       ///< remeshes done, the reported one included
  double search_seconds = 0;          ///< wall time of all of them
  std::string failure;                ///< why there is no result
  std::int64_t failed_child_rss = 0;  ///< the failed run's peak RSS
};

/// The target edge length whose remesh has `target` vertices within the
/// tolerance (see the file comment).
CgalSearch search_cgal(const TriangleMesh& input, std::int64_t target, const Options& options) {
  CgalSearch search;
  const auto start = Clock::now();
  EdgeLengthSearch lengths(surface_area(input), target);
  ChildLimits limits;
  limits.time_limit_seconds = options.time_limit_seconds;
  for (int run = 0; run < options.max_runs; ++run) {
    const double length = lengths.length();
    const ChildOutcome outcome =
        run_in_child(limits, [&] { return to_bytes(run_cgal(input, length, target, false, options)); });
    ++search.runs;
    if (outcome.status != ChildOutcome::Status::ok) {
      search.failure = outcome.message;
      search.failed_child_rss = outcome.child_max_rss_bytes;
      search.search_seconds = seconds_since(start);
      return search;
    }
    const RunResult result = from_bytes(outcome.payload);
    std::cerr << "quality_bench:   CGAL L = " << scientific(length, 4) << ": " << result.vertices << " vertices ("
              << fixed(100 * (static_cast<double>(result.vertices) / static_cast<double>(target) - 1), 2) << " %), "
              << fixed(result.seconds, 2) << " s\n";
    if (result.has_figures) {
      search.result = result;
      search.length = length;
      search.search_seconds = seconds_since(start);
      return search;
    }
    lengths.record(result.vertices);
  }
  // None within the tolerance: report the closest one, with its miss.
  const double best_length = lengths.best_length();
  const ChildOutcome outcome =
      run_in_child(limits, [&] { return to_bytes(run_cgal(input, best_length, target, true, options)); });
  ++search.runs;
  search.search_seconds = seconds_since(start);
  if (outcome.status != ChildOutcome::Status::ok) {
    search.failure = outcome.message;
    search.failed_child_rss = outcome.child_max_rss_bytes;
    return search;
  }
  search.result = from_bytes(outcome.payload);
  search.length = best_length;
  return search;
}

// ---------------------------------------------------------------------------
// Tables

TextTable make_table() {
  return TextTable({{"method", TextTable::Align::left},
                    {"sites"},
                    {"vertices"},
                    {"faces"},
                    {"chi"},
                    {"loops"},
                    {"Qmin"},
                    {"Qavg"},
                    {"min angle"},
                    {"avg min angle"},
                    {"% <30 deg"},
                    {"P30"},
                    {"% val6"},
                    {"H %"},
                    {"RMS %"},
                    {"time s"},
                    {"CPU s"},
                    {"peak RSS MiB"},
                    {"notes", TextTable::Align::left}});
}

void add_row(TextTable& table, const std::string& method, const std::string& sites, const Figures& f,
             const std::string& seconds, const std::string& cpu, const std::string& rss, const std::string& notes) {
  table.add_row({method, sites, grouped(f.vertices), grouped(f.faces), std::to_string(f.euler_characteristic),
                 std::to_string(f.boundary_loops), fixed(f.q_min, 3), fixed(f.q_avg, 3), fixed(f.theta_min_deg, 1),
                 fixed(f.theta_min_avg_deg, 1), fixed(f.pct_angles_lt30, 2), fixed(f.p30, 2), fixed(f.pct_valence6, 1),
                 fixed(f.hausdorff_pct, 3), fixed(f.rms_pct, 4), seconds, cpu, rss, notes});
}

void add_run_row(TextTable& table, const std::string& method, std::int64_t sites, const RunResult& run,
                 const std::string& notes) {
  add_row(table, method, grouped(sites), run.output, fixed(run.seconds, 2), fixed(run.cpu_seconds, 2),
          mebibytes(run.peak_rss), notes);
}

void add_failed_row(TextTable& table, const std::string& method, std::int64_t sites, const std::string& why,
                    std::int64_t child_rss) {
  std::vector<std::string> cells(19, "-");
  cells[0] = method;
  cells[1] = grouped(sites);
  cells[17] = mebibytes(child_rss);
  cells[18] = "failed: " + why;
  table.add_row(std::move(cells));
}

int run_benchmark(const Options& options) {
  std::cout << "machine: " << cpu_model() << ", " << std::thread::hardware_concurrency() << " hardware threads, load "
            << load_average() << "\n";
  std::cout << "options: Lloyd " << options.lloyd << " iterations (tolerance " << options.lloyd_tolerance
            << ", warm start " << options.warm_start << " steps), CGAL isotropic_remeshing " << options.cgal_iterations
            << " iterations, borders "
            << (options.border == BorderMode::keep ? "kept (CGAL default)" : "protected (split to L, then fixed)")
            << ", vertex count within " << options.tolerance_pct << " %, " << grouped(options.samples)
            << " samples per side\n";
  ChildLimits limits;
  limits.time_limit_seconds = options.time_limit_seconds;
  int failures = 0;
  for (const auto& path : options.meshes) {
    const io::LoadedMesh input = io::read_mesh(path);
    const std::string name = path.filename().string();
    std::cerr << "quality_bench: " << name << " (" << input.mesh.num_vertices() << " vertices, "
              << input.mesh.num_faces() << " faces)\n";
    TextTable table = make_table();
    std::optional<Figures> input_figures;
    for (const std::int64_t sites : options.site_counts) {
      std::optional<std::int64_t> target;
      struct Variant {
        int lloyd;
        bool newton;
        double adapt;
        std::string method;
      };
      std::vector<Variant> variants = {{0, true, 0.0, "geodual"}};
      if (options.lloyd > 0 && options.plain_lloyd) variants.push_back({options.lloyd, false, 0.0, "geodual+plain"});
      if (options.lloyd > 0) variants.push_back({options.lloyd, true, 0.0, "geodual+Lloyd"});
      if (options.lloyd > 0 && options.adapt > 0)
        variants.push_back({options.lloyd, true, options.adapt, "geodual+adapt"});
      for (const auto& [lloyd, newton, adapt, method] : variants) {
        std::cerr << "quality_bench:   " << method << " " << sites << " sites\n";
        const ChildOutcome outcome =
            run_in_child(limits, [&] { return to_bytes(run_geodual(input, sites, lloyd, newton, adapt, options)); });
        if (outcome.status != ChildOutcome::Status::ok) {
          add_failed_row(table, method, sites, outcome.message, outcome.child_max_rss_bytes);
          ++failures;
          continue;
        }
        const RunResult run = from_bytes(outcome.payload);
        if (!input_figures) input_figures = run.input;
        std::string notes;
        if (lloyd > 0) notes = std::to_string(run.lloyd_iterations) + " Lloyd iterations";
        if (run.warm_start_iterations > 0)
          notes += " after " + std::to_string(run.warm_start_iterations) + " warm-start steps";
        if (run.sites_added > 0)
          notes += (notes.empty() ? "" : ", ") + ("+" + std::to_string(run.sites_added) + " repair sites");
        add_run_row(table, method, sites, run, notes);
        if (adapt == 0) target = run.vertices;  // the Lloyd row's when it succeeds
      }
      if (!options.cgal) continue;
      if (!target) target = sites;
      std::cerr << "quality_bench:   CGAL isotropic_remeshing to " << *target << " vertices\n";
      const CgalSearch search = search_cgal(input.mesh, *target, options);
      const std::string method = "CGAL isotropic";
      if (!search.result) {
        add_failed_row(table, method, sites, search.failure, search.failed_child_rss);
        ++failures;
        continue;
      }
      const RunResult& run = *search.result;
      if (!input_figures) input_figures = run.input;
      const double miss = 100.0 * (static_cast<double>(run.vertices) / static_cast<double>(*target) - 1.0);
      std::string notes = "L=" + scientific(search.length, 4) + ", " + std::to_string(options.cgal_iterations) +
                          " iter, " + (miss >= 0 ? "+" : "") + fixed(miss, 2) + " % of " + grouped(*target) +
                          " vertices after " + std::to_string(search.runs) + " runs (" +
                          fixed(search.search_seconds, 1) + " s)";
      if (std::abs(miss) > options.tolerance_pct) notes += ", NOT within the tolerance";
      add_run_row(table, method, sites, run, notes);
    }
    std::cout << "\n### " << name << " (" << grouped(input.mesh.num_vertices()) << " vertices, "
              << grouped(input.mesh.num_faces()) << " faces)\n\n";
    if (input_figures) add_row(table, "input", "-", *input_figures, "-", "-", "-", "");
    table.print(std::cout);
    std::cout.flush();
  }
  return failures == 0 ? 0 : 1;
}

// ---------------------------------------------------------------------------
// Command line

constexpr const char* usage =
    "usage: quality_bench [--sites 5000,20000] [--lloyd K] [--lloyd-tol T] [--warm-start W] [--plain-lloyd] [--adapt "
    "S]\n"
    "                     [--no-cgal]\n"
    "                     [--cgal-iterations N]\n"
    "                     [--cgal-border keep|protect] [--tolerance PCT] [--max-runs R] [--samples S]\n"
    "                     [--time-limit S] [MESH...]\n"
    "default meshes: tests/data/{bunny,armadillo_86k,fertility}.ply\n";

Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--sites") {
      options.site_counts = parse_integer_list(arg, value(), 4, 100'000'000);
    } else if (arg == "--lloyd") {
      options.lloyd = static_cast<int>(parse_integer(arg, value(), 0, 10'000));
    } else if (arg == "--warm-start") {
      options.warm_start = static_cast<int>(parse_integer(arg, value(), 0, 10'000));
    } else if (arg == "--plain-lloyd") {
      options.plain_lloyd = true;
    } else if (arg == "--adapt") {
      options.adapt = parse_number(arg, value());
      if (options.adapt < 0) throw UsageError("--adapt must be >= 0");
    } else if (arg == "--no-cgal") {
      options.cgal = false;
    } else if (arg == "--lloyd-tol") {
      options.lloyd_tolerance = parse_number(arg, value());
      if (options.lloyd_tolerance < 0) throw UsageError("--lloyd-tol must be >= 0");
    } else if (arg == "--cgal-iterations") {
      options.cgal_iterations = static_cast<unsigned>(parse_integer(arg, value(), 1, 1000));
    } else if (arg == "--cgal-border") {
      const std::string mode = value();
      if (mode == "keep") {
        options.border = BorderMode::keep;
      } else if (mode == "protect") {
        options.border = BorderMode::protect;
      } else {
        throw UsageError("--cgal-border: expected keep or protect, got '" + mode + "'");
      }
    } else if (arg == "--tolerance") {
      options.tolerance_pct = parse_number(arg, value());
      if (!(options.tolerance_pct > 0)) throw UsageError("--tolerance must be > 0");
    } else if (arg == "--max-runs") {
      options.max_runs = static_cast<int>(parse_integer(arg, value(), 1, 100));
    } else if (arg == "--samples") {
      options.samples = parse_integer(arg, value(), 0, quality::max_samples_per_side);
    } else if (arg == "--time-limit") {
      options.time_limit_seconds = static_cast<unsigned>(parse_integer(arg, value(), 1, 1'000'000));
    } else if (arg == "--help" || arg == "-h") {
      std::cout << usage;
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg + "\n" + usage);
    } else {
      options.meshes.emplace_back(arg);
    }
  }
  if (options.meshes.empty()) {
    for (const char* name : {"bunny", "armadillo_86k", "fertility"}) {
      options.meshes.push_back(std::filesystem::path("tests/data") / (std::string(name) + ".ply"));
    }
  }
  return options;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "quality_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
