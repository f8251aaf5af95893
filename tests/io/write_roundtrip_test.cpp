// Writing and reading back: binary PLY keeps every double bit for bit, OBJ
// keeps them exactly through text; PLY vertex properties land in the header
// and body as declared; write_mesh picks the writer by extension.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace geodual::test {
namespace {

using io::read_mesh;

/// Doubles that text and narrowing get wrong most easily.
TriangleMesh awkward_mesh() {
  TriangleMesh mesh;
  mesh.vertices.resize(5, 3);
  mesh.vertices << 0.1, 1.0 / 3.0, -0.0,                                               //
      std::numbers::pi, -1e300, 4.9406564584124654e-324,                               //
      std::numeric_limits<double>::max(), std::numeric_limits<double>::min(), 1e-310,  //
      0.1 + 0.2, -123456789.123456789, 2.0 / 3.0,                                      //
      1e22, 5e-324, -7.0;
  mesh.faces.resize(3, 3);
  mesh.faces << 0, 1, 2, 2, 3, 4, 4, 4, 0;  // the last one degenerate
  return mesh;
}

/// Random finite doubles of every magnitude, from random bit patterns.
TriangleMesh random_mesh(std::size_t vertices) {
  std::mt19937_64 random(7);
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices), 3);
  for (Eigen::Index i = 0; i < mesh.vertices.size(); ++i) {
    double value = 0;
    do {
      value = std::bit_cast<double>(random());
    } while (!std::isfinite(value));
    mesh.vertices.data()[i] = value;
  }
  mesh.faces.resize(static_cast<Eigen::Index>(vertices - 2), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    mesh.faces.row(f) << 0, static_cast<Index>(f + 1), static_cast<Index>(f + 2);
  }
  return mesh;
}

/// Bit-for-bit equality (tells -0.0 from 0.0, unlike ==).
void expect_same_bits(const TriangleMesh& actual, const TriangleMesh& expected) {
  ASSERT_EQ(actual.vertices.rows(), expected.vertices.rows());
  EXPECT_EQ(std::memcmp(actual.vertices.data(), expected.vertices.data(),
                        sizeof(double) * static_cast<std::size_t>(expected.vertices.size())),
            0);
  EXPECT_EQ(face_list(actual), face_list(expected));
}

TEST(WriteRoundTrip, BinaryPlyIsBitExact) {
  TempDir dir;
  for (const TriangleMesh& mesh : {awkward_mesh(), random_mesh(2000)}) {
    io::write_ply(dir / "out.ply", mesh);
    const io::LoadedMesh loaded = read_mesh(dir / "out.ply");
    expect_same_bits(loaded.mesh, mesh);
    EXPECT_EQ(loaded.info.encoding, "binary_little_endian float64");
  }
}

TEST(WriteRoundTrip, ObjIsExact) {
  TempDir dir;
  for (const TriangleMesh& mesh : {awkward_mesh(), random_mesh(2000)}) {
    io::write_obj(dir / "out.obj", mesh);
    expect_same_bits(read_mesh(dir / "out.obj").mesh, mesh);
  }
}

TEST(WriteRoundTrip, ObjTextIsShortestAndOneBased) {
  TempDir dir;
  TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0.1, 0, -2.5, 1, 1e-7, 3, 0.30000000000000004, 2, 1e300;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 2, 1;
  io::write_obj(dir / "small.obj", mesh);
  EXPECT_EQ(read_file(dir / "small.obj"),
            "# written by geodual\n"
            "v 0.1 0 -2.5\n"
            "v 1 1e-07 3\n"
            "v 0.30000000000000004 2 1e+300\n"
            "f 1 3 2\n");
}

TEST(WriteRoundTrip, RealScansThroughPlyAndObj) {
  TempDir dir;
  for (const char* name : {"nefertiti_100k.ply", "fertility.ply"}) {  // float64 and float32 sources
    SCOPED_TRACE(name);
    const io::LoadedMesh original = read_mesh(test_mesh(name));
    io::write_ply(dir / "scan.ply", original.mesh);
    expect_same_bits(read_mesh(dir / "scan.ply").mesh, original.mesh);
    io::write_obj(dir / "scan.obj", original.mesh);
    expect_same_bits(read_mesh(dir / "scan.obj").mesh, original.mesh);
  }
}

/// The header lines of a PLY file, up to and including end_header.
std::vector<std::string> header_lines(const std::string& file) {
  std::vector<std::string> lines;
  std::istringstream stream(file);
  std::string line;
  while (std::getline(stream, line)) {
    lines.push_back(line);
    if (line == "end_header") break;
  }
  return lines;
}

template <class T>
T value_at(const std::string& file, std::size_t offset) {
  T value;
  std::memcpy(&value, file.data() + offset, sizeof value);
  return value;  // the test host is little-endian, like the file
}

TEST(WriteRoundTrip, PlyVertexPropertiesAreWrittenAsDeclared) {
  static_assert(std::endian::native == std::endian::little);
  TempDir dir;
  TriangleMesh mesh = awkward_mesh();
  VertexAttributes properties;
  properties.scalars = {
      {"distance", ValueType::float64, {0.5, 1.0 / 3.0, 2, 3, 1e-300}},
      {"weight", ValueType::float32, {1.5, -2, static_cast<double>(0.1f), 4, 5}},
      {"site", ValueType::int32, {-1, 0, 7, 2147483647, -2147483648.0}},
  };
  io::write_ply(dir / "props.ply", mesh, properties);
  const std::string file = read_file(dir / "props.ply");

  EXPECT_EQ(header_lines(file),
            (std::vector<std::string>{"ply", "format binary_little_endian 1.0", "comment written by geodual",
                                      "element vertex 5", "property double x", "property double y", "property double z",
                                      "property double distance", "property float weight", "property int site",
                                      "element face 3", "property list uchar int vertex_indices", "end_header"}));
  const std::size_t body = file.find("end_header\n") + 11;
  constexpr std::size_t record = 3 * 8 + 8 + 4 + 4;
  ASSERT_EQ(file.size(), body + 5 * record + 3 * 13);
  for (std::size_t v = 0; v < 5; ++v) {
    const std::size_t at = body + v * record;
    EXPECT_EQ(value_at<double>(file, at + 8), mesh.vertices(static_cast<Eigen::Index>(v), 1));
    EXPECT_EQ(value_at<double>(file, at + 24), properties.scalars[0].values[v]);
    EXPECT_EQ(value_at<float>(file, at + 32), static_cast<float>(properties.scalars[1].values[v]));
    EXPECT_EQ(value_at<std::int32_t>(file, at + 36), static_cast<std::int32_t>(properties.scalars[2].values[v]));
  }
  const std::size_t faces = body + 5 * record;
  EXPECT_EQ(file[faces], 3);
  EXPECT_EQ(value_at<std::int32_t>(file, faces + 13 + 1 + 4), 3);  // face 1, corner 1

  // The reader gives the properties back with their names, types and values.
  const io::LoadedMesh loaded = read_mesh(dir / "props.ply");
  expect_same_bits(loaded.mesh, mesh);
  ASSERT_EQ(loaded.attributes.scalars.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(loaded.attributes.scalars[s].name, properties.scalars[s].name);
    EXPECT_EQ(loaded.attributes.scalars[s].type, properties.scalars[s].type);
    EXPECT_EQ(loaded.attributes.scalars[s].values, properties.scalars[s].values);
  }
  EXPECT_TRUE(loaded.info.notes.empty());
}

TEST(WriteRoundTrip, InvalidPlyPropertiesAreRefusedAndNothingIsWritten) {
  TempDir dir;
  const TriangleMesh mesh = awkward_mesh();
  const fs::path path = dir / "bad.ply";
  const auto refuse = [&](VertexScalar scalar, std::string_view expected) {
    VertexAttributes attributes;
    attributes.scalars.push_back(std::move(scalar));
    const std::string message = error_message([&] { io::write_ply(path, mesh, attributes); });
    EXPECT_TRUE(message.starts_with(path.string() + ": ")) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(path));
  };
  refuse({"short", ValueType::float64, {1, 2}}, "scalar 'short': 2 rows for 5 vertices");
  refuse({"two words", ValueType::float32, std::vector<double>(5)}, "must be one word");
  refuse({"", ValueType::float32, std::vector<double>(5)}, "must be one word");
  refuse({"x", ValueType::int32, std::vector<double>(5)}, "taken by the coordinates");
  VertexAttributes twice_given;
  twice_given.scalars = {{"a", ValueType::float32, std::vector<double>(5)},
                         {"a", ValueType::float64, std::vector<double>(5)}};
  const std::string twice = error_message([&] { io::write_ply(path, mesh, twice_given); });
  EXPECT_NE(twice.find("vertex property 'a' is given twice"), std::string::npos) << twice;
  // A scalar named like a colour channel that is written too.
  VertexAttributes clash;
  clash.colors = ColorMatrix::Zero(5, 3);
  clash.scalars = {{"red", ValueType::uint8, std::vector<double>(5)}};
  const std::string red = error_message([&] { io::write_ply(path, mesh, clash); });
  EXPECT_NE(red.find("vertex property 'red' is given twice"), std::string::npos) << red;
  EXPECT_FALSE(fs::exists(path));
}

TEST(WriteRoundTrip, FacesOutOfRangeAreRefused) {
  TempDir dir;
  TriangleMesh mesh = awkward_mesh();
  mesh.faces(2, 1) = 5;
  for (const char* name : {"bad.ply", "bad.obj"}) {
    const std::string message = error_message([&] { io::write_mesh(dir / name, mesh); });
    EXPECT_EQ(message, (dir / name).string() + ": triangle 2 refers to vertex 5, but the mesh has 5 vertices");
    EXPECT_FALSE(fs::exists(dir / name));
  }
}

TEST(WriteRoundTrip, WriteMeshChoosesTheWriterByExtension) {
  TempDir dir;
  const TriangleMesh mesh = awkward_mesh();
  io::write_mesh(dir / "a.ply", mesh);
  EXPECT_TRUE(read_file(dir / "a.ply").starts_with("ply\nformat binary_little_endian 1.0\n"));
  io::write_mesh(dir / "b.OBJ", mesh);
  EXPECT_TRUE(read_file(dir / "b.OBJ").starts_with("# written by geodual\nv "));
  TriangleMesh small;  // glTF stores float32: use values it can hold
  small.vertices.resize(3, 3);
  small.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  small.faces.resize(1, 3);
  small.faces << 0, 1, 2;
  io::write_mesh(dir / "c.glb", small);
  EXPECT_TRUE(read_file(dir / "c.glb").starts_with("glTF"));
  io::write_mesh(dir / "d.gltf", small);
  EXPECT_TRUE(read_file(dir / "d.gltf").starts_with("{"));
  for (const char* name : {"c.glb", "d.gltf"}) {
    EXPECT_EQ(vertex_list(read_mesh(dir / name).mesh), vertex_list(small));
  }
}

TEST(WriteRoundTrip, WriteMeshRefusesOtherExtensions) {
  TempDir dir;
  const TriangleMesh mesh = awkward_mesh();
  EXPECT_EQ(error_message([&] { io::write_mesh(dir / "out.xyz", mesh); }),
            (dir / "out.xyz").string() + ": unknown output extension '.xyz' (expected .ply, .obj, .glb or .gltf)");
  EXPECT_EQ(error_message([&] { io::write_mesh(dir / "out", mesh); }),
            (dir / "out").string() + ": unknown output extension '' (expected .ply, .obj, .glb or .gltf)");
  EXPECT_EQ(error_message([&] { io::write_mesh(dir / "out.stl", mesh); }),
            (dir / "out.stl").string() + ": writing STL is not supported (use .ply, .obj, .glb or .gltf)");
  EXPECT_EQ(error_message([&] { io::write_mesh(dir / "out.off", mesh); }),
            (dir / "out.off").string() + ": writing OFF is not supported (use .ply, .obj, .glb or .gltf)");
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace geodual::test
