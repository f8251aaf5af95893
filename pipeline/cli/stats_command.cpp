// geodual stats REFERENCE CANDIDATE [--json] [--samples N] [--seed S]
//               [--sharp-angle DEG] [--feature-tolerance PCT]
// Quality of the candidate mesh, its distance to the reference and how well
// its edges follow the reference's sharp edges: the figures remeshing papers
// and tools publish (quality/quality_stats.hpp has the exact definitions), for
// any two meshes, ours or another tool's.

#include "command.hpp"
#include "option_checks.hpp"
#include "progress_bar.hpp"
#include "text_table.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/report_json.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geodual::cli {
namespace {

std::string percent(double value) { return significant(value, 4) + "%"; }

std::string signed_percent(double value) { return (value > 0 ? "+" : "") + percent(value); }

class StatsCommand final : public Command {
 public:
  CLI::App& add_to(CLI::App& app) override {
    CLI::App& command =
        *app.add_subcommand("stats", "Quality of a mesh and its Hausdorff/RMS distance to a reference mesh");
    command.footer(
        "Example:\n  geodual stats scan.ply remeshed.ply --json\n"
        "Distances: all vertices plus N area-uniform samples per side, exact distance to the "
        "other surface;\nin % of the reference's bounding-box diagonal.\n"
        "Feature recall: the share of the reference's sharp-edge length within the tolerance of an edge of the\n"
        "candidate, and the largest distance from a sharp edge to the candidate's edges.");
    command.add_option("REFERENCE", reference_path_, "The original mesh (.ply, .obj, .off, .stl, .gltf, .glb)")
        ->required();
    command.add_option("CANDIDATE", candidate_path_, "The mesh to assess, e.g. a remesh of REFERENCE")->required();
    command.add_flag("--json", json_, "Print one JSON object instead of a table");
    command
        .add_option("--samples-per-side,--samples", options_.samples_per_side,
                    "Area-uniform samples per mesh for the distances, besides the vertices")
        ->capture_default_str()
        ->check(integer_between(0, quality::max_samples_per_side));
    command.add_option("--seed", options_.seed, "Seed for the samples")
        ->capture_default_str()
        ->check(unsigned_integer());
    command
        .add_option("--sharp-angle", options_.sharp_angle_deg,
                    "Feature recall: the reference's sharp edges are those whose faces' normals turn by at least this "
                    "many degrees (0: no feature recall)")
        ->capture_default_str()
        ->check(number_between(0, 180));
    command
        .add_option("--feature-tolerance", options_.feature_tolerance_pct,
                    "Feature recall: a point of a sharp edge is recalled within this distance of a candidate edge, "
                    "in % of the reference's bbox diagonal")
        ->capture_default_str()
        ->check(finite_positive());
    command.add_flag("-q,--quiet", quiet_, "No progress line on the terminal");
    return command;
  }

  int run() override {
    ProgressBar bar(quiet_);
    const auto read = [&bar](const std::string& path, double fraction) {
      if (!bar.update("read", fraction)) throw Cancelled("stats cancelled");
      io::LoadedMesh loaded = io::read_mesh(path);
      if (!bar.update("read", fraction + 0.5)) throw Cancelled("stats cancelled");
      return loaded;
    };
    const auto start = std::chrono::steady_clock::now();
    const io::LoadedMesh reference = read(reference_path_, 0.0);
    const io::LoadedMesh candidate = read(candidate_path_, 0.5);
    require_computable_range(reference.mesh, reference_path_);
    require_computable_range(candidate.mesh, candidate_path_);
    const double read_seconds = seconds_since(start);
    const auto stats_start = std::chrono::steady_clock::now();
    quality::QualityOptions options = options_;
    options.progress = [&bar](double fraction) { return bar.update("statistics", fraction); };
    quality::QualityReport report;
    try {
      report = quality::compare_meshes(reference.mesh, candidate.mesh, options);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& error) {
      throw Error(name_the_file(error.what()));
    }
    bar.finish();
    const double stats_seconds = seconds_since(stats_start);
    if (json_) {
      print_json(report, read_seconds, stats_seconds);
    } else {
      print_table(report, read_seconds, stats_seconds);
    }
    return 0;
  }

 private:
  /// compare_meshes says "reference mesh: ..." or "candidate mesh: ...": put
  /// the file's path there instead.
  std::string name_the_file(std::string_view message) const {
    for (const auto& [prefix, path] : {std::pair{std::string_view("reference mesh"), &reference_path_},
                                       std::pair{std::string_view("candidate mesh"), &candidate_path_}}) {
      if (message.substr(0, prefix.size()) == prefix) {
        return *path + std::string(message.substr(prefix.size()));
      }
    }
    return std::string(message);
  }

  void print_json(const quality::QualityReport& report, double read_seconds, double stats_seconds) const {
    nlohmann::ordered_json json;
    json["reference"] = reference_path_;
    json["candidate"] = candidate_path_;
    json.update(pipeline::quality_report_json(report, options_));
    json["read_s"] = read_seconds;
    json["stats_s"] = stats_seconds;
    // Paths need not be UTF-8: replace what is not rather than fail.
    std::cout << json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << '\n';
  }

  void print_table(const quality::QualityReport& report, double read_seconds, double stats_seconds) const {
    const quality::TriangleQuality& r = report.reference;
    const quality::TriangleQuality& c = report.candidate;
    KeyValueTable table;
    table.add("reference", reference_path_);
    table.add("candidate", candidate_path_);

    // Figures of each mesh: two columns, the reference's padded to one width.
    std::vector<std::pair<std::string, std::pair<std::string, std::string>>> rows;
    const auto both = [&rows](std::string key, std::string ref, std::string cand) {
      rows.push_back({std::move(key), {std::move(ref), std::move(cand)}});
    };
    const auto valence6 = [](const quality::TriangleQuality& q) {
      return q.pct_valence6 ? percent(*q.pct_valence6) + " of " + with_thousands(q.interior_vertices)
                            : std::string("no interior vertex");
    };
    const auto genus = [](const quality::TriangleQuality& q) {
      return q.genus ? significant(*q.genus) : std::string("not defined");
    };
    both("", "reference", "candidate");
    both("vertices", with_thousands(r.vertices), with_thousands(c.vertices));
    both("faces", with_thousands(r.faces), with_thousands(c.faces));
    both("degenerate faces", with_thousands(r.degenerate_faces), with_thousands(c.degenerate_faces));
    both("Q min", significant(r.q_min, 4), significant(c.q_min, 4));
    both("Q avg", significant(r.q_avg, 4), significant(c.q_avg, 4));
    both("min angle", significant(r.theta_min_deg, 4) + " deg", significant(c.theta_min_deg, 4) + " deg");
    both("mean min angle", significant(r.theta_min_avg_deg, 4) + " deg", significant(c.theta_min_avg_deg, 4) + " deg");
    both("angles < 30 deg", percent(r.pct_angles_lt30), percent(c.pct_angles_lt30));
    both("P30", percent(r.p30), percent(c.p30));
    both("valence 6 (interior)", valence6(r), valence6(c));
    both("euler characteristic", with_thousands(r.euler_characteristic), with_thousands(c.euler_characteristic));
    both("genus", genus(r), genus(c));
    both("components", with_thousands(r.components), with_thousands(c.components));
    both("boundary loops", with_thousands(r.boundary_loops), with_thousands(c.boundary_loops));
    both("non-manifold edges", with_thousands(r.nonmanifold_edges), with_thousands(c.nonmanifold_edges));
    both("area", significant(r.area), significant(c.area));
    both("volume", significant(r.volume), significant(c.volume));
    std::size_t width = 0;
    for (const auto& row : rows) width = std::max(width, row.second.first.size());
    for (auto& [key, values] : rows) {
      table.add(key.empty() ? "mesh" : key,
                values.first + std::string(width - values.first.size() + 2, ' ') + values.second);
    }

    const double diagonal = r.bbox_diagonal;
    const auto distance = [diagonal](double d) { return percent(100.0 * d / diagonal) + " (" + significant(d) + ")"; };
    table.add("hausdorff", distance(report.hausdorff));
    table.add("  reference to candidate", distance(report.hausdorff_reference_to_candidate));
    table.add("  candidate to reference", distance(report.hausdorff_candidate_to_reference));
    table.add("rms", distance(report.rms));
    table.add("area change", signed_percent(report.area_change_pct));
    table.add("volume change", report.volume_change_pct ? signed_percent(*report.volume_change_pct)
                                                        : std::string("not defined (reference volume 0)"));
    if (const std::optional<quality::FeatureRecall>& features = report.features) {
      const std::string threshold = "normals turning >= " + significant(features->sharp_angle_deg) + " deg";
      if (features->edges == 0) {
        table.add("sharp edges", "none in the reference (" + threshold + ")");
      } else {
        table.add("sharp edges", with_thousands(features->edges) + " in the reference (" + threshold + "), length " +
                                     significant(features->length));
        table.add("feature recall", percent(features->recall_pct) + " of their length within " +
                                        percent(options_.feature_tolerance_pct) + " of a candidate edge");
        table.add("feature max gap", distance(features->max_gap));
      }
    } else {
      table.add("sharp edges", "not measured (--sharp-angle 0)");
    }
    table.add("distances in", "% of the reference's bbox diagonal " + significant(diagonal));
    table.add("samples", with_thousands(options_.samples_per_side) + " per side + vertices (seed " +
                             std::to_string(options_.seed) + "): " + with_thousands(report.reference_samples) + " + " +
                             with_thousands(report.candidate_samples) + " points");
    table.add("time", duration(stats_seconds) + " (reading " + duration(read_seconds) + ")");
    table.print(std::cout);
  }

  std::string reference_path_;
  std::string candidate_path_;
  bool json_ = false;
  bool quiet_ = false;
  quality::QualityOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_stats_command() { return std::make_unique<StatsCommand>(); }

}  // namespace geodual::cli
