// Every way reading can fail ends in a geodual::Error whose message starts
// with the file's path and says precisely what is wrong: the line for text
// formats, the element and its index for binary ones.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::test {
namespace {

using io::read_mesh;

/// Writes `bytes` to `name`, reads it, and checks that the error message
/// starts with the path and contains every one of `parts`.
void expect_read_error(const TempDir& dir, std::string_view name, std::string_view bytes,
                       std::initializer_list<std::string_view> parts) {
  const fs::path path = write_file(dir / name, bytes);
  const std::string message = error_message([&] { read_mesh(path); });
  EXPECT_TRUE(message.starts_with(path.string() + ": ")) << message;
  for (const std::string_view part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing in: " << message;
  }
}

constexpr std::string_view ply_triangle_header =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

/// A binary little-endian PLY with `vertices` float vertices at (i, 0, 0)
/// and the triangles (0, i, i+1).
std::string binary_fan(std::uint32_t vertices) {
  ByteWriter file;
  file.text("ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
            "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(vertices - 2) +
            "\nproperty list uchar int vertex_indices\nend_header\n");
  for (std::uint32_t i = 0; i < vertices; ++i) {
    file.put(static_cast<float>(i)).put(0.f).put(0.f);
  }
  for (std::uint32_t i = 1; i + 1 < vertices; ++i) {
    file.put<std::uint8_t>(3).put<std::int32_t>(0);
    file.put(static_cast<std::int32_t>(i)).put(static_cast<std::int32_t>(i + 1));
  }
  return file.str();
}

std::size_t header_size(const std::string& ply) { return ply.find("end_header\n") + 11; }

TEST(ReadMeshErrors, MissingFile) {
  TempDir dir;
  const fs::path path = dir / "absent.ply";
  const std::string message = error_message([&] { read_mesh(path); });
  EXPECT_EQ(message, path.string() + ": no such file");
}

TEST(ReadMeshErrors, Directory) {
  TempDir dir;
  fs::create_directory(dir / "folder.obj");
  const std::string message = error_message([&] { read_mesh(dir / "folder.obj"); });
  EXPECT_EQ(message, (dir / "folder.obj").string() + ": is a directory, expected a mesh file");
}

TEST(ReadMeshErrors, UnknownExtension) {
  TempDir dir;
  const fs::path path = write_file(dir / "mesh.xyz", "1 2 3\n");
  const std::string message = error_message([&] { read_mesh(path); });
  EXPECT_TRUE(message.starts_with(path.string() + ": unknown mesh file extension '.xyz'")) << message;
  const std::string none = error_message([&] { read_mesh(write_file(dir / "mesh", "")); });
  EXPECT_NE(none.find("unknown mesh file extension"), std::string::npos) << none;
}

TEST(ReadMeshErrors, EmptyFileOfEveryFormat) {
  TempDir dir;
  for (const char* name : {"e.ply", "e.obj", "e.off", "e.stl", "e.glb", "e.gltf"}) {
    const fs::path path = write_file(dir / name, "");
    EXPECT_EQ(error_message([&] { read_mesh(path); }), path.string() + ": the file is empty");
  }
}

TEST(ReadMeshErrors, TruncatedBinaryPlyNamesTheElementRecord) {
  TempDir dir;
  const std::string full = binary_fan(5000);
  // Cut inside vertex 1234 (12 bytes per vertex).
  const std::size_t cut = header_size(full) + 1234 * 12 + 5;
  const fs::path path = write_file(dir / "cut.ply", full.substr(0, cut));
  EXPECT_EQ(error_message([&] { read_mesh(path); }),
            path.string() + ": truncated binary data: vertex 1234 of 5000 ends past the end of the file (file is " +
                std::to_string(cut) + " bytes)");
  // Cut inside the last face: the list's items run past the end.
  expect_read_error(dir, "cut_face.ply", full.substr(0, full.size() - 3),
                    {"truncated binary data: face 4997 of 4998 ends past the end of the file"});
  // Cut right after the count byte of the last face.
  expect_read_error(dir, "cut_count.ply", full.substr(0, full.size() - 12),
                    {"truncated binary data: face 4997 of 4998"});
}

TEST(ReadMeshErrors, TruncatedRealScan) {
  TempDir dir;
  const std::string bunny = read_file(test_mesh("bunny.ply"));
  expect_read_error(dir, "bunny.ply", bunny.substr(0, bunny.size() / 2),
                    {"truncated binary data: face ", " of 69451 ends past the end of the file"});
  expect_read_error(dir, "bunny_header.ply", bunny.substr(0, header_size(bunny) + 100),
                    {"truncated binary data: vertex 8 of 35947"});
}

TEST(ReadMeshErrors, TruncatedBinaryStl) {
  TempDir dir;
  ByteWriter stl;
  stl.text(std::string(80, ' ')).put<std::uint32_t>(3);
  for (int t = 0; t < 2; ++t) {
    for (int i = 0; i < 12; ++i) stl.put(static_cast<float>(i + t));
    stl.put<std::uint16_t>(0);
  }
  expect_read_error(dir, "cut.stl", stl.str(),
                    {"truncated binary data: triangle 2 of 3 ends past the end of the file (file is 184 bytes; 3 "
                     "triangles need 234)"});
  // The same when the comment begins with "solid" but the bytes are not text.
  std::string solid = stl.str();
  solid.replace(0, 5, "solid");
  expect_read_error(dir, "cut_solid.stl", solid, {"truncated binary data: triangle 2 of 3"});
}

TEST(ReadMeshErrors, FaceIndexOutOfRangeNamesFaceAndIndex) {
  TempDir dir;
  expect_read_error(dir, "ascii.ply", std::string(ply_triangle_header) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                    {"face 0 of 1: vertex index 3 is out of range (the file has 3 vertices)"});
  std::string binary = binary_fan(10);
  binary[binary.size() - 1] = '\x7f';  // the last corner of face 7 becomes 0x7f000009
  expect_read_error(dir, "binary.ply", binary, {"face 7 of 8: vertex index 2130706441 is out of range"});
  expect_read_error(dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n",
                    {"line 5: face 2 refers to vertex 4, but the file has only 3 vertices"});
  expect_read_error(dir, "range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n",
                    {"line 6: face 0: vertex index -1 is out of range (the file has 3 vertices)"});
}

TEST(ReadMeshErrors, NonFiniteCoordinatesNameTheVertex) {
  TempDir dir;
  expect_read_error(dir, "nan.ply", std::string(ply_triangle_header) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
                    {"vertex 1 (counting from 0) has a non-finite coordinate y = nan"});
  expect_read_error(dir, "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n",
                    {"vertex 2 (counting from 0) has a non-finite coordinate z = -inf"});
  expect_read_error(dir, "inf.off", "OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n", {"vertex 1", "x = inf"});
  std::string binary = binary_fan(4);
  const std::size_t vertex_3_x = header_size(binary) + 3 * 12;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(binary.data() + vertex_3_x, &nan, sizeof nan);
  expect_read_error(dir, "nan_binary.ply", binary, {"vertex 3 (counting from 0) has a non-finite coordinate x"});
}

TEST(ReadMeshErrors, NoTrianglesAtAll) {
  TempDir dir;
  expect_read_error(dir, "points.ply",
                    "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n1 1 1\n",
                    {"the file holds no triangles (2 vertices, 0 faces)"});
  expect_read_error(dir, "nofaces.ply",
                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
                    {"no triangles"});
  expect_read_error(dir, "points.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", {"no triangles (2 vertices, 0 faces)"});
  expect_read_error(dir, "empty.off", "OFF\n0 0 0\n", {"no triangles"});
  ByteWriter stl;
  stl.text(std::string(80, 'x')).put<std::uint32_t>(0);
  expect_read_error(dir, "empty.stl", stl.str(), {"no triangles"});
  expect_read_error(dir, "empty_ascii.stl", "solid nothing\nendsolid nothing\n", {"no triangles"});
}

TEST(ReadMeshErrors, RandomBytesUnderEveryExtension) {
  TempDir dir;
  std::mt19937 random(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  for (const char* extension : {".ply", ".obj", ".off", ".stl", ".glb", ".gltf"}) {
    for (const std::size_t size : {1u, 7u, 83u, 84u, 85u, 134u, 1000u, 65536u}) {
      std::string bytes(size, '\0');
      for (char& c : bytes) c = static_cast<char>(byte(random));
      const fs::path path = write_file(dir / (std::string("random") + extension), bytes);
      const std::string message = error_message([&] { read_mesh(path); });
      EXPECT_TRUE(message.starts_with(path.string() + ": ")) << extension << " " << size << ": " << message;
    }
  }
}

TEST(ReadMeshErrors, HugeCountsAreRefusedBeforeAllocating) {
  TempDir dir;
  // 10^8 vertices (2.4 GB as doubles) in a file of a few hundred bytes; a
  // giant allocation would first take seconds or fail with "not enough memory".
  expect_read_error(dir, "huge_binary.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "end_header\n" +
                        std::string(100, '\0'),
                    {"truncated binary data: vertex 8 of 100000000 ends past the end of the file"});
  expect_read_error(dir, "huge_faces.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 2000000000\n"
                    "property list uchar int vertex_indices\nend_header\n" +
                        std::string(100, '\0'),
                    {"truncated binary data: face 64 of 2000000000 ends past the end of the file"});
  expect_read_error(dir, "huge_ascii.ply",
                    "ply\nformat ascii 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
                    {"the file ends after 1 of 100000000 'vertex' records (line 10)"});
  expect_read_error(dir, "huge.off", "OFF\n100000000 2000000000 0\n0 0 0\n",
                    {"the file ends before vertex 1 of 100000000 (line 3)"});
  expect_read_error(dir, "too_many.ply",
                    "ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n",
                    {"line 3: the header declares 3000000000 vertices, more than geodual's 32-bit indices"});
}

TEST(ReadMeshErrors, MalformedPlyHeaderLines) {
  TempDir dir;
  const std::string start = "ply\nformat ascii 1.0\n";
  expect_read_error(dir, "magic.ply", "plx\nformat ascii 1.0\nend_header\n", {"not a PLY file"});
  expect_read_error(dir, "format.ply", "ply\nformat binary 1.0\nend_header\n", {"line 2: unknown PLY format 'binary'"});
  expect_read_error(dir, "noformat.ply", "ply\nelement vertex 1\nend_header\n", {"no format line"});
  expect_read_error(dir, "element.ply", start + "element vertex\nend_header\n", {"line 3: malformed element line"});
  expect_read_error(dir, "count.ply", start + "element vertex -5\nend_header\n",
                    {"line 3: element 'vertex' has an invalid count '-5'"});
  expect_read_error(dir, "property.ply", start + "element vertex 1\nproperty float\nend_header\n",
                    {"line 4: malformed property line"});
  expect_read_error(dir, "orphan.ply", start + "property float x\nend_header\n",
                    {"line 3: property declared before any element"});
  expect_read_error(dir, "keyword.ply", start + "elements vertex 1\nend_header\n",
                    {"line 3: malformed PLY header line: unknown keyword 'elements'"});
  expect_read_error(dir, "noend.ply", start + "element vertex 1\nproperty float x\n", {"no end_header line"});
  expect_read_error(dir, "nox.ply", start + "element vertex 1\nproperty float y\nproperty float z\nend_header\n",
                    {"line 3: element 'vertex' has no property 'x'"});
  expect_read_error(dir, "nolist.ply",
                    start +
                        "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 0\nproperty int vertex_indices\nend_header\n",
                    {"line 7: face property 'vertex_indices' is not a list"});
  expect_read_error(dir, "twice.ply", start + "element vertex 1\nproperty float x\nproperty float x\nend_header\n",
                    {"line 5: property 'x' of element 'vertex' is declared twice"});
}

TEST(ReadMeshErrors, UnsupportedPlyPropertyTypes) {
  TempDir dir;
  const std::string start = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n";
  expect_read_error(dir, "half.ply", start + "property float16 x\nend_header\n",
                    {"line 4: unsupported PLY property type 'float16'"});
  expect_read_error(dir, "string.ply", start + "property float x\nproperty string name\nend_header\n",
                    {"line 5: unsupported PLY property type 'string'"});
  expect_read_error(dir, "float_count.ply", start + "property list float int values\nend_header\n",
                    {"line 4: list property 'values' has a length of type 'float'"});
  expect_read_error(dir, "float_index.ply",
                    start +
                        "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                        "property list uchar float vertex_indices\nend_header\n",
                    {"line 7: face property 'vertex_indices' holds items of type float"});
}

TEST(ReadMeshErrors, MalformedPlyBodies) {
  TempDir dir;
  const std::string header(ply_triangle_header);
  expect_read_error(dir, "few.ply", header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", {"line 11: too few values for vertex 1"});
  expect_read_error(dir, "word.ply", header + "0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n", {"line 11: 'zero' is not a number"});
  expect_read_error(dir, "extra.ply", header + "0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", {"line 10: more values than the 3"});
  expect_read_error(dir, "short.ply", header + "0 0 0\n1 0 0\n", {"the file ends after 2 of 3 'vertex' records"});
  expect_read_error(dir, "uchar.ply", header + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n",
                    {"line 13: value 300 does not fit the type uchar"});
  expect_read_error(dir, "corners.ply", header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                    {"face 0 of 1 has 2 corners; a face needs at least 3"});
  // A negative list length in a binary file (count type char).
  ByteWriter binary;
  binary.text(
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list char int vertex_indices\nelement extra 1\n"
      "property list char int values\nend_header\n");
  for (int i = 0; i < 9; ++i) binary.put(static_cast<float>(i));
  binary.put<std::int8_t>(3).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2);
  binary.put<std::int8_t>(-2);
  expect_read_error(dir, "negative.ply", binary.str(), {"extra 0 of 1: list 'values' has a negative length -2"});
}

TEST(ReadMeshErrors, ObjIndicesAndCorners) {
  TempDir dir;
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_read_error(dir, "zero.obj", triangle + "f 0 1 2\n", {"line 4: vertex index 0 in face corner '0'"});
  expect_read_error(dir, "negative.obj", triangle + "f 1 2 -4\n",
                    {"line 4: relative vertex index -4 reaches before the first vertex (3 vertices read so far)"});
  expect_read_error(dir, "two.obj", triangle + "f 1 2\n", {"line 4: face 1 has 2 corners; a face needs at least 3"});
  expect_read_error(dir, "bare.obj", triangle + "f\n", {"line 4: face 1 has 0 corners"});
  expect_read_error(dir, "word.obj", triangle + "f 1 2 three\n", {"line 4: malformed face corner 'three'"});
  expect_read_error(dir, "slash.obj", triangle + "f 1 2 /3\n", {"line 4: malformed face corner '/3'"});
  expect_read_error(dir, "vertex.obj", "v 0 0\n", {"line 1: vertex has 2 coordinates"});
  expect_read_error(dir, "coordinate.obj", "v 0 x 0\n", {"line 1: vertex coordinate 'x' is not a number"});
}

TEST(ReadMeshErrors, MalformedOffAndStl) {
  TempDir dir;
  expect_read_error(dir, "header.off", "OFX\n3 1 0\n", {"line 1: not an OFF file"});
  expect_read_error(dir, "binary.off", "OFF BINARY\n", {"binary OFF is not supported"});
  expect_read_error(dir, "counts.off", "OFF\n3 x 0\n", {"line 2: malformed face count 'x'"});
  expect_read_error(dir, "corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                    {"line 6: face 0 has 2 corners; a face needs at least 3"});
  expect_read_error(dir, "missing.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                    {"line 6: face 0 declares 4 corners but lists 3"});
  expect_read_error(dir, "short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", {"the file ends before vertex 3 of 4"});
  expect_read_error(dir, "keyword.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvortex 1 0 0\n",
                    {"line 5: unexpected 'vortex' in ASCII STL (inside a facet)"});
  expect_read_error(dir, "open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
                    {"the file ends inside the facet that begins on line 2"});
  expect_read_error(dir, "two.stl",
                    "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                    "endfacet\nendsolid x\n",
                    {"line 7: facet has 2 vertices"});
  expect_read_error(dir, "tiny.stl", "hello", {"not an STL file"});
}

TEST(ReadMeshErrors, FromMemoryUsesTheGivenName) {
  const std::string text = "v 0 0 0\nf 1 1 1 1 2\n";
  const auto bytes = std::as_bytes(std::span(text.data(), text.size()));
  const std::string message =
      error_message([&] { io::read_mesh_from_memory(bytes, io::MeshFormat::obj, "upload/scan.obj"); });
  EXPECT_EQ(message, "upload/scan.obj: line 2: face 1 refers to vertex 2, but the file has only 1 vertices");
}

}  // namespace
}  // namespace geodual::test
