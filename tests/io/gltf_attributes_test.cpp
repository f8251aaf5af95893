// glTF vertex attributes: COLOR_0, material base colours and textures,
// NORMAL under node transforms, "_NAME" scalars, and how they follow the
// merge of primitives into one mesh. The files are built here: JSON text with
// base64 buffers, PNG textures encoded with stb_image_write.

#include "../../io/src/format_readers.hpp"
#include "../../io/src/preview_png.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "gltf_test_bytes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

// The JPEG encoder for one test, compiled privately into this file (as preview_png.cpp does for PNG).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;

using gltf_test::as_span;
using gltf_test::base64;
using gltf_test::bytes_of;
using gltf_test::data_uri;

constexpr int float_type = 5126;
constexpr int ubyte_type = 5121;

// One buffer (a base64 data URI) with one buffer view per added chunk.
class BufferBuilder {
 public:
  std::size_t add(const std::vector<std::byte>& chunk) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(std::byte{0});
    views_ += std::string(views_.empty() ? "" : ",") + R"({"buffer":0,"byteOffset":)" + std::to_string(bytes_.size()) +
              R"(,"byteLength":)" + std::to_string(chunk.size()) + "}";
    bytes_.insert(bytes_.end(), chunk.begin(), chunk.end());
    return view_count_++;
  }
  // The "bufferViews" and "buffers" members.
  std::string json() const {
    return R"("bufferViews":[)" + views_ + R"(],"buffers":[{"byteLength":)" + std::to_string(bytes_.size()) +
           R"(,"uri":")" + data_uri(bytes_) + R"("}])";
  }

 private:
  std::vector<std::byte> bytes_;
  std::string views_;
  std::size_t view_count_ = 0;
};

std::string accessor(std::size_t view, int component_type, std::size_t count, const std::string& type,
                     bool normalized = false) {
  return R"({"bufferView":)" + std::to_string(view) + R"(,"componentType":)" + std::to_string(component_type) +
         R"(,"count":)" + std::to_string(count) + R"(,"type":")" + type + "\"" +
         (normalized ? R"(,"normalized":true)" : "") + "}";
}

// A file around the given members (each a complete "key":value text, comma-separated).
std::string gltf_file(const std::string& members) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)" + members + "}";
}

LoadedMesh read_json(const std::string& json, const fs::path& name = "hand.gltf") {
  return detail::read_gltf(as_span(json), false, name);
}

bool has_note_containing(const ReadInfo& info, std::string_view text) {
  return std::any_of(info.notes.begin(), info.notes.end(),
                     [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

// A triangle in z = 0.
const std::vector<std::byte> triangle_positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});

constexpr float byte_tolerance = 1.0f / 255.0f;
// srgb_from_linear(1) is 0.99999994 in float arithmetic, not 1.

TEST(GltfAttributes, FloatColorVec3ComesOutSrgbEncoded) {
  BufferBuilder buffer;
  const std::vector<float> linear = {0.5f, 0.25f, 0.0f, 1.0f, 0.002f, 0.04f, 0.001f, 0.2f, 0.8f};
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t colors = buffer.add(bytes_of<float>({0.5f, 0.25f, 0.0f, 1.0f, 0.002f, 0.04f, 0.001f, 0.2f, 0.8f}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(colors, float_type, 3, "VEC3") + "]," +
      buffer.json()));

  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 3);
  ASSERT_EQ(out.cols(), 3);  // no alpha in the file
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(out(v, c), srgb_from_linear(linear[3 * v + c])) << v << " " << c;
  }
  EXPECT_GT(out(0, 0), 0.7f);  // encoded, not the linear 0.5
  EXPECT_EQ(loaded.attributes.color_type, ValueType::float32);
  EXPECT_TRUE(has_note_containing(loaded.info, "vertex colours: COLOR_0"));
  EXPECT_EQ(loaded.attributes.normals.rows(), 0);
  EXPECT_TRUE(loaded.attributes.scalars.empty());
}

TEST(GltfAttributes, NormalizedByteColorVec4KeepsAlphaLinear) {
  BufferBuilder buffer;
  const std::vector<std::uint8_t> bytes = {255, 128, 0, 255, 10, 20, 30, 128, 0, 64, 200, 255};
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t colors = buffer.add(bytes_of<std::uint8_t>({255, 128, 0, 255, 10, 20, 30, 128, 0, 64, 200, 255}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(colors, ubyte_type, 3, "VEC4", true) + "]," +
      buffer.json()));

  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 3);
  ASSERT_EQ(out.cols(), 4);  // vertex 1 has alpha 128/255
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(out(v, c), srgb_from_linear(static_cast<float>(bytes[4 * v + c]) / 255.0f)) << v << " " << c;
    }
    EXPECT_FLOAT_EQ(out(v, 3), static_cast<float>(bytes[4 * v + 3]) / 255.0f);  // alpha is not sRGB-encoded
  }
  EXPECT_EQ(loaded.attributes.color_type, ValueType::uint8);
  EXPECT_TRUE(has_note_containing(loaded.info, "alpha column"));
}

TEST(GltfAttributes, OpaqueVec4ColorsGiveThreeColumns) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t colors = buffer.add(bytes_of<std::uint8_t>({255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(colors, ubyte_type, 3, "VEC4", true) + "]," +
      buffer.json()));
  ASSERT_EQ(loaded.attributes.colors.cols(), 3);
  EXPECT_LT((loaded.attributes.colors.row(1) - Eigen::RowVector3f(0, 1, 0)).cwiseAbs().maxCoeff(), 1e-6f);
}

// Primitive 0: COLOR_0 under a material whose factor halves red; primitive 1:
// no COLOR_0, a factor only; primitive 2: neither, so white.
TEST(GltfAttributes, PrimitivesWithAndWithoutColorMergeInOrder) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t colors = buffer.add(bytes_of<float>({0.8f, 0.6f, 0.4f, 0.2f, 0.1f, 0.0f, 1.0f, 1.0f, 1.0f}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[
          {"attributes":{"POSITION":0,"COLOR_0":1},"material":0},
          {"attributes":{"POSITION":2},"material":1},
          {"attributes":{"POSITION":3}}]}],
        "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,1,1,1]}},
                     {"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.4,0.6,1]}}],
        "accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(colors, float_type, 3, "VEC3") + "," +
      R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","byteOffset":0},)" +
      accessor(positions, float_type, 3, "VEC3") + "]," + buffer.json()));

  ASSERT_EQ(loaded.mesh.num_vertices(), 9);
  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 9);
  ASSERT_EQ(out.cols(), 3);
  EXPECT_FLOAT_EQ(out(0, 0), srgb_from_linear(0.5f * 0.8f));
  EXPECT_FLOAT_EQ(out(0, 1), srgb_from_linear(0.6f));
  EXPECT_FLOAT_EQ(out(1, 0), srgb_from_linear(0.5f * 0.2f));
  EXPECT_FLOAT_EQ(out(2, 0), srgb_from_linear(0.5f));
  for (int v = 3; v < 6; ++v) {
    EXPECT_FLOAT_EQ(out(v, 0), srgb_from_linear(0.2f));
    EXPECT_FLOAT_EQ(out(v, 1), srgb_from_linear(0.4f));
    EXPECT_FLOAT_EQ(out(v, 2), srgb_from_linear(0.6f));
  }
  for (int v = 6; v < 9; ++v) EXPECT_LT((out.row(v) - Eigen::RowVector3f(1, 1, 1)).cwiseAbs().maxCoeff(), 1e-6f);
  EXPECT_TRUE(has_note_containing(loaded.info, "COLOR_0 x baseColorFactor"));
}

TEST(GltfAttributes, NoColorsWhenNothingColours) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
         "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1]}}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "]," + buffer.json()));
  EXPECT_TRUE(loaded.attributes.empty());
}

// The triangle has normal n = (1, 1, 0) / sqrt 2 at every vertex. Under
// scale (2, 1, 1) normals turn by the inverse transpose diag(1/2, 1, 1);
// under the mirror (-2, 1, 1) by diag(-1/2, 1, 1).
TEST(GltfAttributes, NormalsFollowNonUniformScaleAndMirror) {
  BufferBuilder buffer;
  const auto s = static_cast<float>(1.0 / std::sqrt(2.0));
  const std::size_t positions = buffer.add(bytes_of<float>({1, 0, 0, 0, 1, 0, 1, 0, 1}));
  const std::size_t normals = buffer.add(bytes_of<float>({s, s, 0, s, s, 0, s, s, 0}));
  const LoadedMesh loaded = read_json(
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
          "nodes":[{"mesh":0,"scale":[2,1,1]},{"mesh":0,"scale":[-2,1,1]}],
          "meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(normals, float_type, 3, "VEC3") + "]," +
      buffer.json() + "}");

  const VertexMatrix& out = loaded.attributes.normals;
  ASSERT_EQ(out.rows(), 6);
  const Eigen::RowVector3d scaled = Eigen::RowVector3d(0.5, 1, 0).normalized();
  const Eigen::RowVector3d mirrored = Eigen::RowVector3d(-0.5, 1, 0).normalized();
  for (int v = 0; v < 3; ++v) {
    EXPECT_LT((out.row(v) - scaled).norm(), 1e-7) << out.row(v);
    EXPECT_LT((out.row(3 + v) - mirrored).norm(), 1e-7) << out.row(3 + v);
  }
  EXPECT_EQ(loaded.attributes.normal_type, ValueType::float32);
  // The transformed normal is still perpendicular to the transformed triangle.
  const Eigen::RowVector3d e1 = loaded.mesh.vertices.row(1) - loaded.mesh.vertices.row(0);
  const Eigen::RowVector3d e2 = loaded.mesh.vertices.row(2) - loaded.mesh.vertices.row(0);
  EXPECT_NEAR(out.row(0).dot(e1), 0.0, 1e-7);
  EXPECT_NEAR(out.row(0).dot(e2), 0.0, 1e-7);
}

TEST(GltfAttributes, NormalsDroppedWithANoteWhenAPrimitiveLacksThem) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t normals = buffer.add(bytes_of<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}},
                                                       {"attributes":{"POSITION":2}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(normals, float_type, 3, "VEC3") + "," +
      accessor(positions, float_type, 3, "VEC3") + "]," + buffer.json()));
  EXPECT_EQ(loaded.mesh.num_vertices(), 6);
  EXPECT_EQ(loaded.attributes.normals.rows(), 0);
  EXPECT_TRUE(has_note_containing(loaded.info, "NORMAL missing in 1 of 2 triangle primitives"));
}

TEST(GltfAttributes, ApplicationScalarsKeepNameAndType) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t temperature = buffer.add(bytes_of<float>({20.5f, -3.25f, 100.0f}));
  const std::size_t label = buffer.add(bytes_of<std::uint8_t>({7, 0, 255}));
  const std::size_t texcoord = buffer.add(bytes_of<float>({0, 0, 1, 0, 0, 1}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":
          {"POSITION":0,"_TEMPERATURE":1,"_LABEL":2,"_UV":3,"TEXCOORD_0":3}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(temperature, float_type, 3, "SCALAR") + "," +
      accessor(label, ubyte_type, 3, "SCALAR") + "," + accessor(texcoord, float_type, 3, "VEC2") + "]," +
      buffer.json()));

  const std::vector<VertexScalar>& scalars = loaded.attributes.scalars;
  ASSERT_EQ(scalars.size(), 2u);  // by name; _UV is not a scalar
  EXPECT_EQ(scalars[0].name, "LABEL");
  EXPECT_EQ(scalars[0].type, ValueType::uint8);
  EXPECT_EQ(scalars[0].values, (std::vector<double>{7, 0, 255}));
  EXPECT_EQ(scalars[1].name, "TEMPERATURE");
  EXPECT_EQ(scalars[1].type, ValueType::float32);
  EXPECT_EQ(scalars[1].values, (std::vector<double>{20.5, -3.25, 100.0}));
  EXPECT_TRUE(has_note_containing(loaded.info, "'_TEMPERATURE' read as scalar 'TEMPERATURE'"));
  EXPECT_TRUE(has_note_containing(loaded.info, "vertex attributes ignored: TEXCOORD_0, _UV"));
}

TEST(GltfAttributes, ScalarMissingInOnePrimitiveIsDropped) {
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::size_t temperature = buffer.add(bytes_of<float>({1, 2, 3}));
  const LoadedMesh loaded = read_json(gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"_TEMPERATURE":1}},
                                                       {"attributes":{"POSITION":2}}]}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "," + accessor(temperature, float_type, 3, "SCALAR") + "," +
      accessor(positions, float_type, 3, "VEC3") + "]," + buffer.json()));
  EXPECT_TRUE(loaded.attributes.scalars.empty());
  EXPECT_TRUE(has_note_containing(loaded.info, "'_TEMPERATURE' missing in 1 of 2"));
}

// A 2 x 2 texture; texel (i, j) is column i of row j, row 0 at v = 0.
const std::vector<std::uint8_t> texels = {200, 100, 50,  10,  220, 30,  // row 0
                                          90,  90,  255, 255, 255, 0};

std::vector<std::byte> png_of(const std::vector<std::uint8_t>& rgb, int width, int height) {
  const std::vector<std::uint8_t> png = detail::encode_png_rgb(rgb, width, height);
  return std::vector<std::byte>(reinterpret_cast<const std::byte*>(png.data()),
                                reinterpret_cast<const std::byte*>(png.data()) + png.size());
}

std::string png_data_uri(const std::vector<std::byte>& png) { return "data:image/png;base64," + base64(png); }

// One triangle per row of `uv` (three texture coordinates each), textured by
// image 0 ("images" given), with `sampler` (JSON members of sampler 0).
std::string textured_file(const std::vector<float>& uv, const std::string& images, const std::string& sampler = "",
                          const std::string& factor = "[1,1,1,1]") {
  BufferBuilder buffer;
  const std::size_t count = uv.size() / 2;
  std::vector<float> xyz;
  for (std::size_t v = 0; v < count; ++v) {
    xyz.insert(xyz.end(), {static_cast<float>(v % 3 == 1), static_cast<float>(v % 3 == 2), static_cast<float>(v / 3)});
  }
  const auto floats = [](const std::vector<float>& values) {
    return std::vector<std::byte>(reinterpret_cast<const std::byte*>(values.data()),
                                  reinterpret_cast<const std::byte*>(values.data() + values.size()));
  };
  const std::size_t positions = buffer.add(floats(xyz));
  const std::size_t texcoords = buffer.add(floats(uv));
  return gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
         "materials":[{"pbrMetallicRoughness":{"baseColorFactor":)" +
      factor + R"(,"baseColorTexture":{"index":0}}}],
         "textures":[{"source":0,"sampler":0}],"samplers":[{)" +
      sampler + R"(}],"images":)" + images + R"(,"accessors":[)" + accessor(positions, float_type, count, "VEC3") +
      "," + accessor(texcoords, float_type, count, "VEC2") + "]," + buffer.json());
}

Eigen::RowVector3f texel(int i, int j) {
  const std::size_t at = 3 * static_cast<std::size_t>(2 * j + i);
  return Eigen::RowVector3f(texels[at], texels[at + 1], texels[at + 2]) / 255.0f;
}

float linear_mean(std::initializer_list<float> encoded) {
  float sum = 0;
  for (const float e : encoded) sum += linear_from_srgb(e);
  return srgb_from_linear(sum / static_cast<float>(encoded.size()));
}

TEST(GltfAttributes, TextureAtTexelCentresGivesTheTexels) {
  const std::string images = R"([{"uri":")" + png_data_uri(png_of(texels, 2, 2)) + R"("}])";
  const LoadedMesh loaded = read_json(textured_file({0.25f, 0.25f, 0.75f, 0.25f, 0.25f, 0.75f,  //
                                                     0.75f, 0.75f, 0.75f, 0.25f, 0.25f, 0.25f},
                                                    images));
  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 6);
  ASSERT_EQ(out.cols(), 3);
  const Eigen::RowVector3f expected[] = {texel(0, 0), texel(1, 0), texel(0, 1), texel(1, 1), texel(1, 0), texel(0, 0)};
  for (int v = 0; v < 6; ++v) {
    EXPECT_LT((out.row(v) - expected[v]).cwiseAbs().maxCoeff(), byte_tolerance) << v << ": " << out.row(v);
  }
  EXPECT_EQ(loaded.attributes.color_type, ValueType::uint8);
  EXPECT_TRUE(has_note_containing(loaded.info, "baseColorTexture sampled at TEXCOORD_0"));
}

TEST(GltfAttributes, BilinearMidpointsAverageInLinearSpace) {
  const std::string images = R"([{"uri":")" + png_data_uri(png_of(texels, 2, 2)) + R"("}])";
  // Between texels (0,0) and (1,0); between (0,0) and (0,1); the middle of all four.
  const LoadedMesh loaded = read_json(textured_file({0.5f, 0.25f, 0.25f, 0.5f, 0.5f, 0.5f}, images));
  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(out(0, c), linear_mean({texel(0, 0)[c], texel(1, 0)[c]}), 1e-5) << c;
    EXPECT_NEAR(out(1, c), linear_mean({texel(0, 0)[c], texel(0, 1)[c]}), 1e-5) << c;
    EXPECT_NEAR(out(2, c), linear_mean({texel(0, 0)[c], texel(1, 0)[c], texel(0, 1)[c], texel(1, 1)[c]}), 1e-5) << c;
  }
  // Not the mean of the encoded values: (200 + 10) / 2 / 255 = 0.41 is well below the linear-space mean.
  EXPECT_GT(out(0, 0), 0.5f);
}

TEST(GltfAttributes, SamplerWrapModesAndNearestFilter) {
  const std::string images = R"([{"uri":")" + png_data_uri(png_of(texels, 2, 2)) + R"("}])";
  // u = 1.2 lies in texel 0 (repeat), texel 1 (mirrored: 0.8) or texel 1 (clamped);
  // u = -0.3 in texel 1 (repeat: 0.7), texel 0 (mirrored: 0.3) or texel 0 (clamped).
  const std::vector<float> uv = {1.2f, 0.1f, -0.3f, 0.1f, 0.4f, 0.6f};
  const auto colors = [&](const std::string& wrap) {
    return read_json(textured_file(uv, images, R"("magFilter":9728,"wrapS":)" + wrap)).attributes.colors;
  };
  const ColorMatrix repeat = colors("10497");
  const ColorMatrix mirrored = colors("33648");
  const ColorMatrix clamped = colors("33071");
  const auto near = [](const auto& a, const Eigen::RowVector3f& b) {
    return (a - b).cwiseAbs().maxCoeff() < byte_tolerance;
  };
  EXPECT_TRUE(near(repeat.row(0), texel(0, 0))) << repeat.row(0);
  EXPECT_TRUE(near(repeat.row(1), texel(1, 0))) << repeat.row(1);
  EXPECT_TRUE(near(mirrored.row(0), texel(1, 0))) << mirrored.row(0);
  EXPECT_TRUE(near(mirrored.row(1), texel(0, 0))) << mirrored.row(1);
  EXPECT_TRUE(near(clamped.row(0), texel(1, 0))) << clamped.row(0);
  EXPECT_TRUE(near(clamped.row(1), texel(0, 0))) << clamped.row(1);
  EXPECT_TRUE(near(repeat.row(2), texel(0, 1))) << repeat.row(2);  // nearest: no mixing
}

TEST(GltfAttributes, OnlyATextureSampledAsTheBakerSamplesIsKeptWhole) {
  const std::string images = R"([{"uri":")" + png_data_uri(png_of(texels, 2, 2)) + R"("}])";
  const std::vector<float> uv = {0.25f, 0.25f, 0.75f, 0.25f, 0.25f, 0.75f};
  const LoadedMesh repeated = read_json(textured_file(uv, images, R"("wrapS":10497)"));
  ASSERT_EQ(repeated.texture.images.size(), 1u);
  EXPECT_EQ(repeated.texture.images[0].texels, texels) << "the PNG's texels, whole";
  EXPECT_EQ(repeated.texture.corner_uvs.row(1), Eigen::RowVector2d(0.75, 0.25));
  // A clamping sampler, or a factor that is not white: the vertex colours only, with a note.
  const LoadedMesh clamped = read_json(textured_file(uv, images, R"("wrapS":33071)"));
  EXPECT_TRUE(clamped.texture.empty());
  EXPECT_TRUE(has_note_containing(clamped.info, "not kept for baking"));
  EXPECT_EQ(clamped.attributes.colors.rows(), 3);
  EXPECT_TRUE(read_json(textured_file(uv, images, "", "[1,0.5,1,1]")).texture.empty());
}

TEST(GltfAttributes, TextureTimesFactorAndTextureFromAGlbBufferView) {
  // The same texture as a GLB image in the BIN chunk, under a factor that halves green (linear).
  const std::vector<std::byte> png = png_of(texels, 2, 2);
  const std::vector<std::byte> positions = bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::vector<std::byte> uv = bytes_of<float>({0.25f, 0.25f, 0.75f, 0.25f, 0.25f, 0.75f});
  std::vector<std::byte> bin = positions;
  bin.insert(bin.end(), uv.begin(), uv.end());
  bin.insert(bin.end(), png.begin(), png.end());
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
      "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,1,1],"baseColorTexture":{"index":0}}}],
      "textures":[{"source":0}],"images":[{"bufferView":2,"mimeType":"image/png"}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                   {"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],
      "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24},
                     {"buffer":0,"byteOffset":60,"byteLength":)" +
                           std::to_string(png.size()) + R"(}],
      "buffers":[{"byteLength":)" +
                           std::to_string(bin.size()) + "}]}";
  const std::vector<std::byte> glb = gltf_test::glb_of(json, bin);
  const LoadedMesh loaded = detail::read_gltf(glb, true, "scan.glb");
  const ColorMatrix& out = loaded.attributes.colors;
  ASSERT_EQ(out.rows(), 3);
  const Eigen::RowVector3f expected[] = {texel(0, 0), texel(1, 0), texel(0, 1)};
  for (int v = 0; v < 3; ++v) {
    EXPECT_NEAR(out(v, 0), expected[v][0], byte_tolerance);
    EXPECT_NEAR(out(v, 1), srgb_from_linear(0.5f * linear_from_srgb(expected[v][1])), byte_tolerance);
    EXPECT_NEAR(out(v, 2), expected[v][2], byte_tolerance);
  }
}

TEST(GltfAttributes, JpegTexture) {
  // An 8 x 8 JPEG of one colour: decoded within a few levels of it (JPEG is lossy).
  std::vector<std::uint8_t> rgb;
  for (int i = 0; i < 64; ++i) rgb.insert(rgb.end(), {120, 60, 200});
  std::vector<std::byte> jpeg;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::byte>*>(context);
    out->insert(out->end(), static_cast<const std::byte*>(data), static_cast<const std::byte*>(data) + size);
  };
  ASSERT_NE(stbi_write_jpg_to_func(append, &jpeg, 8, 8, 3, rgb.data(), 100), 0);
  const std::string images = R"([{"uri":"data:image/jpeg;base64,)" + base64(jpeg) + R"("}])";
  const LoadedMesh loaded = read_json(textured_file({0.1f, 0.1f, 0.5f, 0.5f, 0.9f, 0.3f}, images));
  ASSERT_EQ(loaded.attributes.colors.rows(), 3);
  const Eigen::RowVector3f expected = Eigen::RowVector3f(120, 60, 200) / 255.0f;
  for (int v = 0; v < 3; ++v) {
    EXPECT_LT((loaded.attributes.colors.row(v) - expected).cwiseAbs().maxCoeff(), 4.0f / 255.0f)
        << loaded.attributes.colors.row(v) * 255.0f;
  }
}

TEST(GltfAttributes, BrokenPngNamesTheFileAndTheImage) {
  std::vector<std::byte> broken = png_of(texels, 2, 2);
  broken.resize(broken.size() / 2);  // cut off in the middle of the image data
  const std::string images = R"([{"name":"albedo","uri":")" + png_data_uri(broken) + R"("}])";
  try {
    read_json(textured_file({0.25f, 0.25f, 0.75f, 0.25f, 0.25f, 0.75f}, images), "broken.gltf");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("image 0 'albedo'"), std::string::npos) << message;
    EXPECT_NE(message.find("cannot be decoded"), std::string::npos) << message;
  }
}

TEST(GltfAttributes, UnusedImagesAreNeverDecoded) {
  // Image 1 is garbage, but only material 1 uses it and no primitive uses material 1.
  BufferBuilder buffer;
  const std::size_t positions = buffer.add(triangle_positions);
  const std::string json = gltf_file(
      R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
         "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}},
                      {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
         "textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,AAAA"}],"accessors":[)" +
      accessor(positions, float_type, 3, "VEC3") + "]," + buffer.json());
  const LoadedMesh loaded = read_json(json);
  ASSERT_EQ(loaded.attributes.colors.rows(), 3);
  EXPECT_LT((loaded.attributes.colors.row(0) - Eigen::RowVector3f(1, 0, 0)).cwiseAbs().maxCoeff(), 1e-6f);
}

class GltfAttributeFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("geodual_gltf_attributes_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const fs::path& path, std::span<const std::byte> bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  fs::path dir_;
};

TEST_F(GltfAttributeFiles, ExternalImageBesideTheFile) {
  write(dir_ / "albedo.png", png_of(texels, 2, 2));
  const std::string json = textured_file({0.75f, 0.75f, 0.25f, 0.25f, 0.75f, 0.25f}, R"([{"uri":"albedo.png"}])");
  write(dir_ / "scan.gltf", as_span(json));
  const LoadedMesh loaded = read_mesh(dir_ / "scan.gltf");
  ASSERT_EQ(loaded.attributes.colors.rows(), 3);
  EXPECT_LT((loaded.attributes.colors.row(0) - texel(1, 1)).cwiseAbs().maxCoeff(), byte_tolerance);

  // The same text from memory without a name cannot find the image.
  try {
    detail::read_gltf(as_span(json), false, "");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("image 0: external image 'albedo.png'"), std::string::npos) << e.what();
  }
}

TEST_F(GltfAttributeFiles, BrokenExternalImageNamesItsPath) {
  write(dir_ / "albedo.png", as_span(std::string("\x89PNG\r\n\x1a\n not really")));
  const std::string json = textured_file({0.75f, 0.75f, 0.25f, 0.25f, 0.75f, 0.25f}, R"([{"uri":"albedo.png"}])");
  write(dir_ / "scan.gltf", as_span(json));
  try {
    read_mesh(dir_ / "scan.gltf");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("scan.gltf: image 0"), std::string::npos) << message;
    EXPECT_NE(message.find("albedo.png"), std::string::npos) << message;
  }
}

// What geodual writes (linear COLOR_0, "_NAME" scalars), geodual reads back:
// the colours sRGB-encoded, the scalars by name.
TEST_F(GltfAttributeFiles, WriterRoundTripGivesColoursAndScalarsBack) {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0.5;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3;
  ColorMatrix linear(4, 3);
  linear << 0.5f, 0.25f, 0.125f, 1, 0, 0, 0.01f, 0.5f, 0.99f, 0.2f, 0.2f, 0.2f;
  GltfScene scene;
  scene.triangle_meshes.push_back(
      {.name = "scan", .mesh = mesh, .colors = linear, .scalars = {{"_TEMPERATURE", {20.5f, 21.0f, -4.0f, 0.125f}}}});
  for (const std::string extension : {".glb", ".gltf"}) {
    const fs::path path = dir_ / ("scene" + extension);
    write_gltf(path, scene);
    const LoadedMesh loaded = read_mesh(path);
    const VertexAttributes& attributes = loaded.attributes;
    ASSERT_EQ(attributes.colors.rows(), 4) << extension;
    ASSERT_EQ(attributes.colors.cols(), 3) << extension;
    for (int v = 0; v < 4; ++v) {
      for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(attributes.colors(v, c), srgb_from_linear(linear(v, c)));
    }
    ASSERT_EQ(attributes.scalars.size(), 1u) << extension;
    EXPECT_EQ(attributes.scalars[0].name, "TEMPERATURE");
    EXPECT_EQ(attributes.scalars[0].values, (std::vector<double>{20.5, 21.0, -4.0, 0.125}));
    EXPECT_EQ(attributes.normals.rows(), 4);
    EXPECT_TRUE(attribute_size_problem(attributes, loaded.mesh.num_vertices()).empty());
  }
}

}  // namespace
}  // namespace geodual::io
