// feature_bench: geodual's remesh beside CGAL's isotropic remeshing with its
// manual's recipe for sharp features, at the same vertex count, with the
// feature recall (issue 16).
//
//   build/bench/feature_bench [--vertices 3000,10000] [--sharp-angle DEG] [--feature-tolerance PCT]
//                             [--geodual-sharp-angle DEG] [--geodual-pin-creases] [--cgal-iterations N]
//                             [--tolerance PCT] [--max-runs R]
//                             [--samples S]
//                             [--time-limit S] MESH...
//
// A MESH that names no file but a generated hard case (bench/hard_cases.hpp,
// such as `gear`; `remesh_sweep --list` names them) is built in memory.
//
// For each mesh (read once, by the parent process) and each vertex count n,
// every run below is a forked child, so its peak RSS is its own (plus the
// input the parent had already read):
//
//   geodual  geodual::pipeline::run_remesh_pipeline with its default options
//            (what `geodual remesh --sites n` does) at n sites;
//            --geodual-sharp-angle DEG sets RemeshOptions::sharp_angle (the
//            remesher's own features) instead of its default;
//            --geodual-pin-creases sets RemeshOptions::pin_short_creases.
//   CGAL protected
//            CGAL::Polygon_mesh_processing on a Surface_mesh of the input:
//            detect_sharp_edges at --sharp-angle (default 60 degrees) into an
//            edge-is-constrained map, split_long_edges of those edges to the
//            target length L (keeping the map up to date), then
//            isotropic_remeshing to L with that map and protect_constraints,
//            number_of_iterations N (default 3): the sharp edges stay exactly
//            as split, the input's short ones included.
//   CGAL collapsible
//            the same without protect_constraints: sharp edges may be split
//            and collapsed along their chains (never flipped, their vertices
//            never smoothed), so short ones merge, and curved creases are cut
//            by chords where a vertex on them is collapsed away.
//            For each, L is searched (EdgeLengthSearch, cgal_remeshing.hpp) so
//            that CGAL's vertex count lands within --tolerance % (default 3)
//            of geodual's, in at most --max-runs runs (default 8); if none
//            does, the closest L is run once more and reported with its miss.
//
// Time and peak RSS: of the remesh alone (geodual: sampling, Lloyd, the dual
// from the mesh in memory; CGAL: building the Surface_mesh, the recipe and
// reading it back), not of the statistics.
//
// Figures: geodual::quality::compare_meshes(input, output) for both rows
// (10^6 area-uniform samples per side plus all vertices, --samples changes
// it): Qmin, Qavg, the smallest angle, the Hausdorff distance H in % of the
// input's bounding-box diagonal, and the feature recall: the share of the
// input's sharp-edge length (normals turning by at least --sharp-angle)
// within --feature-tolerance % (default 0.1) of the diagonal of an edge of
// the output, and the largest distance from a sharp edge to the output's
// edges (quality_stats.hpp, FeatureRecall).

#include "bench_support.hpp"
#include "cgal_remeshing.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/quality/quality_stats.hpp"
#include "geodual/remesh/features.hpp"
#include "hard_cases.hpp"

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace geodual::bench {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

struct Options {
  std::vector<std::int64_t> vertex_counts = {3000, 10000};
  double sharp_angle_deg = 60.0;
  double feature_tolerance_pct = quality::QualityOptions{}.feature_tolerance_pct;
  std::optional<double> geodual_sharp_angle;  ///< RemeshOptions::sharp_angle; empty: its default
  bool geodual_pin_creases = false;           ///< RemeshOptions::pin_short_creases
  ComparisonOptions comparison;               ///< CGAL's iterations (3) and search, the statistics, the time limit
  std::vector<std::filesystem::path> meshes;
};

/// What one run reports (trivially copyable: sent back from a child).
struct RunResult {
  std::int64_t vertices = 0;  ///< of the output
  double seconds = 0, cpu_seconds = 0;
  std::int64_t peak_rss = 0;
  std::int64_t sites_added = 0;  ///< geodual: by repair
  /// geodual: the narrowest angle between the kept features at a corner
  /// (remesh::narrowest_corner_angle), which bounds the smallest angle; 360 without corners.
  double narrowest_corner_deg = 360;
  std::int64_t constrained_edges = 0;  ///< CGAL: sharp edges found (before the split)
  bool has_figures = false;
  double q_min = 0, q_avg = 0, theta_min_deg = 0, hausdorff_pct = 0;
  double recall_pct = 0, max_gap_pct = 0;
  std::int64_t feature_edges = 0;  ///< the input's sharp edges
  double feature_length_pct = 0;   ///< their total length in % of the input's diagonal
};

void add_figures(RunResult& run, const TriangleMesh& input, const TriangleMesh& output, const Options& options) {
  quality::QualityOptions quality;
  quality.samples_per_side = options.comparison.samples;
  quality.sharp_angle_deg = options.sharp_angle_deg;
  quality.feature_tolerance_pct = options.feature_tolerance_pct;
  const quality::QualityReport report = quality::compare_meshes(input, output, quality);
  run.q_min = report.candidate.q_min;
  run.q_avg = report.candidate.q_avg;
  run.theta_min_deg = report.candidate.theta_min_deg;
  run.hausdorff_pct = report.hausdorff_pct;
  run.recall_pct = report.features->recall_pct;
  run.max_gap_pct = report.features->max_gap_pct;
  run.feature_edges = report.features->edges;
  run.feature_length_pct = 100.0 * report.features->length / report.reference.bbox_diagonal;
  run.has_figures = true;
}

RunResult run_geodual(const io::LoadedMesh& input, std::int64_t sites, const Options& options) {
  pipeline::RemeshPipelineOptions pipeline_options;
  pipeline_options.sites = sites;
  if (options.geodual_sharp_angle) pipeline_options.remesh.sharp_angle = *options.geodual_sharp_angle;
  pipeline_options.remesh.pin_short_creases = options.geodual_pin_creases;
  pipeline_options.statistics = false;  // measured below, the same way for both rows
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
  run.narrowest_corner_deg = remesh::narrowest_corner_angle(result.surface.mesh, result.features);
  add_figures(run, input.mesh, result.remesh.mesh, options);
  return run;
}

/// CGAL's feature recipe at target edge length `length`, the sharp edges
/// protected or collapsible; figures only when asked for, or when the vertex
/// count lands within the tolerance of `target`.
RunResult run_cgal(const TriangleMesh& input, double length, bool protect, std::int64_t target, bool force_figures,
                   const Options& options) {
  RunResult run;
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  CgalMesh mesh = to_cgal(input);
  auto constrained = mesh.add_property_map<CgalMesh::Edge_index, bool>("e:constrained", false).first;
  PMP::detect_sharp_edges(mesh, options.sharp_angle_deg, constrained);
  std::vector<CgalMesh::Edge_index> sharp;
  for (const CgalMesh::Edge_index e : mesh.edges()) {
    if (constrained[e]) sharp.push_back(e);
  }
  run.constrained_edges = static_cast<std::int64_t>(sharp.size());
  PMP::split_long_edges(sharp, length, mesh, CGAL::parameters::edge_is_constrained_map(constrained));
  PMP::isotropic_remeshing(mesh.faces(), length, mesh,
                           CGAL::parameters::number_of_iterations(options.comparison.cgal.iterations)
                               .edge_is_constrained_map(constrained)
                               .protect_constraints(protect));
  const TriangleMesh output = from_cgal(mesh);
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = output.num_vertices();
  if (force_figures || miss_pct(run.vertices, target) <= options.comparison.tolerance_pct)
    add_figures(run, input, output, options);
  return run;
}

/// CGAL's run whose vertex count is within the tolerance of `target`, or the
/// closest one.
EdgeLengthSearchResult<RunResult> search_cgal(const TriangleMesh& input, bool protect, std::int64_t target,
                                              const Options& options) {
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  return search_edge_length<RunResult>(
      surface_area(input), target, options.comparison.max_runs,
      "feature_bench:   ", [&](double length, bool force_figures) {
        return run_in_child(limits,
                            [&] { return to_bytes(run_cgal(input, length, protect, target, force_figures, options)); });
      });
}

TextTable make_table() {
  return TextTable({{"method", TextTable::Align::left},
                    {"vertices"},
                    {"time s"},
                    {"CPU s"},
                    {"peak RSS MiB"},
                    {"Qmin"},
                    {"Qavg"},
                    {"min angle"},
                    {"H %"},
                    {"recall %"},
                    {"max gap %"},
                    {"notes", TextTable::Align::left}});
}

void add_run_row(TextTable& table, const std::string& method, const RunResult& run, const std::string& notes) {
  table.add_row({method, grouped(run.vertices), fixed(run.seconds, 2), fixed(run.cpu_seconds, 2),
                 mebibytes(run.peak_rss), fixed(run.q_min, 3), fixed(run.q_avg, 3), fixed(run.theta_min_deg, 1),
                 fixed(run.hausdorff_pct, 3), fixed(run.recall_pct, 1), fixed(run.max_gap_pct, 3), notes});
}

void add_failed_row(TextTable& table, const std::string& method, const std::string& why, std::int64_t child_rss) {
  std::vector<std::string> cells(12, "-");
  cells[0] = method;
  cells[4] = mebibytes(child_rss);
  cells[11] = "failed: " + why;
  table.add_row(std::move(cells));
}

/// The mesh file at `path`, or where no file is there, the generated hard case of that name.
io::LoadedMesh read_mesh_or_hard_case(const std::filesystem::path& path) {
  if (std::filesystem::exists(path)) return io::read_mesh(path);
  for (const HardCase& hard_case : hard_cases()) {
    if (hard_case.name != path.string()) continue;
    io::LoadedMesh loaded;
    loaded.mesh = hard_case.build();
    return loaded;
  }
  throw UsageError("feature_bench: " + path.string() + " is neither a file nor a generated hard case");
}

int run_benchmark(const Options& options) {
  std::cout << "machine: " << cpu_model() << ", " << std::thread::hardware_concurrency() << " hardware threads, load "
            << load_average() << "\n";
  std::cout << "options: geodual remesh defaults"
            << (options.geodual_sharp_angle ? " but sharp_angle " + fixed(*options.geodual_sharp_angle, 1)
                                            : std::string())
            << (options.geodual_pin_creases ? ", short creases pinned" : "") << "; CGAL detect_sharp_edges "
            << options.sharp_angle_deg << " deg, split_long_edges, isotropic_remeshing "
            << options.comparison.cgal.iterations
            << " iterations with the sharp edges constrained (protected or collapsible), vertex count within "
            << options.comparison.tolerance_pct << " % of geodual's; recall within " << options.feature_tolerance_pct
            << " % of the diagonal; " << grouped(options.comparison.samples) << " samples per side\n";
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  int failures = 0;
  for (const auto& path : options.meshes) {
    const io::LoadedMesh input = read_mesh_or_hard_case(path);
    const std::string name = path.filename().string();
    std::cerr << "feature_bench: " << name << " (" << input.mesh.num_vertices() << " vertices, "
              << input.mesh.num_faces() << " faces)\n";
    TextTable table = make_table();
    std::optional<RunResult> any;  // for the input's sharp edges
    for (const std::int64_t count : options.vertex_counts) {
      std::cerr << "feature_bench:   geodual " << count << " sites\n";
      const ChildOutcome outcome = run_in_child(limits, [&] { return to_bytes(run_geodual(input, count, options)); });
      std::int64_t target = count;
      if (outcome.status == ChildOutcome::Status::ok) {
        const RunResult run = from_bytes<RunResult>(outcome.payload);
        any = run;
        target = run.vertices;
        add_run_row(table, "geodual", run,
                    grouped(count) + " sites" +
                        (run.sites_added > 0 ? ", +" + grouped(run.sites_added) + " repair sites" : std::string()) +
                        (run.narrowest_corner_deg < 180 ? ", features meet at " + fixed(run.narrowest_corner_deg, 1) +
                                                              " deg at the narrowest corner"
                                                        : std::string()));
      } else {
        add_failed_row(table, "geodual", outcome.message, outcome.child_max_rss_bytes);
        ++failures;
      }
      for (const bool protect : {true, false}) {
        const std::string method = protect ? "CGAL protected" : "CGAL collapsible";
        std::cerr << "feature_bench:   " << method << " to " << target << " vertices\n";
        const EdgeLengthSearchResult<RunResult> search = search_cgal(input.mesh, protect, target, options);
        if (!search.result) {
          add_failed_row(table, method, search.failure, search.failed_child_rss);
          ++failures;
          continue;
        }
        const RunResult& run = *search.result;
        any = run;
        const double miss = 100.0 * (static_cast<double>(run.vertices) / static_cast<double>(target) - 1.0);
        std::string notes = "L=" + scientific(search.length, 4) + ", " + (miss >= 0 ? "+" : "") + fixed(miss, 2) +
                            " % of " + grouped(target) + " vertices after " + std::to_string(search.runs) + " runs";
        if (std::abs(miss) > options.comparison.tolerance_pct) notes += ", NOT within the tolerance";
        if (run.constrained_edges != run.feature_edges) {
          notes += ", CGAL finds " + grouped(run.constrained_edges) + " sharp edges";
        }
        add_run_row(table, method, run, notes);
      }
    }
    std::cout << "\n### " << name << " (" << grouped(input.mesh.num_vertices()) << " vertices, "
              << grouped(input.mesh.num_faces()) << " faces";
    if (any) {
      std::cout << "; " << grouped(any->feature_edges) << " sharp edges at " << options.sharp_angle_deg
                << " deg, length " << fixed(any->feature_length_pct / 100.0, 2) << " diagonals";
    }
    std::cout << ")\n\n";
    table.print(std::cout);
    std::cout.flush();
  }
  return failures == 0 ? 0 : 1;
}

constexpr const char* usage =
    "usage: feature_bench [--vertices 3000,10000] [--sharp-angle DEG] [--feature-tolerance PCT]\n"
    "                     [--geodual-sharp-angle DEG] [--geodual-pin-creases]\n"
    "                     [--cgal-iterations N] [--tolerance PCT] [--max-runs R] [--samples S]\n"
    "                     [--time-limit S] MESH...\n";

Options parse_options(int argc, char** argv) {
  Options options;
  options.meshes = parse_command_line(argc, argv, usage, [&](const std::string& word, const NextValue& value) {
    if (word == "--vertices") {
      options.vertex_counts = parse_integer_list(word, value(), 4, 100'000'000);
    } else if (word == "--sharp-angle") {
      options.sharp_angle_deg = parse_number(word, value());
      if (!(options.sharp_angle_deg > 0 && options.sharp_angle_deg <= 180)) {
        throw UsageError("--sharp-angle must be in (0, 180]");
      }
    } else if (word == "--feature-tolerance") {
      options.feature_tolerance_pct = parse_number(word, value());
      if (!(options.feature_tolerance_pct > 0)) throw UsageError("--feature-tolerance must be > 0");
    } else if (word == "--geodual-sharp-angle") {
      options.geodual_sharp_angle = parse_number(word, value());
      if (!(*options.geodual_sharp_angle >= 0 && *options.geodual_sharp_angle <= 180)) {
        throw UsageError("--geodual-sharp-angle must be in [0, 180]");
      }
    } else if (word == "--geodual-pin-creases") {
      options.geodual_pin_creases = true;
    } else {
      return parse_comparison_option(word, value, options.comparison);
    }
    return true;
  });
  if (options.meshes.empty()) throw UsageError(std::string("give at least one mesh\n") + usage);
  return options;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "feature_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
