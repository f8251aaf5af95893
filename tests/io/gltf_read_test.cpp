// glTF reading of hand-built files: buffer sources, node transforms,
// instancing, primitive kinds and accessor layouts.

#include "../../io/src/format_readers.hpp"
#include "gltf_test_bytes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;

using gltf_test::as_span;
using gltf_test::bytes_of;
using gltf_test::data_uri;
using gltf_test::glb_of;

std::vector<std::byte> concat(std::initializer_list<std::vector<std::byte>> parts) {
  std::vector<std::byte> out;
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

LoadedMesh read_json(const std::string& json, const fs::path& name = "hand.gltf") {
  return detail::read_gltf(as_span(json), false, name);
}

bool has_note_containing(const ReadInfo& info, std::string_view text) {
  return std::any_of(info.notes.begin(), info.notes.end(),
                     [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

// A unit square in z = 0 as 4 float positions and 2 triangles.
const std::vector<std::byte> square_positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
const std::vector<std::byte> square_indices_u16 = bytes_of<std::uint16_t>({0, 1, 2, 0, 2, 3});

// A file with one square mesh; buffer 0 = positions (48 bytes) + indices (12 bytes).
std::string square_gltf(const std::string& buffer_uri_member, const std::string& nodes = R"([{"mesh":0}])") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes + R"(,
    "meshes":[{"name":"square","primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60)" +
         buffer_uri_member + "}]}";
}

void expect_square(const TriangleMesh& mesh, double dx = 0.0) {
  ASSERT_EQ(mesh.num_vertices(), 4);
  ASSERT_EQ(mesh.num_faces(), 2);
  EXPECT_EQ(mesh.vertices.row(2), Eigen::RowVector3d(1 + dx, 1, 0));
  EXPECT_EQ(mesh.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
}

class GltfReadFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geodual_gltf_read_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const fs::path& path, std::span<const std::byte> bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }

  fs::path dir_;
};

TEST_F(GltfReadFiles, ExternalBinNextToTheGltf) {
  write(dir_ / "square.bin", concat({square_positions, square_indices_u16}));
  const LoadedMesh loaded = read_json(square_gltf(R"(,"uri":"square.bin")"), dir_ / "square.gltf");
  expect_square(loaded.mesh);
  EXPECT_EQ(loaded.info.format, MeshFormat::gltf);
}

TEST_F(GltfReadFiles, ExternalBinInSubfolderWithPercentEscapes) {
  write(dir_ / "data dir" / "square.bin", concat({square_positions, square_indices_u16}));
  const LoadedMesh loaded =
      read_json(square_gltf(R"(,"uri":"./data%20dir/../data%20dir/square.bin")"), dir_ / "square.gltf");
  expect_square(loaded.mesh);
}

TEST_F(GltfReadFiles, ExternalBinMayBeLongerThanByteLength) {
  write(dir_ / "square.bin", concat({square_positions, square_indices_u16, bytes_of<std::uint32_t>({7, 7})}));
  expect_square(read_json(square_gltf(R"(,"uri":"square.bin")"), dir_ / "square.gltf").mesh);
}

TEST(GltfRead, DataUriBuffer) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  expect_square(read_json(square_gltf(R"(,"uri":")" + uri + "\"")).mesh);
}

TEST(GltfRead, DataUriWithGltfBufferMediaTypeAndNoPadding) {
  std::string uri =
      "data:application/gltf-buffer;base64," + gltf_test::base64(concat({square_positions, square_indices_u16}));
  while (uri.back() == '=') uri.pop_back();
  expect_square(read_json(square_gltf(R"(,"uri":")" + uri + "\"")).mesh);
}

TEST(GltfRead, GlbWithBinChunk) {
  const std::vector<std::byte> bin = concat({square_positions, square_indices_u16});
  const std::vector<std::byte> glb = glb_of(square_gltf(""), bin);
  const LoadedMesh loaded = detail::read_gltf(glb, true, "square.glb");
  expect_square(loaded.mesh);
  EXPECT_EQ(loaded.info.format, MeshFormat::glb);
  EXPECT_EQ(loaded.info.file_bytes, glb.size());
}

TEST(GltfRead, ContentDecidesBetweenGlbAndJson) {
  const std::vector<std::byte> glb = glb_of(square_gltf(""), concat({square_positions, square_indices_u16}));
  const LoadedMesh glb_named_gltf = detail::read_gltf(glb, false, "misnamed.gltf");
  expect_square(glb_named_gltf.mesh);
  EXPECT_EQ(glb_named_gltf.info.format, MeshFormat::glb);
  EXPECT_TRUE(has_note_containing(glb_named_gltf.info, "despite its name"));

  const std::string json = square_gltf(R"(,"uri":")" + data_uri(concat({square_positions, square_indices_u16})) + "\"");
  const LoadedMesh json_named_glb = detail::read_gltf(as_span(json), true, "misnamed.glb");
  expect_square(json_named_glb.mesh);
  EXPECT_EQ(json_named_glb.info.format, MeshFormat::gltf);
  expect_square(detail::read_gltf(as_span("\xEF\xBB\xBF \n\t" + json), true, "misnamed.glb").mesh);
}

TEST(GltfRead, Utf8ByteOrderMarkIsSkipped) {
  const std::string json =
      "\xEF\xBB\xBF" + square_gltf(R"(,"uri":")" + data_uri(concat({square_positions, square_indices_u16})) + "\"");
  expect_square(read_json(json).mesh);
}

// Two meshes: mesh 0 (the square) under a translated parent node with a
// rotated and scaled child; mesh 1 (a single triangle) under a node with a
// matrix. Positions and triangles are in one data-URI buffer.
TEST(GltfRead, NestedNodesComposeTrsAndMatrixTransforms) {
  const std::vector<std::byte> triangle = bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string uri = data_uri(concat({square_positions, square_indices_u16, triangle}));
  const double s = std::sqrt(0.5);
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,2]}],
    "nodes":[{"name":"parent","translation":[1,2,3],"children":[1]},
             {"name":"child","rotation":[0,0,)" +
                           std::to_string(s) + "," + std::to_string(s) + R"(],"scale":[2,2,2],"mesh":0},
             {"name":"matrix","matrix":[3,0,0,0, 0,1,0,0, 0,0,1,0, 10,20,30,1],"mesh":1}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]},
              {"primitives":[{"attributes":{"POSITION":2}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},
                 {"bufferView":2,"componentType":5126,"count":3,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12},
                   {"buffer":0,"byteOffset":60,"byteLength":36}],
    "buffers":[{"byteLength":96,"uri":")" +
                           uri + R"("}]})";
  const LoadedMesh loaded = read_json(json);
  const TriangleMesh& mesh = loaded.mesh;
  ASSERT_EQ(mesh.num_vertices(), 7);
  ASSERT_EQ(mesh.num_faces(), 3);
  // Square corner (1, 0, 0): scale 2 -> (2, 0, 0), rotate 90 degrees about z
  // -> (0, 2, 0), translate -> (1, 4, 3). std::to_string keeps 6 decimals of
  // sqrt(0.5), so the rotation is exact only to about 1e-6.
  EXPECT_LT((mesh.vertices.row(1) - Eigen::RowVector3d(1, 4, 3)).norm(), 1e-5);
  EXPECT_LT((mesh.vertices.row(2) - Eigen::RowVector3d(-1, 4, 3)).norm(), 1e-5);
  // Triangle through the column-major matrix: x' = 3x + 10, y' = y + 20, z' = z + 30.
  EXPECT_EQ(mesh.vertices.row(4), Eigen::RowVector3d(10, 20, 30));
  EXPECT_EQ(mesh.vertices.row(5), Eigen::RowVector3d(13, 20, 30));
  EXPECT_EQ(mesh.vertices.row(6), Eigen::RowVector3d(10, 21, 30));
  EXPECT_EQ(mesh.faces.row(2), Eigen::RowVector3i(4, 5, 6));
  EXPECT_TRUE(has_note_containing(loaded.info, "node transforms applied to 2 mesh instances"));
}

TEST(GltfRead, MeshInstancedByTwoNodesGivesTwoCopies) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0,1]}],
    "nodes":[{"mesh":0},{"mesh":0,"translation":[5,0,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60,"uri":")" +
                           uri + R"("}]})";
  const TriangleMesh mesh = read_json(json).mesh;
  ASSERT_EQ(mesh.num_vertices(), 8);
  ASSERT_EQ(mesh.num_faces(), 4);
  EXPECT_EQ(mesh.vertices.row(2), Eigen::RowVector3d(1, 1, 0));
  EXPECT_EQ(mesh.vertices.row(6), Eigen::RowVector3d(6, 1, 0));
  EXPECT_EQ(mesh.faces.row(2), Eigen::RowVector3i(4, 5, 6));
  EXPECT_EQ(mesh.faces.row(3), Eigen::RowVector3i(4, 6, 7));
}

TEST(GltfRead, MirroringTransformFlipsWinding) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  const TriangleMesh mesh = read_json(square_gltf(R"(,"uri":")" + uri + "\"", R"([{"mesh":0,"scale":[-1,1,1]}])")).mesh;
  ASSERT_EQ(mesh.num_faces(), 2);
  EXPECT_EQ(mesh.vertices.row(1), Eigen::RowVector3d(-1, 0, 0));
  EXPECT_EQ(mesh.faces.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 3, 2));
}

TEST(GltfRead, IdentityTransformKeepsCoordinatesBitExact) {
  // -0.0 and a value with all mantissa bits set: any arithmetic would disturb them.
  const std::vector<std::byte> positions =
      bytes_of<float>({-0.0F, 0.1F, 3.4e38F, std::nextafter(1.0F, 2.0F), -1e-38F, 0, 0, 1, 0});
  const std::string json =
      R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":")" +
      data_uri(positions) + R"("}]})";
  const TriangleMesh mesh = read_json(json).mesh;
  ASSERT_EQ(mesh.num_vertices(), 3);
  EXPECT_TRUE(std::signbit(mesh.vertices(0, 0)));
  EXPECT_EQ(mesh.vertices(0, 1), static_cast<double>(0.1F));
  EXPECT_EQ(mesh.vertices(0, 2), static_cast<double>(3.4e38F));
  EXPECT_EQ(mesh.vertices(1, 0), static_cast<double>(std::nextafter(1.0F, 2.0F)));
  EXPECT_EQ(mesh.vertices(1, 1), static_cast<double>(-1e-38F));
}

TEST(GltfRead, NonIndexedPrimitiveDrawsVerticesInOrder) {
  const std::vector<std::byte> positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0});
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":4}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":72}],
    "buffers":[{"byteLength":72,"uri":")" +
                           data_uri(positions) + R"("}]})";
  const TriangleMesh mesh = read_json(json).mesh;
  ASSERT_EQ(mesh.num_vertices(), 6);
  ASSERT_EQ(mesh.num_faces(), 2);
  EXPECT_EQ(mesh.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(3, 4, 5));
  EXPECT_EQ(mesh.vertices.row(4), Eigen::RowVector3d(6, 0, 0));
}

struct IndexTypeCase {
  int component_type;
  std::vector<std::byte> indices;
};

class GltfReadIndexTypes : public ::testing::TestWithParam<IndexTypeCase> {};

TEST_P(GltfReadIndexTypes, SameTrianglesFromEveryIndexWidth) {
  const IndexTypeCase& c = GetParam();
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":)" +
                           std::to_string(c.component_type) + R"(,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":)" +
                           std::to_string(c.indices.size()) + R"(}],
    "buffers":[{"byteLength":)" +
                           std::to_string(48 + c.indices.size()) + R"(,"uri":")" +
                           data_uri(concat({square_positions, c.indices})) + R"("}]})";
  expect_square(read_json(json).mesh);
}

INSTANTIATE_TEST_SUITE_P(Widths, GltfReadIndexTypes,
                         ::testing::Values(IndexTypeCase{5121, bytes_of<std::uint8_t>({0, 1, 2, 0, 2, 3})},
                                           IndexTypeCase{5123, bytes_of<std::uint16_t>({0, 1, 2, 0, 2, 3})},
                                           IndexTypeCase{5125, bytes_of<std::uint32_t>({0, 1, 2, 0, 2, 3})}));

TEST(GltfRead, LinesAndPointsPrimitivesAreSkippedAndCounted) {
  const std::vector<std::byte> line_indices = bytes_of<std::uint16_t>({0, 1, 1, 2});
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":2,"mode":1},
                             {"attributes":{"POSITION":0},"indices":1},
                             {"attributes":{"POSITION":0},"mode":0}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},
                 {"bufferView":2,"componentType":5123,"count":4,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12},
                   {"buffer":0,"byteOffset":60,"byteLength":8}],
    "buffers":[{"byteLength":68,"uri":")" +
                           data_uri(concat({square_positions, square_indices_u16, line_indices})) + R"("}]})";
  const LoadedMesh loaded = read_json(json);
  expect_square(loaded.mesh);  // the triangle primitive, its POSITION accessor read once
  EXPECT_TRUE(has_note_containing(loaded.info, "skipped 2 non-triangle primitives (1 LINES, 1 POINTS)"));
}

TEST(GltfRead, PrimitivesSharingPositionsShareVerticesWithinAnInstance) {
  const std::vector<std::byte> first = bytes_of<std::uint16_t>({0, 1, 2});
  const std::vector<std::byte> second = bytes_of<std::uint16_t>({0, 2, 3});
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1},{"attributes":{"POSITION":0},"indices":2}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"},
                 {"bufferView":1,"byteOffset":8,"componentType":5123,"count":3,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":14}],
    "buffers":[{"byteLength":62,"uri":")" +
                           data_uri(concat({square_positions, first, bytes_of<std::uint16_t>({9}), second})) +
                           R"("}]})";
  expect_square(read_json(json).mesh);
}

TEST(GltfRead, InterleavedPositionsWithByteStride) {
  // position (12 bytes) + normal (12 bytes) per vertex, stride 24.
  const std::vector<std::byte> interleaved =
      bytes_of<float>({0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1});
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":2},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},
                 {"bufferView":0,"byteOffset":12,"componentType":5126,"count":4,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":96,"byteStride":24},{"buffer":0,"byteOffset":96,"byteLength":12}],
    "buffers":[{"byteLength":108,"uri":")" +
                           data_uri(concat({interleaved, square_indices_u16})) + R"("}]})";
  const TriangleMesh mesh = read_json(json).mesh;
  expect_square(mesh);
  EXPECT_EQ(mesh.vertices.row(3), Eigen::RowVector3d(0, 1, 0));
  EXPECT_EQ(mesh.vertices.col(2).cwiseAbs().maxCoeff(), 0.0);  // no normal leaked into z
}

TEST(GltfRead, TriangleStripAndFanFollowTheSpecOrder) {
  const std::vector<std::byte> positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0});
  const std::vector<std::byte> strip = bytes_of<std::uint16_t>({0, 1, 2, 3, 4, 4});  // last index: a degenerate
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":5},
                             {"attributes":{"POSITION":0},"mode":6}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":60},{"buffer":0,"byteOffset":60,"byteLength":12}],
    "buffers":[{"byteLength":72,"uri":")" +
                           data_uri(concat({positions, strip})) + R"("}]})";
  const LoadedMesh loaded = read_json(json);
  const TriangleMesh& mesh = loaded.mesh;
  ASSERT_EQ(mesh.num_vertices(), 5);
  ASSERT_EQ(mesh.num_faces(), 6);
  // Strip, triangle i = (v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]): (0,1,2),
  // (1,3,2), (2,3,4); (3,4,4) is degenerate and dropped.
  EXPECT_EQ(mesh.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(mesh.faces.row(2), Eigen::RowVector3i(2, 3, 4));
  // Fan over vertices 0..4: (1,2,0), (2,3,0), (3,4,0).
  EXPECT_EQ(mesh.faces.row(3), Eigen::RowVector3i(1, 2, 0));
  EXPECT_EQ(mesh.faces.row(4), Eigen::RowVector3i(2, 3, 0));
  EXPECT_EQ(mesh.faces.row(5), Eigen::RowVector3i(3, 4, 0));
  EXPECT_TRUE(has_note_containing(loaded.info, "dropped 1 degenerate"));
}

TEST(GltfRead, DefaultSceneIsTheOneRead) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  const std::string json = R"({"asset":{"version":"2.0"},"scene":1,"scenes":[{"nodes":[0]},{"nodes":[1]}],
    "nodes":[{"mesh":0},{"mesh":0,"translation":[7,0,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60,"uri":")" +
                           uri + R"("}]})";
  expect_square(read_json(json).mesh, 7.0);
}

TEST(GltfRead, WithoutScenesEveryRootNodeIsRead) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  const std::string json = R"({"asset":{"version":"2.0"},
    "nodes":[{"translation":[1,0,0],"children":[2]},{"mesh":0},{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60,"uri":")" +
                           uri + R"("}]})";
  const LoadedMesh loaded = read_json(json);
  ASSERT_EQ(loaded.mesh.num_vertices(), 8);
  EXPECT_EQ(loaded.mesh.vertices.row(2), Eigen::RowVector3d(2, 1, 0));  // node 2 under node 0
  EXPECT_EQ(loaded.mesh.vertices.row(6), Eigen::RowVector3d(1, 1, 0));  // node 1
  EXPECT_TRUE(has_note_containing(loaded.info, "no scenes"));
}

TEST(GltfRead, WithoutNodesEveryMeshIsReadOnce) {
  const std::string uri = data_uri(concat({square_positions, square_indices_u16}));
  const std::string json = R"({"asset":{"version":"2.0"},
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60,"uri":")" +
                           uri + R"("}]})";
  expect_square(read_json(json).mesh);
}

TEST(GltfRead, QuantizedPositionsWithKhrMeshQuantization) {
  // Normalized SHORT positions: 32767 -> 1.0, -32767 -> -1.0 (and -32768 clamps to -1.0).
  const std::vector<std::byte> positions =
      bytes_of<std::int16_t>({0, 0, 0, 0, 32767, 0, -32767, 0, 32767, -32768, 0, 0});  // stride 8: one padding short
  const std::string json = R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_mesh_quantization"],
    "extensionsRequired":["KHR_mesh_quantization"],"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5122,"normalized":true,"count":3,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":24,"byteStride":8}],
    "buffers":[{"byteLength":24,"uri":")" +
                           data_uri(positions) + R"("}]})";
  const TriangleMesh mesh = read_json(json).mesh;
  ASSERT_EQ(mesh.num_vertices(), 3);
  EXPECT_EQ(mesh.vertices.row(1), Eigen::RowVector3d(1, 0, -1));
  EXPECT_EQ(mesh.vertices.row(2), Eigen::RowVector3d(1, -1, 0));
}

TEST(GltfRead, TrailingIndicesOfAnIncompleteTriangleAreIgnoredWithANote) {
  const std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                 {"bufferView":1,"componentType":5123,"count":5,"type":"SCALAR"}],
    "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
    "buffers":[{"byteLength":60,"uri":")" +
                           data_uri(concat({square_positions, square_indices_u16})) + R"("}]})";
  const LoadedMesh loaded = read_json(json);
  EXPECT_EQ(loaded.mesh.num_faces(), 1);
  EXPECT_TRUE(has_note_containing(loaded.info, "ignored 2 indices"));
}

}  // namespace
}  // namespace geodual::io
