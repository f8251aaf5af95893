// geodual stats: the JSON has exactly the documented keys, with the library's
// figures for the same files and options; the table shows them; bad files and
// bad command lines fail cleanly.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {

constexpr const char* reference_mesh = "tests/data/bunny.ply";
constexpr const char* candidate_mesh = "tests/data/bunny_res2.ply";
constexpr std::int64_t test_samples = 20000;

/// The figures of one mesh, in the order the README documents them.
const std::vector<std::string> mesh_keys = {"vertices",
                                            "faces",
                                            "degenerate_faces",
                                            "q_min",
                                            "q_avg",
                                            "theta_min_deg",
                                            "theta_min_avg_deg",
                                            "pct_angles_lt30",
                                            "p30",
                                            "valence_histogram",
                                            "interior_vertices",
                                            "pct_valence6",
                                            "euler_characteristic",
                                            "genus",
                                            "components",
                                            "boundary_loops",
                                            "nonmanifold_edges",
                                            "bbox_diagonal",
                                            "area",
                                            "volume"};

std::vector<std::string> keys_of(const nlohmann::ordered_json& json) {
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  return keys;
}

/// The table's rows: key, then two or more spaces, then the value.
std::map<std::string, std::string> table_rows(const std::string& text) {
  std::map<std::string, std::string> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto gap = line.find("  ");
    if (gap == std::string::npos) continue;
    rows[line.substr(0, gap)] = line.substr(line.find_first_not_of(' ', gap));
  }
  return rows;
}

void expect_one_error_line(const CliRun& run, int status, const std::string& mention) {
  EXPECT_EQ(run.signal, 0) << run.err;
  EXPECT_EQ(run.exit_status, status) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  const std::vector<std::string> lines = run.err_lines();
  ASSERT_EQ(lines.size(), 1U) << run.err;
  EXPECT_EQ(lines[0].rfind("geodual: error: ", 0), 0U) << lines[0];
  EXPECT_NE(lines[0].find(mention), std::string::npos) << "'" << mention << "' not in: " << lines[0];
}

TEST(StatsCommand, JsonHasTheDocumentedKeysAndTheLibrarysFigures) {
  const CliRun run = run_cli(
      {"stats", reference_mesh, candidate_mesh, "--json", "--samples", std::to_string(test_samples), "--seed", "3"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(run.out);

  std::vector<std::string> expected = {"reference", "candidate"};
  expected.insert(expected.end(), mesh_keys.begin(), mesh_keys.end());
  for (const char* key : {"hausdorff",
                          "rms",
                          "hausdorff_pct",
                          "rms_pct",
                          "hausdorff_reference_to_candidate_pct",
                          "hausdorff_candidate_to_reference_pct",
                          "hausdorff_at",
                          "area_change_pct",
                          "volume_change_pct",
                          "sharp_angle_deg",
                          "feature_tolerance_pct",
                          "feature_recall_edges",
                          "feature_recall_length",
                          "feature_recall_pct",
                          "feature_max_gap_pct",
                          "samples_per_side",
                          "seed",
                          "reference_samples",
                          "candidate_samples",
                          "reference_quality",
                          "read_s",
                          "stats_s"}) {
    expected.emplace_back(key);
  }
  EXPECT_EQ(keys_of(json), expected);
  EXPECT_EQ(keys_of(json.at("reference_quality")), mesh_keys);

  // The same figures as the library's for the same meshes and options (JSON
  // numbers round-trip doubles exactly).
  quality::QualityOptions options;
  options.samples_per_side = test_samples;
  options.seed = 3;
  const quality::QualityReport report =
      quality::compare_meshes(io::read_mesh(reference_mesh).mesh, io::read_mesh(candidate_mesh).mesh, options);
  const quality::TriangleQuality& c = report.candidate;
  EXPECT_EQ(json.at("vertices").get<std::int64_t>(), c.vertices);
  EXPECT_EQ(json.at("faces").get<std::int64_t>(), c.faces);
  EXPECT_EQ(json.at("q_min").get<double>(), c.q_min);
  EXPECT_EQ(json.at("q_avg").get<double>(), c.q_avg);
  EXPECT_EQ(json.at("theta_min_deg").get<double>(), c.theta_min_deg);
  EXPECT_EQ(json.at("theta_min_avg_deg").get<double>(), c.theta_min_avg_deg);
  EXPECT_EQ(json.at("pct_angles_lt30").get<double>(), c.pct_angles_lt30);
  EXPECT_EQ(json.at("p30").get<double>(), c.p30);
  EXPECT_EQ(json.at("valence_histogram").get<std::vector<std::int64_t>>(), c.valence_histogram);
  EXPECT_EQ(json.at("pct_valence6").get<double>(), c.pct_valence6.value());
  EXPECT_EQ(json.at("euler_characteristic").get<std::int64_t>(), c.euler_characteristic);
  EXPECT_EQ(json.at("boundary_loops").get<std::int64_t>(), c.boundary_loops);
  EXPECT_EQ(json.at("nonmanifold_edges").get<std::int64_t>(), c.nonmanifold_edges);
  EXPECT_EQ(json.at("hausdorff_pct").get<double>(), report.hausdorff_pct);
  EXPECT_EQ(json.at("rms_pct").get<double>(), report.rms_pct);
  EXPECT_EQ(json.at("area_change_pct").get<double>(), report.area_change_pct);
  EXPECT_EQ(json.at("volume_change_pct").get<double>(), report.volume_change_pct.value());
  EXPECT_EQ(json.at("reference_quality").at("faces").get<std::int64_t>(), report.reference.faces);
  ASSERT_TRUE(report.features.has_value());
  EXPECT_EQ(json.at("sharp_angle_deg").get<double>(), 60.0);
  EXPECT_EQ(json.at("feature_tolerance_pct").get<double>(), 0.1);
  EXPECT_EQ(json.at("feature_recall_edges").get<std::int64_t>(), report.features->edges);
  EXPECT_EQ(json.at("feature_recall_length").get<double>(), report.features->length);
  EXPECT_EQ(json.at("feature_recall_pct").get<double>(), report.features->recall_pct);
  EXPECT_EQ(json.at("feature_max_gap_pct").get<double>(), report.features->max_gap_pct);

  // Sane values for the decimated bunny against the full scan (MANIFEST.md:
  // bunny_res2 has 16,301 faces, 150 non-manifold edges, 5 boundary loops, so
  // no genus).
  EXPECT_EQ(json.at("faces").get<std::int64_t>(), 16301);
  EXPECT_EQ(json.at("nonmanifold_edges").get<std::int64_t>(), 150);
  EXPECT_EQ(json.at("boundary_loops").get<std::int64_t>(), 5);
  EXPECT_TRUE(json.at("genus").is_null());
  EXPECT_EQ(json.at("reference_quality").at("genus").get<int>(), 0);
  EXPECT_GT(json.at("q_min").get<double>(), 0.0);
  EXPECT_LE(json.at("q_min").get<double>(), json.at("q_avg").get<double>());
  EXPECT_LT(json.at("q_avg").get<double>(), 1.0);
  EXPECT_LE(json.at("p30").get<double>(), json.at("pct_angles_lt30").get<double>());
  const double hausdorff = json.at("hausdorff_pct").get<double>();
  EXPECT_GT(hausdorff, 0.01);  // a decimation moves the surface
  EXPECT_LT(hausdorff, 5.0);   // but not by much
  EXPECT_LT(json.at("rms_pct").get<double>(), hausdorff);
  EXPECT_EQ(hausdorff, std::max(json.at("hausdorff_reference_to_candidate_pct").get<double>(),
                                json.at("hausdorff_candidate_to_reference_pct").get<double>()));
  EXPECT_LT(std::abs(json.at("area_change_pct").get<double>()), 5.0);
  EXPECT_EQ(json.at("candidate_samples").get<std::int64_t>(), 8171 - 25 + test_samples);  // 25 unreferenced
}

TEST(StatsCommand, TableShowsTheFigures) {
  const CliRun run = run_cli({"stats", reference_mesh, candidate_mesh, "--samples", "2000"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const auto rows = table_rows(run.out);
  for (const char* key : {"reference",
                          "candidate",
                          "mesh",
                          "faces",
                          "Q min",
                          "Q avg",
                          "min angle",
                          "mean min angle",
                          "angles < 30 deg",
                          "P30",
                          "valence 6 (interior)",
                          "euler characteristic",
                          "genus",
                          "boundary loops",
                          "non-manifold edges",
                          "hausdorff",
                          "rms",
                          "area change",
                          "volume change",
                          "samples"}) {
    EXPECT_EQ(rows.count(key), 1U) << "no row '" << key << "' in\n" << run.out;
  }
  ASSERT_EQ(rows.count("faces"), 1U);
  EXPECT_EQ(rows.at("faces").substr(0, 6), "69,451") << rows.at("faces");
  EXPECT_NE(rows.at("faces").find("16,301"), std::string::npos) << rows.at("faces");
  EXPECT_EQ(rows.at("candidate"), candidate_mesh);
  ASSERT_EQ(rows.count("genus"), 1U);
  EXPECT_NE(rows.at("genus").find("not defined"), std::string::npos) << rows.at("genus");
  ASSERT_EQ(rows.count("hausdorff"), 1U);
  EXPECT_NE(rows.at("hausdorff").find('%'), std::string::npos) << rows.at("hausdorff");
}

/// The unit cube as OBJ text, with the corner (1, 1, 1) cut off `a` from it
/// when `a` > 0 (its three pentagons fanned from their corner opposite the
/// cut, so that the cut's chords are the edges nearest its creases).
std::string cube_obj(double a) {
  std::ostringstream obj;
  for (int k = 0; k < 7; ++k) obj << "v " << (k & 1) << ' ' << ((k >> 1) & 1) << ' ' << ((k >> 2) & 1) << '\n';
  if (a == 0) {
    obj << "v 1 1 1\n"
           "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
           "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  } else {
    obj << "v " << 1 - a << " 1 1\nv 1 " << 1 - a << " 1\nv 1 1 " << 1 - a << '\n';  // 8, 9, 10
    obj << "f 1 3 4\nf 1 4 2\nf 1 2 6\nf 1 6 5\nf 1 5 7\nf 1 7 3\n"
           "f 5 6 9\nf 5 9 8\nf 5 8 7\nf 3 7 8\nf 3 8 10\nf 3 10 4\nf 2 4 10\nf 2 10 9\nf 2 9 6\n"
           "f 8 9 10\n";
  }
  return obj.str();
}

TEST(StatsCommand, FeatureRecallOfACubeCutAtACorner) {
  // The three creases into the cut corner lose a - sqrt(2) tau each, tau =
  // 0.1 % of the diagonal sqrt(3); the corner is a / sqrt(2) from the cut's chords.
  const ScratchFolder folder;
  const double a = 0.05;
  const auto cube = folder.write("cube.obj", cube_obj(0)).string();
  const auto cut = folder.write("cut.obj", cube_obj(a)).string();
  const CliRun run = run_cli({"stats", cube, cut, "--json", "--samples", "1000"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(run.out);
  const double tau = 0.001 * std::sqrt(3.0);
  EXPECT_EQ(json.at("feature_recall_edges").get<std::int64_t>(), 12);
  EXPECT_NEAR(json.at("feature_recall_length").get<double>(), 12.0, 1e-12);
  EXPECT_NEAR(json.at("feature_recall_pct").get<double>(), 100 * (12 - 3 * (a - std::sqrt(2.0) * tau)) / 12, 0.003);
  EXPECT_NEAR(json.at("feature_max_gap_pct").get<double>(), 100 * a / std::sqrt(2.0) / std::sqrt(3.0), 1e-9);

  // The cube against itself recalls everything; with a wider tolerance the cut is recalled too.
  const nlohmann::ordered_json same =
      nlohmann::ordered_json::parse(run_cli({"stats", cut, cut, "--json", "--samples", "0"}).out);
  EXPECT_EQ(same.at("feature_recall_pct").get<double>(), 100.0);
  const nlohmann::ordered_json wide = nlohmann::ordered_json::parse(
      run_cli({"stats", cube, cut, "--json", "--samples", "0", "--feature-tolerance", "2.1"}).out);
  EXPECT_EQ(wide.at("feature_tolerance_pct").get<double>(), 2.1);
  EXPECT_EQ(wide.at("feature_recall_pct").get<double>(), 100.0);
  // Creases turning by 90 degrees are not sharp at 91 degrees; 0 measures nothing.
  const nlohmann::ordered_json blunt = nlohmann::ordered_json::parse(
      run_cli({"stats", cube, cut, "--json", "--samples", "0", "--sharp-angle", "91"}).out);
  EXPECT_EQ(blunt.at("feature_recall_edges").get<std::int64_t>(), 0);
  EXPECT_EQ(blunt.at("feature_recall_length").get<double>(), 0.0);
  EXPECT_EQ(blunt.at("feature_recall_pct").get<double>(), 100.0);
  EXPECT_EQ(blunt.at("feature_max_gap_pct").get<double>(), 0.0);
  const nlohmann::ordered_json off = nlohmann::ordered_json::parse(
      run_cli({"stats", cube, cut, "--json", "--samples", "0", "--sharp-angle", "0"}).out);
  EXPECT_EQ(off.at("sharp_angle_deg").get<double>(), 0.0);
  EXPECT_TRUE(off.at("feature_recall_pct").is_null());
  EXPECT_TRUE(off.at("feature_max_gap_pct").is_null());

  // The table says it in words.
  const auto rows = table_rows(run_cli({"stats", cube, cut, "--samples", "0"}).out);
  ASSERT_EQ(rows.count("sharp edges"), 1U);
  EXPECT_EQ(rows.at("sharp edges").rfind("12 in the reference", 0), 0U) << rows.at("sharp edges");
  ASSERT_EQ(rows.count("feature recall"), 1U);
  EXPECT_EQ(rows.at("feature recall").rfind("98.81%", 0), 0U) << rows.at("feature recall");
  ASSERT_EQ(rows.count("feature max gap"), 1U);
  EXPECT_EQ(rows.at("feature max gap").rfind("2.041%", 0), 0U) << rows.at("feature max gap");
}

TEST(StatsCommand, BadFilesFailNamingThePath) {
  const ScratchFolder folder;
  const auto missing = (folder.path() / "no-such-mesh.ply").string();
  expect_one_error_line(run_cli({"stats", missing, reference_mesh}), 1, missing);
  expect_one_error_line(run_cli({"stats", reference_mesh, missing, "--json"}), 1, missing);
  const auto garbage = folder.write("garbage.ply", "ply\nformat nonsense\n").string();
  expect_one_error_line(run_cli({"stats", reference_mesh, garbage}), 1, garbage);
  // A readable mesh without area has nothing to sample: named by its path.
  const auto flat = folder.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").string();
  expect_one_error_line(run_cli({"stats", flat, reference_mesh}), 1, flat + ": every face has zero area");
}

TEST(StatsCommand, BadCommandLinesAreUsageErrors) {
  expect_one_error_line(run_cli({"stats"}), 2, "REFERENCE");
  expect_one_error_line(run_cli({"stats", reference_mesh}), 2, "CANDIDATE");
  expect_one_error_line(run_cli({"stats", reference_mesh, candidate_mesh, "--samples", "-5"}), 2, "--samples");
  expect_one_error_line(run_cli({"stats", reference_mesh, candidate_mesh, "--samples", "1000000000001"}), 2,
                        "--samples");
  expect_one_error_line(run_cli({"stats", reference_mesh, candidate_mesh, "--frobnicate"}), 2, "--frobnicate");
  for (const char* angle : {"-1", "181", "nan", "sixty"}) {
    expect_one_error_line(run_cli({"stats", reference_mesh, candidate_mesh, "--sharp-angle", angle}), 2,
                          "--sharp-angle");
  }
  for (const char* tolerance : {"0", "-0.1", "inf"}) {
    expect_one_error_line(run_cli({"stats", reference_mesh, candidate_mesh, "--feature-tolerance", tolerance}), 2,
                          "--feature-tolerance");
  }
}

}  // namespace
}  // namespace geodual::cli_test
