// geodual info on real meshes: the JSON output agrees with analyze_mesh of the
// same file, and the table shows the same figures.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/remesh/feature_sampling.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/manifold_cut.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

namespace geodual::cli_test {
namespace {

constexpr const char* bundled_scan = "examples/data/bunny.ply";

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

TEST(InfoCommand, JsonAgreesWithAnalyzeMesh) {
  const CliRun run = run_cli({"info", bundled_scan, "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;

  const nlohmann::json json = nlohmann::json::parse(run.out);
  ASSERT_TRUE(json.is_object());
  const io::LoadedMesh loaded = io::read_mesh(bundled_scan);
  const MeshReport report = analyze_mesh(loaded.mesh);

  EXPECT_EQ(json.at("vertices").get<std::int64_t>(), report.vertices);
  EXPECT_EQ(json.at("faces").get<std::int64_t>(), report.faces);
  EXPECT_EQ(json.at("components").get<std::int64_t>(), report.components);
  EXPECT_EQ(json.at("boundary_loops").get<std::int64_t>(), report.boundary_loops);
  EXPECT_EQ(json.at("nonmanifold_edges").get<std::int64_t>(), report.nonmanifold_edges);
  EXPECT_EQ(json.at("nonmanifold_vertices").get<std::int64_t>(), report.nonmanifold_vertices);
  EXPECT_EQ(json.at("degenerate_faces").get<std::int64_t>(), report.degenerate_faces);
  EXPECT_EQ(json.at("duplicate_faces").get<std::int64_t>(), report.duplicate_faces);
  EXPECT_EQ(json.at("duplicate_vertices").get<std::int64_t>(), report.duplicate_vertices);
  EXPECT_EQ(json.at("unreferenced_vertices").get<std::int64_t>(), report.unreferenced_vertices);
  EXPECT_EQ(json.at("euler_characteristic").get<std::int64_t>(), report.euler_characteristic);
  EXPECT_DOUBLE_EQ(json.at("bbox_diagonal").get<double>(), report.bbox_diagonal);
  ASSERT_TRUE(report.genus.has_value());
  EXPECT_EQ(json.at("genus").get<double>(), *report.genus);

  EXPECT_EQ(json.at("format").get<std::string>(), "PLY");
  EXPECT_EQ(json.at("file_bytes").get<std::uintmax_t>(), loaded.info.file_bytes);
  EXPECT_GE(json.at("read_seconds").get<double>(), 0.0);
  EXPECT_TRUE(json.at("notes").is_array());
}

TEST(InfoCommand, GenusIsNullWhereItMeansNothing) {
  // A bow tie: two triangles sharing one vertex, a pinch.
  const ScratchFolder folder;
  const auto path = folder.write("bowtie.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n");
  const CliRun run = run_cli({"info", path.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_TRUE(json.at("genus").is_null());
  EXPECT_EQ(json.at("nonmanifold_vertices").get<int>(), 1);
}

TEST(InfoCommand, ReportsTheSharpFeaturesOfABox) {
  // A unit cube of 12 triangles: 12 creases of length 1 meeting at 8 corners;
  // the diagonals of its sides are flat.
  const ScratchFolder folder;
  const auto path = folder.write("cube.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                 "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                 "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n");
  CliRun run = run_cli({"info", path.string(), "--json", "--sharp-angle", "60"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["feature_chains"], 12);
  EXPECT_EQ(json["feature_corners"], 8);
  EXPECT_NEAR(json["feature_length"].get<double>(), 12.0, 1e-12);
  EXPECT_EQ(json["short_creases"], 0);  // every sharp edge is on a chain
  // Three sides of 90 degrees meet at each corner.
  EXPECT_NEAR(json["feature_narrowest_corner_deg"].get<double>(), 90.0, 1e-9);
  // Creases turning by 90 degrees are not sharp at 91.
  run = run_cli({"info", path.string(), "--json", "--sharp-angle", "91"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["feature_chains"], 0);
  run = run_cli({"info", path.string(), "--sharp-angle", "60"});
  EXPECT_NE(run.out.find("12 chains, 8 corners"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("90 deg between features"), std::string::npos) << run.out;
  run = run_cli({"info", path.string()});  // off by default: it takes several times the analysis
  EXPECT_EQ(run.out.find("sharp features"), std::string::npos) << run.out;
  EXPECT_EQ(run_cli({"info", path.string(), "--sharp-angle", "nan"}).exit_status, 2);
}

TEST(InfoCommand, ReportsTheCreasesTheRemeshSamplesForItsCount) {
  // OpenSCAD's candleStand at 500 sites: the chains round all its narrow
  // smooth regions would hold more points than the count, and the remesh's
  // sampling keeps fewer (FeatureSamplingOptions::max_share_narrow_regions);
  // info reports those, not the detection's all.
  const CliRun run =
      run_cli({"info", "tests/data/cad/candleStand.stl", "--sites", "500", "--sharp-angle", "60", "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  const TriangleMesh cut = remesh::cut_to_manifold(io::read_mesh("tests/data/cad/candleStand.stl").mesh).mesh;
  const remesh::FeatureSampling sampled = remesh::sample_features(remesh::RemeshSurface(cut), 500);
  EXPECT_EQ(json["feature_chains"].get<std::int64_t>(), sampled.features.sharp_chains);
  EXPECT_DOUBLE_EQ(json["feature_length"].get<double>(), sampled.features.sharp_length);
  const remesh::FeatureSet detected = remesh::detect_features(cut, remesh::remesh_feature_options(cut, 500, 60, 0.5));
  EXPECT_LT(json["feature_length"].get<double>(), detected.sharp_length);
}

TEST(InfoCommand, NoNarrowestCornerWhereNoCornerJoinsTwoFeatures) {
  // cheburashka at 1,000 sites: its creases all fade out on the scan, their
  // chains end in the open, so its corners bound no angle.
  CliRun run = run_cli({"info", "tests/data/cheburashka.ply", "--json", "--sharp-angle", "60", "--sites", "1000"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_GT(json["feature_corners"].get<int>(), 0);
  EXPECT_TRUE(json["feature_narrowest_corner_deg"].is_null()) << json["feature_narrowest_corner_deg"];
  run = run_cli({"info", "tests/data/cheburashka.ply", "--sharp-angle", "60", "--sites", "1000"});
  EXPECT_NE(run.out.find("corners"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("narrowest corner"), std::string::npos) << run.out;
  // The remesh says the same.
  const ScratchFolder folder;
  const std::filesystem::path out = folder.path() / "cheburashka.ply";
  run = run_cli(
      {"remesh", "tests/data/cheburashka.ply", "--sites", "1000", "--samples", "-1", "--json", "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json remeshed = nlohmann::json::parse(run.out);
  EXPECT_GT(remeshed["feature_corners"].get<int>(), 0);
  EXPECT_TRUE(remeshed["feature_narrowest_corner_deg"].is_null());
  run = run_cli({"remesh", "tests/data/cheburashka.ply", "--sites", "1000", "--samples", "-1", "-o", out.string()});
  const std::string table = run.out + run.err;
  EXPECT_NE(table.find(" corners"), std::string::npos) << table;
  EXPECT_EQ(table.find("the narrowest"), std::string::npos) << table;
}

TEST(InfoCommand, ReportsTheShortCreasesThatNoChainKeeps) {
  // rocker_arm's 50 sharp edges (0.35 long in all) are creases of one to
  // nine edges fading into fillets: at 3,000 sites none is a chain.
  const CliRun run = run_cli({"info", "tests/data/rocker_arm.ply", "--json", "--sharp-angle", "60", "--sites", "3000"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["feature_chains"], 0);
  EXPECT_GE(json["short_creases"].get<int>(), 20);
  EXPECT_NEAR(json["short_crease_length"].get<double>(), 0.35, 0.02);
}

TEST(InfoCommand, TableShowsTheFigures) {
  const CliRun run = run_cli({"info", bundled_scan});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const auto rows = table_rows(run.out);
  const std::map<std::string, std::string> expected{{"vertices", "35,947"},
                                                    {"faces", "69,451"},
                                                    {"boundary loops", "5 (223 boundary edges)"},
                                                    {"unreferenced vertices", "1,113"},
                                                    {"non-manifold edges", "0"},
                                                    {"genus", "0"},
                                                    {"bbox diagonal", "0.250246"},
                                                    {"format", "PLY, binary_little_endian float32"}};
  for (const auto& [key, value] : expected) {
    ASSERT_EQ(rows.count(key), 1U) << "no row '" << key << "' in\n" << run.out;
    EXPECT_EQ(rows.at(key), value) << key;
  }
  EXPECT_EQ(rows.count("read time"), 1U);
}

}  // namespace
}  // namespace geodual::cli_test
