// geodual remesh keeps a scan's vertex attributes: a colour field linear in
// space and a scalar come out at every remesh vertex as the field there, in
// every output format, and --attributes none drops them.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {

namespace fs = std::filesystem;

constexpr const char* scan = "examples/data/bunny.ply";

/// The bunny with 8-bit colours of a field linear in space (spanning most of
/// [0, 1] over its bounding box) and a float scalar linear in space.
class ColouredScan : public ::testing::Test {
 protected:
  void SetUp() override {
    io::LoadedMesh loaded = io::read_mesh(scan);
    const VertexMatrix& v = loaded.mesh.vertices;
    low_ = v.colwise().minCoeff();
    size_ = v.colwise().maxCoeff() - low_;
    VertexAttributes attributes;
    attributes.colors.resize(v.rows(), 3);
    attributes.color_type = ValueType::uint8;
    attributes.scalars.push_back({"height", ValueType::float32, {}});
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      const Eigen::RowVector3d c = color_field(v.row(i));
      for (int k = 0; k < 3; ++k) attributes.colors(i, k) = static_cast<float>(std::round(255 * c[k]) / 255);
      attributes.scalars[0].values.push_back(static_cast<float>(height_field(v.row(i))));
    }
    input_ = folder_.path() / "coloured.ply";
    io::write_ply(input_, loaded.mesh, attributes);
  }

  Eigen::RowVector3d color_field(const Eigen::RowVector3d& p) const {
    return (p - low_).cwiseQuotient(size_) * 0.9 + Eigen::RowVector3d::Constant(0.05);
  }
  double height_field(const Eigen::RowVector3d& p) const { return 2 * (p - low_).y() / size_.y() - 0.5; }

  CliRun remesh(const fs::path& out, const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> arguments = {"remesh", input_.string(), "--sites", "800", "--lloyd",
                                          "2",      "--samples",     "-1",      "-o",  out.string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return run_cli(arguments);
  }

  ScratchFolder folder_;
  fs::path input_;
  Eigen::RowVector3d low_, size_;
};

TEST_F(ColouredScan, PlyOutputCarriesTheLinearColourFieldWithin3Over255) {
  const fs::path out = folder_.path() / "out.ply";
  const CliRun run = remesh(out);
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const std::string header = slurp(out).substr(0, 400);
  EXPECT_NE(header.find("property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float height\n"),
            std::string::npos)
      << header;
  const io::LoadedMesh remeshed = io::read_mesh(out);
  ASSERT_EQ(remeshed.attributes.colors.rows(), remeshed.mesh.num_vertices());
  ASSERT_EQ(remeshed.attributes.scalars.size(), 1u);
  double worst_color = 0, worst_height = 0;
  for (Index i = 0; i < remeshed.mesh.num_vertices(); ++i) {
    const Eigen::RowVector3d p = remeshed.mesh.vertices.row(i);
    const Eigen::RowVector3d expected = color_field(p);
    for (int k = 0; k < 3; ++k) {
      worst_color = std::max(worst_color, std::abs(remeshed.attributes.colors(i, k) - expected[k]));
    }
    worst_height = std::max(
        worst_height, std::abs(remeshed.attributes.scalars[0].values[static_cast<std::size_t>(i)] - height_field(p)));
  }
  EXPECT_LE(worst_color, 3.0 / 255);
  EXPECT_LT(worst_height, 1e-5);  // float32 storage
}

TEST_F(ColouredScan, GlbHasColour0AndTheScalarObjHasVertexColours) {
  const fs::path glb = folder_.path() / "out.glb";
  ASSERT_EQ(remesh(glb).exit_status, 0);
  const std::string bytes = slurp(glb);
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  const nlohmann::json document = nlohmann::json::parse(bytes.substr(20, json_length));
  const nlohmann::json& attributes = document["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_TRUE(attributes.contains("COLOR_0")) << attributes.dump();
  EXPECT_TRUE(attributes.contains("_height")) << attributes.dump();

  const fs::path obj = folder_.path() / "out.obj";
  ASSERT_EQ(remesh(obj).exit_status, 0);
  std::istringstream lines(slurp(obj));
  std::string line;
  int vertices = 0, with_colour = 0;
  while (std::getline(lines, line)) {
    if (!line.starts_with("v ")) continue;
    std::istringstream words(line.substr(2));
    int count = 0;
    for (double value = 0; words >> value;) ++count;
    ++vertices;
    with_colour += count == 6;
  }
  EXPECT_GT(vertices, 0);
  EXPECT_EQ(with_colour, vertices);
}

TEST_F(ColouredScan, AttributesNoneDropsThem) {
  const fs::path out = folder_.path() / "plain.ply";
  ASSERT_EQ(remesh(out, {"--attributes", "none"}).exit_status, 0);
  EXPECT_TRUE(io::read_mesh(out).attributes.empty());
  const CliRun bad = remesh(folder_.path() / "x.ply", {"--attributes", "some"});
  EXPECT_NE(bad.exit_status, 0);
  EXPECT_FALSE(fs::exists(folder_.path() / "x.ply"));
}

// A glTF scalar "_x" would be PLY's property x: refused before the work, and
// nothing is written; glTF output, or --attributes none, goes through.
TEST(RemeshAttributes, NamesAPlyOutputCannotHoldFailBeforeTheWork) {
  ScratchFolder folder;
  io::LoadedMesh loaded = io::read_mesh("tests/data/woody.ply");
  const auto n = static_cast<std::size_t>(loaded.mesh.num_vertices());
  io::GltfScene scene;
  scene.triangle_meshes.push_back(
      {.mesh = loaded.mesh, .scalars = {{.name = "_x", .values = std::vector<float>(n, 1.0f)}}});
  const fs::path input = folder.path() / "scalar_x.glb";
  io::write_gltf(input, scene);
  const std::vector<std::string> options = {"--sites", "100", "--lloyd", "0", "--samples", "-1"};
  const auto run = [&](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> arguments = {"remesh", input.string(), "-o", out.string()};
    arguments.insert(arguments.end(), options.begin(), options.end());
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return run_cli(arguments);
  };
  const CliRun refused = run(folder.path() / "out.ply", {});
  EXPECT_EQ(refused.exit_status, 1);
  EXPECT_NE(refused.err.find("'x' is taken by the coordinates"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--attributes none"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(folder.path() / "out.ply"));
  EXPECT_EQ(run(folder.path() / "plain.ply", {"--attributes", "none"}).exit_status, 0);
  EXPECT_EQ(run(folder.path() / "out.glb", {}).exit_status, 0);
}

}  // namespace
}  // namespace geodual::cli_test
