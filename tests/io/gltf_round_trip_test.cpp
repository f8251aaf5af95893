// write_gltf -> read: what geodual writes, geodual reads back unchanged.
//
// glTF stores coordinates as float32, so only coordinates that are float32
// values survive bit for bit; the meshes here are built from floats for that
// reason (doubles in general come back rounded to the nearest float).

#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;

// Through the public entry point: file loading, the glTF reader and the
// checks read_mesh applies to every format.
LoadedMesh read_back(const fs::path& path) { return read_mesh(path); }

// A bumpy grid of float32-representable coordinates (awkward values, not
// round numbers), plus one unreferenced vertex at the end.
TriangleMesh float_grid(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-1e-3F, 1e-3F);
  TriangleMesh mesh;
  mesh.vertices.resize(n * n + 1, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const float x = static_cast<float>(i) * 0.1F + jitter(random);
      const float y = static_cast<float>(j) * 0.1F + jitter(random);
      const float z = std::sin(x) * std::cos(y) * 1e3F + jitter(random);
      mesh.vertices.row(i * n + j) << x, y, z;
    }
  }
  mesh.vertices.row(n * n) << -0.0F, 3.4e38F, 1.17549435e-38F;
  mesh.faces.resize(2 * (n - 1) * (n - 1), 3);
  Index f = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const Index a = i * n + j;
      mesh.faces.row(f++) << a, a + n, a + 1;
      mesh.faces.row(f++) << a + 1, a + n, a + n + 1;
    }
  }
  return mesh;
}

void expect_bit_exact(const TriangleMesh& written, const TriangleMesh& read) {
  ASSERT_EQ(read.num_vertices(), written.num_vertices());
  ASSERT_EQ(read.num_faces(), written.num_faces());
  EXPECT_EQ(std::memcmp(read.vertices.data(), written.vertices.data(),
                        sizeof(double) * static_cast<std::size_t>(written.vertices.size())),
            0);
  EXPECT_EQ(read.faces, written.faces);
}

class GltfRoundTrip : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("geodual_gltf_round_trip_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_P(GltfRoundTrip, PositionsBitExactAndFacesExact) {
  const fs::path path = dir_ / ("grid" + GetParam());
  const TriangleMesh mesh = float_grid(20, 7);
  write_gltf(path, mesh);
  const LoadedMesh loaded = read_back(path);
  expect_bit_exact(mesh, loaded.mesh);
  EXPECT_EQ(loaded.info.format, GetParam() == ".glb" ? MeshFormat::glb : MeshFormat::gltf);
  // The writer always stores NORMAL; the reader says it read them, and nothing else.
  EXPECT_EQ(loaded.info.notes, std::vector<std::string>{"vertex normals from NORMAL"});
  EXPECT_EQ(loaded.attributes.normals.rows(), mesh.num_vertices());
}

TEST_P(GltfRoundTrip, LargeMeshWithUint32Indices) {
  const fs::path path = dir_ / ("large" + GetParam());
  const TriangleMesh mesh = float_grid(300, 11);  // 90001 vertices
  write_gltf(path, mesh);
  expect_bit_exact(mesh, read_back(path).mesh);
}

TEST_P(GltfRoundTrip, DoublesComeBackRoundedToFloat32) {
  const fs::path path = dir_ / ("doubles" + GetParam());
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0.1, 0.2, 0.3}, {1.0 / 3.0, 0, 0}, {0, 2.0 / 3.0, 1e-9}};
  mesh.faces = FaceMatrix{{0, 1, 2}};
  write_gltf(path, mesh);
  const TriangleMesh read = read_back(path).mesh;
  EXPECT_EQ(read.vertices, mesh.vertices.cast<float>().cast<double>());
}

TEST_P(GltfRoundTrip, SceneExtrasDoNotDisturbTheTriangles) {
  // Lines and points are written for viewers; reading skips them.
  const fs::path path = dir_ / ("scene" + GetParam());
  GltfScene scene;
  const TriangleMesh first = float_grid(4, 1);
  const TriangleMesh second = float_grid(3, 2);
  scene.triangle_meshes.push_back({.name = "a", .mesh = first, .colors = ColorMatrix::Zero(17, 3), .scalars = {}});
  scene.triangle_meshes.push_back(
      {.name = "b", .mesh = second, .scalars = {{.name = "_X", .values = std::vector<float>(10, 1.0F)}}});
  GltfLineSet lines;
  lines.points = VertexMatrix{{0, 0, 0}, {1, 1, 1}};
  lines.segments = SegmentMatrix{{0, 1}};
  scene.line_sets.push_back(lines);
  GltfPointSet points;
  points.points = VertexMatrix{{2, 2, 2}};
  scene.point_sets.push_back(points);
  scene.extras_json = R"({"note": "round trip"})";
  write_gltf(path, scene);

  const LoadedMesh loaded = read_back(path);
  TriangleMesh expected;
  expected.vertices.resize(first.num_vertices() + second.num_vertices(), 3);
  expected.vertices << first.vertices, second.vertices;
  expected.faces.resize(first.num_faces() + second.num_faces(), 3);
  expected.faces << first.faces, (second.faces.array() + first.num_vertices()).matrix();
  expect_bit_exact(expected, loaded.mesh);
  EXPECT_TRUE(std::any_of(loaded.info.notes.begin(), loaded.info.notes.end(),
                          [](const std::string& note) { return note.find("1 LINES, 1 POINTS") != std::string::npos; }));
}

INSTANTIATE_TEST_SUITE_P(Containers, GltfRoundTrip, ::testing::Values(".glb", ".gltf"),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param.substr(1); });

}  // namespace
}  // namespace geodual::io
