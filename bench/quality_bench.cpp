// quality_bench: geodual's remesh side by side with CGAL's isotropic
// remeshing at the same vertex count, with the quality figures of
// shared/DESIGN.md for all of them (issue 5, deliverable 4).
//
//   build/bench/quality_bench [--sites 5000,20000] [--lloyd K] [--lloyd-tol T] [--warm-start W]
//                             [--momentum M] [--plain-lloyd] [--adapt S] [--no-cgal]
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
//                  (default: LloydOptions' default; 0: none) with momentum M
//                  (default: LloydOptions' default; 0: none).
//   geodual+plain  with --plain-lloyd: the same, plain (over-relaxed) Lloyd
//                  steps.
//   geodual+adapt  with --adapt S: the Lloyd row's run with curvature-adapted
//                  sizing (RemeshOptions::curvature strength S, a
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

struct Options {
  std::vector<std::int64_t> site_counts = {5000, 20000};
  int lloyd = 10;
  double lloyd_tolerance = remesh::LloydOptions{}.tolerance;
  int warm_start = remesh::LloydOptions{}.warm_start_iterations;
  double momentum = remesh::LloydOptions{}.warm_start_momentum;
  bool plain_lloyd = false;      ///< also a row with plain Lloyd steps
  double adapt = 0;              ///< > 0: also a row with curvature-adapted sizing of this strength
  bool cgal = true;              ///< the CGAL row
  ComparisonOptions comparison;  ///< CGAL's remesh (3 iterations, borders kept) and search, the statistics
  std::vector<std::filesystem::path> meshes;
};

// ---------------------------------------------------------------------------
// geodual

RemeshRun run_geodual(const io::LoadedMesh& input, std::int64_t sites, int lloyd, bool newton, double adapt,
                      const Options& options) {
  pipeline::RemeshPipelineOptions pipeline_options;
  pipeline_options.sites = sites;
  pipeline_options.remesh.lloyd.iterations = lloyd;
  pipeline_options.remesh.lloyd.newton = newton;
  if (adapt > 0) pipeline_options.remesh.curvature = remesh::CurvatureDensityOptions{.strength = adapt};
  pipeline_options.remesh.lloyd.tolerance = options.lloyd_tolerance;
  pipeline_options.remesh.lloyd.warm_start_iterations = options.warm_start;
  pipeline_options.remesh.lloyd.warm_start_momentum = options.momentum;
  pipeline_options.statistics = false;  // measured below, the same way for every row
  RemeshRun run;
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
  add_figures(run, input.mesh, result.remesh.mesh, options.comparison.samples);
  return run;
}

// ---------------------------------------------------------------------------
// CGAL

/// One CGAL remesh with target edge length `length`; figures only when asked
/// for, or when the vertex count lands within the tolerance of `target`.
RemeshRun run_cgal(const TriangleMesh& input, double length, std::int64_t target, bool force_figures,
                   const Options& options) {
  RemeshRun run;
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  const TriangleMesh output = cgal_isotropic_remesh(input, length, options.comparison.cgal);
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = output.num_vertices();
  if (force_figures || miss_pct(run.vertices, target) <= options.comparison.tolerance_pct) {
    add_figures(run, input, output, options.comparison.samples);
  }
  return run;
}

/// The CGAL run whose vertex count is within the tolerance of `target`, or
/// the closest one (see the file comment).
EdgeLengthSearchResult<RemeshRun> search_cgal(const TriangleMesh& input, std::int64_t target, const Options& options) {
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  return search_edge_length<RemeshRun>(
      surface_area(input), target, options.comparison.max_runs,
      "quality_bench:   ", [&](double length, bool force_figures) {
        return run_in_child(limits, [&] { return to_bytes(run_cgal(input, length, target, force_figures, options)); });
      });
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

void add_row(TextTable& table, const std::string& method, const std::string& sites, const QualityFigures& f,
             const std::string& seconds, const std::string& cpu, const std::string& rss, const std::string& notes) {
  table.add_row({method, sites, grouped(f.vertices), grouped(f.faces), std::to_string(f.euler_characteristic),
                 std::to_string(f.boundary_loops), fixed(f.q_min, 3), fixed(f.q_avg, 3), fixed(f.theta_min_deg, 1),
                 fixed(f.theta_min_avg_deg, 1), fixed(f.pct_angles_lt30, 2), fixed(f.p30, 2), fixed(f.pct_valence6, 1),
                 fixed(f.hausdorff_pct, 3), fixed(f.rms_pct, 4), seconds, cpu, rss, notes});
}

void add_run_row(TextTable& table, const std::string& method, std::int64_t sites, const RemeshRun& run,
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
            << ", warm start " << options.warm_start << " steps, momentum " << options.momentum
            << "), CGAL isotropic_remeshing " << options.comparison.cgal.iterations << " iterations, borders "
            << (options.comparison.cgal.border == CgalBorder::keep ? "kept (CGAL default)"
                                                                   : "protected (split to L, then fixed)")
            << ", vertex count within " << options.comparison.tolerance_pct << " %, "
            << grouped(options.comparison.samples) << " samples per side\n";
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  int failures = 0;
  for (const auto& path : options.meshes) {
    const io::LoadedMesh input = io::read_mesh(path);
    const std::string name = path.filename().string();
    std::cerr << "quality_bench: " << name << " (" << input.mesh.num_vertices() << " vertices, "
              << input.mesh.num_faces() << " faces)\n";
    TextTable table = make_table();
    std::optional<QualityFigures> input_figures;
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
        const RemeshRun run = from_bytes<RemeshRun>(outcome.payload);
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
      const EdgeLengthSearchResult<RemeshRun> search = search_cgal(input.mesh, *target, options);
      const std::string method = "CGAL isotropic";
      if (!search.result) {
        add_failed_row(table, method, sites, search.failure, search.failed_child_rss);
        ++failures;
        continue;
      }
      const RemeshRun& run = *search.result;
      if (!input_figures) input_figures = run.input;
      const double miss = 100.0 * (static_cast<double>(run.vertices) / static_cast<double>(*target) - 1.0);
      std::string notes = "L=" + scientific(search.length, 4) + ", " +
                          std::to_string(options.comparison.cgal.iterations) + " iter, " + (miss >= 0 ? "+" : "") +
                          fixed(miss, 2) + " % of " + grouped(*target) + " vertices after " +
                          std::to_string(search.runs) + " runs (" + fixed(search.search_seconds, 1) + " s)";
      if (std::abs(miss) > options.comparison.tolerance_pct) notes += ", NOT within the tolerance";
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
    "usage: quality_bench [--sites 5000,20000] [--lloyd K] [--lloyd-tol T] [--warm-start W] [--momentum M] "
    "[--plain-lloyd] "
    "[--adapt S]\n"
    "                     [--no-cgal]\n"
    "                     [--cgal-iterations N]\n"
    "                     [--cgal-border keep|protect] [--tolerance PCT] [--max-runs R] [--samples S]\n"
    "                     [--time-limit S] [MESH...]\n"
    "default meshes: tests/data/{bunny,armadillo_86k,fertility}.ply\n";

Options parse_options(int argc, char** argv) {
  Options options;
  options.meshes = parse_command_line(argc, argv, usage, [&](const std::string& word, const NextValue& value) {
    if (word == "--sites") {
      options.site_counts = parse_integer_list(word, value(), 4, 100'000'000);
    } else if (word == "--lloyd") {
      options.lloyd = static_cast<int>(parse_integer(word, value(), 0, 10'000));
    } else if (word == "--warm-start") {
      options.warm_start = static_cast<int>(parse_integer(word, value(), 0, 10'000));
    } else if (word == "--momentum") {
      options.momentum = parse_number(word, value());
      if (!(options.momentum >= 0 && options.momentum < 1)) throw UsageError("--momentum must be in [0, 1)");
    } else if (word == "--plain-lloyd") {
      options.plain_lloyd = true;
    } else if (word == "--adapt") {
      options.adapt = parse_number(word, value());
      if (options.adapt < 0) throw UsageError("--adapt must be >= 0");
    } else if (word == "--no-cgal") {
      options.cgal = false;
    } else if (word == "--lloyd-tol") {
      options.lloyd_tolerance = parse_number(word, value());
      if (options.lloyd_tolerance < 0) throw UsageError("--lloyd-tol must be >= 0");
    } else if (word == "--cgal-border") {
      const std::string mode = value();
      if (mode == "keep") {
        options.comparison.cgal.border = CgalBorder::keep;
      } else if (mode == "protect") {
        options.comparison.cgal.border = CgalBorder::protect;
      } else {
        throw UsageError("--cgal-border: expected keep or protect, got '" + mode + "'");
      }
    } else {
      return parse_comparison_option(word, value, options.comparison);
    }
    return true;
  });
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
