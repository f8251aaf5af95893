// geodual remesh and geodual voronoi: outputs read back with the right
// topology, deterministic bytes, and clean failures.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace geodual::cli_test {
namespace {

constexpr const char* genus_four = "tests/data/fertility.ply";
constexpr const char* open_scan = "examples/data/bunny.ply";

TEST(RemeshCommand, EveryOutputFormatHoldsTheRemesh) {
  ScratchFolder folder;
  const MeshReport input = analyze_mesh(io::read_mesh(open_scan).mesh);
  for (const char* extension : {".glb", ".gltf", ".ply", ".obj"}) {
    const auto out = folder.path() / (std::string("bunny") + extension);
    const CliRun run = run_cli(
        {"remesh", open_scan, "--sites", "600", "--lloyd", "1", "--samples", "10000", "-o", out.string(), "--json"});
    ASSERT_EQ(run.exit_status, 0) << run.err;
    const nlohmann::json json = nlohmann::json::parse(run.out);
    const MeshReport output = analyze_mesh(io::read_mesh(out).mesh);
    EXPECT_EQ(output.vertices, json["vertices"].get<std::int64_t>()) << extension;
    EXPECT_EQ(output.faces, json["faces"].get<std::int64_t>());
    EXPECT_EQ(json["vertices"].get<std::int64_t>(),
              600 + json["sites_added"].get<std::int64_t>() - json["sites_left_out"].get<std::int64_t>());
    EXPECT_EQ(json["repair_problems"].empty(), json["repair_rounds"].get<int>() == 0);
    EXPECT_EQ(output.euler_characteristic, input.euler_characteristic);
    EXPECT_EQ(output.boundary_loops, input.boundary_loops);
    EXPECT_EQ(output.nonmanifold_edges, 0);
    const auto energy = json["energy_history"].get<std::vector<double>>();
    ASSERT_EQ(energy.size(), json["lloyd_iterations"].get<std::size_t>() + 1);
    for (std::size_t i = 1; i < energy.size(); ++i) EXPECT_LE(energy[i], energy[i - 1]);
    for (const char* key : {"sample_s",
                            "geodesic_s",
                            "diagram_s",
                            "dual_s",
                            "write_s",
                            "time_s",
                            "peak_memory_bytes",
                            "q_min",
                            "q_avg",
                            "lloyd_iterations",
                            "warm_start_iterations",
                            "warm_start_s",
                            "energy_history",
                            "hausdorff_pct",
                            "rms_pct",
                            "relax_s",
                            "statistics_s",
                            "feature_recall_pct",
                            "feature_max_gap_pct",
                            "hausdorff_at",
                            "smoothing_angle_deg",
                            "vertices_smoothed",
                            "smoothing_s",
                            "fit_deviations",
                            "vertices_fitted",
                            "fitting_s"}) {
      EXPECT_TRUE(json.contains(key)) << key;
    }
    // Where the Hausdorff distance is reached: a point of the input or the
    // remesh, within the input's box grown by that distance.
    const auto at = json["hausdorff_at"].get<std::vector<double>>();
    ASSERT_EQ(at.size(), 3u);
    const double reach = json["hausdorff_pct"].get<double>() / 100 * input.bbox_diagonal;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(at[k], input.bbox_min[k] - reach - 1e-12);
      EXPECT_LE(at[k], input.bbox_max[k] + reach + 1e-12);
    }
  }
}

TEST(RemeshCommand, SameInputSameBytesForEverySampling) {
  ScratchFolder folder;
  for (const char* sampling : {"random", "poisson", "fps"}) {
    const auto a = folder.path() / (std::string(sampling) + "-a.ply"),
               b = folder.path() / (std::string(sampling) + "-b.ply");
    for (const auto& out : {a, b}) {
      const CliRun run = run_cli({"remesh", genus_four, "--sites", "700", "--sampling", sampling, "--seed", "3",
                                  "--lloyd", "1", "--samples", "-1", "-o", out.string()});
      ASSERT_EQ(run.exit_status, 0) << run.err;
      EXPECT_NE(run.out.find("Euler characteristic -6"), std::string::npos) << run.out;
    }
    EXPECT_EQ(slurp(a), slurp(b)) << sampling;
  }
}

TEST(RemeshCommand, SameInputSameBytesInEveryFormat) {
  // Outputs named differently, so that nothing of the path or the run (times,
  // memory) may leak into the bytes (glTF extras included).
  ScratchFolder folder;
  for (const char* extension : {".glb", ".gltf", ".ply", ".obj"}) {
    const auto a = folder.path() / (std::string("a") + extension),
               b = folder.path() / (std::string("other-b") + extension);
    for (const auto& out : {a, b}) {
      const CliRun run =
          run_cli({"remesh", genus_four, "--sites", "500", "--lloyd", "1", "--samples", "2000", "-o", out.string()});
      ASSERT_EQ(run.exit_status, 0) << run.err;
    }
    EXPECT_EQ(slurp(a), slurp(b)) << extension;
    if (std::string(extension) == ".gltf") {
      const nlohmann::json gltf = nlohmann::json::parse(slurp(a));
      EXPECT_EQ(gltf["asset"]["generator"].get<std::string>().rfind("geodual " GEODUAL_PROJECT_VERSION, 0), 0U);
      EXPECT_FALSE(gltf["asset"]["extras"].contains("time_s"));
    }
  }
}

TEST(RemeshCommand, LeftOutAreaIsReportedAndStrictRefusesIt) {
  // A 20 x 20 grid on the unit square, plus 20 lone triangles of area 0.0005
  // each: scraps (each under 0.1 % of the area), together about 1 % of it.
  ScratchFolder folder;
  TriangleMesh mesh;
  const int n = 20, lone = 20;
  const Index grid_vertices = (n + 1) * (n + 1);
  mesh.vertices.resize(grid_vertices + 3 * lone, 3);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) mesh.vertices.row(j * (n + 1) + i) << double(i) / n, double(j) / n, 0;
  }
  mesh.faces.resize(2 * n * n + lone, 3);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Index v = j * (n + 1) + i;
      mesh.faces.row(2 * (j * n + i)) << v, v + 1, v + n + 2;
      mesh.faces.row(2 * (j * n + i) + 1) << v, v + n + 2, v + n + 1;
    }
  }
  for (int k = 0; k < lone; ++k) {
    const Index p = grid_vertices + 3 * k;
    mesh.vertices.row(p) << 2 + 0.1 * k, 0, 0;
    mesh.vertices.row(p + 1) << 2.01 + 0.1 * k, 0, 0;
    mesh.vertices.row(p + 2) << 2 + 0.1 * k, 0.1, 0;
    mesh.faces.row(2 * n * n + k) << p, p + 1, p + 2;
  }
  const auto input = folder.path() / "grid-and-scraps.ply";
  io::write_ply(input, mesh);
  const double scraps_pct = 100 * (lone * 0.0005) / (1 + lone * 0.0005);

  const auto out = folder.path() / "out.glb";
  const CliRun run = run_cli(
      {"remesh", input.string(), "--sites", "60", "--lloyd", "0", "--samples", "-1", "-o", out.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["dropped_faces"].get<int>(), lone);
  EXPECT_NEAR(json["dropped_area_pct"].get<double>(), scraps_pct, 1e-9);
  EXPECT_NE(run.err.find("warning"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("grid-and-scraps.ply"), std::string::npos) << run.err;

  const auto strict_out = folder.path() / "strict.glb";
  const CliRun strict = run_cli({"remesh", input.string(), "--sites", "60", "--lloyd", "0", "--samples", "-1",
                                 "--strict", "-o", strict_out.string()});
  EXPECT_NE(strict.exit_status, 0);
  EXPECT_NE(strict.err.find("strict"), std::string::npos) << strict.err;
  EXPECT_FALSE(std::filesystem::exists(strict_out));
}

TEST(RemeshCommand, NewtonStepsByDefaultPlainLloydOnRequest) {
  ScratchFolder folder;
  auto remesh = [&](std::vector<std::string> extra) {
    std::vector<std::string> arguments = {"remesh",
                                          open_scan,
                                          "--sites",
                                          "800",
                                          "--lloyd",
                                          "4",
                                          "--lloyd-tol",
                                          "0",
                                          "--geodesic-tolerance",
                                          "0",
                                          "--warm-start",
                                          "0",
                                          "--samples",
                                          "-1",
                                          "-o",
                                          (folder.path() / "out.ply").string(),
                                          "--json",
                                          "--report",
                                          (folder.path() / "report.json").string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const CliRun run = run_cli(arguments);
    EXPECT_EQ(run.exit_status, 0) << run.err;
    nlohmann::json report = nlohmann::json::parse(slurp(folder.path() / "report.json"));
    return std::pair(nlohmann::json::parse(run.out), report);
  };
  const auto [newton, newton_report] = remesh({});
  const auto [plain, plain_report] = remesh({"--plain-lloyd"});
  EXPECT_EQ(newton["sampling"], "poisson");  // remesh starts from blue noise
  EXPECT_EQ(newton_report["options"]["newton"], true);
  EXPECT_EQ(newton_report["geodual_version"].get<std::string>().rfind(GEODUAL_PROJECT_VERSION, 0), 0U);
  EXPECT_EQ(plain_report["options"]["newton"], false);
  EXPECT_EQ(newton["lloyd_iterations"], 4);
  EXPECT_EQ(plain["lloyd_iterations"], 4);
  EXPECT_GE(newton["lloyd_diagrams"].get<int>(), 5);  // the first diagram, then one per iteration at least
  EXPECT_EQ(newton["energy_history"][0], plain["energy_history"][0]);  // the same sites to start from
  EXPECT_LT(newton["energy_history"][4].get<double>(), plain["energy_history"][4].get<double>());
}

TEST(RemeshCommand, CurvatureAdaptationOnRequest) {
  ScratchFolder folder;
  auto remesh = [&](std::vector<std::string> extra) {
    std::vector<std::string> arguments = {"remesh",
                                          open_scan,
                                          "--sites",
                                          "800",
                                          "--lloyd",
                                          "2",
                                          "--samples",
                                          "-1",
                                          "-o",
                                          (folder.path() / "out.ply").string(),
                                          "--json",
                                          "--report",
                                          (folder.path() / "report.json").string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const CliRun run = run_cli(arguments);
    EXPECT_EQ(run.exit_status, 0) << run.err;
    return std::pair(nlohmann::json::parse(run.out), nlohmann::json::parse(slurp(folder.path() / "report.json")));
  };
  const auto [uniform, uniform_report] = remesh({});
  const auto [adapted, adapted_report] = remesh({"--curvature-adaptation", "1"});
  EXPECT_EQ(uniform_report["options"]["curvature_adaptation"], 0.0);
  EXPECT_EQ(adapted_report["options"]["curvature_adaptation"], 1.0);
  EXPECT_EQ(adapted["vertices"], uniform["vertices"]);  // the same vertex count
  // The same sites to start from, weighted by a density >= 1 that exceeds 1
  // where the scan bends: a larger energy.
  EXPECT_GT(adapted["energy_history"][0].get<double>(), uniform["energy_history"][0].get<double>());
  const CliRun negative = run_cli({"remesh", open_scan, "--sites", "800", "--curvature-adaptation", "-1", "-o",
                                   (folder.path() / "bad.ply").string()});
  EXPECT_EQ(negative.exit_status, 2);
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "bad.ply"));
}

TEST(RemeshCommand, WarmStartMomentumIsReportedAndBelowOne) {
  // The report records the momentum the warm start ran with; 1 and above are refused.
  ScratchFolder folder;
  auto remesh = [&](const std::string& momentum) {
    const auto report = folder.path() / "report.json";
    const CliRun run =
        run_cli({"remesh", genus_four, "--sites", "300", "--no-statistics", "--warm-start-momentum", momentum, "--json",
                 "-o", (folder.path() / "out.ply").string(), "--report", report.string()});
    EXPECT_EQ(run.exit_status, 0) << run.err;
    return std::pair(nlohmann::json::parse(run.out), nlohmann::json::parse(slurp(report)));
  };
  const auto [plain, plain_report] = remesh("0");
  const auto [heavy, heavy_report] = remesh("0.6");
  EXPECT_EQ(plain_report["options"]["warm_start_momentum"], 0.0);
  EXPECT_EQ(heavy_report["options"]["warm_start_momentum"], 0.6);
  EXPECT_NE(plain["energy_history"], heavy["energy_history"]);  // the warm start went elsewhere
  const CliRun too_much = run_cli({"remesh", genus_four, "--sites", "300", "--warm-start-momentum", "1", "-o",
                                   (folder.path() / "bad.ply").string()});
  EXPECT_EQ(too_much.exit_status, 2);
  EXPECT_NE(too_much.err.find("--warm-start-momentum"), std::string::npos) << too_much.err;
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "bad.ply"));
}

TEST(RemeshCommand, FlagsAreNamedAfterTheOptionFieldsAndTheOldNamesStillWork) {
  ScratchFolder folder;
  auto report_of = [&](std::vector<std::string> flags) {
    const auto out = folder.path() / "out.ply", report = folder.path() / "report.json";
    std::vector<std::string> arguments = {"remesh", genus_four,   "--sites",  "300",
                                          "-o",     out.string(), "--report", report.string()};
    arguments.insert(arguments.end(), flags.begin(), flags.end());
    const CliRun run = run_cli(arguments);
    EXPECT_EQ(run.exit_status, 0) << run.err;
    return nlohmann::json::parse(slurp(report))["options"];
  };
  const nlohmann::json now =
      report_of({"--lloyd-iterations", "1", "--lloyd-tolerance", "0.5", "--warm-start-iterations", "3", "--no-newton",
                 "--no-statistics", "--no-rwr", "--window-memory", "512"});
  const nlohmann::json old = report_of({"--lloyd", "1", "--lloyd-tol", "0.5", "--warm-start", "3", "--plain-lloyd",
                                        "--samples", "-1", "--no-rwr", "--window-memory", "512"});
  EXPECT_EQ(now, old);
  EXPECT_EQ(now["lloyd_iterations"], 1);
  EXPECT_EQ(now["lloyd_tolerance"], 0.5);
  EXPECT_EQ(now["warm_start_iterations"], 3);
  EXPECT_EQ(now["newton"], false);
  EXPECT_EQ(now["statistics"], false);
  EXPECT_EQ(now["remove_redundant_windows"], false);
  EXPECT_EQ(now["window_memory"], 512);
}

/// The mean length of `mesh`'s edges, each counted once.
double mean_edge_length(const TriangleMesh& mesh) {
  std::vector<std::pair<Index, Index>> edges;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double total = 0;
  for (const auto& [a, b] : edges) total += (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
  return total / static_cast<double>(edges.size());
}

TEST(RemeshCommand, AnEdgeLengthGivesThatMeanEdgeLength) {
  // L = 6 on fertility (diagonal 257): about 1,900 sites.
  ScratchFolder folder;
  const auto out = folder.path() / "sized.ply";
  const CliRun run =
      run_cli({"remesh", genus_four, "--edge-length", "6", "--samples", "-1", "-o", out.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["edge_length_target"].get<double>(), 6.0);
  EXPECT_TRUE(json["faces_target"].is_null());
  const double mean = mean_edge_length(io::read_mesh(out).mesh);
  EXPECT_GT(mean, 0.9 * 6) << json["vertices"];
  EXPECT_LT(mean, 1.1 * 6) << json["vertices"];
}

TEST(RemeshCommand, AFaceCountGivesThatManyFaces) {
  ScratchFolder folder;
  const auto out = folder.path() / "sized.ply";
  const CliRun run = run_cli({"remesh", open_scan, "--faces", "4000", "--samples", "-1", "-o", out.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["faces_target"].get<std::int64_t>(), 4000);
  EXPECT_TRUE(json["edge_length_target"].is_null());
  const Index faces = io::read_mesh(out).mesh.num_faces();
  EXPECT_GE(faces, 0.98 * 4000);
  EXPECT_LE(faces, 1.02 * 4000);
}

TEST(RemeshCommand, AnEdgeLengthInPercentIsOfTheDiagonal) {
  ScratchFolder folder;
  const double diagonal = analyze_mesh(io::read_mesh(open_scan).mesh).bbox_diagonal;
  const auto by_percent = folder.path() / "percent.ply", by_length = folder.path() / "length.ply";
  const CliRun percent = run_cli(
      {"remesh", open_scan, "--edge-length", "2%", "--lloyd", "0", "--samples", "-1", "-o", by_percent.string()});
  ASSERT_EQ(percent.exit_status, 0) << percent.err;
  // The text table says what the count is for: 2 % of 0.2502 is 0.005.
  EXPECT_NE(percent.out.find("for edge length 0.005 "), std::string::npos) << percent.out;
  std::ostringstream length;
  length << std::setprecision(17) << 0.02 * diagonal;
  const CliRun absolute = run_cli({"remesh", open_scan, "--edge-length", length.str(), "--lloyd", "0", "--samples",
                                   "-1", "-o", by_length.string(), "--json"});
  ASSERT_EQ(absolute.exit_status, 0) << absolute.err;
  const nlohmann::json json = nlohmann::json::parse(absolute.out);
  EXPECT_NEAR(json["edge_length_target"].get<double>(), 0.02 * diagonal, 1e-12 * diagonal);
  EXPECT_EQ(slurp(by_percent), slurp(by_length));  // the same sites, the same remesh
}

TEST(RemeshCommand, SitesEdgeLengthFacesAndSiteFileExcludeEachOther) {
  ScratchFolder folder;
  const std::string out = (folder.path() / "out.ply").string();
  for (const std::vector<std::string>& flags :
       std::vector<std::vector<std::string>>{{"--sites", "100", "--faces", "100"},
                                             {"--sites", "100", "--edge-length", "1%"},
                                             {"--edge-length", "1%", "--faces", "100"},
                                             {"--site-file", "sites.txt", "--faces", "100"},
                                             {"--edge-length", "0"},
                                             {"--edge-length", "-1"},
                                             {"--edge-length", "nan"},
                                             {"--edge-length", "inf"},
                                             {"--edge-length", "150%"},
                                             {"--edge-length", "%"},
                                             {"--faces", "0"},
                                             {"--faces", "1e3"}}) {
    std::vector<std::string> arguments = {"remesh", genus_four, "-o", out};
    arguments.insert(arguments.end(), flags.begin(), flags.end());
    const CliRun run = run_cli(arguments);
    EXPECT_EQ(run.exit_status, 2) << flags[0] << " " << flags[1] << ": " << run.err;
    EXPECT_LT(run.err.size(), 300u) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // None given: the message names every way.
  const CliRun none = run_cli({"remesh", genus_four, "-o", out});
  EXPECT_EQ(none.exit_status, 2);
  for (const char* flag : {"--sites", "--site-file", "--edge-length", "--faces"}) {
    EXPECT_NE(none.err.find(flag), std::string::npos) << none.err;
  }
  // Only remesh sizes its output.
  EXPECT_EQ(run_cli({"voronoi", genus_four, "--faces", "100", "-o", out}).exit_status, 2);
}

TEST(RemeshCommand, OutOfRangeValuesAreShortUsageErrors) {
  ScratchFolder folder;
  const std::string out = (folder.path() / "out.ply").string();
  for (const std::vector<std::string>& flags : std::vector<std::vector<std::string>>{{"--seed", "-1"},
                                                                                     {"--curvature-adaptation", "nan"},
                                                                                     {"--curvature-adaptation", "inf"},
                                                                                     {"--lloyd-tolerance", "-1"},
                                                                                     {"--lloyd-iterations", "-2"},
                                                                                     {"--window-memory", "0"},
                                                                                     {"--sites", "0"},
                                                                                     {"--sites", "2000000000"}}) {
    std::vector<std::string> arguments = {"remesh", genus_four, "-o", out};
    if (flags[0] != "--sites") arguments.insert(arguments.end(), {"--sites", "100"});
    arguments.insert(arguments.end(), flags.begin(), flags.end());
    const CliRun run = run_cli(arguments);
    EXPECT_EQ(run.exit_status, 2) << flags[0] << " " << flags[1] << ": " << run.err;
    EXPECT_NE(run.err.find(flags[0]), std::string::npos) << run.err;
    EXPECT_LT(run.err.size(), 300u) << run.err;  // no limit printed as a 309-digit number
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(RemeshCommand, AnOutputFolderThatTakesNoFileFailsBeforeTheWork) {
  // /proc takes no new files, even for root. 20,000 sites with Lloyd would take
  // minutes; the failure must come before the work. The input is not a mesh
  // either: a tool that read it first would fail on that instead.
  ScratchFolder folder;
  const auto broken = folder.path() / "broken.ply";
  std::ofstream(broken) << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n";
  const CliRun run = run_cli({"remesh", broken.string(), "--sites", "20000", "-o", "/proc/geodual-out.glb"});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("cannot create a file"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("broken.ply"), std::string::npos) << run.err;
}

TEST(RemeshCommand, BadRequestsFailCleanly) {
  ScratchFolder folder;
  const auto out = folder.path() / "out.glb";
  // No sites: usage error.
  CliRun run = run_cli({"remesh", genus_four, "-o", out.string()});
  EXPECT_EQ(run.exit_status, 2);
  // Unknown sampling: usage error.
  run = run_cli({"remesh", genus_four, "--sites", "100", "--sampling", "grid", "-o", out.string()});
  EXPECT_EQ(run.exit_status, 2);
  // Unsupported output extension: named, nothing written.
  const auto bad = folder.path() / "out.stl";
  run = run_cli({"remesh", genus_four, "--sites", "100", "-o", bad.string()});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("out.stl"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
  // Missing input.
  run = run_cli({"remesh", "no-such-scan.ply", "--sites", "100", "-o", out.string()});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("no-such-scan.ply"), std::string::npos);
  // Too few sites and no repair: a reason, no output.
  run = run_cli({"remesh", genus_four, "--sites", "6", "--lloyd", "0", "--max-repair-rounds", "0", "-o", out.string()});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("not a valid remesh"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // Never over the input.
  run = run_cli({"remesh", genus_four, "--sites", "100", "-o", genus_four});
  EXPECT_NE(run.exit_status, 0);
  // A smoothing angle beyond the equilateral triangle's: usage error, nothing written.
  run = run_cli({"remesh", genus_four, "--sites", "100", "--smoothing-angle", "61", "-o", out.string()});
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.err.find("--smoothing-angle"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RemeshCommand, SaysHowManySitesRepairAddedAndWhy) {
  // 100 unrelaxed sites on a genus-4 surface: the first dual loses handles,
  // so repair adds sites; the remesh says how many and why.
  ScratchFolder folder;
  const auto out = folder.path() / "out.ply";
  const CliRun run = run_cli(
      {"remesh", genus_four, "--sites", "100", "--lloyd", "0", "--samples", "-1", "-o", out.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  const auto added = json["sites_added"].get<std::int64_t>();
  ASSERT_GT(added, 0);
  EXPECT_GT(json["repair_rounds"].get<int>(), 0);
  EXPECT_FALSE(json["repair_problems"].empty());
  EXPECT_EQ(json["euler_characteristic"].get<int>(), -6);
  EXPECT_NE(run.err.find("repair added " + std::to_string(added) + " sites"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(json["repair_problems"][0].get<std::string>()), std::string::npos) << run.err;
}

TEST(VoronoiCommand, WritesCellsBoundariesAndSites) {
  ScratchFolder folder;
  const auto out = folder.path() / "cells.glb";
  const auto picture = folder.path() / "cells.png";
  const CliRun run =
      run_cli({"voronoi", genus_four, "--sites", "50", "-o", out.string(), "--preview", picture.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_EQ(json["cells"].size(), 50u);
  double area = 0;
  for (const auto& cell : json["cells"]) {
    area += cell["area"].get<double>();
    EXPECT_GE(cell["neighbours"].size(), 1u);
  }
  // The cells tile the surface.
  const TriangleMesh mesh = io::read_mesh(genus_four).mesh;
  double surface = 0;
  for (Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                          c = mesh.vertices.row(mesh.faces(f, 2));
    surface += 0.5 * (b - a).cross(c - a).norm();
  }
  EXPECT_NEAR(area, surface, 1e-9 * surface);
  for (const auto& vertex : json["voronoi_vertices"]) EXPECT_GE(vertex["sites"].size(), 3u);
  EXPECT_GT(json["total_boundary_length"].get<double>(), 0);
  // The glTF holds the mesh (read back as triangles) and the PNG was made.
  EXPECT_EQ(io::read_mesh(out).mesh.faces.rows(), io::read_mesh(genus_four).mesh.faces.rows());
  const std::string png = slurp(picture);
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

}  // namespace
}  // namespace geodual::cli_test

namespace geodual::cli_test {
namespace {

TEST(RemeshCommand, ReportAndQualityColours) {
  ScratchFolder folder;
  const auto out = folder.path() / "coloured.glb", report = folder.path() / "report.json",
             picture = folder.path() / "quality.png";
  const CliRun run =
      run_cli({"remesh", genus_four, "--sites", "500", "--lloyd", "2", "--samples", "5000", "--color", "quality",
               "--report", report.string(), "--preview", picture.string(), "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(report));
  for (const char* key : {"options", "input", "stages", "energy_history", "sites_added", "result"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["options"]["lloyd_iterations"].get<int>(), 2);
  EXPECT_EQ(json["input"]["euler_characteristic"].get<int>(), -6);
  ASSERT_GE(json["stages"].size(), 4u);
  for (const auto& stage : json["stages"]) EXPECT_GT(stage["peak_memory_bytes"].get<std::int64_t>(), 0);
  EXPECT_EQ(json["result"]["euler_characteristic"].get<int>(), -6);
  EXPECT_GT(json["result"]["q_avg"].get<double>(), 0.5);
  // The glTF carries COLOR_0 and the figures in asset.extras.
  const std::string glb = slurp(out);
  EXPECT_NE(glb.find("COLOR_0"), std::string::npos);
  EXPECT_NE(glb.find("\"extras\""), std::string::npos);
  EXPECT_NE(glb.find("q_avg"), std::string::npos);
  EXPECT_EQ(slurp(picture).substr(1, 3), "PNG");
}

TEST(RemeshCommand, FeatureColoursPaintTheCreasesKept) {
  ScratchFolder folder;
  const auto out = folder.path() / "features.glb", picture = folder.path() / "features.png";
  const CliRun run = run_cli({"remesh", "tests/data/fandisk.ply", "--sites", "800", "--sharp-angle", "60", "--samples",
                              "-1", "--color", "features", "--preview", picture.string(), "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const io::LoadedMesh written = io::read_mesh(out);
  const ColorMatrix& colors = written.attributes.colors;
  ASSERT_EQ(colors.rows(), written.mesh.num_vertices());
  Index red = 0;
  for (Index v = 0; v < colors.rows(); ++v) red += colors(v, 0) > 0.8f && colors(v, 1) < 0.2f;
  // fandisk's creases carry a good share of the vertices, but not most.
  EXPECT_GT(red, written.mesh.num_vertices() / 20);
  EXPECT_LT(red, written.mesh.num_vertices() / 2);
  EXPECT_EQ(slurp(picture).substr(1, 3), "PNG");
}

TEST(RemeshCommand, SaysWhereItLeftCreasesOutAndWhy) {
  // OpenSCAD's surface_image at 500 sites: the remesh that keeps its 87
  // creases fails at one place; the creases there are left out, the others
  // kept.
  ScratchFolder folder;
  const auto out = folder.path() / "surface_image.glb";
  const CliRun run = run_cli({"remesh", "tests/data/cad/surface_image.stl", "--sites", "500", "--samples", "-1",
                              "--json", "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_NE(run.err.find("tests/data/cad/surface_image.stl: the sharp features could not all be kept, remeshed "
                         "without the creases near the 1 place where the remesh that kept them failed: "),
            std::string::npos)
      << run.err;
  const nlohmann::json figures = nlohmann::json::parse(run.out);
  EXPECT_TRUE(figures["features_dropped_reason"].is_null());
  EXPECT_GT(figures["feature_chains"].get<int>(), 0);
  ASSERT_EQ(figures["features_dropped_near"].size(), 1u);
  ASSERT_EQ(figures["features_dropped_near"][0].size(), 3u);
  EXPECT_NE(figures["features_partly_dropped_reason"].get<std::string>().find("the faults lie near ("),
            std::string::npos);
}

/// `geodual remesh MESH --sites SITES --json -o OUT [extra...]`'s JSON, after checking it succeeded.
nlohmann::json remesh_json(const std::string& mesh, const std::string& sites, const std::filesystem::path& out,
                           const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"remesh", mesh, "--sites", sites, "--json", "-o", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliRun run = run_cli(args);
  EXPECT_EQ(run.exit_status, 0) << run.err;
  return nlohmann::json::parse(run.out);
}

TEST(RemeshCommand, KeepsTheCreasesOfAMachinedPartByDefault) {
  ScratchFolder folder;
  const auto out = folder.path() / "fandisk.glb";
  const auto remesh = [&](const std::vector<std::string>& extra) {
    return remesh_json("tests/data/fandisk.ply", "2000", out, extra);
  };
  const nlohmann::json by_default = remesh({});
  EXPECT_EQ(by_default["sharp_angle_deg"].get<double>(), 60.0);
  EXPECT_GE(by_default["feature_chains"].get<double>(), 30);  // fandisk has 35 chains
  EXPECT_TRUE(by_default["features_dropped_reason"].is_null());
  EXPECT_TRUE(by_default["features_dropped_near"].empty());
  EXPECT_TRUE(by_default["features_partly_dropped_reason"].is_null());
  // Its round creases too: where the chords at the spacing would leave them
  // by more than the recall tolerance, the sites on them and beside them are
  // closer, and the triangles keep their shape (fandisk's smallest angle
  // between two creases is 19.4 degrees).
  EXPECT_GT(by_default["feature_recall_pct"].get<double>(), 99.0);
  EXPECT_GT(by_default["sites_added_near_features"].get<double>(), 0);
  EXPECT_GT(by_default["feature_sites_tightened"].get<double>(), 0);
  EXPECT_LT(by_default["feature_sites_tightened"].get<double>(), by_default["feature_sites"].get<double>());
  EXPECT_GT(by_default["q_min"].get<double>(), 0.4);
  // That corner is reported: the remesh's smallest angle can be no wider.
  EXPECT_NEAR(by_default["feature_narrowest_corner_deg"].get<double>(), 19.4, 0.05);
  // Its creases that fade below 60 degrees are kept too, between flat sides:
  // without them they are chamfers, where the Hausdorff distance peaks.
  EXPECT_EQ(by_default["continuation_angle_deg"].get<double>(), 30.0);
  const nlohmann::json uncontinued = remesh({"--continuation-angle", "0"});
  EXPECT_LT(by_default["hausdorff_pct"].get<double>(), 0.8 * uncontinued["hausdorff_pct"].get<double>());
  // Off, the creases come out as sawtooth chamfers.
  const nlohmann::json off = remesh({"--sharp-angle", "0"});
  EXPECT_EQ(off["feature_chains"].get<double>(), 0);
  EXPECT_TRUE(off["feature_narrowest_corner_deg"].is_null());
  EXPECT_LT(off["feature_recall_pct"].get<double>(), 50.0);
  // The summary says how many of the sites on the creases are there because they bend.
  const CliRun table =
      run_cli({"remesh", "tests/data/fandisk.ply", "--sites", "2000", "--no-statistics", "-q", "-o", out.string()});
  ASSERT_EQ(table.exit_status, 0) << table.err;
  const std::string tightened = std::to_string(by_default["feature_sites_tightened"].get<std::int64_t>());  // < 1,000
  EXPECT_NE((table.out + table.err).find("(" + tightened + " of them where a crease bends)"), std::string::npos)
      << table.out << table.err;
}

TEST(RemeshCommand, PinCreasesFollowsTheCreasesTooShortToCutAlong) {
  ScratchFolder folder;
  const auto out = folder.path() / "rocker_arm.obj";
  const auto remesh = [&](const std::vector<std::string>& extra) {
    return remesh_json("tests/data/rocker_arm.ply", "1500", out, extra);
  };
  const nlohmann::json by_default = remesh({});
  EXPECT_EQ(by_default["crease_pins"].get<double>(), 0);
  const nlohmann::json pinned = remesh({"--pin-creases"});
  EXPECT_GT(pinned["crease_pins"].get<double>(), 20);
  EXPECT_GT(pinned["crease_segments_followed"].get<double>(), pinned["crease_pins"].get<double>() / 2);
  EXPECT_GT(pinned["feature_recall_pct"].get<double>(), 90.0);
  EXPECT_LT(by_default["feature_recall_pct"].get<double>(), 30.0);
  EXPECT_GT(pinned["q_min"].get<double>(), 0.3);
}

}  // namespace
}  // namespace geodual::cli_test

namespace geodual::cli_test {
namespace {

TEST(RemeshCommand, BadSideOutputsFailBeforeAnyWork) {
  ScratchFolder folder;
  const auto out = folder.path() / "out.glb";
  const auto picture = folder.path() / "picture.jpg";
  CliRun run = run_cli({"remesh", genus_four, "--sites", "100", "-o", out.string(), "--preview", picture.string()});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("picture.jpg"), std::string::npos) << run.err;
  const auto report = folder.path() / "no-such-folder" / "report.json";
  run = run_cli({"remesh", genus_four, "--sites", "100", "-o", out.string(), "--report", report.string()});
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_NE(run.err.find("does not exist"), std::string::npos) << run.err;
  run = run_cli({"voronoi", genus_four, "--sites", "20", "-o", (folder.path() / "cells.glb").string(), "--preview",
                 (folder.path() / "cells.bmp").string()});
  EXPECT_EQ(run.exit_status, 1);
  run = run_cli({"geodesic", genus_four, "--sites", "3", "-o", (folder.path() / "field.stl").string()});
  EXPECT_EQ(run.exit_status, 1);
  // Nothing at all was written.
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

/// OBJ text of unit cubes (12 triangles each, outward) at x = 0, 3, 6, ...,
/// then `extra_faces` lines.
std::string cubes_obj(int count, const std::string& extra_faces = "") {
  std::string text;
  for (int c = 0; c < count; ++c) {
    for (int k = 0; k < 8; ++k) {
      const int x = (k == 1 || k == 2 || k == 5 || k == 6) ? 1 : 0, y = (k == 2 || k == 3 || k == 6 || k == 7) ? 1 : 0;
      text += "v " + std::to_string(3 * c + x) + " " + std::to_string(y) + " " + std::to_string(k >= 4 ? 1 : 0) + "\n";
    }
  }
  const int faces[12][3] = {{1, 3, 2}, {1, 4, 3}, {5, 6, 7}, {5, 7, 8}, {1, 2, 6}, {1, 6, 5},
                            {4, 8, 7}, {4, 7, 3}, {1, 5, 8}, {1, 8, 4}, {2, 3, 7}, {2, 7, 6}};
  for (int c = 0; c < count; ++c) {
    for (const auto& f : faces) {
      text += "f " + std::to_string(f[0] + 8 * c) + " " + std::to_string(f[1] + 8 * c) + " " +
              std::to_string(f[2] + 8 * c) + "\n";
    }
  }
  return text + extra_faces;
}

TEST(RemeshCommand, SitesAddedForTopologyAreReported) {
  // Three cubes need 12 sites: 4 asked used to leave two of them out.
  ScratchFolder folder;
  const auto input = folder.write("cubes.obj", cubes_obj(3));
  const auto out = folder.path() / "cubes.ply";
  const CliRun run =
      run_cli({"remesh", input.string(), "--sites", "4", "--samples", "-1", "-q", "--json", "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["sites"].get<std::int64_t>(), 12);
  EXPECT_EQ(json["sites_added_for_topology"].get<std::int64_t>(), 8);
  EXPECT_NE(run.err.find("site count 4 raised to 12"), std::string::npos) << run.err;
  const MeshReport output = analyze_mesh(io::read_mesh(out).mesh);
  EXPECT_EQ(output.components, 3);
  EXPECT_EQ(output.euler_characteristic, 6);
  // Enough sites: none added, nothing said.
  const CliRun enough =
      run_cli({"remesh", input.string(), "--sites", "60", "--samples", "-1", "-q", "--json", "-o", out.string()});
  ASSERT_EQ(enough.exit_status, 0) << enough.err;
  EXPECT_EQ(nlohmann::json::parse(enough.out)["sites_added_for_topology"].get<std::int64_t>(), 0);
  EXPECT_EQ(enough.err.find("raised"), std::string::npos) << enough.err;
  // Closed manifold cubes: the cut changes nothing, and nothing is said of it.
  EXPECT_EQ(enough.err.find("changes the part's topology"), std::string::npos) << enough.err;
}

TEST(RemeshCommand, ReportsTheRecallOnTheCreasesAtLeastOneSpacingLong) {
  // A unit cube's twelve edges are its creases, each longer than the spacing
  // of 300 vertices: kept with the features, rounded off without them.
  ScratchFolder folder;
  const auto input = folder.write("cube.obj", cubes_obj(1));
  const auto out = folder.path() / "cube.ply";
  const auto recall = [&](const char* sharp_angle) {
    const CliRun run = run_cli({"remesh", input.string(), "--sites", "300", "--sharp-angle", sharp_angle, "--samples",
                                "20000", "-q", "--json", "-o", out.string()});
    EXPECT_EQ(run.exit_status, 0) << run.err;
    const nlohmann::json json = nlohmann::json::parse(run.out);
    const double spacing = json["feature_long_crease_length"].get<double>();
    EXPECT_GT(spacing, 0.05);
    EXPECT_LT(spacing, 0.2);
    EXPECT_EQ(json["feature_long_creases"].get<std::int64_t>(), 12);
    EXPECT_NEAR(json["feature_long_length"].get<double>(), 12.0, 1e-9);
    return json["feature_long_recall_pct"].get<double>();
  };
  EXPECT_GE(recall("60"), 99.0);
  EXPECT_LT(recall("0"), 50.0);
}

TEST(RemeshCommand, DuplicateFacesLoseNoSurface) {
  // A cube with its first face again, flipped, and its second face again:
  // the copies are left out, the cube stays closed and whole.
  ScratchFolder folder;
  const auto input = folder.write("cube.obj", cubes_obj(1, "f 1 2 3\nf 1 4 3\n"));
  const auto out = folder.path() / "cube.ply";
  const CliRun run =
      run_cli({"remesh", input.string(), "--sites", "40", "--samples", "-1", "-q", "--json", "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["dropped_faces"].get<std::int64_t>(), 2);
  EXPECT_EQ(json["dropped_area_pct"].get<double>(), 0.0);
  const MeshReport output = analyze_mesh(io::read_mesh(out).mesh);
  EXPECT_EQ(output.components, 1);
  EXPECT_EQ(output.euler_characteristic, 2);
  EXPECT_EQ(output.boundary_loops, 0);
}

TEST(RemeshCommand, LoopsMadeByTheCutAreNamedAsSuch) {
  // Three square sheets of 32 faces hinged on one edge (a non-manifold edge
  // of three faces): the cut makes three disks, whose three loops need 12
  // sites; the note says that the loops come from the cut.
  constexpr int n = 4;
  std::string obj;
  for (int sheet = 0; sheet < 3; ++sheet) {
    const double angle = 2.0943951023931953 * sheet;
    for (int j = 0; j <= n; ++j) {
      for (int i = (sheet == 0 ? 0 : 1); i <= n; ++i) {
        const double r = double(i) / n;
        obj += "v " + std::to_string(r * std::cos(angle)) + " " + std::to_string(r * std::sin(angle)) + " " +
               std::to_string(double(j) / n) + "\n";
      }
    }
  }
  // Vertex (sheet, i, j), 1-based: the hinge (i = 0) is sheet 0's.
  auto vertex = [&](int sheet, int i, int j) {
    if (i == 0) sheet = 0;
    const int first = sheet == 0 ? 0 : (n + 1) * (n + 1) + (sheet - 1) * n * (n + 1);
    const int row = sheet == 0 ? n + 1 : n;
    return first + j * row + (sheet == 0 ? i : i - 1) + 1;
  };
  for (int sheet = 0; sheet < 3; ++sheet) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const int a = vertex(sheet, i, j), b = vertex(sheet, i + 1, j), c = vertex(sheet, i + 1, j + 1),
                  d = vertex(sheet, i, j + 1);
        obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
        obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
      }
    }
  }
  ScratchFolder folder;
  const auto input = folder.write("hinge.obj", obj);
  const auto out = folder.path() / "hinge.ply";
  const CliRun run =
      run_cli({"remesh", input.string(), "--sites", "4", "--samples", "-1", "-q", "--json", "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["sites_added_for_topology"].get<std::int64_t>(), 8);
  EXPECT_NE(run.err.find("3 boundary loops"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("made by the cut to a manifold"), std::string::npos) << run.err;
  const MeshReport output = analyze_mesh(io::read_mesh(out).mesh);
  EXPECT_EQ(output.components, 3);
  EXPECT_EQ(output.boundary_loops, 3);
  // The topology changed by the cut is said on stderr and in JSON: the
  // input's and the cut surface's (three disks), which the remesh has.
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["surface_euler_characteristic"].get<std::int64_t>(), 3);
  EXPECT_EQ(json["surface_boundary_loops"].get<std::int64_t>(), 3);
  EXPECT_EQ(output.euler_characteristic, 3);
  EXPECT_TRUE(json["input_euler_characteristic"].get<std::int64_t>() != 3 ||
              json["input_boundary_loops"].get<std::int64_t>() != 3)
      << run.out;
  EXPECT_NE(run.err.find("changes the part's topology"), std::string::npos) << run.err;
}

// --- Batches: several scans, one output each in --output-dir ---------------

constexpr const char* small_scan = "tests/data/woody.ply";

/// The options every batch test remeshes with: few sites, no Lloyd, a cheap
/// comparison with the input.
std::vector<std::string> batch_options() { return {"--sites", "150", "--lloyd", "0", "--samples", "2000"}; }

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(RemeshCommand, MaxErrorRemeshesUntilTheBoundHoldsOrExitsFourWithTheClosest) {
  ScratchFolder folder;
  const auto out = folder.path() / "bounded.ply";
  // 200 sites are 2.8 % off fertility's surface: more sites where it strays.
  const std::vector<std::string> args = {"remesh", genus_four,    "--sites", "200", "--samples",
                                         "20000",  "--max-error", "1.5",     "-o",  out.string()};
  const CliRun met = run_cli(concat(args, {"--json"}));
  ASSERT_EQ(met.exit_status, 0) << met.err;
  const nlohmann::json json = nlohmann::json::parse(met.out);
  EXPECT_EQ(json["max_error_pct"].get<double>(), 1.5);
  EXPECT_TRUE(json["error_bound_met"].get<bool>());
  EXPECT_LE(json["hausdorff_pct"].get<double>(), 1.5);
  const nlohmann::json& rounds = json["error_rounds"];
  ASSERT_GE(rounds.size(), 2u);
  EXPECT_EQ(rounds[0]["sites"].get<std::int64_t>(), 200);
  EXPECT_GT(rounds[0]["hausdorff_pct"].get<double>(), 1.5);
  EXPECT_EQ(rounds.back()["hausdorff_pct"].get<double>(), json["hausdorff_pct"].get<double>());
  EXPECT_EQ(analyze_mesh(io::read_mesh(out).mesh).vertices, json["vertices"].get<std::int64_t>());

  // --refine-globally relaxes every site again after the first remesh, which
  // is the same: the later remeshes differ.
  const auto global_out = folder.path() / "global.ply";
  std::vector<std::string> global_args = args;
  global_args.back() = global_out.string();
  const CliRun global = run_cli(concat(global_args, {"--json", "--refine-globally"}));
  ASSERT_EQ(global.exit_status, 0) << global.err;
  const nlohmann::json global_json = nlohmann::json::parse(global.out);
  ASSERT_GE(global_json["error_rounds"].size(), 2u);
  EXPECT_EQ(global_json["error_rounds"][0], rounds[0]);
  EXPECT_NE(global_json["error_rounds"][1]["hausdorff_pct"], rounds[1]["hausdorff_pct"]);
  EXPECT_NE(slurp(global_out), slurp(out));

  // Stopped by the site limit: the closest remesh is written, a warning
  // says how far it is, and the exit status is 4.
  std::filesystem::remove(out);
  const CliRun missed = run_cli(concat(args, {"--max-sites", "250"}));
  EXPECT_EQ(missed.exit_status, 4) << missed.err;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_NE(missed.err.find("above --max-error 1.5 %"), std::string::npos) << missed.err;
  EXPECT_NE(missed.err.find("250 sites"), std::string::npos) << missed.err;
  EXPECT_NE(missed.out.find("error bound"), std::string::npos) << missed.out;

  // It needs the statistics and chooses the sites itself.
  const CliRun no_statistics =
      run_cli({"remesh", genus_four, "--sites", "200", "--max-error", "1", "--no-statistics", "-o", out.string()});
  EXPECT_EQ(no_statistics.exit_status, 2) << no_statistics.err;
  EXPECT_NE(no_statistics.err.find("--no-statistics"), std::string::npos) << no_statistics.err;
  const auto site_file = folder.write("sites.txt", "0\n1\n2\n3\n");
  const CliRun given =
      run_cli({"remesh", genus_four, "--site-file", site_file.string(), "--max-error", "1", "-o", out.string()});
  EXPECT_EQ(given.exit_status, 2) << given.err;
  EXPECT_NE(given.err.find("--site-file"), std::string::npos) << given.err;
}

TEST(RemeshCommand, ABatchWritesEveryOutputTheSameBytesAsSingleRuns) {
  ScratchFolder folder;
  const auto dir = folder.path() / "out";
  std::filesystem::create_directories(dir);
  // Two threads: the scans run side by side; their tables come in the inputs' order.
  const CliRun batch = run_cli(
      concat({"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--format", "ply", "--threads", "2"},
             batch_options()));
  ASSERT_EQ(batch.exit_status, 0) << batch.err;
  EXPECT_LT(batch.out.find(std::string(small_scan) + " ("), batch.out.find(std::string(genus_four) + " ("))
      << batch.out;
  // The per-scan tables, then the summary naming both scans as ok.
  const std::size_t summary = batch.out.find("scan ");
  ASSERT_NE(summary, std::string::npos) << batch.out;
  for (const char* header : {"vertices", "Qavg", "H %", "time s", "status"}) {
    EXPECT_NE(batch.out.find(header, summary), std::string::npos) << header;
  }
  for (const std::string& scan : {std::string(small_scan), std::string(genus_four)}) {
    const std::size_t row = batch.out.find("\n" + scan + " ", summary);
    ASSERT_NE(row, std::string::npos) << batch.out;
    const std::string line = batch.out.substr(row + 1, batch.out.find('\n', row + 1) - row - 1);
    EXPECT_EQ(line.substr(line.size() - 2), "ok") << line;
  }
  EXPECT_NE(batch.out.find("2 of 2 scans"), std::string::npos) << batch.out;
  // --jobs 1: one scan at a time, the same bytes (checked against the single runs below).
  const auto sequential = folder.path() / "sequential";
  std::filesystem::create_directories(sequential);
  ASSERT_EQ(run_cli(concat({"remesh", small_scan, genus_four, "--output-dir", sequential.string(), "--format", "ply",
                            "--jobs", "1"},
                           batch_options()))
                .exit_status,
            0);
  EXPECT_EQ(slurp(sequential / "woody.ply"), slurp(dir / "woody.ply"));
  EXPECT_EQ(slurp(sequential / "fertility.ply"), slurp(dir / "fertility.ply"));
  // Each output is the single run's bytes, with the same options.
  for (const auto& [scan, name] :
       {std::pair<std::string, std::string>{small_scan, "woody.ply"}, {genus_four, "fertility.ply"}}) {
    const auto single = folder.path() / name;
    const CliRun run = run_cli(concat({"remesh", scan, "-o", single.string(), "--threads", "1"}, batch_options()));
    ASSERT_EQ(run.exit_status, 0) << run.err;
    ASSERT_TRUE(std::filesystem::exists(dir / name)) << name;
    EXPECT_EQ(slurp(dir / name), slurp(single)) << name;
  }
  // The default format is .glb; --json prints one array, an object per scan.
  const CliRun json_run =
      run_cli(concat({"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--json"}, batch_options()));
  ASSERT_EQ(json_run.exit_status, 0) << json_run.err;
  const nlohmann::json json = nlohmann::json::parse(json_run.out);
  ASSERT_TRUE(json.is_array());
  ASSERT_EQ(json.size(), 2U);
  EXPECT_EQ(json[0]["mesh"], small_scan);
  EXPECT_EQ(json[0]["output"], (dir / "woody.glb").string());
  EXPECT_EQ(json[1]["mesh"], genus_four);
  EXPECT_GT(json[1]["vertices"].get<int>(), 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "woody.glb"));
  EXPECT_TRUE(std::filesystem::exists(dir / "fertility.glb"));
}

TEST(RemeshCommand, ABatchGoesOnPastAFailedScanAndExitsOne) {
  ScratchFolder folder;
  const auto dir = folder.path() / "out";
  std::filesystem::create_directories(dir);
  const auto malformed = folder.write("malformed.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0\n");
  const auto missing = folder.path() / "missing.obj";
  const CliRun run = run_cli(concat(
      {"remesh", missing.string(), small_scan, malformed.string(), "--output-dir", dir.string()}, batch_options()));
  EXPECT_EQ(run.exit_status, 1) << run.err;
  // The good scan's output is there, the bad ones' are not.
  EXPECT_TRUE(std::filesystem::exists(dir / "woody.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "missing.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "malformed.glb"));
  // Each error names its file; the summary says which failed.
  EXPECT_NE(run.err.find(missing.string()), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(malformed.string()), std::string::npos) << run.err;
  const std::size_t summary = run.out.find("scan ");
  ASSERT_NE(summary, std::string::npos) << run.out;
  for (const std::string& scan : {missing.string(), std::string(small_scan), malformed.string()}) {
    const std::size_t row = run.out.find("\n" + scan + " ", summary);
    ASSERT_NE(row, std::string::npos) << scan << "\n" << run.out;
    const std::string line = run.out.substr(row + 1, run.out.find('\n', row + 1) - row - 1);
    EXPECT_EQ(line.substr(line.size() - 2) == "ok", scan == small_scan) << line;
  }
  EXPECT_NE(run.out.find("1 of 3 scans"), std::string::npos) << run.out;
}

TEST(RemeshCommand, BatchUsageErrorsComeBeforeAnyWork) {
  ScratchFolder folder;
  const auto dir = folder.path();
  const auto other = folder.path() / "elsewhere";
  std::filesystem::create_directories(other);
  std::filesystem::copy_file(small_scan, other / "woody.ply");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      // Two inputs with the same stem would write the same output.
      {{"remesh", small_scan, (other / "woody.ply").string(), "--output-dir", dir.string()}, "woody"},
      // Several inputs need --output-dir, and -o excludes it.
      {{"remesh", small_scan, genus_four, "-o", (dir / "out.glb").string()}, "--output-dir"},
      {{"remesh", small_scan, "-o", (dir / "out.glb").string(), "--output-dir", dir.string()}, "excludes"},
      {{"remesh", small_scan, genus_four}, "-o OUT"},
      // --format goes with --output-dir; options naming one file do not.
      {{"remesh", small_scan, "-o", (dir / "out.glb").string(), "--format", "ply"}, "--output-dir"},
      {{"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--format", "stl"}, "stl"},
      {{"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--report", (dir / "r.json").string()},
       "--report"},
      {{"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--preview", (dir / "p.png").string()},
       "--preview"},
  };
  for (const auto& [args, named] : cases) {
    const CliRun run = run_cli(concat(args, batch_options()));
    EXPECT_EQ(run.exit_status, 2) << args.back() << ": " << run.err;
    EXPECT_NE(run.err.find(named), std::string::npos) << run.err;
  }
  const auto features = folder.write("features.txt", "0 1\n");
  const CliRun with_features =
      run_cli({"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--feature-file", features.string(),
               "--sites", "40", "--lloyd", "0", "--samples", "-1"});
  EXPECT_EQ(with_features.exit_status, 2) << with_features.err;
  EXPECT_NE(with_features.err.find("--feature-file"), std::string::npos) << with_features.err;
  const auto sites = folder.write("sites.txt", "0 0.2 0.3 0.5\n");
  const CliRun run = run_cli({"remesh", small_scan, genus_four, "--output-dir", dir.string(), "--site-file",
                              sites.string(), "--lloyd", "0", "--samples", "-1"});
  EXPECT_EQ(run.exit_status, 2) << run.err;
  EXPECT_NE(run.err.find("--site-file"), std::string::npos) << run.err;
  // Nothing was written.
  EXPECT_FALSE(std::filesystem::exists(dir / "woody.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "fertility.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
}

}  // namespace
}  // namespace geodual::cli_test
