// speed_bench: geodual's default job against CGAL's isotropic remeshing at
// the same vertex count (time, peak memory and the quality figures), and
// geodual's scaling with threads (issue 17, deliverable 4). The README's
// results table comes from it.
//
//   build/bench/speed_bench [--sites 5000] [--threads 1,2] [--cgal-iterations N] [--tolerance PCT]
//                           [--max-runs R] [--samples S] [--time-limit S] [--output-dir DIR]
//                           [--cgal-kept-heap] [MESH...]
//
// Default meshes: examples/data/bunny.ply, tests/data/{armadillo_86k,fertility}.ply
// (run from the repository root). For each mesh and site count n, every run
// is a forked child, so its wall time, CPU time and peak RSS are its own:
//
//   geodual  the work of `geodual --threads T remesh MESH --sites n --no-statistics -o OUT.glb`:
//            read MESH; geodual::pipeline::run_remesh_pipeline with the
//            default options (blue-noise sites, seed 1, the default warm start
//            and Lloyd-Newton iterations, repair, attributes carried) and
//            statistics off; the triangle quality the CLI puts in the
//            output's extras; write OUT.glb. Once per T of --threads (default
//            1,2; tbb::global_control max_allowed_parallelism, as --threads
//            sets it). The outputs of all T must be the same bytes; the
//            speed-up is the time of the first T over the time of T. Its
//            malloc keeps freed memory in the heap, as the CLI's does
//            (pipeline::keep_freed_memory_in_heap).
//   CGAL     read MESH; CGAL::Polygon_mesh_processing::isotropic_remeshing
//            (number_of_iterations N, default 3; CGAL's own border handling)
//            at a target edge length L; write OUT.glb. L is searched as in
//            quality_bench (search_edge_length, cgal_remeshing.hpp: each try
//            its own child) until the vertex count is within --tolerance %
//            (default 3) of geodual's output; the time reported is that of
//            the one run at the L found, not of the search. CGAL's remeshing
//            runs on one thread, with glibc's malloc as a program that calls
//            it has it; --cgal-kept-heap tunes it as geodual's.
//
// With --max-error PCT, also at every T, after the default job:
//
//   geodual --max-error           the same job under an error bound of PCT %
//                                 (`geodual remesh MESH --sites n --max-error PCT
//                                 -o OUT.glb`: statistics on, as the bound needs
//                                 them), each remesh after the first refined
//                                 locally (RemeshPipelineOptions::refine_locally);
//   geodual --max-error, global   the same with every site relaxed again
//                                 (--refine-globally).
//
//            Their notes give the remeshes made, whether the bound held, and
//            the time over the default job's at the same T.
//
// Timing: wall and CPU seconds from the file to the written output, for
// both. Peak RSS: the child's high-water mark at the end of that, which
// includes what the child inherited from this process (which keeps no mesh).
// Quality: geodual::quality::compare_meshes(input, output) after the timing
// (--samples points per side, default 10^6; all threads), for geodual once
// (the outputs are the same for every T). H and RMS are in % of the input's
// bounding-box diagonal.
//
// Output on stdout: one JSON object per row as each row is done (lines that
// start with '{'), then one Markdown table of all rows. A run that fails
// (an exception, the time limit, out of memory) is a row that says why, and
// the exit status is 1, as it is when the outputs of two T differ.

#include "bench_support.hpp"
#include "cgal_remeshing.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/pipeline/heap.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/pipeline/report_json.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace geodual::bench {
namespace {

struct Options {
  std::vector<std::int64_t> site_counts = {5000};
  std::vector<std::int64_t> threads = {1, 2};
  ComparisonOptions comparison;      ///< CGAL's remesh and search, the statistics, the time limit
  std::filesystem::path output_dir;  ///< empty: a temporary folder, removed at the end
  bool cgal_kept_heap = false;       ///< CGAL's runs keep freed memory in the heap too
  double max_error_pct = 0;          ///< > 0: the jobs under this error bound too
  std::vector<std::filesystem::path> meshes;
};

/// One row of the table: a geodual run at one thread count, or CGAL's.
struct Row {
  std::string input;  ///< the file name
  std::int64_t sites = 0;
  std::string method;  ///< "geodual" or "CGAL isotropic"
  std::int64_t threads = 0;
  std::optional<RemeshRun> run;  ///< empty when it failed
  std::string failure;
  std::int64_t failed_child_rss = 0;
  std::optional<bool> same_output;  ///< geodual after the first T: the same bytes as the first T's
  double speedup = std::numeric_limits<double>::quiet_NaN();
  double cgal_length = std::numeric_limits<double>::quiet_NaN();
  int cgal_runs = 0;
  double cgal_search_seconds = std::numeric_limits<double>::quiet_NaN();
  double cgal_miss_pct = std::numeric_limits<double>::quiet_NaN();  ///< signed, of the geodual vertex count
  std::string notes;
};

Row new_row(const std::string& input, std::int64_t sites, const std::string& method, std::int64_t threads) {
  Row row;
  row.input = input;
  row.sites = sites;
  row.method = method;
  row.threads = threads;
  return row;
}

// ---------------------------------------------------------------------------
// The runs (each in a forked child)

/// geodual's jobs: the default one, and under the error bound refined
/// locally or globally.
enum class Job { plain, bounded_locally, bounded_globally };

std::string method_name(Job job) {
  switch (job) {
    case Job::plain: return "geodual";
    case Job::bounded_locally: return "geodual --max-error";
    case Job::bounded_globally: return "geodual --max-error, global";
  }
  return "";
}

/// geodual's `job` on `threads` threads, file to file (see the file
/// comment); the figures after the timing when `figures`.
RemeshRun run_geodual(const std::filesystem::path& mesh, std::int64_t sites, std::int64_t threads, Job job,
                      const std::filesystem::path& output, bool figures, const Options& options) {
  RemeshRun run;
  pipeline::keep_freed_memory_in_heap();  // as the CLI's main does
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  std::optional<pipeline::RemeshPipelineResult> result;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    pipeline::RemeshPipelineOptions pipeline_options;  // the CLI's defaults
    pipeline_options.sites = sites;
    pipeline_options.statistics = job != Job::plain;  // --no-statistics but for the bound
    if (job != Job::plain) {
      pipeline_options.max_error_pct = options.max_error_pct;
      pipeline_options.refine_locally = job == Job::bounded_locally;
    }
    result = pipeline::run_remesh_pipeline(mesh, pipeline_options);
    // The CLI computes these for the output's extras when the statistics are off.
    const quality::TriangleQuality quality = quality::triangle_quality(result->remesh.mesh);
    write_remesh(output, result->remesh.mesh, result->attributes, pipeline::triangle_quality_json(quality).dump());
  }
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = result->remesh.mesh.num_vertices();
  run.sites_added = result->remesh.sites_added;
  run.lloyd_iterations = result->relaxation.iterations;
  run.warm_start_iterations = result->relaxation.warm_start_iterations;
  run.error_rounds = static_cast<int>(result->error_rounds.size());
  run.error_bound_met = result->error_bound_met;
  if (result->statistics) run.bound_checked_pct = result->statistics->hausdorff_pct;
  if (figures) add_figures(run, result->input.mesh, result->remesh.mesh, options.comparison.samples);
  return run;
}

/// CGAL's remesh at target edge length `length`, file to file; the figures
/// when asked for, or when the vertex count lands within the tolerance of
/// `target`.
RemeshRun run_cgal(const std::filesystem::path& mesh, double length, std::int64_t target, bool force_figures,
                   const std::filesystem::path& output, const Options& options) {
  RemeshRun run;
  if (options.cgal_kept_heap) pipeline::keep_freed_memory_in_heap();
  reset_peak_rss();
  const double cpu_start = process_cpu_seconds();
  const auto start = Clock::now();
  const io::LoadedMesh input = io::read_mesh(mesh);
  const TriangleMesh remeshed = cgal_isotropic_remesh(input.mesh, length, options.comparison.cgal);
  write_remesh(output, remeshed);
  run.seconds = seconds_since(start);
  run.cpu_seconds = process_cpu_seconds() - cpu_start;
  run.peak_rss = peak_rss_bytes().value_or(0);
  run.vertices = remeshed.num_vertices();
  if (force_figures || miss_pct(run.vertices, target) <= options.comparison.tolerance_pct) {
    add_figures(run, input.mesh, remeshed, options.comparison.samples);
  }
  return run;
}

/// Whether two files hold the same bytes (false when either cannot be read).
bool same_bytes(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::ifstream in_a(a, std::ios::binary), in_b(b, std::ios::binary);
  if (!in_a || !in_b) return false;
  return std::equal(std::istreambuf_iterator<char>(in_a), std::istreambuf_iterator<char>(),
                    std::istreambuf_iterator<char>(in_b), std::istreambuf_iterator<char>());
}

/// Of one geodual job, its first run that succeeded (the later T are
/// checked for the same bytes and timed against it).
struct JobRuns {
  std::optional<std::filesystem::path> first_output;  ///< of the first T that succeeded
  std::optional<double> first_seconds;
  std::int64_t first_threads = 0;
  std::optional<RemeshRun> figures_of_first;  ///< the first run that measured the figures
};

/// The rows of one mesh and site count: geodual's jobs at every T, then CGAL.
std::vector<Row> measure(const std::filesystem::path& mesh, double area, std::int64_t sites,
                         const std::filesystem::path& output_dir, const Options& options) {
  ChildLimits limits;
  limits.time_limit_seconds = options.comparison.time_limit_seconds;
  const std::string name = mesh.filename().string();
  const std::string stem = mesh.stem().string() + "-" + std::to_string(sites);
  std::vector<Row> rows;
  std::optional<std::int64_t> target;
  std::vector<Job> jobs = {Job::plain};
  if (options.max_error_pct > 0) jobs.insert(jobs.end(), {Job::bounded_locally, Job::bounded_globally});
  std::vector<JobRuns> job_runs(jobs.size());
  std::vector<std::pair<std::int64_t, double>> plain_seconds;  // per T
  for (const std::int64_t threads : options.threads) {
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      const Job job = jobs[j];
      auto& [first_output, first_seconds, first_threads, figures_of_first] = job_runs[j];
      Row row = new_row(name, sites, method_name(job), threads);
      const std::filesystem::path output =
          output_dir / (stem + "-geodual-" + std::to_string(j) + "-t" + std::to_string(threads) + ".glb");
      std::cerr << "speed_bench:   " << method_name(job) << " " << sites << " sites, " << threads
                << (threads == 1 ? " thread\n" : " threads\n");
      const bool figures = !figures_of_first;
      const ChildOutcome outcome = run_in_child(
          limits, [&] { return to_bytes(run_geodual(mesh, sites, threads, job, output, figures, options)); });
      if (outcome.status != ChildOutcome::Status::ok) {
        row.failure = outcome.message;
        row.failed_child_rss = outcome.child_max_rss_bytes;
        rows.push_back(std::move(row));
        continue;
      }
      RemeshRun run = from_bytes<RemeshRun>(outcome.payload);
      if (first_output) row.same_output = same_bytes(*first_output, output);
      if (figures_of_first && row.same_output == true) {  // measured once for the same mesh
        run.output = figures_of_first->output;
        run.input = figures_of_first->input;
        run.has_figures = true;
      } else if (run.has_figures) {
        figures_of_first = run;
      }
      if (run.lloyd_iterations > 0 || run.warm_start_iterations > 0) {
        row.notes = std::to_string(run.warm_start_iterations) + " warm-start steps, " +
                    std::to_string(run.lloyd_iterations) + " Lloyd iteration(s)";
      }
      if (run.sites_added > 0) {
        row.notes += (row.notes.empty() ? "" : ", ") + ("+" + std::to_string(run.sites_added) + " repair sites");
      }
      if (first_output) {
        row.speedup = *first_seconds / run.seconds;
        const std::string first = std::to_string(first_threads) + (first_threads == 1 ? " thread" : " threads");
        row.notes = *row.same_output ? "the same bytes as on " + first : "OUTPUT DIFFERS from the one on " + first;
      } else {
        first_output = output;
        first_seconds = run.seconds;
        first_threads = threads;
        if (job == Job::plain) target = run.vertices;
      }
      if (job == Job::plain) {
        plain_seconds.emplace_back(threads, run.seconds);
      } else {
        std::string bound = std::to_string(run.error_rounds) + " remeshes, H " + fixed(run.bound_checked_pct, 3) +
                            (run.error_bound_met ? " % <= " : " % > ") + fixed(options.max_error_pct, 3) + " %";
        for (const auto& [t, seconds] : plain_seconds) {
          if (t == threads) bound += ", " + fixed(run.seconds / seconds, 2) + "x the default job";
        }
        row.notes = bound + "; " + row.notes;
      }
      row.run = run;
      rows.push_back(std::move(row));
    }
  }

  Row cgal = new_row(name, sites, "CGAL isotropic", 1);
  const std::int64_t vertices = target.value_or(sites);
  const std::filesystem::path output = output_dir / (stem + "-cgal.glb");
  std::cerr << "speed_bench:   CGAL isotropic_remeshing to " << vertices << " vertices\n";
  const EdgeLengthSearchResult<RemeshRun> search = search_edge_length<RemeshRun>(
      area, vertices, options.comparison.max_runs, "speed_bench:   ", [&](double length, bool force_figures) {
        return run_in_child(limits,
                            [&] { return to_bytes(run_cgal(mesh, length, vertices, force_figures, output, options)); });
      });
  cgal.cgal_runs = search.runs;
  cgal.cgal_search_seconds = search.search_seconds;
  if (search.result) {
    cgal.run = search.result;
    cgal.cgal_length = search.length;
    cgal.cgal_miss_pct = 100.0 * (static_cast<double>(search.result->vertices) / static_cast<double>(vertices) - 1.0);
    cgal.notes = "L=" + scientific(search.length, 4) + ", " + std::to_string(options.comparison.cgal.iterations) +
                 " iter, " + (cgal.cgal_miss_pct >= 0 ? "+" : "") + fixed(cgal.cgal_miss_pct, 2) + " % of " +
                 grouped(vertices) + " vertices; L found in " + std::to_string(search.runs) + " runs (" +
                 fixed(search.search_seconds, 1) + " s)";
    if (std::abs(cgal.cgal_miss_pct) > options.comparison.tolerance_pct) cgal.notes += ", NOT within the tolerance";
  } else {
    cgal.failure = search.failure;
    cgal.failed_child_rss = search.failed_child_rss;
  }
  rows.push_back(std::move(cgal));
  return rows;
}

// ---------------------------------------------------------------------------
// Output

/// geodual's time over CGAL's for the geodual rows of one mesh and site
/// count (NaN where either is missing).
double time_ratio(const Row& row, const std::vector<Row>& group) {
  if (row.method == "CGAL isotropic" || !row.run) return std::numeric_limits<double>::quiet_NaN();
  const Row& cgal = group.back();
  return cgal.run ? row.run->seconds / cgal.run->seconds : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::ordered_json row_json(const Row& row, double ratio_to_cgal) {
  nlohmann::ordered_json json;
  json["input"] = row.input;
  json["sites"] = row.sites;
  json["method"] = row.method;
  json["threads"] = row.threads;
  json["ok"] = row.run.has_value();
  json["error"] = row.run ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(row.failure);
  if (row.run) {
    const RemeshRun& run = *row.run;
    const QualityFigures& f = run.output;
    json["vertices"] = run.vertices;
    json["faces"] = run.has_figures ? nlohmann::ordered_json(f.faces) : nlohmann::ordered_json(nullptr);
    json["q_min"] = f.q_min;
    json["q_avg"] = f.q_avg;
    json["theta_min_deg"] = f.theta_min_deg;
    json["pct_angles_lt30"] = f.pct_angles_lt30;
    json["pct_valence6"] = f.pct_valence6;
    json["hausdorff_pct"] = f.hausdorff_pct;
    json["rms_pct"] = f.rms_pct;
    json["seconds"] = run.seconds;
    json["cpu_seconds"] = run.cpu_seconds;
    json["peak_rss_bytes"] = run.peak_rss;
  } else {
    json["peak_rss_bytes"] = row.failed_child_rss;
  }
  json["time_over_cgal"] = ratio_to_cgal;
  json["speedup"] = row.speedup;
  json["same_output"] = row.same_output ? nlohmann::ordered_json(*row.same_output) : nlohmann::ordered_json(nullptr);
  if (row.method == "CGAL isotropic") {
    json["cgal_edge_length"] = row.cgal_length;
    json["cgal_miss_pct"] = row.cgal_miss_pct;
    json["cgal_search_runs"] = row.cgal_runs;
    json["cgal_search_seconds"] = row.cgal_search_seconds;
  }
  json["load"] = load_average();
  return json;
}

/// row_json on one line of stdout.
void print_json(const Row& row, double ratio_to_cgal) {
  std::cout << row_json(row, ratio_to_cgal).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace)
            << '\n';
}

TextTable make_table() {
  return TextTable({{"input", TextTable::Align::left},
                    {"method", TextTable::Align::left},
                    {"threads"},
                    {"V"},
                    {"Qmin"},
                    {"Qavg"},
                    {"min angle"},
                    {"% <30 deg"},
                    {"H %"},
                    {"RMS %"},
                    {"time s"},
                    {"CPU s"},
                    {"peak MiB"},
                    {"time / CGAL"},
                    {"speed-up"},
                    {"notes", TextTable::Align::left}});
}

void add_table_row(TextTable& table, const Row& row, bool first_of_group, double ratio_to_cgal) {
  const std::string input = !first_of_group ? ""
                            : row.sites > 0 ? row.input + " " + grouped(row.sites) + " sites"
                                            : row.input;
  const std::string method = row.method == "geodual" ? "**geodual**" : row.method;
  if (!row.run) {
    std::vector<std::string> cells(16, "-");
    cells[0] = input;
    cells[1] = method;
    if (row.threads > 0) cells[2] = std::to_string(row.threads);
    if (row.failed_child_rss > 0) cells[12] = mebibytes(row.failed_child_rss);
    cells[15] = "failed: " + row.failure;
    table.add_row(std::move(cells));
    return;
  }
  const RemeshRun& run = *row.run;
  const QualityFigures& f = run.output;
  const bool figures = run.has_figures;
  table.add_row({input, method, std::to_string(row.threads), grouped(run.vertices), figures ? fixed(f.q_min, 3) : "-",
                 figures ? fixed(f.q_avg, 3) : "-", figures ? fixed(f.theta_min_deg, 1) : "-",
                 figures ? fixed(f.pct_angles_lt30, 2) : "-", figures ? fixed(f.hausdorff_pct, 3) : "-",
                 figures ? fixed(f.rms_pct, 4) : "-", fixed(run.seconds, 2), fixed(run.cpu_seconds, 2),
                 mebibytes(run.peak_rss), std::isnan(ratio_to_cgal) ? "-" : fixed(ratio_to_cgal, 2) + "x",
                 std::isnan(row.speedup) ? "-" : fixed(row.speedup, 2) + "x", row.notes});
}

/// A folder of its own for the outputs when --output-dir is not given.
std::filesystem::path temporary_folder() {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("speed_bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  return folder;
}

int run_benchmark(const Options& options) {
  std::cout << "machine: " << cpu_model() << ", " << std::thread::hardware_concurrency() << " hardware threads, load "
            << load_average() << "\n";
  std::cout << "options: geodual's default job (as `geodual remesh MESH --sites N --no-statistics -o OUT.glb`) on ";
  for (std::size_t i = 0; i < options.threads.size(); ++i) std::cout << (i ? "," : "") << options.threads[i];
  std::cout << " threads; CGAL isotropic_remeshing " << options.comparison.cgal.iterations
            << " iterations at the vertex count within " << options.comparison.tolerance_pct << " %; "
            << grouped(options.comparison.samples) << " samples per side\n";
  const bool temporary = options.output_dir.empty();
  const std::filesystem::path output_dir = temporary ? temporary_folder() : options.output_dir;
  if (!temporary) std::filesystem::create_directories(output_dir);

  std::vector<std::vector<Row>> groups;
  int failures = 0;
  for (const auto& path : options.meshes) {
    double area = 0;
    try {
      // Read here for the area only (the children read the file themselves).
      const io::LoadedMesh input = io::read_mesh(path);
      area = surface_area(input.mesh);
      std::cerr << "speed_bench: " << path.filename().string() << " (" << input.mesh.num_vertices() << " vertices, "
                << input.mesh.num_faces() << " faces)\n";
    } catch (const std::exception& e) {
      Row row = new_row(path.filename().string(), 0, "read", 0);
      row.failure = e.what();
      print_json(row, std::numeric_limits<double>::quiet_NaN());
      groups.push_back({std::move(row)});
      ++failures;
      continue;
    }
    for (const std::int64_t sites : options.site_counts) {
      std::vector<Row> rows = measure(path, area, sites, output_dir, options);
      for (const Row& row : rows) {
        if (!row.run || row.same_output == false) ++failures;
        print_json(row, time_ratio(row, rows));
      }
      std::cout.flush();
      groups.push_back(std::move(rows));
    }
  }
  if (temporary) {
    std::error_code ignored;
    std::filesystem::remove_all(output_dir, ignored);
  }

  std::cout << "\nload at the end " << load_average() << "\n\n";
  TextTable table = make_table();
  for (const std::vector<Row>& rows : groups) {
    for (std::size_t i = 0; i < rows.size(); ++i) add_table_row(table, rows[i], i == 0, time_ratio(rows[i], rows));
  }
  table.print(std::cout);
  return failures == 0 ? 0 : 1;
}

// ---------------------------------------------------------------------------
// Command line

constexpr const char* usage =
    "usage: speed_bench [--sites 5000] [--threads 1,2] [--cgal-iterations N] [--tolerance PCT] [--max-runs R]\n"
    "                   [--samples S] [--time-limit S] [--output-dir DIR] [--cgal-kept-heap] [--max-error PCT]\n"
    "                   [MESH...]\n"
    "geodual's default job (geodual remesh MESH --sites N --no-statistics -o OUT.glb) on each thread count,\n"
    "and CGAL's isotropic_remeshing at the same vertex count within PCT % (default 3): time, CPU time,\n"
    "peak memory and quality. Prints one JSON object per row, then a Markdown table.\n"
    "--output-dir DIR keeps the outputs there (default: a temporary folder, removed).\n"
    "--cgal-kept-heap: CGAL's runs keep freed memory in the heap, as geodual's (and its CLI's) do.\n"
    "--max-error PCT: also the job under this error bound (geodual remesh ... --max-error PCT), refined locally\n"
    "and globally (--refine-globally).\n"
    "default meshes: examples/data/bunny.ply tests/data/armadillo_86k.ply tests/data/fertility.ply\n";

Options parse_options(int argc, char** argv) {
  Options options;
  options.meshes = parse_command_line(argc, argv, usage, [&](const std::string& word, const NextValue& value) {
    if (word == "--sites") {
      options.site_counts = parse_integer_list(word, value(), 4, 100'000'000);
    } else if (word == "--threads") {
      options.threads = parse_integer_list(word, value(), 1, 4096);
    } else if (word == "--output-dir") {
      options.output_dir = value();
    } else if (word == "--cgal-kept-heap") {
      options.cgal_kept_heap = true;
    } else if (word == "--max-error") {
      options.max_error_pct = parse_number(word, value());
      if (!(options.max_error_pct > 0 && options.max_error_pct <= 100)) {
        throw UsageError("--max-error: expected a number in (0, 100] (% of the diagonal)");
      }
    } else {
      return parse_comparison_option(word, value, options.comparison);
    }
    return true;
  });
  if (options.meshes.empty()) {
    options.meshes = {"examples/data/bunny.ply", "tests/data/armadillo_86k.ply", "tests/data/fertility.ply"};
  }
  return options;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "speed_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
