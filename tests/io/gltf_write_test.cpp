// glTF writing: container layout, the JSON the spec (and the Khronos
// validator) requires, normals, colours and custom attributes, determinism,
// input checks and atomic replacement.

#include "glb_parts.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/mesh/error.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;
using gltf_test::Glb;
using gltf_test::split_glb;
using gltf_test::u32_at;
using nlohmann::json;

std::vector<std::byte> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> bytes(chars.size());
  std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

// A tetrahedron's surface plus an isolated vertex (index 4).
TriangleMesh tetrahedron_and_lone_vertex() {
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {5, 5, 5}};
  mesh.faces = FaceMatrix{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

GltfScene one_mesh_scene(TriangleMesh mesh) {
  GltfScene scene;
  scene.triangle_meshes.push_back({.name = "tet", .mesh = std::move(mesh)});
  return scene;
}

// The floats of a FLOAT accessor, read through its buffer view.
std::vector<float> floats_of(const Glb& glb, int accessor_index) {
  const json& accessor = glb.document["accessors"][accessor_index];
  const json& view = glb.document["bufferViews"][accessor["bufferView"].get<int>()];
  EXPECT_EQ(accessor["componentType"], 5126);
  std::vector<float> values(view["byteLength"].get<std::size_t>() / 4);
  std::memcpy(values.data(), glb.bin.data() + view.value("byteOffset", std::size_t{0}), values.size() * 4);
  return values;
}

TEST(GltfWrite, GlbContainerIsWellFormed) {
  const std::vector<std::byte> glb = encode_gltf(one_mesh_scene(tetrahedron_and_lone_vertex()), GltfContainer::glb);
  const Glb parts = split_glb(glb);
  // JSON padding is spaces, BIN padding zeros; the buffer covers the BIN chunk up to its padding.
  const std::size_t json_end = 20 + u32_at(glb, 12);
  EXPECT_NE(glb[json_end - 1], std::byte{0});
  const std::size_t byte_length = parts.document["buffers"][0]["byteLength"].get<std::size_t>();
  EXPECT_LE(byte_length, parts.bin.size());
  EXPECT_GT(byte_length + 4, parts.bin.size());
  for (std::size_t i = byte_length; i < parts.bin.size(); ++i) EXPECT_EQ(parts.bin[i], std::byte{0});
  EXPECT_FALSE(parts.document["buffers"][0].contains("uri"));
}

TEST(GltfWrite, JsonFollowsTheSpec) {
  const Glb glb = split_glb(encode_gltf(one_mesh_scene(tetrahedron_and_lone_vertex()), GltfContainer::glb));
  const json& doc = glb.document;
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  EXPECT_EQ(doc["asset"]["generator"], "geodual");
  EXPECT_EQ(doc["scene"], 0);
  EXPECT_EQ(doc["scenes"][0]["nodes"], json::array({0}));
  EXPECT_EQ(doc["nodes"][0]["mesh"], 0);
  EXPECT_EQ(doc["nodes"][0]["name"], "tet");
  const json& primitive = doc["meshes"][0]["primitives"][0];
  EXPECT_EQ(primitive["mode"], 4);
  const json& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(position["type"], "VEC3");
  EXPECT_EQ(position["count"], 5);
  EXPECT_EQ(position["min"], json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(position["max"], json::array({5.0, 5.0, 5.0}));
  const json& indices = doc["accessors"][primitive["indices"].get<int>()];
  EXPECT_EQ(indices["componentType"], 5123);  // UNSIGNED_SHORT: 5 vertices
  EXPECT_EQ(indices["count"], 12);
  EXPECT_EQ(indices["type"], "SCALAR");

  // Every buffer view is used once, 4-byte aligned, inside the buffer, with
  // the target its accessor's use calls for.
  const std::size_t byte_length = doc["buffers"][0]["byteLength"].get<std::size_t>();
  std::vector<int> uses(doc["bufferViews"].size(), 0);
  for (const json& accessor : doc["accessors"]) ++uses[accessor["bufferView"].get<std::size_t>()];
  for (std::size_t v = 0; v < doc["bufferViews"].size(); ++v) {
    const json& view = doc["bufferViews"][v];
    EXPECT_EQ(uses[v], 1);
    const std::size_t offset = view.value("byteOffset", std::size_t{0});  // optional, 0 by default
    EXPECT_EQ(offset % 4, 0u);
    EXPECT_LE(offset + view["byteLength"].get<std::size_t>(), byte_length);
    EXPECT_FALSE(view.contains("byteStride"));
  }
  EXPECT_EQ(doc["bufferViews"][indices["bufferView"].get<int>()]["target"], 34963);
  EXPECT_EQ(doc["bufferViews"][position["bufferView"].get<int>()]["target"], 34962);
}

TEST(GltfWrite, PositionBoundsAreTheStoredFloat32Values) {
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0.1, -0.3, 1e-7}, {2.5, 0.7, -4.0}, {1.0 / 3.0, 1e20, 0.0}};
  mesh.faces = FaceMatrix{{0, 1, 2}};
  const Glb glb = split_glb(encode_gltf(one_mesh_scene(mesh), GltfContainer::glb));
  const json& position = glb.document["accessors"][0];
  EXPECT_EQ(position["min"][0].get<double>(), static_cast<double>(0.1F));
  EXPECT_EQ(position["min"][1].get<double>(), static_cast<double>(-0.3F));
  EXPECT_EQ(position["max"][1].get<double>(), static_cast<double>(1e20F));
  EXPECT_EQ(position["max"][2].get<double>(), static_cast<double>(1e-7F));
  EXPECT_EQ(floats_of(glb, 0)[6], static_cast<float>(1.0 / 3.0));
}

TEST(GltfWrite, NormalsAreAreaWeightedUnitVectors) {
  // Vertex 0 is shared by a large triangle facing +z and a small one facing +x:
  // its normal leans towards +z in proportion to the areas (4 : 1).
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 1, 0}, {0, 0, 1}, {9, 9, 9}};
  mesh.faces = FaceMatrix{{0, 1, 2}, {0, 3, 4}};
  const Glb glb = split_glb(encode_gltf(one_mesh_scene(mesh), GltfContainer::glb));
  const json& primitive = glb.document["meshes"][0]["primitives"][0];
  const std::vector<float> normals = floats_of(glb, primitive["attributes"]["NORMAL"].get<int>());
  ASSERT_EQ(normals.size(), 18u);
  for (std::size_t v = 0; v < 6; ++v) {
    const double length = std::hypot(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    EXPECT_NEAR(length, 1.0, 1e-6) << "vertex " << v;
  }
  const double expected = 1.0 / std::sqrt(17.0);  // (1, 0, 4) / sqrt(17)
  EXPECT_NEAR(normals[0], expected, 1e-7);
  EXPECT_NEAR(normals[2], 4 * expected, 1e-7);
  EXPECT_EQ(normals[5], 1.0F);   // vertex 1: only the +z triangle
  EXPECT_EQ(normals[9], 1.0F);   // vertex 3: only the +x triangle
  EXPECT_EQ(normals[15], 0.0F);  // vertex 5: no triangle -> (0, 0, 1)
  EXPECT_EQ(normals[17], 1.0F);
}

TEST(GltfWrite, DegenerateTrianglesGiveTheFallbackNormal) {
  TriangleMesh mesh;
  mesh.vertices = VertexMatrix{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  mesh.faces = FaceMatrix{{0, 1, 2}};
  const Glb glb = split_glb(encode_gltf(one_mesh_scene(mesh), GltfContainer::glb));
  const std::vector<float> normals = floats_of(glb, 1);
  EXPECT_EQ(normals, std::vector<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}));
}

TEST(GltfWrite, IndexWidthFollowsTheVertexCount) {
  const auto index_type = [](Index vertex_count) {
    TriangleMesh mesh;
    mesh.vertices = VertexMatrix::Zero(vertex_count, 3);
    mesh.vertices.col(0).setLinSpaced(0.0, 1.0);
    mesh.vertices(1, 1) = 1.0;
    mesh.faces = FaceMatrix{{0, 1, vertex_count - 1}};
    const Glb glb = split_glb(encode_gltf(one_mesh_scene(mesh), GltfContainer::glb));
    return glb.document["accessors"][2]["componentType"].get<int>();
  };
  EXPECT_EQ(index_type(65535), 5123);  // largest index 65534: below the restart value 65535
  EXPECT_EQ(index_type(65536), 5125);
}

TEST(GltfWrite, ColoursScalarsLinesPointsAndExtras) {
  GltfScene scene = one_mesh_scene(tetrahedron_and_lone_vertex());
  scene.triangle_meshes[0].colors = ColorMatrix::Constant(5, 4, 0.5F);
  scene.triangle_meshes[0].scalars.push_back({.name = "_DISTANCE", .values = {0, 1, 2, 3, 4}});
  scene.triangle_meshes[0].scalars.push_back({.name = "_CELL", .values = {0, 0, 1, 1, 2}});
  GltfLineSet lines;
  lines.name = "bisectors";
  lines.points = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  lines.segments = SegmentMatrix{{0, 1}, {1, 2}};
  lines.colors = ColorMatrix::Constant(3, 3, 1.0F);
  scene.line_sets.push_back(lines);
  GltfPointSet points;
  points.points = VertexMatrix{{0.5, 0.5, 0.5}};
  scene.point_sets.push_back(points);
  scene.extras_json = R"({"sites": 42, "energy": [1.5, 0.25], "name": "run"})";

  const Glb glb = split_glb(encode_gltf(scene, GltfContainer::glb));
  const json& doc = glb.document;
  ASSERT_EQ(doc["nodes"].size(), 3u);
  EXPECT_EQ(doc["scenes"][0]["nodes"], json::array({0, 1, 2}));
  EXPECT_EQ(doc["nodes"][1]["name"], "bisectors");
  EXPECT_FALSE(doc["nodes"][2].contains("name"));

  const json& triangles = doc["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_EQ(doc["accessors"][triangles["COLOR_0"].get<int>()]["type"], "VEC4");
  const json& distance = doc["accessors"][triangles["_DISTANCE"].get<int>()];
  EXPECT_EQ(distance["type"], "SCALAR");
  EXPECT_EQ(distance["count"], 5);
  EXPECT_EQ(floats_of(glb, triangles["_DISTANCE"].get<int>()), std::vector<float>({0, 1, 2, 3, 4}));
  EXPECT_EQ(floats_of(glb, triangles["_CELL"].get<int>()), std::vector<float>({0, 0, 1, 1, 2}));

  const json& line_primitive = doc["meshes"][1]["primitives"][0];
  EXPECT_EQ(line_primitive["mode"], 1);
  EXPECT_EQ(doc["accessors"][line_primitive["indices"].get<int>()]["count"], 4);
  EXPECT_EQ(doc["accessors"][line_primitive["attributes"]["COLOR_0"].get<int>()]["type"], "VEC3");
  EXPECT_TRUE(doc["accessors"][line_primitive["attributes"]["POSITION"].get<int>()].contains("min"));

  const json& point_primitive = doc["meshes"][2]["primitives"][0];
  EXPECT_EQ(point_primitive["mode"], 0);
  EXPECT_FALSE(point_primitive.contains("indices"));
  EXPECT_EQ(doc["accessors"][point_primitive["attributes"]["POSITION"].get<int>()]["max"],
            json::array({0.5, 0.5, 0.5}));

  EXPECT_EQ(doc["asset"]["extras"]["sites"], 42);
  EXPECT_EQ(doc["asset"]["extras"]["energy"], json::array({1.5, 0.25}));
  EXPECT_EQ(doc["asset"]["extras"]["name"], "run");
}

TEST(GltfWrite, AttributesBecomeLinearColoursGivenNormalsAndNamedScalars) {
  const TriangleMesh mesh = tetrahedron_and_lone_vertex();
  VertexAttributes attributes;
  attributes.colors = ColorMatrix{{1, 0.5f, 0, 0.25f}, {0, 0, 0, 1}, {0.2f, 0.4f, 0.6f, 1}, {1, 1, 1, 1}, {0, 1, 0, 0}};
  attributes.normals = VertexMatrix{{0, 0, 2}, {0, 0, 0}, {1, 0, 0}, {0, 3, 4}, {0, 1, 0}};
  attributes.scalars.push_back({"intensity", ValueType::uint16, {10, 20, 30, 40, 50}});
  const Glb glb =
      split_glb(encode_gltf({.triangle_meshes = {gltf_triangle_mesh("scan", mesh, attributes)}}, GltfContainer::glb));
  const json& names = glb.document["meshes"][0]["primitives"][0]["attributes"];
  // COLOR_0 is linear: sRGB-decoded colour channels, alpha as it is.
  const std::vector<float> colors = floats_of(glb, names["COLOR_0"].get<int>());
  ASSERT_EQ(colors.size(), 20u);
  for (std::size_t i = 0; i < 20; ++i) {
    const float given = attributes.colors(static_cast<Eigen::Index>(i / 4), static_cast<Eigen::Index>(i % 4));
    EXPECT_FLOAT_EQ(colors[i], i % 4 == 3 ? given : linear_from_srgb(given)) << i;
  }
  EXPECT_NEAR(colors[1], 0.2140, 1e-4);  // sRGB 0.5
  // NORMAL: the given ones normalised; the zero one replaced by the area-weighted normal.
  const std::vector<float> normals = floats_of(glb, names["NORMAL"].get<int>());
  EXPECT_EQ(std::vector<float>(normals.begin(), normals.begin() + 3), std::vector<float>({0, 0, 1}));
  EXPECT_NEAR(std::hypot(normals[3], normals[4], normals[5]), 1.0, 1e-6);
  EXPECT_EQ(std::vector<float>(normals.begin() + 9, normals.begin() + 12), std::vector<float>({0, 0.6f, 0.8f}));
  EXPECT_EQ(floats_of(glb, names["_intensity"].get<int>()), std::vector<float>({10, 20, 30, 40, 50}));
}

TEST(GltfWrite, EmbeddedGltfHoldsTheSameJsonAndADataUri) {
  const GltfScene scene = one_mesh_scene(tetrahedron_and_lone_vertex());
  const Glb glb = split_glb(encode_gltf(scene, GltfContainer::glb));
  const std::vector<std::byte> text = encode_gltf(scene, GltfContainer::gltf_embedded);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), std::byte{'\n'});
  const auto* chars = reinterpret_cast<const char*>(text.data());
  json doc = json::parse(chars, chars + text.size());
  const std::string uri = doc["buffers"][0]["uri"];
  EXPECT_EQ(uri.rfind("data:application/octet-stream;base64,", 0), 0u);
  doc["buffers"][0].erase("uri");
  EXPECT_EQ(doc, glb.document);
}

TEST(GltfWrite, ExtrasAreWrittenVerbatim) {
  // Nulls, empty arrays and objects, integers beyond 32 bits, member order and
  // escapes survive; so do extras shorter than tinygltf's placeholder.
  for (const std::string& extras :
       {std::string(R"({"sampling": null, "energy": [], "o": {}, "bytes": 3000000000, "q": 0.1, "s": "a\"b"})"),
        std::string("{}"), std::string(R"({"a":1})")}) {
    for (const GltfContainer container : {GltfContainer::glb, GltfContainer::gltf_embedded}) {
      SCOPED_TRACE(extras);
      GltfScene scene = one_mesh_scene(tetrahedron_and_lone_vertex());
      scene.triangle_meshes[0].name = R"({"":""})";  // the shape of a placeholder, as a name
      scene.extras_json = extras;
      const std::vector<std::byte> file = encode_gltf(scene, container);
      const std::string text(reinterpret_cast<const char*>(file.data()), file.size());
      EXPECT_NE(text.find("\"extras\":" + nlohmann::ordered_json::parse(extras).dump()), std::string::npos);
      const json doc = container == GltfContainer::glb ? split_glb(file).document : json::parse(text);
      EXPECT_EQ(doc["asset"]["extras"], json::parse(extras));
      EXPECT_EQ(doc["nodes"][0]["name"], R"({"":""})");
    }
  }
}

TEST(GltfWrite, SameSceneSameBytes) {
  GltfScene scene = one_mesh_scene(tetrahedron_and_lone_vertex());
  scene.extras_json = R"({"b": 1, "a": 2})";
  EXPECT_EQ(encode_gltf(scene, GltfContainer::glb), encode_gltf(scene, GltfContainer::glb));
  EXPECT_EQ(encode_gltf(scene, GltfContainer::gltf_embedded), encode_gltf(scene, GltfContainer::gltf_embedded));
}

void expect_encode_error(const GltfScene& scene, std::initializer_list<std::string_view> fragments) {
  try {
    encode_gltf(scene, GltfContainer::glb);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("glTF output: ", 0), 0u) << message;
    for (std::string_view fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
    }
  }
}

TEST(GltfWrite, InvalidInputIsRefusedWithAClearMessage) {
  const GltfScene good = one_mesh_scene(tetrahedron_and_lone_vertex());
  expect_encode_error(GltfScene{}, {"nothing to write"});
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].mesh.faces(3, 1) = 5;
    expect_encode_error(scene, {"triangle mesh 0 'tet'", "face 3 refers to vertex 5", "5 vertices"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].mesh.faces(0, 0) = -1;
    expect_encode_error(scene, {"face 0 refers to vertex -1"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].mesh.vertices(2, 1) = std::nan("");
    expect_encode_error(scene, {"vertex 2", "not a finite float32"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].mesh.vertices(1, 0) = 1e39;  // finite double, beyond float32
    expect_encode_error(scene, {"vertex 1", "not a finite float32"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].mesh.faces.resize(0, 3);
    expect_encode_error(scene, {"triangle mesh 0 'tet'", "no triangles"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].colors = ColorMatrix::Constant(5, 3, 0.5F);
    scene.triangle_meshes[0].colors(4, 2) = 1.5F;
    expect_encode_error(scene, {"colour of vertex 4", "outside [0, 1]"});
    scene.triangle_meshes[0].colors = ColorMatrix::Constant(4, 3, 0.5F);
    expect_encode_error(scene, {"colours are 4 x 3"});
    scene.triangle_meshes[0].colors = ColorMatrix::Constant(5, 2, 0.5F);
    expect_encode_error(scene, {"colours are 5 x 2"});
  }
  {
    GltfScene scene = good;
    scene.triangle_meshes[0].scalars.push_back({.name = "DISTANCE", .values = {0, 1, 2, 3, 4}});
    expect_encode_error(scene, {"'DISTANCE'", "must start with '_'"});
    scene.triangle_meshes[0].scalars = {{.name = "_D", .values = {0, 1, 2, 3, 4}},
                                        {.name = "_D", .values = {0, 1, 2, 3, 4}}};
    expect_encode_error(scene, {"'_D'", "twice"});
    scene.triangle_meshes[0].scalars = {{.name = "_D", .values = {0, 1, 2}}};
    expect_encode_error(scene, {"'_D'", "3 values for 5 vertices"});
    scene.triangle_meshes[0].scalars = {{.name = "_D", .values = {0, 1, INFINITY, 3, 4}}};
    expect_encode_error(scene, {"'_D'", "vertex 2 is not finite"});
  }
  {
    GltfScene scene = good;
    GltfLineSet lines;
    lines.points = VertexMatrix{{0, 0, 0}, {1, 0, 0}};
    lines.segments = SegmentMatrix{{0, 1}, {1, 2}};
    scene.line_sets.push_back(lines);
    expect_encode_error(scene, {"line set 0", "segment 1 refers to vertex 2"});
    scene.line_sets[0].segments.resize(0, 2);
    expect_encode_error(scene, {"line set 0", "no segments"});
  }
  {
    GltfScene scene = good;
    scene.point_sets.push_back({});
    expect_encode_error(scene, {"point set 0", "no vertices"});
  }
  {
    GltfScene scene = good;
    scene.extras_json = "[1, 2]";
    expect_encode_error(scene, {"extras must be a JSON object"});
    scene.extras_json = "{\"unclosed\": ";
    expect_encode_error(scene, {"extras are not valid JSON"});
  }
}

TEST(GltfWrite, InvalidUtf8InNamesIsReplacedNotThrown) {
  GltfScene scene = one_mesh_scene(tetrahedron_and_lone_vertex());
  scene.triangle_meshes[0].name = "bad\xFF name";
  const Glb glb = split_glb(encode_gltf(scene, GltfContainer::glb));
  EXPECT_EQ(glb.document["nodes"][0]["name"], "bad\xEF\xBF\xBD name");
}

class GltfWriteFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geodual_gltf_write_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(GltfWriteFiles, ExtensionPicksTheContainer) {
  const TriangleMesh mesh = tetrahedron_and_lone_vertex();
  write_gltf(dir_ / "a.glb", mesh);
  write_gltf(dir_ / "b.GLTF", mesh);
  const std::vector<std::byte> glb = read_file(dir_ / "a.glb");
  const std::vector<std::byte> gltf = read_file(dir_ / "b.GLTF");
  EXPECT_EQ(std::memcmp(glb.data(), "glTF", 4), 0);
  split_glb(glb);
  ASSERT_FALSE(gltf.empty());
  EXPECT_EQ(gltf.front(), std::byte{'{'});
  // The mesh-only entry point writes what an unnamed one-mesh scene gives.
  GltfScene scene;
  scene.triangle_meshes.push_back({.name = "", .mesh = mesh});
  EXPECT_EQ(glb, encode_gltf(scene, GltfContainer::glb));
  EXPECT_EQ(gltf, encode_gltf(scene, GltfContainer::gltf_embedded));
}

TEST_F(GltfWriteFiles, WrongExtensionIsAnErrorNamingThePath) {
  const fs::path path = dir_ / "mesh.ply";
  try {
    write_gltf(path, tetrahedron_and_lone_vertex());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ": "), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(GltfWriteFiles, FailedWriteLeavesTheOldFileAndNoTemporaries) {
  const fs::path path = dir_ / "out.glb";
  write_gltf(path, tetrahedron_and_lone_vertex());
  const std::vector<std::byte> before = read_file(path);
  TriangleMesh broken = tetrahedron_and_lone_vertex();
  broken.faces(0, 0) = 99;
  try {
    write_gltf(path, broken);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u) << e.what();
  }
  EXPECT_EQ(read_file(path), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace geodual::io
