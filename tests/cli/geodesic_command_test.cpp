// geodual geodesic: the written field matches the library, output is
// deterministic and independent of RWR, and bad requests fail cleanly.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/remesh/sample_sites.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {

constexpr const char* small_mesh = "tests/data/fertility.ply";

/// Per-vertex (distance, site) from a PLY written by `geodual geodesic`:
/// vertex records are x y z distance (double) and site (int).
void read_field(const std::string& bytes, std::vector<double>& distance, std::vector<std::int32_t>& site) {
  const std::string marker = "end_header\n";
  const auto body = bytes.find(marker);
  ASSERT_NE(body, std::string::npos);
  const std::string header = bytes.substr(0, body);
  ASSERT_NE(header.find("property double distance"), std::string::npos) << header;
  ASSERT_NE(header.find("property int site"), std::string::npos) << header;
  const auto count_at = header.find("element vertex ") + std::strlen("element vertex ");
  const auto count = std::stoul(header.substr(count_at));
  constexpr std::size_t record = 4 * sizeof(double) + sizeof(std::int32_t);
  ASSERT_GE(bytes.size(), body + marker.size() + count * record);
  distance.resize(count);
  site.resize(count);
  const char* p = bytes.data() + body + marker.size();
  for (std::size_t v = 0; v < count; ++v, p += record) {
    std::memcpy(&distance[v], p + 3 * sizeof(double), sizeof(double));
    std::memcpy(&site[v], p + 4 * sizeof(double), sizeof(std::int32_t));
  }
}

TEST(GeodesicCommand, WritesTheLibrarysFieldDeterministically) {
  ScratchFolder folder;
  const auto out1 = folder.path() / "a.ply", out2 = folder.path() / "b.ply", out3 = folder.path() / "c.ply";
  const CliRun run = run_cli({"geodesic", small_mesh, "--sites", "12", "--seed", "5", "-o", out1.string(), "--json"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  for (const char* key :
       {"windows_created", "windows_stored", "peak_windows", "peak_window_bytes", "vertices_popped", "time_s"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_LE(json.at("windows_stored").get<std::int64_t>(), json.at("peak_windows").get<std::int64_t>());
  EXPECT_LE(json.at("peak_windows").get<std::int64_t>(), json.at("windows_created").get<std::int64_t>());

  ASSERT_EQ(run_cli({"geodesic", small_mesh, "--sites", "12", "--seed", "5", "-o", out2.string()}).exit_status, 0);
  ASSERT_EQ(
      run_cli({"geodesic", small_mesh, "--sites", "12", "--seed", "5", "--no-rwr", "-o", out3.string()}).exit_status,
      0);
  const std::string bytes = slurp(out1);
  EXPECT_EQ(bytes, slurp(out2)) << "same input, options and seed must give the same bytes";
  EXPECT_EQ(bytes, slurp(out3)) << "RWR must not change distances or labels";

  std::vector<double> distance;
  std::vector<std::int32_t> site;
  read_field(bytes, distance, site);
  const TriangleMesh mesh = io::read_mesh(small_mesh).mesh;
  // --sites samples the surface the same way in every command: random by area here.
  const auto sites = remesh::sample_sites(mesh, 12, {.strategy = remesh::SamplingStrategy::random, .seed = 5});
  const auto field = voronoi::compute_geodesic_field(mesh, sites);
  ASSERT_EQ(distance.size(), field.distance.size());
  for (std::size_t v = 0; v < distance.size(); ++v) {
    ASSERT_EQ(distance[v], field.distance[v]) << "vertex " << v;
    ASSERT_EQ(site[v], field.nearest_site[v]) << "vertex " << v;
  }
}

TEST(GeodesicCommand, SiteFileWithFaceSitesAndGlbOutput) {
  ScratchFolder folder;
  const auto sites = folder.write("sites.txt", "# two sites\n17\nf 100 0.2 0.3 0.5\n");
  const auto out = folder.path() / "field.glb";
  const CliRun run = run_cli({"geodesic", small_mesh, "--site-file", sites.string(), "-o", out.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  ASSERT_TRUE(std::filesystem::exists(out));
  const std::string bytes = slurp(out);
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_NE(bytes.find("_DISTANCE"), std::string::npos);
  EXPECT_NE(bytes.find("COLOR_0"), std::string::npos);
  // The glTF reads back as the same mesh.
  const TriangleMesh back = io::read_mesh(out).mesh;
  EXPECT_EQ(back.num_faces(), io::read_mesh(small_mesh).mesh.num_faces());
}

// --site-groups: by default a few sites propagate in two groups; one group
// (the leanest) and five give the same distances to rounding and the same
// nearest sites (but for a tie or two), each on any number of threads.
TEST(GeodesicCommand, SiteGroupsChangeTheWorkNotTheField) {
  ScratchFolder folder;
  std::vector<std::vector<double>> distances;
  std::vector<std::vector<std::int32_t>> sites;
  for (const char* groups : {"0", "1", "5"}) {
    const auto out = folder.path() / (std::string("g") + groups + ".ply");
    const CliRun run = run_cli({"geodesic", small_mesh, "--sites", "20", "--seed", "3", "--site-groups", groups, "-o",
                                out.string(), "--json"});
    ASSERT_EQ(run.exit_status, 0) << run.err;
    const int expected = std::string(groups) == "0" ? 2 : std::stoi(groups);
    EXPECT_EQ(nlohmann::json::parse(run.out).at("site_groups").get<int>(), expected) << groups;
    const auto again = folder.path() / "again.ply";
    ASSERT_EQ(run_cli({"--threads", "1", "geodesic", small_mesh, "--sites", "20", "--seed", "3", "--site-groups",
                       groups, "-o", again.string()})
                  .exit_status,
              0);
    EXPECT_EQ(slurp(out), slurp(again)) << "one thread and the default must give the same bytes, groups " << groups;
    distances.emplace_back();
    sites.emplace_back();
    read_field(slurp(out), distances.back(), sites.back());
  }
  const double largest = *std::max_element(distances[0].begin(), distances[0].end());
  for (std::size_t i = 1; i < distances.size(); ++i) {
    ASSERT_EQ(distances[i].size(), distances[0].size());
    int differing_sites = 0;
    for (std::size_t v = 0; v < distances[0].size(); ++v) {
      ASSERT_NEAR(distances[i][v], distances[0][v], 1e-12 * largest) << "vertex " << v;
      differing_sites += sites[i][v] != sites[0][v];
    }
    EXPECT_LE(differing_sites, 2);
  }
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--sites", "3", "--site-groups", "-1"}).exit_status, 2);
}

TEST(GeodesicCommand, BadRequestsFailCleanly) {
  ScratchFolder folder;
  // Usage errors: exit 2.
  EXPECT_EQ(run_cli({"geodesic", small_mesh}).exit_status, 2);
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--sites", "3", "--site-file", "x.txt"}).exit_status, 2);
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--sites", "0"}).exit_status, 2);
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--sites", "200000000"}).exit_status, 2);

  // A site out of range: exit 1, one line naming the site file.
  const auto bad_sites = folder.write("bad.txt", "5\n999999999\n");
  const CliRun out_of_range = run_cli({"geodesic", small_mesh, "--site-file", bad_sites.string()});
  EXPECT_EQ(out_of_range.exit_status, 1);
  ASSERT_EQ(out_of_range.err_lines().size(), 1u) << out_of_range.err;
  EXPECT_NE(out_of_range.err.find(bad_sites.string()), std::string::npos) << out_of_range.err;

  // Two sites at the same point.
  const auto twice = folder.write("twice.txt", "5\n5\n");
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--site-file", twice.string()}).exit_status, 1);

  // Output onto the input: refused, input untouched.
  const auto copy = folder.path() / "copy.ply";
  std::filesystem::copy_file(small_mesh, copy);
  const std::string before = slurp(copy);
  const CliRun onto_input = run_cli({"geodesic", copy.string(), "--sites", "3", "-o", copy.string()});
  EXPECT_EQ(onto_input.exit_status, 1);
  EXPECT_EQ(slurp(copy), before);

  // An extension that cannot hold a field: error, and no file left behind.
  const auto obj = folder.path() / "field.obj";
  EXPECT_EQ(run_cli({"geodesic", small_mesh, "--sites", "3", "-o", obj.string()}).exit_status, 1);
  EXPECT_FALSE(std::filesystem::exists(obj));
  for (const auto& entry : std::filesystem::directory_iterator(folder.path())) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace geodual::cli_test
