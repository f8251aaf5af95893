// glTF reading of broken and hostile input: each case must end in a
// geodual::Error whose message names the file and the problem.

#include "../../io/src/format_readers.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/mesh/error.hpp"
#include "gltf_test_bytes.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
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

// Reads `data` and expects a geodual::Error whose message starts with `name`
// and contains every string in `fragments`.
void expect_read_error(std::span<const std::byte> data, bool binary, const fs::path& name,
                       std::initializer_list<std::string_view> fragments) {
  try {
    detail::read_gltf(data, binary, name);
    ADD_FAILURE() << "no error for " << name;
  } catch (const Error& e) {
    const std::string message = e.what();
    const std::string prefix = name.empty() ? "<memory>" : name.string();
    EXPECT_EQ(message.rfind(prefix + ": ", 0), 0u) << message;
    for (std::string_view fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
    }
  }
}

void expect_json_error(const std::string& json, std::initializer_list<std::string_view> fragments,
                       const fs::path& name = "broken.gltf") {
  expect_read_error(as_span(json), false, name, fragments);
}

const std::vector<std::byte> square_positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
const std::vector<std::byte> square_indices = bytes_of<std::uint16_t>({0, 1, 2, 0, 2, 3});

std::vector<std::byte> square_buffer() {
  std::vector<std::byte> out = square_positions;
  out.insert(out.end(), square_indices.begin(), square_indices.end());
  return out;
}

// The square of gltf_read_test.cpp with parts replaceable: the accessors, the
// buffer views, the buffer, the nodes.
struct SquareFile {
  std::string accessors = R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                              {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])";
  std::string buffer_views = R"([{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}])";
  std::string buffer = R"({"byteLength":60,"uri":")" + data_uri(square_buffer()) + "\"}";
  std::string nodes = R"([{"mesh":0}])";
  std::string primitive = R"({"attributes":{"POSITION":0},"indices":1})";
  std::string extra_members;

  std::string json() const {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
           R"(,"meshes":[{"name":"sq","primitives":[)" + primitive + "]}],\"accessors\":" + accessors +
           ",\"bufferViews\":" + buffer_views + ",\"buffers\":[" + buffer + "]" + extra_members + "}";
  }
};

// The square file with some parts replaced, e.g. square_json({{&SquareFile::nodes, "[]"}}).
using SquarePart = std::string SquareFile::*;
std::string square_json(std::initializer_list<std::pair<SquarePart, std::string>> changes = {}) {
  SquareFile file;
  for (const auto& [part, text] : changes) file.*part = text;
  return file.json();
}

std::vector<std::byte> valid_glb() {
  GltfTriangleMesh entry;
  entry.mesh.vertices = VertexMatrix{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  entry.mesh.faces = FaceMatrix{{0, 1, 2}};
  GltfScene scene;
  scene.triangle_meshes.push_back(entry);
  return encode_gltf(scene, GltfContainer::glb);
}

void put_u32(std::vector<std::byte>& data, std::size_t at, std::uint32_t value) {
  std::memcpy(data.data() + at, &value, sizeof value);
}

TEST(GltfReadErrors, SquareFileIsValidAsBuilt) {
  // Guards the fixture: every other test breaks exactly one thing in it.
  EXPECT_EQ(detail::read_gltf(as_span(square_json()), false, "ok.gltf").mesh.num_faces(), 2);
  EXPECT_EQ(detail::read_gltf(valid_glb(), true, "ok.glb").mesh.num_faces(), 1);
}

TEST(GltfReadErrors, TruncatedGlb) {
  const std::vector<std::byte> glb = valid_glb();
  for (const std::size_t length : {std::size_t{0}, std::size_t{3}, std::size_t{11}, std::size_t{12}, std::size_t{19},
                                   std::size_t{40}, glb.size() - 4, glb.size() - 1}) {
    SCOPED_TRACE(length);
    expect_read_error(std::span(glb).first(length), true, "cut.glb", {"truncated"});
  }
}

TEST(GltfReadErrors, TruncatedGlbWithMatchingHeaderLength) {
  // The header's length is patched to match, so only the chunk lengths tell.
  std::vector<std::byte> glb = valid_glb();
  glb.resize(glb.size() - 8);
  put_u32(glb, 8, static_cast<std::uint32_t>(glb.size()));
  expect_read_error(glb, true, "cut.glb", {"truncated", "BIN"});
}

TEST(GltfReadErrors, BinChunkLongerThanTheFile) {
  // The case Debian's tinygltf 2.7 gets wrong: the BIN chunk header claims 8
  // bytes more than remain, which is exactly the size of a chunk header.
  std::vector<std::byte> glb = valid_glb();
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const std::size_t bin_header = 20 + json_length;
  std::uint32_t bin_length = 0;
  std::memcpy(&bin_length, glb.data() + bin_header, 4);
  put_u32(glb, bin_header, bin_length + 8);
  expect_read_error(glb, true, "long.glb", {"chunk 1", "remain"});
}

TEST(GltfReadErrors, BadMagic) {
  std::vector<std::byte> glb = valid_glb();
  glb[3] = std::byte{'X'};
  expect_read_error(glb, true, "magic.glb", {"not a GLB file"});
}

TEST(GltfReadErrors, WrongGlbVersion) {
  std::vector<std::byte> glb = valid_glb();
  put_u32(glb, 4, 1);
  expect_read_error(glb, true, "v1.glb", {"version 1"});
}

TEST(GltfReadErrors, GlbLengthFieldDisagreesWithTheData) {
  std::vector<std::byte> glb = valid_glb();
  glb.resize(glb.size() + 4);
  expect_read_error(glb, true, "long.glb", {"trailing bytes"});
}

TEST(GltfReadErrors, GlbWithoutBinChunkButBufferWithoutUri) {
  const std::string json = square_json({{&SquareFile::buffer, R"({"byteLength":60})"}});
  expect_read_error(glb_of(json, {}), true, "nobin.glb", {"buffer 0", "no GLB BIN chunk"});
}

TEST(GltfReadErrors, GlbBufferLongerThanBinChunk) {
  const std::string json = square_json({{&SquareFile::buffer, R"({"byteLength":64})"}});
  expect_read_error(glb_of(json, square_buffer()), true, "short.glb", {"buffer 0", "exceeds the GLB BIN chunk"});
}

TEST(GltfReadErrors, IndexOutOfRange) {
  std::vector<std::byte> buffer = square_positions;
  const std::vector<std::byte> bad = bytes_of<std::uint16_t>({0, 1, 2, 0, 2, 4});
  buffer.insert(buffer.end(), bad.begin(), bad.end());
  const std::string json =
      square_json({{&SquareFile::buffer, R"({"byteLength":60,"uri":")" + data_uri(buffer) + "\"}"}});
  expect_json_error(
      json, {"mesh 0 'sq' primitive 0", "indices accessor 1", "element 5 is vertex index 4", "only 4 vertices"});
}

TEST(GltfReadErrors, AccessorPastTheEndOfItsBufferView) {
  const std::string json =
      square_json({{&SquareFile::accessors, R"([{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3"},
      {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])"}});
  expect_json_error(json, {"POSITION accessor 0", "5 elements", "bufferView 0 has 48"});
}

TEST(GltfReadErrors, AccessorOffsetPastTheEndOfItsBufferView) {
  const std::string json =
      square_json({{&SquareFile::accessors, R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
      {"bufferView":1,"byteOffset":4,"componentType":5123,"count":6,"type":"SCALAR"}])"}});
  expect_json_error(json, {"indices accessor 1", "byteOffset 4"});
}

TEST(GltfReadErrors, BufferViewPastTheEndOfItsBuffer) {
  const std::string json = square_json(
      {{&SquareFile::buffer_views, R"([{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":52,"byteLength":12}])"}});
  expect_json_error(json, {"bufferView 1", "run past the end of buffer 0"});
}

TEST(GltfReadErrors, HugeCountDoesNotOverflowTheBoundsCheck) {
  // count * 12 wraps around 2^64 for this count if computed naively.
  const std::string json = square_json(
      {{&SquareFile::accessors, R"([{"bufferView":0,"componentType":5126,"count":1537228672809129302,"type":"VEC3"},
      {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])"}});
  expect_json_error(json, {"POSITION accessor 0", "at most 2^53"});
  const std::string below_limit = square_json(
      {{&SquareFile::accessors, R"([{"bufferView":0,"componentType":5126,"count":9007199254740992,"type":"VEC3"},
      {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])"}});
  expect_json_error(below_limit, {"POSITION accessor 0", "bufferView 0 has 48"});
}

TEST(GltfReadErrors, ByteStrideShorterThanAnElement) {
  const std::string json =
      square_json({{&SquareFile::buffer_views,
                    R"([{"buffer":0,"byteLength":48,"byteStride":8},{"buffer":0,"byteOffset":48,"byteLength":12}])"}});
  expect_json_error(json, {"bufferView 0", "'byteStride' 8 is shorter than one element"});
}

TEST(GltfReadErrors, ByteStrideOutOfRange) {
  const std::string json = square_json(
      {{&SquareFile::buffer_views,
        R"([{"buffer":0,"byteLength":48,"byteStride":256},{"buffer":0,"byteOffset":48,"byteLength":12}])"}});
  expect_json_error(json, {"bufferView 0", "outside 4..252"});
}

TEST(GltfReadErrors, BadComponentTypesAndShapes) {
  const auto with_accessors = [](const std::string& position, const std::string& indices) {
    return square_json({{&SquareFile::accessors, "[" + position + "," + indices + "]"}});
  };
  const std::string good_position = R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"})";
  const std::string good_indices = R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"})";
  expect_json_error(with_accessors(R"({"bufferView":0,"componentType":5124,"count":4,"type":"VEC3"})", good_indices),
                    {"POSITION accessor 0", "invalid componentType 5124"});
  expect_json_error(with_accessors(R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC4"})", good_indices),
                    {"POSITION accessor 0", "type 'VEC4', expected VEC3"});
  expect_json_error(with_accessors(R"({"bufferView":0,"componentType":5123,"count":4,"type":"VEC3"})", good_indices),
                    {"POSITION accessor 0", "KHR_mesh_quantization"});
  expect_json_error(with_accessors(good_position, R"({"bufferView":1,"componentType":5126,"count":3,"type":"SCALAR"})"),
                    {"indices accessor 1", "componentType FLOAT"});
  expect_json_error(with_accessors(good_position, R"({"bufferView":1,"componentType":5123,"count":0,"type":"SCALAR"})"),
                    {"indices accessor 1", "'count' must be at least 1"});
  expect_json_error(
      with_accessors(good_position, R"({"bufferView":1,"componentType":5123,"count":-6,"type":"SCALAR"})"),
      {"indices accessor 1", "non-negative integer"});
  expect_json_error(with_accessors(good_position, R"({"componentType":5123,"count":6,"type":"SCALAR"})"),
                    {"indices accessor 1", "no bufferView"});
  expect_json_error(
      with_accessors(R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","sparse":{"count":1}})",
                     good_indices),
      {"POSITION accessor 0", "sparse"});
}

TEST(GltfReadErrors, DanglingReferences) {
  expect_json_error(square_json({{&SquareFile::primitive, R"({"attributes":{"POSITION":7},"indices":1})"}}),
                    {"primitive 0: POSITION", "accessor 7", "has 2"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":3}])"}}), {"node 0", "mesh 3"});
  expect_json_error(square_json({{&SquareFile::buffer_views,
                                  R"([{"buffer":2,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}])"}}),
                    {"bufferView 0", "buffer 2"});
  expect_json_error(square_json({{&SquareFile::extra_members, R"(,"scene":4)"}}), {"scene 4"});
}

TEST(GltfReadErrors, InvalidPrimitiveMode) {
  expect_json_error(square_json({{&SquareFile::primitive, R"({"attributes":{"POSITION":0},"indices":1,"mode":9})"}}),
                    {"mesh 0 'sq' primitive 0", "invalid 'mode' 9"});
}

TEST(GltfReadErrors, NodeWithTwoParentsOrInALoop) {
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"children":[2]},{"children":[2]},{"mesh":0}])"},
                                 {&SquareFile::extra_members, R"(,"scenes":[{"nodes":[0,1]}])"}}),
                    {"node 1", "at most one parent"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0},{"children":[1]}])"}}), {"node 1", "itself"});
  // A loop through node 0: the scene's node is not a root.
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0,"children":[1]},{"children":[0]}])"}}),
                    {"scene 0", "node 0, which is a child of node 1"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0,"children":[1]},{}])"},
                                 {&SquareFile::extra_members, R"(,"scenes":[{"nodes":[1]}])"}}),
                    {"scene 0", "child of node 0"});
  expect_json_error(square_json({{&SquareFile::extra_members, R"(,"scenes":[{"nodes":[0,0]}])"}}),
                    {"scene 0", "twice"});
}

TEST(GltfReadErrors, BadTransforms) {
  expect_json_error(
      square_json({{&SquareFile::nodes, R"([{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],"scale":[2,2,2]}])"}}),
      {"node 0", "both 'matrix' and"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0,"rotation":[0,0,0,0]}])"}}),
                    {"node 0", "zero length"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0,"matrix":[1,0,0,1,0,1,0,0,0,0,1,0,0,0,0,1]}])"}}),
                    {"node 0", "not affine"});
  expect_json_error(square_json({{&SquareFile::nodes, R"([{"mesh":0,"translation":[1,2]}])"}}),
                    {"node 0", "'translation'"});
  expect_json_error(
      square_json(
          {{&SquareFile::nodes, R"([{"mesh":0,"scale":[1e300,1,1],"children":[1]},{"mesh":0,"scale":[1e300,1,1]}])"}}),
      {"node 1", "non-finite"});
}

class GltfReadErrorFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geodual_gltf_errors_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "inner");
    const std::vector<std::byte> buffer = square_buffer();
    std::ofstream(dir_ / "secret.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(buffer.size()));
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string with_uri(const std::string& uri) const {
    return square_json({{&SquareFile::buffer, R"({"byteLength":60,"uri":")" + uri + "\"}"}});
  }

  fs::path dir_;
};

TEST_F(GltfReadErrorFiles, MissingExternalBin) {
  const fs::path gltf = dir_ / "inner" / "mesh.gltf";
  expect_json_error(with_uri("mesh.bin"), {"buffer 0", "'mesh.bin' not found"}, gltf);
}

TEST_F(GltfReadErrorFiles, ExternalBinShorterThanByteLength) {
  const fs::path gltf = dir_ / "mesh.gltf";
  const std::string json = square_json({{&SquareFile::buffer, R"({"byteLength":64,"uri":"secret.bin"})"}});
  expect_json_error(json, {"buffer 0", "60 bytes, fewer than the declared byteLength 64"}, gltf);
}

TEST_F(GltfReadErrorFiles, ExternalUrisMayNotLeaveTheFolder) {
  const fs::path gltf = dir_ / "inner" / "mesh.gltf";
  // secret.bin exists one folder up: reading it would succeed if allowed.
  expect_json_error(with_uri("../secret.bin"), {"buffer 0", "leaves the glTF file's folder"}, gltf);
  expect_json_error(with_uri("a/../../secret.bin"), {"leaves the glTF file's folder"}, gltf);
  expect_json_error(with_uri("%2E%2E/secret.bin"), {"leaves the glTF file's folder"}, gltf);
  expect_json_error(with_uri((dir_ / "secret.bin").string()), {"absolute path"}, gltf);
  expect_json_error(with_uri("file://" + (dir_ / "secret.bin").string()), {"not a relative file reference"}, gltf);
  expect_json_error(with_uri("https://example.com/secret.bin"), {"not a relative file reference"}, gltf);
  expect_json_error(with_uri("secret.bin%00.png"), {"does not name a file"}, gltf);
  expect_json_error(with_uri("bad%zzescape.bin"), {"invalid %-escape"}, gltf);
}

TEST_F(GltfReadErrorFiles, ExternalUrisMayNotLeaveTheFolderThroughASymlink) {
  // Issue 19, finding 8: a same-folder name that links to a file outside.
  fs::create_symlink(dir_ / "secret.bin", dir_ / "inner" / "link.bin");
  expect_json_error(with_uri("link.bin"), {"buffer 0", "symbolic link", "outside the glTF file's folder"},
                    dir_ / "inner" / "mesh.gltf");
  // A link that stays inside the folder is read.
  fs::copy_file(dir_ / "secret.bin", dir_ / "inner" / "real.bin");
  fs::create_symlink("real.bin", dir_ / "inner" / "alias.bin");
  EXPECT_EQ(detail::read_gltf(as_span(with_uri("alias.bin")), false, dir_ / "inner" / "mesh.gltf").mesh.num_faces(), 2);
}

TEST_F(GltfReadErrorFiles, ExternalBufferIsNotARegularFile) {
  expect_json_error(with_uri("inner"), {"buffer 0", "not a regular file"}, dir_ / "mesh.gltf");
}

TEST(GltfReadErrors, ExternalBufferFromMemoryWithoutName) {
  const std::string json = square_json({{&SquareFile::buffer, R"({"byteLength":60,"uri":"mesh.bin"})"}});
  expect_read_error(as_span(json), false, "", {"read from memory without a file name"});
}

TEST(GltfReadErrors, BrokenDataUris) {
  const auto with_buffer = [](const std::string& buffer) { return square_json({{&SquareFile::buffer, buffer}}); };
  expect_json_error(with_buffer(R"({"byteLength":60,"uri":"data:application/octet-stream,AAAA"})"),
                    {"buffer 0", "not base64"});
  expect_json_error(with_buffer(R"({"byteLength":60,"uri":"data:application/octet-stream;base64,AA*A"})"),
                    {"buffer 0", "invalid base64"});
  expect_json_error(with_buffer(R"({"byteLength":60,"uri":"data:;base64,AAAA"})"), {"buffer 0", "3 bytes, fewer"});
  expect_json_error(with_buffer(R"({"byteLength":0,"uri":"data:;base64,AAAA"})"), {"buffer 0", "at least 1"});
  expect_json_error(with_buffer(R"({"uri":"data:;base64,AAAA"})"), {"buffer 0", "'byteLength' is missing"});
}

TEST(GltfReadErrors, RequiredExtensionThatChangesGeometry) {
  expect_json_error(square_json({{&SquareFile::extra_members, R"(,"extensionsUsed":["KHR_draco_mesh_compression"],
                                                   "extensionsRequired":["KHR_draco_mesh_compression"])"}}),
                    {"KHR_draco_mesh_compression", "cannot read"});
}

TEST(GltfReadErrors, JsonThatIsNotGltf) {
  expect_json_error("", {"invalid JSON"});
  expect_json_error("{\"asset\": {\"version\": \"2.0\"", {"invalid JSON"});
  expect_json_error("[1, 2, 3]", {"not an object"});
  expect_json_error(R"({"hello": "world"})", {"no 'asset'"});
  expect_json_error(R"({"asset": {"generator": "x"}})", {"no 'version'"});
  expect_json_error(R"({"asset": {"version": "1.0"}, "meshes": []})", {"'1.0' is not supported"});
  expect_json_error(R"({"asset": {"version": "2.0", "minVersion": "2.1"}})", {"'2.1'"});
  expect_json_error(R"({"asset": {"version": "2.0"}, "meshes": {}})", {"'meshes' must be an array"});
  expect_json_error(R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": 3}]}]})",
                    {"mesh 0 primitive 0", "'attributes' must be a JSON object"});
  expect_json_error("{\"asset\": {\"version\": \"2.0\", \"generator\": \"\xFF\"}}", {"invalid JSON"});
}

TEST(GltfReadErrors, DeeplyNestedJsonIsAnErrorNotAStackOverflow) {
  const std::string deep =
      R"({"asset":{"version":"2.0"},"extras":)" + std::string(100000, '[') + std::string(100000, ']') + "}";
  // Valid JSON, nothing to read: the reader returns an empty mesh (read_mesh
  // turns that into "no triangles"); the point is that it returns at all.
  EXPECT_EQ(detail::read_gltf(as_span(deep), false, "deep.gltf").mesh.num_faces(), 0);
  expect_json_error(std::string(100000, '['), {"invalid JSON"});
}

TEST(GltfReadErrors, RandomBytes) {
  std::mt19937 random(20240601);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int round = 0; round < 200; ++round) {
    std::vector<std::byte> data(static_cast<std::size_t>(1 + round * 7));
    for (std::byte& b : data) b = static_cast<std::byte>(byte(random));
    if (round % 2 == 0 && data.size() >= 12) {  // half of them with a plausible GLB header
      std::memcpy(data.data(), "glTF", 4);
      put_u32(data, 4, 2);
      put_u32(data, 8, static_cast<std::uint32_t>(data.size()));
    }
    SCOPED_TRACE(round);
    EXPECT_THROW(detail::read_gltf(data, true, "random.glb"), Error);
    EXPECT_THROW(detail::read_gltf(data, false, "random.gltf"), Error);
  }
}

}  // namespace
}  // namespace geodual::io
