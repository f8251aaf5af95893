// geodual remesh --texture-size / --bake / --texture-format: the atlas's
// figures in the JSON, the baked textures in the glTF (read back through
// geodual's own reader) and beside OBJ and PLY outputs, a textured glTF input
// whose seams are welded, and the flags' refusals before any work.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/io/image_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {
namespace fs = std::filesystem;

// A unit sphere as glTF writes a textured one: a latitude-longitude grid
// whose first column is copied at u = 1 (the texture's seam) and whose poles
// are copied per column, textured with a checker of 8 x 4 squares, red and
// blue (sRGB 220, 40, 40 and 40, 40, 220).
fs::path textured_sphere(const fs::path& folder) {
  constexpr int rings = 24, columns = 48;
  io::GltfTriangleMesh entry{.name = "checker sphere"};
  std::vector<Eigen::RowVector3d> points;
  std::vector<Eigen::RowVector2f> uvs;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j <= columns; ++j) {
      // The copies hold the very same coordinates, as an exporter writes them.
      const double theta = std::numbers::pi * i / rings, phi = 2 * std::numbers::pi * (j % columns) / columns;
      const double r = i == 0 || i == rings ? 0.0 : std::sin(theta);
      points.emplace_back(r * std::cos(phi), r * std::sin(phi), i == rings ? -1.0 : std::cos(theta));
      uvs.emplace_back(static_cast<float>(j) / columns, static_cast<float>(i) / rings);
    }
  }
  entry.mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  entry.texcoords.resize(static_cast<Eigen::Index>(uvs.size()), 2);
  for (std::size_t v = 0; v < points.size(); ++v) {
    entry.mesh.vertices.row(static_cast<Eigen::Index>(v)) = points[v];
    entry.texcoords.row(static_cast<Eigen::Index>(v)) = uvs[v];
  }
  std::vector<Eigen::RowVector3i> faces;
  const auto at = [](int i, int j) { return i * (columns + 1) + j; };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < columns; ++j) {
      if (i > 0) faces.emplace_back(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + 1 < rings) faces.emplace_back(at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
    }
  }
  entry.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) entry.mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f];
  TextureImage checker{.width = 256, .height = 128, .channels = 3};
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 256; ++x) {
      const bool red = ((x / 32) + (y / 32)) % 2 == 0;
      checker.texels.insert(checker.texels.end(),
                            {static_cast<std::uint8_t>(red ? 220 : 40), 40, static_cast<std::uint8_t>(red ? 40 : 220)});
    }
  }
  entry.base_color_texture = {.bytes = io::encode_image(checker, io::ImageFormat::png), .mime_type = "image/png"};
  const fs::path path = folder / "checker_sphere.glb";
  io::write_gltf(path, {.triangle_meshes = {entry}});
  return path;
}

TEST(TextureCommand, ATexturedSphereIsRemeshedWithoutItsSeamAndItsCheckerBakedOntoTheAtlas) {
  ScratchFolder folder;
  const fs::path input = textured_sphere(folder.path());
  const fs::path out = folder.path() / "remesh.glb";
  const CliRun run = run_cli({"remesh", input.string(), "--sites", "800", "--texture-size", "512", "--bake", "normal",
                              "--samples", "20000", "-o", out.string(), "--json", "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["boundary_loops"], 0) << "the texture's seam was welded, not kept as a boundary\n" << run.err;
  EXPECT_EQ(json["euler_characteristic"], 2);
  const nlohmann::json& texture = json["texture"];
  EXPECT_EQ(texture["size"], 512);
  EXPECT_EQ(texture["base_color"], true);
  EXPECT_EQ(texture["normal_map"], true);
  EXPECT_GE(texture["charts"].get<int>(), 2) << "a sphere is no disk";
  EXPECT_GT(texture["texture_used"].get<double>(), 0.3);
  EXPECT_LT(texture["mean_angle_distortion_deg"].get<double>(), 3.0);
  EXPECT_GT(texture["atlas_vertices"].get<int>(), json["vertices"].get<int>()) << "the seams copy vertices";

  // Read back: geodual's reader samples the baked texture at the vertices,
  // which must show the checker's two colours, not a blur of them.
  const io::LoadedMesh back = io::read_mesh(out);
  ASSERT_EQ(back.attributes.colors.rows(), back.mesh.num_vertices());
  ASSERT_FALSE(back.texture.empty()) << "one base colour texture, kept whole";
  int pure = 0;
  for (Index v = 0; v < back.mesh.num_vertices(); ++v) {
    const Eigen::RowVector3f c = back.attributes.colors.row(v) * 255;
    const bool red = std::abs(c[0] - 220) < 12 && std::abs(c[2] - 40) < 12;
    const bool blue = std::abs(c[0] - 40) < 12 && std::abs(c[2] - 220) < 12;
    pure += (red || blue) ? 1 : 0;
  }
  EXPECT_GT(pure, 0.75 * back.mesh.num_vertices()) << pure << " of " << back.mesh.num_vertices();
}

TEST(TextureCommand, ObjAndPlyGetTheirImagesBesideThem) {
  ScratchFolder folder;
  const fs::path input = textured_sphere(folder.path());
  const fs::path obj = folder.path() / "remesh.obj";
  CliRun run = run_cli({"remesh", input.string(), "--sites", "300", "--texture-size", "256", "--texture-format", "jpeg",
                        "--bake", "normal", "--no-statistics", "-o", obj.string(), "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(fs::exists(folder.path() / "remesh_basecolor.jpg"));
  EXPECT_TRUE(fs::exists(folder.path() / "remesh_normal.png"));
  const std::string material = slurp(folder.path() / "remesh.mtl");
  EXPECT_NE(material.find("map_Kd remesh_basecolor.jpg\n"), std::string::npos) << material;
  EXPECT_NE(material.find("norm remesh_normal.png\n"), std::string::npos) << material;
  const std::string text = slurp(obj);
  EXPECT_NE(text.find("mtllib remesh.mtl\n"), std::string::npos);
  EXPECT_NE(text.find("\nvt "), std::string::npos);

  // The textured OBJ is an input like any other: remeshed again, its texture baked anew.
  const fs::path again = folder.path() / "again.glb";
  run = run_cli({"remesh", obj.string(), "--sites", "200", "--texture-size", "256", "--no-statistics", "-o",
                 again.string(), "--json", "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["texture"]["base_color"], true);

  const fs::path ply = folder.path() / "remesh.ply";
  run = run_cli({"remesh", input.string(), "--sites", "300", "--texture-size", "256", "--no-statistics", "-o",
                 ply.string(), "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const std::string header = slurp(ply).substr(0, 400);
  EXPECT_NE(header.find("comment TextureFile remesh_basecolor.png\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property float texture_u\nproperty float texture_v\n"), std::string::npos) << header;
  EXPECT_TRUE(fs::exists(folder.path() / "remesh_basecolor.png"));
}

TEST(TextureCommand, FlagsAreCheckedBeforeAnyWork) {
  ScratchFolder folder;
  const fs::path out = folder.path() / "out.glb";
  for (const std::vector<std::string>& flags : {std::vector<std::string>{"--bake", "normal"},
                                                {"--texture-format", "jpeg"},
                                                {"--texture-size", "32"},
                                                {"--texture-size", "20000"},
                                                {"--texture-size", "256", "--bake", "height"}}) {
    std::vector<std::string> args{"remesh", "tests/data/bunny.ply", "--sites", "200", "-o", out.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    const CliRun run = run_cli(args);
    EXPECT_EQ(run.exit_status, 2) << flags.front() << ": " << run.err;
    EXPECT_FALSE(run.err.empty());
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(TextureCommand, TheRemeshsOwnFilesMayNotMeetAndAPlysOwnCoordinatesGiveWay) {
  ScratchFolder folder;
  const fs::path out = folder.path() / "out.obj";
  CliRun run = run_cli({"remesh", "tests/data/spot.ply", "--sites", "300", "--texture-size", "128", "--preview",
                        (folder.path() / "out_basecolor.png").string(), "-o", out.string()});
  EXPECT_EQ(run.exit_status, 2) << run.err;
  EXPECT_NE(run.err.find("texture"), std::string::npos) << run.err;
  EXPECT_TRUE(fs::is_empty(folder.path()));

  // A PLY scan with MeshLab's per-vertex texture_u / texture_v and colours,
  // remeshed into PLY with an atlas: the atlas's coordinates replace the scan's.
  io::LoadedMesh scan = io::read_mesh("tests/data/spot.ply");
  VertexAttributes attributes;
  attributes.colors = ColorMatrix::Constant(scan.mesh.num_vertices(), 3, 0.5F);
  for (const char* name : {"texture_u", "texture_v"}) {
    attributes.scalars.push_back({.name = name, .type = ValueType::float32, .values = {}});
    for (Index v = 0; v < scan.mesh.num_vertices(); ++v) attributes.scalars.back().values.push_back(0.25);
  }
  const fs::path input = folder.path() / "scan.ply";
  io::write_ply(input, scan.mesh, attributes);
  const fs::path ply = folder.path() / "remesh.ply";
  run = run_cli({"remesh", input.string(), "--sites", "300", "--texture-size", "128", "--no-statistics", "-o",
                 ply.string(), "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_TRUE(fs::exists(folder.path() / "remesh_basecolor.png"));
}

TEST(TextureCommand, AnObjsMaterialLibraryAndImagesAreInputsToo) {
  ScratchFolder folder;
  const fs::path input = textured_sphere(folder.path());
  // The sphere as a textured OBJ, a.obj, whose material library is then renamed b.mtl.
  const fs::path a = folder.path() / "a.obj";
  CliRun run = run_cli(
      {"remesh", input.string(), "--sites", "200", "--texture-size", "128", "--no-statistics", "-o", a.string(), "-q"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  fs::rename(folder.path() / "a.mtl", folder.path() / "b.mtl");
  std::string text = slurp(a);
  text.replace(text.find("mtllib a.mtl"), 12, "mtllib b.mtl");
  std::ofstream(a, std::ios::binary | std::ios::trunc) << text;
  const std::string library = slurp(folder.path() / "b.mtl");
  // b.obj would write its own library as b.mtl, over a.obj's: refused before any work.
  run = run_cli({"remesh", a.string(), "--sites", "200", "--texture-size", "128", "--no-statistics", "-o",
                 (folder.path() / "b.obj").string(), "-q"});
  EXPECT_EQ(run.exit_status, 1) << run.err;
  EXPECT_NE(run.err.find("refusing to overwrite"), std::string::npos) << run.err;
  EXPECT_EQ(slurp(folder.path() / "b.mtl"), library);
  EXPECT_FALSE(fs::exists(folder.path() / "b.obj"));
}

TEST(TextureCommand, ATextureTooSmallForTheChartsFailsAndWritesNothing) {
  ScratchFolder folder;
  const fs::path out = folder.path() / "out.obj";
  const CliRun run = run_cli({"remesh", "tests/data/bunny.ply", "--sites", "1000", "--texture-size", "64",
                              "--no-statistics", "-o", out.string(), "-q"});
  EXPECT_EQ(run.exit_status, 1) << run.err;
  EXPECT_NE(run.err.find("charts do not fit a texture of 64 texels"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--texture-size"), std::string::npos) << run.err;
  EXPECT_TRUE(fs::is_empty(folder.path())) << "no remesh, image or material file";
}

}  // namespace
}  // namespace geodual::cli_test
