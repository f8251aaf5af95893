// PLY reading: ascii and both binary byte orders, every count and index type,
// extra properties and elements anywhere, polygons, and the real scans.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::test {
namespace {

using io::read_mesh;

constexpr std::string_view quad_and_triangle_ascii =
    "ply\n"
    "format ascii 1.0\n"
    "comment a unit square as one quad, a triangle, and one unused vertex\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n"
    "5 5 5\n"
    "4 0 1 2 3\n"
    "3 2 1 0\n";

TEST(PlyReader, AsciiQuadIsFanTriangulatedAndUnusedVertexStays) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "quad.ply", quad_and_triangle_ascii);
  EXPECT_EQ(loaded.mesh.num_vertices(), 5);
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 2, 3, 2, 1, 0}));
  EXPECT_EQ(loaded.info.polygons_split, 1);
  EXPECT_EQ(loaded.info.format, io::MeshFormat::ply);
  EXPECT_EQ(loaded.info.encoding, "ascii float32");
  EXPECT_EQ(loaded.mesh.vertices(4, 0), 5.0);
  EXPECT_EQ(loaded.mesh.vertices(2, 1), 1.0);
}

TEST(PlyReader, AsciiValuesTakeTheDeclaredType) {
  TempDir dir;
  const std::string header_start = "ply\nformat ascii 1.0\nelement vertex 3\n";
  const std::string rest =
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0.1 -2.5e-3 +7\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto as_double =
      read_text(dir, "d.ply", header_start + "property double x\nproperty double y\nproperty double z\n" + rest);
  EXPECT_EQ(as_double.mesh.vertices(0, 0), 0.1);
  EXPECT_EQ(as_double.mesh.vertices(0, 1), -2.5e-3);
  EXPECT_EQ(as_double.mesh.vertices(0, 2), 7.0);
  const auto as_float =
      read_text(dir, "f.ply", header_start + "property float x\nproperty float y\nproperty float z\n" + rest);
  EXPECT_EQ(as_float.mesh.vertices(0, 0), static_cast<double>(0.1f));
  EXPECT_EQ(as_float.mesh.vertices(0, 1), static_cast<double>(-2.5e-3f));
}

TEST(PlyReader, CrlfLineEndsInHeaderAndAsciiBody) {
  TempDir dir;
  std::string crlf;
  for (const char c : quad_and_triangle_ascii) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  }
  const io::LoadedMesh loaded = read_text(dir, "crlf.ply", crlf);
  EXPECT_EQ(loaded.mesh.num_vertices(), 5);
  EXPECT_EQ(loaded.mesh.num_faces(), 3);
}

/// A binary PLY with 4 vertices (x y z of `coordinate` type) and faces
/// {0 1 2 3} (a quad) and {3 2 0}, with the given list types.
std::string binary_quad(std::endian order, std::string_view coordinate, std::string_view count_type,
                        std::string_view index_type, std::string_view list_name = "vertex_indices") {
  ByteWriter file(order);
  file.text("ply\nformat ")
      .text(order == std::endian::little ? "binary_little_endian" : "binary_big_endian")
      .text(" 1.0\nelement vertex 4\n");
  for (const char* axis : {"x", "y", "z"}) {
    file.text("property ").text(coordinate).text(" ").text(axis).text("\n");
  }
  file.text("element face 2\nproperty list ").text(count_type).text(" ").text(index_type).text(" ").text(list_name);
  file.text("\nend_header\n");
  const double coordinates[4][3] = {{0, 0, 0}, {1.5, 0, -2}, {1.5, 2.25, 0}, {0, 2.25, 8}};
  for (const auto& vertex : coordinates) {
    for (const double value : vertex) {
      file.put_as(coordinate, value);
    }
  }
  file.put_as(count_type, 4).put_as(index_type, 0).put_as(index_type, 1).put_as(index_type, 2).put_as(index_type, 3);
  file.put_as(count_type, 3).put_as(index_type, 3).put_as(index_type, 2).put_as(index_type, 0);
  return file.str();
}

void expect_binary_quad(const io::LoadedMesh& loaded) {
  EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{0, 0, 0, 1.5, 0, -2, 1.5, 2.25, 0, 0, 2.25, 8}));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 2, 3, 3, 2, 0}));
  EXPECT_EQ(loaded.info.polygons_split, 1);
}

TEST(PlyReader, BinaryBothByteOrdersFloatAndDouble) {
  TempDir dir;
  for (const std::endian order : {std::endian::little, std::endian::big}) {
    for (const std::string_view coordinate : {"float", "double", "float32", "float64"}) {
      SCOPED_TRACE(std::string(coordinate) + (order == std::endian::little ? " little" : " big"));
      const io::LoadedMesh loaded = read_text(dir, "b.ply", binary_quad(order, coordinate, "uchar", "int"));
      expect_binary_quad(loaded);
      const std::string expected_encoding =
          std::string(order == std::endian::little ? "binary_little_endian " : "binary_big_endian ") +
          (coordinate.starts_with("float") && coordinate != "float64" ? "float32" : "float64");
      EXPECT_EQ(loaded.info.encoding, expected_encoding);
    }
  }
}

TEST(PlyReader, EveryListCountTypeAndIndexType) {
  TempDir dir;
  const std::array<std::string_view, 6> integer_types = {"uchar", "char", "ushort", "short", "uint", "int"};
  for (const std::endian order : {std::endian::little, std::endian::big}) {
    for (const std::string_view count_type : integer_types) {
      for (const std::string_view index_type : integer_types) {
        SCOPED_TRACE(std::string(count_type) + " " + std::string(index_type));
        expect_binary_quad(read_text(dir, "t.ply", binary_quad(order, "float", count_type, index_type)));
      }
    }
  }
  // The sized spellings too.
  expect_binary_quad(read_text(dir, "s.ply", binary_quad(std::endian::little, "float32", "uint8", "uint32")));
  expect_binary_quad(read_text(dir, "s.ply", binary_quad(std::endian::big, "float64", "int16", "int16")));
}

TEST(PlyReader, VertexIndexIsAcceptedAsListName) {
  TempDir dir;
  expect_binary_quad(
      read_text(dir, "vi.ply", binary_quad(std::endian::little, "float", "uchar", "int", "vertex_index")));
}

/// Extra properties before, between and after x y z, extra face properties
/// (a scalar before the index list, a list after it) and extra elements with
/// list properties before and after the mesh elements.
std::string binary_with_extras(std::endian order) {
  ByteWriter file(order);
  file.text("ply\nformat ")
      .text(order == std::endian::little ? "binary_little_endian" : "binary_big_endian")
      .text(
          " 1.0\n"
          "obj_info scanner 3000\n"
          "element material 2\n"
          "property list uchar float coefficients\n"
          "property int id\n"
          "element vertex 3\n"
          "property uchar red\n"
          "property double x\n"
          "property float confidence\n"
          "property double y\n"
          "property double z\n"
          "property short label\n"
          "element face 1\n"
          "property int flags\n"
          "property list ushort uint vertex_indices\n"
          "property list uchar float texcoord\n"
          "element edge 2\n"
          "property list int int ends\n"
          "property uchar crease\n"
          "end_header\n");
  // material: two records with lists of 3 and 0 floats.
  file.put<std::uint8_t>(3).put(1.0f).put(2.0f).put(3.0f).put<std::int32_t>(7);
  file.put<std::uint8_t>(0).put<std::int32_t>(8);
  const double xyz[3][3] = {{0.25, -1, 3}, {1e-3, 2, 0}, {-7, 0.5, 1e6}};
  for (const auto& p : xyz) {
    file.put<std::uint8_t>(200).put(p[0]).put(0.75f).put(p[1]).put(p[2]).put<std::int16_t>(-3);
  }
  file.put<std::int32_t>(-1).put<std::uint16_t>(3).put<std::uint32_t>(2).put<std::uint32_t>(0).put<std::uint32_t>(1);
  file.put<std::uint8_t>(6).put(0.f).put(0.f).put(1.f).put(0.f).put(0.f).put(1.f);
  file.put<std::int32_t>(2).put<std::int32_t>(0).put<std::int32_t>(1).put<std::uint8_t>(1);
  file.put<std::int32_t>(2).put<std::int32_t>(1).put<std::int32_t>(2).put<std::uint8_t>(0);
  return file.str();
}

TEST(PlyReader, BinaryExtraElementsAreSkippedAndVertexPropertiesRead) {
  TempDir dir;
  for (const std::endian order : {std::endian::little, std::endian::big}) {
    const io::LoadedMesh loaded = read_text(dir, "extras.ply", binary_with_extras(order));
    EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{0.25, -1, 3, 1e-3, 2, 0, -7, 0.5, 1e6}));
    EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{2, 0, 1}));
    ASSERT_FALSE(loaded.info.notes.empty());
    const std::string& note = loaded.info.notes.back();
    EXPECT_NE(note.find("element 'material'"), std::string::npos) << note;
    EXPECT_EQ(note.find("vertex property"), std::string::npos) << note;
    EXPECT_NE(note.find("face property 'texcoord'"), std::string::npos) << note;
    // A lone red is no colour: every vertex property is a scalar of its own type.
    EXPECT_EQ(loaded.attributes.colors.rows(), 0);
    const std::vector<VertexScalar>& scalars = loaded.attributes.scalars;
    ASSERT_EQ(scalars.size(), 3u);
    EXPECT_EQ(scalars[0].name, "red");
    EXPECT_EQ(scalars[0].type, ValueType::uint8);
    EXPECT_EQ(scalars[0].values, (std::vector<double>{200, 200, 200}));
    EXPECT_EQ(scalars[1].name, "confidence");
    EXPECT_EQ(scalars[1].type, ValueType::float32);
    EXPECT_EQ(scalars[1].values, (std::vector<double>{0.75, 0.75, 0.75}));
    EXPECT_EQ(scalars[2].name, "label");
    EXPECT_EQ(scalars[2].type, ValueType::int16);
    EXPECT_EQ(scalars[2].values, (std::vector<double>{-3, -3, -3}));
  }
}

TEST(PlyReader, AsciiExtraPropertiesAndElementsAreSkipped) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "extras.ply",
                                          "ply\n"
                                          "format ascii 1.0\n"
                                          "element material 1\n"
                                          "property list uchar float coefficients\n"
                                          "element vertex 3\n"
                                          "property uchar red\n"
                                          "property float x\n"
                                          "property float y\n"
                                          "property float nx\n"
                                          "property float z\n"
                                          "element face 1\n"
                                          "property list uchar int vertex_indices\n"
                                          "property list uchar float texcoord\n"
                                          "property uchar flags\n"
                                          "element edge 1\n"
                                          "property list int int ends\n"
                                          "end_header\n"
                                          "3 0.5 0.25 1\n"
                                          "255 1 2 0 3\n"
                                          "\n"
                                          "0 4 5 0 6\n"
                                          "1 7 8 0 9\n"
                                          "3 2 1 0 4 0 0 1 1 7\n"
                                          "2 0 2\n");
  EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{2, 1, 0}));
}

TEST(PlyReader, FaceElementBeforeVertexElement) {
  TempDir dir;
  ByteWriter file;
  file.text(
      "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
  file.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(2).put<std::int32_t>(1);
  for (int i = 0; i < 9; ++i) {
    file.put(static_cast<float>(i));
  }
  const io::LoadedMesh loaded = read_text(dir, "order.ply", file.str());
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 2, 1}));
  EXPECT_EQ(loaded.mesh.vertices(2, 2), 8.0);
}

TEST(PlyReader, BinaryHeaderWithCrlfLineEnds) {
  TempDir dir;
  std::string bytes = binary_quad(std::endian::little, "float", "uchar", "int");
  const std::size_t body = bytes.find("end_header\n") + std::string_view("end_header\n").size();
  std::string header = bytes.substr(0, body);
  std::string crlf;
  for (const char c : header) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  }
  expect_binary_quad(read_text(dir, "crlf.ply", crlf + bytes.substr(body)));
}

TEST(PlyReader, DegenerateFacesAndUnreferencedVerticesStay) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "degenerate.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                          "property float y\nproperty float z\nelement face 3\n"
                                          "property list uchar int vertex_indices\nend_header\n"
                                          "0 0 0\n1 0 0\n0 1 0\n0 0 0\n"
                                          "3 0 1 2\n3 0 0 1\n3 0 1 2\n");
  EXPECT_EQ(loaded.mesh.num_vertices(), 4);  // vertex 3 duplicates vertex 0 and is used by no face
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 0, 1, 0, 1, 2}));
}

TEST(PlyReader, HugeHeadersParseInLinearTime) {
  // 100000 extra elements and 100000 extra vertex properties: checking names
  // for duplicates pairwise would take minutes.
  TempDir dir;
  constexpr int extras = 100000;
  std::string header = "ply\nformat ascii 1.0\n";
  for (int i = 0; i < extras; ++i) {
    header += "element extra" + std::to_string(i) + " 0\n";
  }
  header += "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  std::string values;
  for (int i = 0; i < extras; ++i) {
    header += "property uchar p" + std::to_string(i) + "\n";
    values += " 1";
  }
  header += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string body = "0 0 0" + values + "\n1 0 0" + values + "\n0 1 0" + values + "\n3 0 1 2\n";
  const io::LoadedMesh loaded = read_text(dir, "wide.ply", header + body);
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(loaded.mesh.vertices(1, 0), 1.0);
  ASSERT_FALSE(loaded.info.notes.empty());
  EXPECT_NE(loaded.info.notes.back().find(" and 99988 more"), std::string::npos) << loaded.info.notes.back();
  EXPECT_EQ(loaded.attributes.scalars.size(), static_cast<std::size_t>(extras));
  EXPECT_LT(loaded.info.notes.back().size(), 1000u);
}

/// The columns of tests/data/MANIFEST.tsv by name, one map per mesh.
std::vector<std::map<std::string, std::string>> manifest_rows() {
  std::ifstream in(test_mesh("MANIFEST.tsv"));
  EXPECT_TRUE(in) << "cannot open " << test_mesh("MANIFEST.tsv");
  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream stream(line);
    std::string field;
    while (std::getline(stream, field, '\t')) {
      fields.push_back(field);
    }
    return fields;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> columns = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) {
      continue;
    }
    const std::vector<std::string> fields = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < columns.size() && i < fields.size(); ++i) {
      row[columns[i]] = fields[i];
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(PlyReader, RealScansLoadWithTheManifestCounts) {
  const auto rows = manifest_rows();
  ASSERT_GE(rows.size(), 10u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("file"));
    const io::LoadedMesh loaded = read_mesh(test_mesh(row.at("file")));
    EXPECT_EQ(loaded.mesh.num_vertices(), std::stoll(row.at("vertices")));
    EXPECT_EQ(loaded.mesh.num_faces(), std::stoll(row.at("faces")));
    EXPECT_EQ(loaded.info.encoding, "binary_little_endian " + row.at("coord_type"));
    EXPECT_EQ(loaded.info.file_bytes, std::stoull(row.at("bytes")));
  }
}

/// The file with its body converted to big-endian: every vertex value and
/// face index byte-reversed, the format line changed. Only the layout the
/// shared meshes use (x y z of one type, then `list uchar int`) is handled.
std::string to_big_endian(const std::string& little) {
  const std::size_t body = little.find("end_header\n") + std::string_view("end_header\n").size();
  std::string header = little.substr(0, body);
  const std::string from = "binary_little_endian";
  header.replace(header.find(from), from.size(), "binary_big_endian");
  std::istringstream lines(little.substr(0, body));
  std::string line;
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::size_t value_size = 4;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string keyword, a, b;
    words >> keyword >> a >> b;
    if (keyword == "element" && a == "vertex") vertices = std::stoul(b);
    if (keyword == "element" && a == "face") faces = std::stoul(b);
    if (keyword == "property" && a == "double") value_size = 8;
  }
  std::string swapped = little.substr(body);
  char* at = swapped.data();
  for (std::size_t i = 0; i < 3 * vertices; ++i, at += value_size) {
    std::reverse(at, at + value_size);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    const auto corners = static_cast<unsigned char>(*at++);
    for (std::size_t c = 0; c < corners; ++c, at += 4) {
      std::reverse(at, at + 4);
    }
  }
  EXPECT_EQ(at, swapped.data() + swapped.size());
  return header + swapped;
}

TEST(PlyReader, BigEndianCopyOfRealScansReadsIdentically) {
  TempDir dir;
  for (const char* name : {"bunny.ply", "woody.ply"}) {  // float32 and float64 coordinates
    SCOPED_TRACE(name);
    const io::LoadedMesh little = read_mesh(test_mesh(name));
    const io::LoadedMesh big = read_text(dir, name, to_big_endian(read_file(test_mesh(name))));
    EXPECT_TRUE(big.info.encoding.starts_with("binary_big_endian")) << big.info.encoding;
    EXPECT_EQ(vertex_list(big.mesh), vertex_list(little.mesh));
    EXPECT_EQ(face_list(big.mesh), face_list(little.mesh));
  }
}

}  // namespace
}  // namespace geodual::test
