// feature_bench: geodual's remesh beside CGAL's isotropic remeshing with its
// manual's recipe for sharp features, at the same vertex count, with the
// feature recall (issue 16).
//
//   build/bench/feature_bench [--vertices 3000,10000] [--sharp-angle DEG] [--feature-tolerance PCT]
//                             [--geodual-sharp-angle DEG] [--geodual-pin-creases] [--cgal-iterations N]
//                             [--tolerance PCT] [--max-runs R]
//                             [--samples S]
//                             [--time-limit S] MESH...
//   build/bench/feature_bench --corpus DIR [--vertices 500,2000] [options above] [MESH...]
//
// --corpus DIR adds every mesh file of DIR (by name) to the MESHes and prints
// one table over all of them instead of one per mesh (see "Corpus mode" below).
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
//            --geodual-sharp-angle DEG sets FeatureSamplingOptions::sharp_angle (the
//            remesher's own features) instead of its default;
//            --geodual-pin-creases sets FeatureRemeshOptions::pin_short_creases.
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
//
// Corpus mode (--corpus DIR): for each vertex count, then each mesh, geodual
// and CGAL protected only (the manual's recipe, split_long_edges then
// protect_constraints; the collapsible row would double the time), in one
// table: the recall over all sharp edges, the recall on the long creases
// (sharp chains at least one spacing long, the spacing
// remesh::uniform_spacing(input, n) of the n sites asked for, the same for
// both rows: FeatureRecall::long_recall_pct), H, Qmin, the smallest angle and
// the time, with whether geodual dropped its creases
// (RemeshPipelineResult::features_dropped_reason: all of them;
// features_partly_dropped_reason: those near some places). Then one summary
// line per vertex count: the medians of both recalls, the parts whose
// long-crease recall is at least 99 %, those where geodual's Qmin is above
// CGAL's and its H at most CGAL's, the parts whose smallest angle reaches
// min(30, the narrowest corner between geodual's kept features), the runs
// where geodual dropped its creases, and the parts where CGAL's vertex count
// came within --tolerance of geodual's: protected, no vertex of an input's
// sharp edge is ever removed, so on a part with many short creases at few
// sites CGAL cannot come down to geodual's count; its closest run is
// compared all the same, marked in the table.

#include "bench_support.hpp"
#include "cgal_remeshing.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/quality/quality_stats.hpp"
#include "geodual/remesh/curvature_density.hpp"
#include "geodual/remesh/features.hpp"
#include "hard_cases.hpp"

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
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
  std::optional<double> geodual_sharp_angle;  ///< FeatureSamplingOptions::sharp_angle; empty: its default
  bool geodual_pin_creases = false;           ///< FeatureRemeshOptions::pin_short_creases
  ComparisonOptions comparison;               ///< CGAL's iterations (3) and search, the statistics, the time limit
  std::vector<std::filesystem::path> meshes;
  bool corpus = false;  ///< --corpus: one table over all meshes
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
  /// On the sharp chains at least one spacing long (corpus mode; FeatureRecall).
  double long_recall_pct = 100;
  std::int64_t chains = 0, long_chains = 0;
  std::int64_t feature_chains = 0;  ///< geodual: the sharp chains of its FeatureSet (RemeshPipelineResult::features)
  bool features_dropped = false;    ///< geodual: remeshed without any of its features
  bool features_partly_dropped = false;  ///< geodual: without those near some places
};

/// The length from which a crease counts as long at `sites` sites: the spacing
/// of a uniform remesh of the input with that many vertices.
double long_crease_length(const TriangleMesh& input, std::int64_t sites) {
  return remesh::uniform_spacing(input, sites);
}

void add_figures(RunResult& run, const TriangleMesh& input, const TriangleMesh& output, const Options& options,
                 std::int64_t sites) {
  quality::QualityOptions quality;
  quality.samples_per_side = options.comparison.samples;
  quality.sharp_angle_deg = options.sharp_angle_deg;
  quality.feature_tolerance_pct = options.feature_tolerance_pct;
  quality.long_crease_length = long_crease_length(input, sites);
  const quality::QualityReport report = quality::compare_meshes(input, output, quality);
  run.q_min = report.candidate.q_min;
  run.q_avg = report.candidate.q_avg;
  run.theta_min_deg = report.candidate.theta_min_deg;
  run.hausdorff_pct = report.hausdorff_pct;
  run.recall_pct = report.features->recall_pct;
  run.max_gap_pct = report.features->max_gap_pct;
  run.feature_edges = report.features->edges;
  run.feature_length_pct = 100.0 * report.features->length / report.reference.bbox_diagonal;
  run.long_recall_pct = report.features->long_recall_pct;
  run.chains = report.features->chains;
  run.long_chains = report.features->long_chains;
  run.has_figures = true;
}

RunResult run_geodual(const io::LoadedMesh& input, std::int64_t sites, const Options& options) {
  pipeline::RemeshPipelineOptions pipeline_options;
  pipeline_options.sites = sites;
  if (options.geodual_sharp_angle) pipeline_options.features.sampling.sharp_angle = *options.geodual_sharp_angle;
  pipeline_options.features.pin_short_creases = options.geodual_pin_creases;
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
  run.feature_chains = result.features.sharp_chains;
  run.features_dropped = !result.features_dropped_reason.empty();
  run.features_partly_dropped = !result.features_partly_dropped_reason.empty();
  add_figures(run, input.mesh, result.remesh.mesh, options, sites);
  return run;
}

/// CGAL's feature recipe at target edge length `length`, the sharp edges
/// protected or collapsible; figures only when asked for, or when the vertex
/// count lands within the tolerance of `target`.
RunResult run_cgal(const TriangleMesh& input, double length, bool protect, std::int64_t target, std::int64_t sites,
                   bool force_figures, const Options& options) {
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
    add_figures(run, input, output, options, sites);
  return run;
}

/// CGAL's run whose vertex count is within the tolerance of `target`, or the
/// closest one; `sites`: geodual's, for the long creases' length.
EdgeLengthSearchResult<RunResult> search_cgal(const TriangleMesh& input, bool protect, std::int64_t target,
                                              std::int64_t sites, const Options& options) {
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  return search_edge_length<RunResult>(
      surface_area(input), target, options.comparison.max_runs,
      "feature_bench:   ", [&](double length, bool force_figures) {
        return run_in_child(
            limits, [&] { return to_bytes(run_cgal(input, length, protect, target, sites, force_figures, options)); });
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

/// One part at one vertex count in corpus mode.
struct CorpusRun {
  std::string part;
  std::int64_t faces = 0;
  std::int64_t sites = 0;
  double spacing = 0;  ///< the long creases' length
  std::optional<RunResult> geodual, cgal;
  std::string geodual_failure, cgal_failure;
  double cgal_miss_pct = 0;  ///< CGAL's vertex count against geodual's
};

std::string share(std::int64_t count, std::int64_t of) { return grouped(count) + " of " + grouped(of); }

/// The corpus table's row of one method.
void add_corpus_row(TextTable& table, const CorpusRun& part, const std::string& method,
                    const std::optional<RunResult>& run, const std::string& failure, const std::string& notes) {
  std::vector<std::string> cells{grouped(part.sites), part.part, grouped(part.faces), method};
  if (!run || !run->has_figures) {
    cells.resize(13, "-");
    cells[12] = "failed: " + (failure.empty() ? std::string("no figures") : failure);
    table.add_row(std::move(cells));
    return;
  }
  cells.insert(cells.end(), {grouped(run->vertices), fixed(run->recall_pct, 1), fixed(run->long_recall_pct, 1),
                             grouped(run->long_chains) + "/" + grouped(run->chains), fixed(run->hausdorff_pct, 3),
                             fixed(run->q_min, 3), fixed(run->theta_min_deg, 1), fixed(run->seconds, 2), notes});
  table.add_row(std::move(cells));
}

/// The summary line of one vertex count.
void print_corpus_summary(std::ostream& out, std::int64_t sites, const std::vector<CorpusRun>& runs,
                          double tolerance_pct) {
  std::vector<double> recall[2], long_recall[2];
  std::int64_t parts = 0, long99[2] = {0, 0}, both = 0, q_above = 0, h_at_most = 0, theta_ok = 0, dropped = 0,
               partly = 0, geodual_runs = 0, failed[2] = {0, 0}, same_v = 0;
  for (const CorpusRun& run : runs) {
    if (run.sites != sites) continue;
    ++parts;
    const std::optional<RunResult>* rows[2] = {&run.geodual, &run.cgal};
    for (int m = 0; m < 2; ++m) {
      const std::optional<RunResult>& row = *rows[m];
      if (!row || !row->has_figures) {
        ++failed[m];
        continue;
      }
      recall[m].push_back(row->recall_pct);
      long_recall[m].push_back(row->long_recall_pct);
      long99[m] += row->long_recall_pct >= 99.0;
    }
    if (run.geodual) {
      ++geodual_runs;
      dropped += run.geodual->features_dropped;
      partly += run.geodual->features_partly_dropped;
      if (run.geodual->has_figures) {
        theta_ok += run.geodual->theta_min_deg >= std::min(30.0, run.geodual->narrowest_corner_deg);
      }
    }
    if (run.geodual && run.geodual->has_figures && run.cgal && run.cgal->has_figures) {
      ++both;
      same_v += std::abs(run.cgal_miss_pct) <= tolerance_pct;
      q_above += run.geodual->q_min > run.cgal->q_min;
      h_at_most += run.geodual->hausdorff_pct <= run.cgal->hausdorff_pct;
    }
  }
  out << "summary at " << grouped(sites) << " sites, " << parts << " parts (geodual | CGAL protected):\n"
      << "  median recall over all sharp edges: " << fixed(median(recall[0]), 1) << " | " << fixed(median(recall[1]), 1)
      << " %\n"
      << "  median recall on the creases at least one spacing long: " << fixed(median(long_recall[0]), 1) << " | "
      << fixed(median(long_recall[1]), 1) << " %\n"
      << "  parts with that recall >= 99 %: " << share(long99[0], parts) << " | " << share(long99[1], parts) << "\n"
      << "  parts where CGAL's vertex count is within " << fixed(tolerance_pct, 1)
      << " % of geodual's (the others: the closest it came, compared all the same): " << share(same_v, both) << "\n"
      << "  parts where geodual's Qmin > CGAL's: " << share(q_above, both) << "\n"
      << "  parts where geodual's H <= CGAL's: " << share(h_at_most, both) << "\n"
      << "  parts where geodual's min angle >= min(30, its narrowest corner): " << share(theta_ok, parts) << "\n"
      << "  runs where geodual dropped its creases: " << share(dropped, geodual_runs)
      << " (dropped them near some places: " << partly << ")\n"
      << "  failed runs: " << failed[0] << " | " << failed[1] << "\n";
}

/// The mesh files of `folder` (by name), for --corpus.
std::vector<std::filesystem::path> corpus_meshes(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) throw UsageError("--corpus: " + folder.string() + " is no folder");
  std::vector<std::filesystem::path> meshes;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* known : {".stl", ".ply", ".off", ".obj", ".glb", ".gltf"}) {
      if (extension == known) meshes.push_back(entry.path());
    }
  }
  std::sort(meshes.begin(), meshes.end());
  if (meshes.empty()) throw UsageError("--corpus: no mesh file in " + folder.string());
  return meshes;
}

void print_header(const Options& options) {
  std::cout << "machine: " << cpu_model() << ", " << std::thread::hardware_concurrency() << " hardware threads, load "
            << load_average() << "\n";
  std::cout << "options: geodual remesh defaults"
            << (options.geodual_sharp_angle ? " but sharp_angle " + fixed(*options.geodual_sharp_angle, 1)
                                            : std::string())
            << (options.geodual_pin_creases ? ", short creases pinned" : "") << "; CGAL detect_sharp_edges "
            << options.sharp_angle_deg << " deg, split_long_edges, isotropic_remeshing "
            << options.comparison.cgal.iterations << " iterations with the sharp edges constrained ("
            << (options.corpus ? "protected" : "protected or collapsible") << "), vertex count within "
            << options.comparison.tolerance_pct << " % of geodual's; recall within " << options.feature_tolerance_pct
            << " % of the diagonal; " << grouped(options.comparison.samples) << " samples per side\n";
}

/// Corpus mode: one table over all meshes and vertex counts, then the summaries.
int run_corpus(const Options& options) {
  print_header(options);
  std::cout << "long creases: sharp chains at least remesh::uniform_spacing(input, sites) long (the spacing)\n";
  std::cout.flush();
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  std::vector<std::pair<std::string, io::LoadedMesh>> inputs;
  for (const auto& path : options.meshes) inputs.emplace_back(path.filename().string(), read_mesh_or_hard_case(path));
  std::vector<CorpusRun> runs;
  int failures = 0;
  for (const std::int64_t count : options.vertex_counts) {
    for (const auto& [name, input] : inputs) {
      CorpusRun run;
      run.part = name;
      run.faces = input.mesh.num_faces();
      run.sites = count;
      run.spacing = long_crease_length(input.mesh, count);
      std::cerr << "feature_bench: " << name << " (" << input.mesh.num_faces() << " faces), " << count
                << " sites: geodual\n";
      const ChildOutcome outcome = run_in_child(limits, [&] { return to_bytes(run_geodual(input, count, options)); });
      std::int64_t target = count;
      if (outcome.status == ChildOutcome::Status::ok) {
        run.geodual = from_bytes<RunResult>(outcome.payload);
        target = run.geodual->vertices;
      } else {
        run.geodual_failure = outcome.message;
        ++failures;
      }
      std::cerr << "feature_bench:   CGAL protected to " << target << " vertices\n";
      const EdgeLengthSearchResult<RunResult> search = search_cgal(input.mesh, true, target, count, options);
      if (search.result) {
        run.cgal = *search.result;
        run.cgal_miss_pct = 100.0 * (static_cast<double>(run.cgal->vertices) / static_cast<double>(target) - 1.0);
      } else {
        run.cgal_failure = search.failure;
        ++failures;
      }
      runs.push_back(std::move(run));
    }
  }

  TextTable table({{"sites"},
                   {"part", TextTable::Align::left},
                   {"faces"},
                   {"method", TextTable::Align::left},
                   {"vertices"},
                   {"recall %"},
                   {"long recall %"},
                   {"long/chains"},
                   {"H %"},
                   {"Qmin"},
                   {"min angle"},
                   {"time s"},
                   {"notes", TextTable::Align::left}});
  for (const CorpusRun& run : runs) {
    std::string notes = "spacing " + scientific(run.spacing, 3);
    if (run.geodual) {
      notes += ", " + grouped(run.geodual->feature_chains) + " chains found";
      if (run.geodual->sites_added > 0) notes += ", +" + grouped(run.geodual->sites_added) + " repair sites";
      if (run.geodual->narrowest_corner_deg < 180) {
        notes += ", narrowest corner " + fixed(run.geodual->narrowest_corner_deg, 1) + " deg";
      }
      if (run.geodual->features_dropped) notes += ", CREASES DROPPED";
      if (run.geodual->features_partly_dropped) notes += ", creases dropped near some places";
    }
    add_corpus_row(table, run, "geodual", run.geodual, run.geodual_failure, notes);
    std::string cgal_notes = (run.cgal_miss_pct >= 0 ? "+" : "") + fixed(run.cgal_miss_pct, 2) + " % of V";
    if (std::abs(run.cgal_miss_pct) > options.comparison.tolerance_pct) cgal_notes += ", NOT within the tolerance";
    add_corpus_row(table, run, "CGAL", run.cgal, run.cgal_failure, cgal_notes);
  }
  std::cout << "\n";
  table.print(std::cout);
  std::cout << "\n";
  for (const std::int64_t count : options.vertex_counts)
    print_corpus_summary(std::cout, count, runs, options.comparison.tolerance_pct);
  std::cout.flush();
  return failures == 0 ? 0 : 1;
}

int run_benchmark(const Options& options) {
  if (options.corpus) return run_corpus(options);
  print_header(options);
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
        const EdgeLengthSearchResult<RunResult> search = search_cgal(input.mesh, protect, target, count, options);
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
    "                     [--time-limit S] MESH...\n"
    "       feature_bench --corpus DIR [the options above] [MESH...]\n";

Options parse_options(int argc, char** argv) {
  Options options;
  std::vector<std::filesystem::path> corpus_meshes_found;
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
    } else if (word == "--corpus") {
      const std::vector<std::filesystem::path> found = corpus_meshes(value());
      corpus_meshes_found.insert(corpus_meshes_found.end(), found.begin(), found.end());
      options.corpus = true;
    } else {
      return parse_comparison_option(word, value, options.comparison);
    }
    return true;
  });
  options.meshes.insert(options.meshes.end(), corpus_meshes_found.begin(), corpus_meshes_found.end());
  if (options.meshes.empty()) throw UsageError(std::string("give at least one mesh\n") + usage);
  return options;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "feature_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
