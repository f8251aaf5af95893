// Vertex attributes through the PLY and OBJ readers and writers: colours,
// normals and named scalars read with their types, written back the same way.

#include "geodual/io/write_mesh.hpp"

#include "io/io_test_files.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geodual {
namespace {

using test::read_file;
using test::read_text;
using test::TempDir;

TriangleMesh one_triangle() {
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.faces = FaceMatrix{{0, 1, 2}};
  return mesh;
}

bool has_note(const io::LoadedMesh& loaded, std::string_view text) {
  for (const std::string& note : loaded.info.notes) {
    if (note.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(PlyAttributes, AsciiColoursNormalsAndScalarsAreRead) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "c.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 3\n"
                                          "property float x\nproperty float y\nproperty float z\n"
                                          "property float nx\nproperty float ny\nproperty float nz\n"
                                          "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                          "property uchar alpha\nproperty float quality\n"
                                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                          "0 0 0 0 0 2 255 0 0 255 0.5\n"
                                          "1 0 0 0 0 1 0 128 0 255 1.5\n"
                                          "0 1 0 0 0 1 0 0 51 127 -2\n3 0 1 2\n");
  const VertexAttributes& a = loaded.attributes;
  ASSERT_EQ(a.colors.rows(), 3);
  ASSERT_EQ(a.colors.cols(), 4);
  EXPECT_EQ(a.color_type, ValueType::uint8);
  EXPECT_FLOAT_EQ(a.colors(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(a.colors(1, 1), 128.0f / 255.0f);
  EXPECT_FLOAT_EQ(a.colors(2, 2), 0.2f);
  EXPECT_FLOAT_EQ(a.colors(2, 3), 127.0f / 255.0f);
  ASSERT_EQ(a.normals.rows(), 3);
  EXPECT_EQ(a.normals(0, 2), 2.0);  // as stored; interpolation renormalises
  EXPECT_EQ(a.normal_type, ValueType::float32);
  ASSERT_EQ(a.scalars.size(), 1u);
  EXPECT_EQ(a.scalars[0].name, "quality");
  EXPECT_EQ(a.scalars[0].values, (std::vector<double>{0.5, 1.5, -2}));
  EXPECT_TRUE(loaded.info.notes.empty());
}

TEST(PlyAttributes, WrittenWithTheirTypesAndReadBackTheSame) {
  TempDir dir;
  const TriangleMesh mesh = one_triangle();
  VertexAttributes attributes;
  attributes.colors = ColorMatrix{{1, 0, 0}, {0, 128 / 255.0f, 0}, {0.2f, 0.2f, 1}};
  attributes.color_type = ValueType::uint8;
  attributes.normals = VertexMatrix{{0, 0, 1}, {0, 0.6, 0.8}, {1, 0, 0}};
  attributes.normal_type = ValueType::float32;
  attributes.scalars = {{"intensity", ValueType::uint16, {0, 1000, 65535}},
                        {"confidence", ValueType::float64, {0.125, 1.0 / 3.0, 2}}};
  io::write_ply(dir / "a.ply", mesh, attributes);
  const std::string file = read_file(dir / "a.ply");
  EXPECT_NE(file.find("property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar "
                      "green\nproperty uchar blue\nproperty ushort intensity\nproperty double confidence\n"),
            std::string::npos);

  const io::LoadedMesh loaded = io::read_mesh(dir / "a.ply");
  EXPECT_EQ(loaded.attributes.colors, attributes.colors);  // k / 255 survives the round trip exactly
  EXPECT_EQ(loaded.attributes.color_type, ValueType::uint8);
  EXPECT_TRUE(loaded.attributes.normals.isApprox(attributes.normals, 1e-7));
  ASSERT_EQ(loaded.attributes.scalars.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(loaded.attributes.scalars[s].name, attributes.scalars[s].name);
    EXPECT_EQ(loaded.attributes.scalars[s].type, attributes.scalars[s].type);
    EXPECT_EQ(loaded.attributes.scalars[s].values, attributes.scalars[s].values);
  }
  // Float colours are written as float.
  attributes.color_type = ValueType::float32;
  io::write_ply(dir / "f.ply", mesh, attributes);
  EXPECT_NE(read_file(dir / "f.ply").find("property float red\n"), std::string::npos);
  EXPECT_EQ(io::read_mesh(dir / "f.ply").attributes.colors, attributes.colors);
}

TEST(PlyAttributes, FloatColoursOutsideTheUnitRangeAreKeptAsScalars) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "c.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 3\n"
                                          "property float x\nproperty float y\nproperty float z\n"
                                          "property float red\nproperty float green\nproperty float blue\n"
                                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                          "0 0 0 200 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n");
  EXPECT_EQ(loaded.attributes.colors.rows(), 0);
  ASSERT_EQ(loaded.attributes.scalars.size(), 3u);
  EXPECT_EQ(loaded.attributes.scalars[0].name, "red");
  EXPECT_EQ(loaded.attributes.scalars[0].values[0], 200.0);
  EXPECT_TRUE(has_note(loaded, "outside [0, 1]"));
}

TEST(PlyAttributes, ScalarsThatAreNotFiniteAreDroppedWithANote) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "c.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 3\n"
                                          "property float x\nproperty float y\nproperty float z\n"
                                          "property float q\nproperty float w\n"
                                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                          "0 0 0 nan 1\n1 0 0 0 2\n0 1 0 0 3\n3 0 1 2\n");
  ASSERT_EQ(loaded.attributes.scalars.size(), 1u);
  EXPECT_EQ(loaded.attributes.scalars[0].name, "w");
  EXPECT_TRUE(has_note(loaded, "vertex property 'q' ignored: not all finite"));
}

TEST(ObjAttributes, VertexColoursAreReadWhenEveryVertexHasOne) {
  TempDir dir;
  const io::LoadedMesh unit = read_text(dir, "u.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  ASSERT_EQ(unit.attributes.colors.rows(), 3);
  EXPECT_FLOAT_EQ(unit.attributes.colors(1, 1), 0.5f);
  EXPECT_EQ(unit.mesh.vertices(1, 0), 1.0);

  const io::LoadedMesh bytes = read_text(dir, "b.obj", "v 0 0 0 255 0 0\nv 1 0 0 0 51 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  EXPECT_FLOAT_EQ(bytes.attributes.colors(1, 1), 0.2f);
  EXPECT_TRUE(has_note(bytes, "0-255"));

  const io::LoadedMesh some = read_text(dir, "s.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 1\nf 1 2 3\n");
  EXPECT_EQ(some.attributes.colors.rows(), 0);
  EXPECT_TRUE(has_note(some, "only 1 of 3 vertices"));
}

TEST(ObjAttributes, ColoursRoundTrip) {
  TempDir dir;
  const TriangleMesh mesh = one_triangle();
  const ColorMatrix colors{{1, 0, 0.25f}, {0.1f, 0.2f, 0.3f}, {1.0f / 3.0f, 0, 1}};
  io::write_mesh(dir / "c.obj", mesh, {.colors = colors});
  const io::LoadedMesh loaded = io::read_mesh(dir / "c.obj");
  EXPECT_EQ(loaded.attributes.colors, colors);  // shortest round-trip text of each float
  EXPECT_EQ(loaded.mesh.vertices, mesh.vertices);
}

}  // namespace
}  // namespace geodual
