// geodual remesh MESH -o OUT (--sites N | --edge-length L[%] | --faces N | --site-file F) [--sampling S]
//                     [--seed S] [--plain-lloyd]
//                     [--curvature-adaptation S] [--lloyd K] [--lloyd-tol T] [--geodesic-tolerance T] [--warm-start K]
//                     [--warm-start-momentum M]
//                     [--json]
//                     [--preview OUT.png]
//                     [--max-repair-rounds K]
// geodual remesh MESH... --output-dir DIR [--format glb|gltf|ply|obj] (the same options)
// The main job: a dense scan in, an isotropic mesh of about N vertices out,
// through the dual of the exact geodesic Voronoi diagram.

#include "command.hpp"
#include "geodesic_flags.hpp"
#include "option_checks.hpp"
#include "progress_bar.hpp"
#include "site_source.hpp"
#include "text_table.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/diagram_output.hpp"
#include "geodual/pipeline/feature_file.hpp"
#include "geodual/pipeline/feature_output.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/pipeline/report_json.hpp"
#include "geodual/pipeline/textured_output.hpp"
#include "geodual/pipeline/version.hpp"
#include "geodual/quality/quality_stats.hpp"
#include "geodual/remesh/remesh.hpp"

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace geodual::cli {
namespace {

/// The start of a scan's error for the batch summary: without the leading
/// "<path>: ", at most six words.
std::string first_words(std::string message, const std::string& path) {
  if (message.rfind(path + ": ", 0) == 0) message.erase(0, path.size() + 2);
  std::istringstream words(message);
  std::string word, start;
  for (int count = 0; words >> word; ++count) {
    if (count == 6) return start + " ...";
    start += (start.empty() ? "" : " ") + word;
  }
  return start;
}

/// Seconds with two decimals, for the batch summary's "time s" column.
std::string seconds_column(double seconds) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << seconds;
  return text.str();
}

/// "3 remeshes (4,000, 4,620 and 5,310 sites)".
std::string error_rounds_line(const std::vector<pipeline::ErrorRound>& rounds) {
  std::string sites;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    sites += (i == 0 ? "" : i + 1 == rounds.size() ? " and " : ", ") + with_thousands(rounds[i].sites);
  }
  return std::to_string(rounds.size()) + (rounds.size() == 1 ? " remesh (" : " remeshes (") + sites + " sites)";
}

class RemeshCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command =
        *app.add_subcommand("remesh", "Remesh a scan: the dual of the geodesic Voronoi diagram of N sites on it");
    command.footer(
        "Examples:\n  geodual remesh scan.ply --sites 4000 -o remeshed.glb --preview remeshed.png\n"
        "  geodual remesh scan.ply --edge-length 1% -o remeshed.glb\n"
        "  geodual remesh a.ply b.obj --sites 4000 --output-dir remeshed   (remeshed/a.glb, remeshed/b.glb)\n"
        "Output by extension: .glb, .gltf (statistics in asset.extras), .ply, .obj.");
    command
        .add_option("MESH", mesh_paths_,
                    "Mesh files: .ply, .obj, .off, .stl, .gltf or .glb (several need --output-dir)")
        ->required();
    CLI::Option* output =
        command.add_option("-o,--output", output_path_, "The remeshed surface: .glb, .gltf, .ply or .obj");
    CLI::Option* output_dir = command.add_option(
        "--output-dir", output_dir_, "One output per input: DIR/<input stem>.<format>; a summary table at the end");
    output->excludes(output_dir);
    command.add_option("--format", format_, "With --output-dir: what the outputs are written as")
        ->capture_default_str()
        ->check(CLI::IsMember({"glb", "gltf", "ply", "obj"}))
        ->needs(output_dir);
    command
        .add_option("--jobs", jobs_,
                    "With --output-dir: scans remeshed at once (0: as many as --threads allows); each holds its "
                    "scan in memory")
        ->check(integer_between(0, 4096))
        ->needs(output_dir);
    sites_.add_to(command);
    sites_.add_sizing_to(command);
    // Flags are named after the option fields (RemeshOptions, LloydOptions,
    // GeodesicOptions, QualityOptions); the second name of a flag is its old
    // one, kept for one release.
    command
        .add_option("--lloyd-iterations,--lloyd", options_.lloyd.iterations,
                    "Lloyd iterations towards the geodesic centroids (0: the dual of the sampled sites)")
        ->capture_default_str()
        ->check(integer_between(0, 100000));
    command
        .add_option("--lloyd-tolerance,--lloyd-tol", options_.lloyd.tolerance,
                    "Stop Lloyd (and its warm start) once a step lowers the CVT energy by less than this fraction")
        ->capture_default_str()
        ->check(finite_non_negative());
    command
        .add_option("--geodesic-tolerance", options_.lloyd.geodesic_tolerance,
                    "Stop the Lloyd iterations, each an exact geodesic diagram, once one lowers the CVT energy by "
                    "less than this fraction; after the warm start, try none where moving the sites to their cells' "
                    "centroids would gain less (0: only --lloyd-tolerance stops them)")
        ->capture_default_str()
        ->check(finite_non_negative());
    command
        .add_option("--warm-start-iterations,--warm-start", options_.lloyd.warm_start_iterations,
                    "Steps on the restricted (Euclidean) Voronoi diagram before the geodesic Lloyd iterations: "
                    "a cheap start close to a CVT (0: none)")
        ->capture_default_str()
        ->check(integer_between(0, 100000));
    command
        .add_option("--warm-start-momentum", options_.lloyd.warm_start_momentum,
                    "Each warm-start step also goes this fraction of the step before it (heavy-ball momentum: "
                    "fewer steps to the same quality; 0: none)")
        ->capture_default_str()
        ->check(number_between(0, 0.99));
    command.add_flag_callback(
        "--no-newton,--plain-lloyd", [this] { options_.lloyd.newton = false; },
        "Plain (over-relaxed) Lloyd steps instead of the default Newton-accelerated ones");
    command
        .add_option("--curvature-adaptation", curvature_adaptation_,
                    "Smaller cells where the surface bends sharply at the remesh's scale: Lloyd towards a "
                    "curvature-weighted CVT of this strength (0: uniform; 1 lowers the Hausdorff distance "
                    "at some cost in the worst triangles)")
        ->capture_default_str()
        ->check(finite_non_negative());
    command
        .add_option("--sharp-angle", features_.sampling.sharp_angle,
                    "Keep creases where the normals turn by at least this many degrees (in chains at least half a "
                    "remesh spacing long, two where they fade out) as chains of edges, corners included (0: none; "
                    "ignored with --site-file)")
        ->capture_default_str()
        ->check(number_between(0, 180));
    command
        .add_option("--continuation-angle", features_.sampling.continuation_angle,
                    "Continue those creases through edges where the normals turn by at least this many degrees "
                    "and both sides are smooth at the remesh's scale (a machined crease whose angle fades; 0, or "
                    "not below --sharp-angle: off)")
        ->capture_default_str()
        ->check(number_between(0, 180));
    command.add_flag("--pin-creases", features_.pin_short_creases,
                     "Also follow the creases at --sharp-angle too short to cut along (a fillet's coarse edges, a "
                     "crease that fades within a spacing): sites pinned on their vertices, the sites round them as "
                     "close (beyond --sites: up to twice as many on parts with many such creases), edges flipped "
                     "onto them");
    command.add_option("--feature-file", feature_file_,
                       "Also keep these edges as features, whatever their angle: one polyline of the mesh's vertex "
                       "indices per line, 'A B C ...' (0-based; '#' starts a comment line; ignored with --site-file)");
    command
        .add_option("--max-error", max_error_pct_,
                    "Remesh again with more sites where the remesh strays farther from the input than this "
                    "Hausdorff distance, in % of the bounding-box diagonal, until it does not (0: no bound). "
                    "Exit status 4, the closest remesh written, when --max-sites stops it first")
        ->capture_default_str()
        ->check(number_between(0, 100));
    command
        .add_option("--max-sites", max_sites_,
                    "With --max-error: the most sites a remesh may ask for (0: 8 times the first remesh's)")
        ->capture_default_str()
        ->check(integer_between(0, 100'000'000));
    command.add_flag("--refine-globally", refine_globally_,
                     "With --max-error: relax every site again in each remesh after the first, not only those near "
                     "the sites added (slower; the rest of the remesh then changes too)");
    command
        .add_option("--max-repair-rounds", options_.max_repair_rounds,
                    "Rounds of adding sites where the dual fails before giving up (up to as many more while each needs "
                    "fewer sites than the one before)")
        ->capture_default_str()
        ->check(integer_between(0, 1000));
    command
        .add_option("--smoothing-angle", smoothing_.smoothing_angle,
                    "Last, move the corners of triangles with an angle below this many degrees along the surface to "
                    "where the smallest angle round them is largest (chain, corner, boundary and pinned vertices "
                    "stay; 0, or --lloyd-iterations 0: none, every vertex at its site)")
        ->capture_default_str()
        ->check(number_between(0, 60));
    command.add_flag_callback(
        "--no-fitting", [this] { smoothing_.fit_deviations = false; },
        "Do not move the vertices that answer for the input's points farthest from the remesh (a crease or a "
        "scan's rim the remesh cuts off) along the surface to where that distance is least, before the "
        "smoothing");
    geodesic_.add_to(command);
    command.add_option("--preview", preview_path_, "Also render a picture of the result: .png");
    command
        .add_option("--samples-per-side,--samples", samples_,
                    "Points per side for the Hausdorff and RMS distance to the input (-1: no comparison)")
        ->capture_default_str()
        ->check(integer_between(-1, quality::max_samples_per_side));
    command.add_flag_callback(
        "--no-statistics", [this] { samples_ = -1; },
        "No comparison with the input (the same as --samples-per-side -1)");
    command.add_flag("--strict", strict_,
                     "Fail when more than 0.1 % of the input's area would be left out (scraps and flaps of "
                     "non-manifold pieces); without it, a warning");
    command.add_flag("--json", json_, "Print the statistics as one JSON object");
    command.add_flag("-q,--quiet", quiet_, "No progress line on the terminal");
    command.add_option("--report", report_path_,
                       "Also write a JSON report: options, input report, stage times and memory, Lloyd energy, "
                       "quality and distance figures");
    command
        .add_option("--color", color_,
                    "Colour the output and the preview: none (the input's colours, if any), quality (mean Q per "
                    "vertex, instead of the input's colours) or features (red at the vertices on the sharp features "
                    "kept, grey elsewhere; the preview draws the chains)")
        ->capture_default_str()
        ->check(CLI::IsMember({"none", "quality", "features"}));
    command
        .add_option("--attributes", attributes_,
                    "The input's vertex attributes (colours, normals, other scalars), interpolated at the remesh's "
                    "vertices and written where the output format has room: all or none")
        ->capture_default_str()
        ->check(CLI::IsMember({"all", "none"}));
    command
        .add_option("--compress", compress_,
                    "glTF output for the web: none, meshopt (EXT_meshopt_compression with KHR_mesh_quantization) "
                    "or draco (KHR_draco_mesh_compression); .glb and .gltf only, and only viewers with the "
                    "extension read the file (docs/formats.md)")
        ->capture_default_str()
        ->check(CLI::IsMember({"none", "meshopt", "draco"}));
    command
        .add_option("--texture-size", texture_size_,
                    "A texture atlas for the remesh, N x N texels (0: none), with the input's base colour (its "
                    "texture, else its vertex colours) baked onto it")
        ->capture_default_str()
        ->check(CLI::Range(0, 16384));
    command
        .add_option("--bake", bake_,
                    "What --texture-size bakes besides the base colour: normal (a tangent-space normal map of the "
                    "input's shading normals, with TANGENT frames), or color (the base colour only)")
        ->capture_default_str()
        ->check(CLI::IsMember({"color", "normal"}));
    command
        .add_option("--texture-format", texture_format_,
                    "The base colour texture's format: png or jpeg (the normal map is always PNG); glTF embeds "
                    "them, PLY and OBJ get them beside the output")
        ->capture_default_str()
        ->check(CLI::IsMember({"png", "jpeg"}));
    return command;
  }

  int run() override {
    sites_.validate("remesh");
    check_error_bound_flags();
    check_texture_flags();
    if (!output_dir_.empty()) return run_batch();
    if (output_path_.empty()) throw UsageError("remesh: give the output: -o OUT, or --output-dir DIR");
    if (mesh_paths_.size() > 1) {
      throw UsageError("remesh: " + std::to_string(mesh_paths_.size()) +
                       " inputs need --output-dir DIR (one output each), not -o");
    }
    const std::string& mesh_path = mesh_paths_.front();
    // Every output checked before any work: nothing is written unless all can be.
    check_compression(output_path_);
    io::require_output_path(output_path_, {".glb", ".gltf", ".ply", ".obj"}, "a remesh");
    io::refuse_to_overwrite_inputs(output_path_, {mesh_path, sites_.file(), feature_file_});
    for (const std::filesystem::path& side : texture_files(output_path_)) {
      io::refuse_to_overwrite_inputs(side, {mesh_path, sites_.file(), feature_file_});
      // Nor may the remesh's own outputs overwrite each other.
      for (const std::string& other : {preview_path_, report_path_}) {
        if (!other.empty() && std::filesystem::path(other).lexically_normal() == side.lexically_normal()) {
          throw UsageError("remesh: " + other + " is also where the texture of " + output_path_ +
                           " goes; name it otherwise");
        }
      }
    }
    if (!preview_path_.empty()) {
      io::require_output_path(preview_path_, {".png"}, "a preview");
      io::refuse_to_overwrite_inputs(preview_path_, {mesh_path, sites_.file(), feature_file_});
    }
    if (!report_path_.empty()) {
      io::require_output_path(report_path_, {".json"}, "a report");
      io::refuse_to_overwrite_inputs(report_path_, {mesh_path, sites_.file(), feature_file_});
    }
    const nlohmann::ordered_json json = remesh_scan(mesh_path, output_path_, {std::cout, std::cerr, true});
    if (json_) std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
    return json["error_bound_met"] == false ? kErrorBoundMissed : 0;
  }

  /// The exit status of a remesh written whose Hausdorff distance is still
  /// above --max-error (docs/cli.md).
  static constexpr int kErrorBoundMissed = 4;

  /// --compress is for glTF outputs: refused, before any work, for the others.
  void check_compression(const std::string& output) const {
    const std::string extension = io::lowercase_extension(output);
    if (compress_ != "none" && extension != ".glb" && extension != ".gltf") {
      throw UsageError("remesh: --compress " + compress_ + " compresses glTF; " + output +
                       " is not .glb or .gltf (write .glb, or drop --compress)");
    }
  }

  io::GltfCompression compression() const {
    return compress_ == "meshopt" ? io::GltfCompression::meshopt
           : compress_ == "draco" ? io::GltfCompression::draco
                                  : io::GltfCompression::none;
  }

  /// --bake and --texture-format need --texture-size; refused before any work.
  void check_texture_flags() const {
    if (texture_size_ > 0 && texture_size_ < 64) {
      throw UsageError("remesh: --texture-size " + std::to_string(texture_size_) + " is too small: at least 64");
    }
    if (texture_size_ == 0 && (bake_ != "color" || texture_format_ != "png")) {
      throw UsageError("remesh: --bake and --texture-format are for the texture atlas: give --texture-size N too");
    }
  }

  io::ImageFormat texture_format() const {
    return texture_format_ == "jpeg" ? io::ImageFormat::jpeg : io::ImageFormat::png;
  }

  /// The files a textured output writes beside `output` (none without --texture-size).
  std::vector<std::filesystem::path> texture_files(const std::string& output) const {
    if (texture_size_ == 0) return {};
    return textured_remesh_side_files(output, texture_format());
  }

  /// --max-error's refusals, before any work.
  void check_error_bound_flags() const {
    if (max_error_pct_ == 0) return;
    if (samples_ < 0) throw UsageError("remesh: --max-error is checked by the statistics: drop --no-statistics");
    if (!sites_.file().empty()) {
      throw UsageError("remesh: --max-error adds sites where the remesh strays: it cannot go with --site-file");
    }
  }

 private:
  /// --output-dir: every input remeshed with the same options, as many at
  /// once as --threads allows (each scan's output is the same bytes as when
  /// run alone); a failed scan is reported and the others go on; Ctrl-C
  /// stops the batch. Returns 1 if any scan failed.
  int run_batch() {
    for (const auto& [option, given] : {std::pair<const char*, bool>{"--preview", !preview_path_.empty()},
                                        {"--report", !report_path_.empty()},
                                        {"--site-file", !sites_.file().empty()},
                                        {"--feature-file", !feature_file_.empty()}}) {
      if (given) throw UsageError(std::string("remesh: ") + option + " names one file; it cannot go with --output-dir");
    }
    // Every output named and checked before any work.
    std::vector<std::string> outputs;
    std::map<std::string, std::string> input_of_stem;
    for (const std::string& mesh_path : mesh_paths_) {
      const std::string stem = std::filesystem::path(mesh_path).stem().string();
      const std::string output = (std::filesystem::path(output_dir_) / (stem + "." + format_)).string();
      const auto [known, added] = input_of_stem.emplace(stem, mesh_path);
      if (!added) {
        throw UsageError("remesh: " + known->second + " and " + mesh_path + " would both be written as " + output);
      }
      outputs.push_back(output);
    }
    for (const std::string& output : outputs) {
      check_compression(output);
      io::require_output_path(output, {".glb", ".gltf", ".ply", ".obj"}, "a remesh");
      for (const std::string& mesh_path : mesh_paths_) {
        io::refuse_to_overwrite_inputs(output, {mesh_path});
        for (const std::filesystem::path& side : texture_files(output)) {
          io::refuse_to_overwrite_inputs(side, {mesh_path});
        }
      }
    }

    // Scans run side by side, as many at once as --threads allows; each
    // one's messages are held back and printed in the order of the inputs.
    const std::size_t concurrent =
        std::min(mesh_paths_.size(),
                 jobs_ > 0 ? static_cast<std::size_t>(jobs_)
                           : tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    std::vector<ScanRun> runs(mesh_paths_.size());
    if (concurrent <= 1) {
      for (std::size_t i = 0; i < runs.size(); ++i) {
        if (interrupted()) throw Cancelled("remesh cancelled before " + mesh_paths_[i]);
        run_scan(i, outputs[i], {std::cout, std::cerr, true}, runs[i]);
        if (runs[i].cancelled) throw Cancelled("remesh cancelled");  // the scan under way wrote nothing
        if (!runs[i].error.empty()) report_error(runs[i].error);
        if (!json_ && runs[i].json) std::cout << '\n';  // a blank line after the scan's table
      }
    } else {
      run_concurrently(outputs, concurrent, runs);
    }

    ColumnTable summary({"scan", "vertices", "Qavg", "H %", "time s", "status"});
    nlohmann::ordered_json results = nlohmann::ordered_json::array();
    std::size_t failed = 0, missed = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const std::string& mesh_path = mesh_paths_[i];
      const ScanRun& scan = runs[i];
      if (scan.json) {
        const nlohmann::ordered_json& json = *scan.json;
        const bool met = json["error_bound_met"] != false;
        missed += met ? 0 : 1;
        summary.add({mesh_path, with_thousands(json["vertices"].get<std::int64_t>()),
                     significant(json["q_avg"].get<double>(), 3),
                     json.contains("hausdorff_pct") ? significant(json["hausdorff_pct"].get<double>(), 3) : "-",
                     seconds_column(scan.seconds), met ? "ok" : "above --max-error"});
        results.push_back(json);
      } else {
        ++failed;
        summary.add({mesh_path, "-", "-", "-", seconds_column(scan.seconds), first_words(scan.error, mesh_path)});
        results.push_back({{"mesh", mesh_path}, {"output", outputs[i]}, {"error", scan.error}});
      }
    }
    if (json_) {
      std::cout << results.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
    } else {
      summary.print(std::cout);
      std::cout << mesh_paths_.size() - failed << " of " << mesh_paths_.size() << " scans remeshed into " << output_dir_
                << '\n';
    }
    return failed > 0 ? 1 : missed > 0 ? kErrorBoundMissed : 0;
  }

  /// Where one scan's messages go: the terminal, or buffers in a batch.
  struct ScanStreams {
    std::ostream& out;
    std::ostream& err;
    bool progress_bar = false;
  };

  /// A batch's scan: its figures (none if it failed), why it failed, its time.
  struct ScanRun {
    std::optional<nlohmann::ordered_json> json;
    std::string error;  ///< the message, starting with the input's path
    bool cancelled = false;
    double seconds = 0;
    std::ostringstream out, err;  ///< held back for printing in order (concurrent batches)
  };

  /// Scan `i` of the batch into `output`, failures caught into `scan` (none escapes).
  void run_scan(std::size_t i, const std::string& output, const ScanStreams& streams, ScanRun& scan) const {
    const std::string& mesh_path = mesh_paths_[i];
    const auto start = std::chrono::steady_clock::now();
    try {
      scan.json = remesh_scan(mesh_path, output, streams);
    } catch (const Cancelled&) {
      scan.cancelled = true;
    } catch (const std::bad_alloc&) {
      scan.error = mesh_path + ": out of memory";
    } catch (const std::exception& error) {
      const std::string message = error.what();
      scan.error = message.rfind(mesh_path + ": ", 0) == 0 ? message : mesh_path + ": " + message;
    } catch (...) {
      scan.error = mesh_path + ": unknown error";
    }
    scan.seconds = seconds_since(start);
  }

  /// Runs the batch on `workers` threads, each taking the next scan not yet
  /// begun, and prints each scan's messages once those before it are printed.
  /// Ctrl-C cancels the scans under way (they write nothing) and those not begun.
  void run_concurrently(const std::vector<std::string>& outputs, std::size_t workers, std::vector<ScanRun>& runs) {
    std::mutex mutex;
    std::condition_variable finished;
    std::vector<std::uint8_t> done(runs.size(), 0);
    std::atomic<std::size_t> next{0};
    std::vector<std::jthread> threads;  // joined on the way out, whatever happens
    for (std::size_t w = 0; w < workers; ++w) {
      threads.emplace_back([&] {
        for (std::size_t i = next++; i < runs.size(); i = next++) {
          if (interrupted()) {
            runs[i].cancelled = true;
          } else {
            run_scan(i, outputs[i], {runs[i].out, runs[i].err, false}, runs[i]);
          }
          const std::lock_guard lock(mutex);
          done[i] = 1;
          finished.notify_all();
        }
      });
    }
    bool cancelled = false;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      std::unique_lock lock(mutex);
      finished.wait(lock, [&] { return done[i] != 0; });
      lock.unlock();
      // After Ctrl-C, the scans that finished anyway (their outputs are written) are still reported.
      cancelled = cancelled || runs[i].cancelled;
      if (runs[i].cancelled || (cancelled && !runs[i].json)) continue;
      std::cerr << runs[i].err.str();
      if (!runs[i].error.empty()) report_error(runs[i].error);
      std::cout << runs[i].out.str();
      if (!json_ && runs[i].json) std::cout << '\n';  // a blank line after the scan's table
      std::cout.flush();
    }
    threads.clear();  // joins
    if (cancelled) throw Cancelled("remesh cancelled");
  }

  /// One scan: remeshes `mesh_path` into `output_path` (and the preview and
  /// report when asked), prints its table unless --json, and returns the
  /// figures --json prints. Throws on failure, writing nothing.
  nlohmann::ordered_json remesh_scan(const std::string& mesh_path, const std::string& output_path,
                                     const ScanStreams& streams) const {
    const auto start = std::chrono::steady_clock::now();
    ProgressBar bar(quiet_ || !streams.progress_bar);
    pipeline::RemeshPipelineOptions options;
    options.sites = sites_.count();
    options.sampling = sites_.sampling_options();
    options.remesh = options_;
    if (curvature_adaptation_ > 0)
      options.remesh.curvature = remesh::CurvatureDensityOptions{.strength = curvature_adaptation_};
    options.features = features_;
    options.smoothing = smoothing_;
    geodesic_.apply(options.remesh.lloyd.voronoi.geodesic);
    options.strict = strict_;
    options.attributes = attributes_ == "all";
    options.statistics = samples_ >= 0;
    options.quality.samples_per_side = std::max<std::int64_t>(samples_, 0);
    options.max_error_pct = max_error_pct_;
    options.max_sites = max_sites_;
    options.refine_locally = !refine_globally_;
    options.texture_size = texture_size_;
    options.bake_normal_map = bake_ == "normal";
    std::string round_label;  // with --max-error: which remesh the bar shows
    options.on_error_round = [&](int round, std::int64_t sites) {
      round_label =
          "remesh " + std::to_string(round) + (sites > 0 ? " (" + with_thousands(sites) + " sites)" : "") + ": ";
    };
    options.progress = [&](pipeline::Stage stage, double fraction) {
      return bar.update(round_label + std::string(pipeline::stage_name(stage)), fraction);
    };
    io::LoadedMesh loaded = io::read_mesh(mesh_path);
    require_computable_range(loaded.mesh, mesh_path);
    // The files the input came with (an OBJ's material libraries and images) are inputs too.
    std::vector<std::filesystem::path> outputs = texture_files(output_path);
    outputs.emplace_back(output_path);
    if (!preview_path_.empty()) outputs.emplace_back(preview_path_);
    if (!report_path_.empty()) outputs.emplace_back(report_path_);
    for (const std::filesystem::path& companion : loaded.info.companion_files) {
      for (const std::filesystem::path& output : outputs) io::refuse_to_overwrite_inputs(output, {companion});
    }
    // Attributes a PLY output could not name: said now, not after the work.
    if (options.attributes && io::lowercase_extension(output_path) == ".ply") {
      if (const std::string problem = io::ply_attribute_problem(loaded.attributes); !problem.empty()) {
        throw Error(mesh_path + ": its vertex attributes cannot be written as PLY (" + problem +
                    "); remesh with --attributes none, or write glTF");
      }
    }
    if (!sites_.file().empty()) options.given_sites = sites_.sites(loaded.mesh);
    if (!feature_file_.empty()) options.features.sampling.given_edges = read_feature_file(feature_file_, loaded.mesh);
    options.edge_length = sites_.edge_length(loaded.mesh);
    options.faces = sites_.faces();
    const pipeline::RemeshPipelineResult run = pipeline::run_remesh_pipeline(std::move(loaded), options);
    const remesh::RepairedDual& result = run.remesh;
    const remesh::LloydResult& relaxation = run.relaxation;
    print_notes(mesh_path, run, options, streams.err);

    // The figures: what the remesh is, the same bytes for the same input,
    // options and seed (they go into the output's extras); then the paths,
    // times and memory for --json and --report.
    const nlohmann::ordered_json figures = pipeline::remesh_report_json(run, options);
    nlohmann::ordered_json json;
    json["mesh"] = mesh_path;
    json["output"] = output_path;
    json["compress"] = compress_;
    json["attributes"] = pipeline::attribute_list(run.attributes);
    json.update(figures);
    for (const auto& [stage, seconds] : pipeline::seconds_per_stage(run.timings)) {
      json[std::string(pipeline::stage_name(stage)) + "_s"] = seconds;
    }
    json["geodesic_s"] = relaxation.geodesic_seconds + result.geodesic_seconds;
    json["diagram_s"] = relaxation.diagram_seconds + result.diagram_seconds;
    json["lloyd_move_s"] = relaxation.move_seconds;
    json["warm_start_s"] = relaxation.warm_start_seconds;
    json["dual_s"] = result.dual_seconds;
    json["smoothing_s"] = run.smoothing.seconds;
    json["fitting_s"] = run.fitting.seconds;
    const auto write_start = std::chrono::steady_clock::now();
    VertexAttributes attributes = run.attributes;
    std::vector<std::vector<Eigen::Vector3d>> lines;
    if (color_ == "quality") {
      attributes.colors = quality_colors(result.mesh);
      attributes.color_type = ValueType::uint8;
    } else if (color_ == "features") {
      attributes.colors = pipeline::feature_colors(run);
      attributes.color_type = ValueType::uint8;
      lines = pipeline::feature_polylines(run);
    }
    // The picture first: it is the part Ctrl-C can stop, and then nothing is written.
    if (!preview_path_.empty()) write_mesh_preview(preview_path_, result.mesh, attributes.colors, still_wanted, lines);
    if (run.atlas) {
      write_textured_remesh(output_path, result.mesh, attributes,
                            {.atlas = *run.atlas, .baked = run.textures, .base_color_format = texture_format()},
                            figures.dump(), compression());
    } else {
      write_remesh(output_path, result.mesh, attributes, figures.dump(), compression());
    }
    const double write_seconds = seconds_since(write_start);
    bar.finish();
    json["write_s"] = write_seconds;
    json["time_s"] = seconds_since(start);
    json["peak_memory_bytes"] = peak_memory_bytes();
    if (!report_path_.empty()) write_report(mesh_path, run, json);

    if (!json_) print_table(mesh_path, output_path, run, options, seconds_since(start), write_seconds, streams.out);
    return json;
  }

  /// The warnings and notes of one remesh, on `err`.
  void print_notes(const std::string& mesh_path, const pipeline::RemeshPipelineResult& run,
                   const pipeline::RemeshPipelineOptions& options, std::ostream& err) const {
    const remesh::RepairedDual& result = run.remesh;
    if (!run.features_dropped_reason.empty()) {
      err << "geodual remesh: warning: " << mesh_path
          << ": the sharp features could not be kept, remeshed without them: " << run.features_dropped_reason << "\n";
    }
    if (!run.features_dropped_near.empty()) {
      const std::size_t places = run.features_dropped_near.size();
      err << "geodual remesh: warning: " << mesh_path << ": the sharp features could not all be kept, "
          << "remeshed without the creases near the " << places << (places == 1 ? " place" : " places")
          << " where the remesh that kept them failed: " << run.features_partly_dropped_reason << "\n";
    }
    if (!run.features_left_out.empty()) {
      double length = 0;
      for (const pipeline::FeatureLeftOut& stretch : run.features_left_out) length += stretch.length;
      const pipeline::FeatureLeftOut& longest = run.features_left_out.front();
      err << "geodual remesh: warning: " << mesh_path
          << ": creases left out: " << with_thousands(static_cast<std::int64_t>(run.features_left_out.size()))
          << (run.features_left_out.size() == 1 ? " stretch, " : " stretches, ") << significant(length, 3)
          << " long together; the longest " << significant(longest.length, 3) << " near ("
          << significant(longest.place.x(), 4) << ", " << significant(longest.place.y(), 4) << ", "
          << significant(longest.place.z(), 4) << ") (JSON features_left_out lists them all)\n";
    }
    if (run.surface_euler_characteristic != run.input_report.euler_characteristic ||
        run.surface_boundary_loops != run.input_report.boundary_loops) {
      err << "geodual remesh: warning: " << mesh_path
          << ": the cut to a manifold at its non-manifold edges and vertices changes the part's topology: "
          << "Euler characteristic " << run.input_report.euler_characteristic << " -> "
          << run.surface_euler_characteristic << ", boundary loops " << run.input_report.boundary_loops << " -> "
          << run.surface_boundary_loops << " (the remesh has the cut surface's)\n";
    }
    if (run.sites_added_for_topology > 0) {
      err << "geodual remesh: note: " << mesh_path << ": " << run.sites_added_reason << "\n";
    }
    if (run.sites_added_for_creases > 0) {
      err << "geodual remesh: note: " << mesh_path << ": " << run.sites_added_for_creases_reason << "\n";
    }
    if (!run.crease_pins_reason.empty()) {
      err << "geodual remesh: note: " << mesh_path << ": " << run.crease_pins_reason << "\n";
    }
    if (result.sites_added > 0 || result.sites_left_out > 0) {
      const std::string problems = remesh::problems_line(result.repair_problems);
      err << "geodual remesh: note: " << mesh_path << ": repair added " << with_thousands(result.sites_added)
          << " sites" << (result.sites_left_out > 0 ? " and left out " + with_thousands(result.sites_left_out) : "")
          << " in " << result.repair_rounds << " rounds, where the dual of the Voronoi diagram was not a valid remesh ("
          << problems << ")\n";
    }
    if (!run.error_bound_met) {
      err << "geodual remesh: warning: " << mesh_path << ": the Hausdorff distance is "
          << significant(run.statistics->hausdorff_pct, 3) << " %, above --max-error " << significant(max_error_pct_, 3)
          << " %, after " << error_rounds_line(run.error_rounds)
          << "; the closest remesh is written (raise --max-sites to go on)\n";
    }
    if (run.dropped.area_pct > options.max_dropped_area_pct) {
      err << "geodual remesh: warning: " << mesh_path << ": " << run.dropped.faces << " faces ("
          << significant(run.dropped.area_pct, 3)
          << " % of the area) left out as scraps or flaps of non-manifold pieces; --strict makes this an "
             "error\n";
    }
  }

  /// The table of one remesh that the CLI prints without --json.
  void print_table(const std::string& mesh_path, const std::string& output_path,
                   const pipeline::RemeshPipelineResult& run, const pipeline::RemeshPipelineOptions& options,
                   double total_seconds, double write_seconds, std::ostream& out) const {
    const remesh::RepairedDual& result = run.remesh;
    const remesh::LloydResult& relaxation = run.relaxation;
    const quality::TriangleQuality quality =
        run.statistics ? run.statistics->candidate : quality::triangle_quality(result.mesh);
    KeyValueTable table;
    table.add("input",
              mesh_path + " (" + with_thousands(run.input.mesh.num_vertices()) + " vertices, " +
                  with_thousands(run.input.mesh.num_faces()) + " faces" +
                  (run.surface.vertices_split > 0
                       ? ", " + with_thousands(run.surface.vertices_split) + " non-manifold vertices cut apart"
                       : std::string()) +
                  (run.dropped.faces > 0 ? ", " + with_thousands(run.dropped.faces) + " faces (" +
                                               significant(run.dropped.area_pct, 3) + " % of the area) left out"
                                         : std::string()) +
                  ")");
    table.add(
        "sites",
        with_thousands(static_cast<std::int64_t>(run.initial_sites.size()) - run.site_twins) +
            (options.edge_length > 0 ? " for edge length " + significant(options.edge_length, 3) : "") +
            (options.faces > 0 ? " for " + with_thousands(options.faces) + " faces" : "") +
            (sites_.file().empty() ? " (" + sites_.sampling() + ", seed " + std::to_string(sites_.seed()) + ")"
                                   : " (" + sites_.file() + ")") +
            (result.sites_added > 0 ? ", " + with_thousands(result.sites_added) + " added by repair" : "") +
            (result.sites_left_out > 0 ? ", " + with_thousands(result.sites_left_out) + " left out by repair" : ""));
    if (!run.features.empty()) {
      const std::string angle =
          features_.sampling.sharp_angle > 0 ? significant(features_.sampling.sharp_angle, 3) + " deg" : "";
      const std::string file = feature_file_.empty() ? "" : "the feature file's";
      const double narrowest_corner = remesh::narrowest_corner_angle(run.surface.mesh, run.features);
      table.add("features",
                with_thousands(run.features.sharp_chains) + " sharp chains (" + angle +
                    (angle.empty() || file.empty() ? "" : " and ") + file + "), " +
                    with_thousands(static_cast<std::int64_t>(run.features.corners.size())) + " corners" +
                    (narrowest_corner < 360 ? " (the narrowest " + significant(narrowest_corner, 3) + " deg)"
                                            : std::string()) +
                    ", lined with " + with_thousands(run.feature_sites) + " of the sites" +
                    (run.feature_sites_tightened > 0
                         ? " (" + with_thousands(run.feature_sites_tightened) + " of them where a crease bends)"
                         : "") +
                    (run.sites_added_near_features > 0 ? ", " + with_thousands(run.sites_added_near_features) +
                                                             " more beside them where they are closer than the spacing"
                                                       : ""));
    }
    if (run.crease_pins > 0) {
      table.add("short creases", with_thousands(run.crease_pins) + " sites pinned on them, " +
                                     with_thousands(run.crease_segments.edges) + " of their " +
                                     with_thousands(run.crease_segments.segments) + " segments followed by edges (" +
                                     with_thousands(run.crease_segments.flipped) + " flipped onto them)");
    }
    if (!relaxation.energy.empty()) {
      auto count = [](int n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); };
      table.add(
          "lloyd",
          (relaxation.warm_start_iterations > 0 ? count(relaxation.warm_start_iterations, "warm-start step") + ", then "
                                                : std::string()) +
              count(relaxation.iterations, "iteration") + " (" + count(relaxation.diagrams, "geodesic diagram") +
              "), CVT energy " + significant(relaxation.energy.front(), 5) + " -> " +
              significant(relaxation.energy.back(), 5));
    }
    if (run.fitting.vertices_moved > 0) {
      table.add("fitting", with_thousands(run.fitting.vertices_moved) +
                               (run.fitting.vertices_moved == 1 ? " vertex" : " vertices") +
                               " moved towards the input's points farthest from their triangles, " +
                               significant(100 * run.fitting.deviation_before / run.input_report.bbox_diagonal, 3) +
                               " -> " +
                               significant(100 * run.fitting.deviation_after / run.input_report.bbox_diagonal, 3) +
                               " % of the diagonal");
    }
    if (run.smoothing.vertices_moved > 0) {
      table.add("smoothing", with_thousands(run.smoothing.vertices_moved) +
                                 (run.smoothing.vertices_moved == 1 ? " vertex" : " vertices") +
                                 " moved along the surface, min angle " +
                                 significant(run.smoothing.min_angle_before, 3) + " -> " +
                                 significant(run.smoothing.min_angle_after, 3) + " deg");
    }
    table.add("output", output_path + " (" + with_thousands(result.mesh.num_vertices()) + " vertices, " +
                            with_thousands(result.mesh.num_faces()) + " faces)");
    if (const std::vector<std::string> kept = pipeline::attribute_list(run.attributes); !kept.empty()) {
      table.add("attributes", comma_list(kept) + " (interpolated)");
    }
    if (run.atlas) {
      const remesh::TextureAtlas& atlas = *run.atlas;
      std::string baked = run.textures.base_color.empty() ? "" : "base colour";
      if (!run.textures.normal_map.empty()) baked += std::string(baked.empty() ? "" : ", ") + "normal map";
      table.add("texture", std::to_string(options.texture_size) + " x " + std::to_string(options.texture_size) + ", " +
                               with_thousands(atlas.charts) + " charts covering " +
                               significant(100 * atlas.texture_used, 3) + " %, angle distortion " +
                               significant(atlas.mean_angle_distortion, 2) + " deg mean (" +
                               significant(atlas.max_angle_distortion, 2) + " max), area distortion " +
                               significant(atlas.mean_area_distortion, 2) + " mean; " +
                               (baked.empty() ? "nothing to bake (no colour in the input)" : baked + " baked"));
    }
    table.add("topology", "Euler characteristic " + std::to_string(quality.euler_characteristic) + ", " +
                              std::to_string(quality.boundary_loops) + " boundary loops, manifold");
    table.add("quality", "Qmin " + significant(quality.q_min, 3) + ", Qavg " + significant(quality.q_avg, 3) +
                             ", min angle " + significant(quality.theta_min_deg, 3) + " deg, " +
                             significant(quality.pct_angles_lt30, 3) + " % of angles < 30 deg");
    if (run.statistics) {
      table.add("distance", "Hausdorff " + significant(run.statistics->hausdorff_pct, 3) + " %, RMS " +
                                significant(run.statistics->rms_pct, 3) + " % of the bounding-box diagonal");
      if (const std::optional<quality::FeatureRecall>& features = run.statistics->features) {
        table.add(
            "feature recall",
            features->edges == 0
                ? "no sharp edge in the input (normals turning >= " + significant(features->sharp_angle_deg) + " deg)"
                : significant(features->recall_pct, 3) + " % of " + with_thousands(features->edges) +
                      " sharp edges' length, max gap " + significant(features->max_gap_pct, 3) +
                      " % of the bounding-box diagonal");
      }
    }
    if (!run.error_rounds.empty()) {
      table.add("error bound", "Hausdorff " + significant(run.statistics->hausdorff_pct, 3) + " %" +
                                   (run.error_bound_met ? " <= " : " > ") + significant(max_error_pct_, 3) +
                                   " % after " + error_rounds_line(run.error_rounds));
    }
    std::string stages;
    for (const auto& [stage, seconds] : pipeline::seconds_per_stage(run.timings)) {
      stages += (stages.empty() ? "" : ", ") + std::string(pipeline::stage_name(stage)) + " " + duration(seconds);
    }
    table.add("time", duration(total_seconds) + " (" + stages + ", write " + duration(write_seconds) + ")");
    table.add("peak memory", byte_size(static_cast<std::uintmax_t>(peak_memory_bytes())));
    if (!preview_path_.empty()) table.add("preview", preview_path_);
    table.print(out);
  }

  /// --report: everything a comparison needs, in one JSON file.
  void write_report(const std::string& mesh_path, const pipeline::RemeshPipelineResult& run,
                    const nlohmann::ordered_json& figures) const {
    nlohmann::ordered_json report;
    report["geodual_version"] = build_version();
    nlohmann::ordered_json options;
    options["sites"] = sites_.count() > 0 ? nlohmann::ordered_json(sites_.count()) : nlohmann::ordered_json(nullptr);
    options["site_file"] =
        sites_.file().empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(sites_.file());
    options["edge_length"] = sites_.edge_length_text().empty() ? nlohmann::ordered_json(nullptr)
                                                               : nlohmann::ordered_json(sites_.edge_length_text());
    options["faces"] = sites_.faces() > 0 ? nlohmann::ordered_json(sites_.faces()) : nlohmann::ordered_json(nullptr);
    options["sampling"] = sites_.sampling();
    options["seed"] = sites_.seed();
    options["lloyd_iterations"] = options_.lloyd.iterations;
    options["lloyd_tolerance"] = options_.lloyd.tolerance;
    options["geodesic_tolerance"] = options_.lloyd.geodesic_tolerance;
    options["warm_start_iterations"] = options_.lloyd.warm_start_iterations;
    options["warm_start_momentum"] = options_.lloyd.warm_start_momentum;
    options["newton"] = options_.lloyd.newton;
    options["curvature_adaptation"] = curvature_adaptation_;
    options["max_repair_rounds"] = options_.max_repair_rounds;
    options["max_error"] =
        max_error_pct_ > 0 ? nlohmann::ordered_json(max_error_pct_) : nlohmann::ordered_json(nullptr);
    options["max_sites"] = max_sites_ > 0 ? nlohmann::ordered_json(max_sites_) : nlohmann::ordered_json(nullptr);
    options["refine_globally"] = refine_globally_;
    options["sharp_angle"] = features_.sampling.sharp_angle;
    options["continuation_angle"] = features_.sampling.continuation_angle;
    options["pin_creases"] = features_.pin_short_creases;
    options["smoothing_angle"] = smoothing_.smoothing_angle;
    options["fit_deviations"] = smoothing_.fit_deviations;
    options["feature_file"] =
        feature_file_.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(feature_file_);
    options["remove_redundant_windows"] = geodesic_.remove_redundant_windows();
    options["window_memory"] = geodesic_.window_memory_mib();
    options["site_groups"] = geodesic_.site_groups();
    options["statistics"] = samples_ >= 0;
    options["samples_per_side"] = std::max<std::int64_t>(samples_, 0);
    options["strict"] = strict_;
    report["options"] = options;
    report["input"] = pipeline::mesh_report_json(run.input_report);
    report["input"]["file"] = mesh_path;
    nlohmann::ordered_json stages = nlohmann::ordered_json::array();
    for (const pipeline::StageTiming& timing : run.timings) {
      stages.push_back({{"stage", pipeline::stage_name(timing.stage)},
                        {"seconds", timing.seconds},
                        {"peak_memory_bytes", timing.peak_memory_bytes}});
    }
    report["stages"] = stages;
    report["energy_history"] = run.relaxation.energy;
    report["sites_added"] = run.remesh.sites_added;
    report["sites_left_out"] = run.remesh.sites_left_out;
    report["repair_rounds"] = run.remesh.repair_rounds;
    report["result"] = figures;
    io::write_file_atomically(report_path_, [&](std::ostream& out) {
      out << report.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
    });
  }

  std::vector<std::string> mesh_paths_;
  std::string output_path_;
  std::string output_dir_;
  std::string format_ = "glb";
  int jobs_ = 0;
  SiteSource sites_;  // blue noise (the library's default): Lloyd converges from it in fewer steps
  std::string preview_path_;
  remesh::RemeshOptions options_;
  double curvature_adaptation_ = 0;  // --curvature-adaptation: options_.curvature's strength where > 0
  remesh::FeatureRemeshOptions features_;
  remesh::RemeshSmoothingOptions smoothing_;
  GeodesicFlags geodesic_;
  std::int64_t samples_ = 1'000'000;
  double max_error_pct_ = 0;
  std::int64_t max_sites_ = 0;
  bool refine_globally_ = false;
  bool strict_ = false;
  bool json_ = false;
  bool quiet_ = false;
  std::string report_path_;
  std::string feature_file_;
  std::string color_ = "none";
  std::string attributes_ = "all";
  std::string compress_ = "none";
  int texture_size_ = 0;
  std::string bake_ = "color";
  std::string texture_format_ = "png";
};

}  // namespace

std::unique_ptr<Command> make_remesh_command() { return std::make_unique<RemeshCommand>(); }

}  // namespace geodual::cli
