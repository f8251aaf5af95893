// glTF compression for the web (GltfCompression): the extensions declared as
// their specifications ask, a decode with meshoptimizer's and Draco's own
// decoders that gives back the positions within the quantisation step and the
// same triangles, the other attributes, determinism, and geodual's reader,
// which refuses compressed files with a message naming the file and extension.

#include "glb_parts.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <draco/compression/decode.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <unistd.h>

namespace geodual::io {
namespace {
namespace fs = std::filesystem;
using gltf_test::Glb;
using gltf_test::split_glb;
using gltf_test::u32_at;
using nlohmann::json;

// A torus of `around` x `across` vertices, with RGBA colours and a scalar that
// vary over it; every vertex is used and none coincide.
GltfTriangleMesh torus(int around, int across) {
  GltfTriangleMesh entry{.name = "torus"};
  const int n = around * across;
  entry.mesh.vertices.resize(n, 3);
  entry.colors.resize(n, 4);
  GltfVertexScalar scalar{.name = "_HEIGHT"};
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      const double u = 2 * std::numbers::pi * i / around, v = 2 * std::numbers::pi * j / across;
      const int k = i * across + j;
      entry.mesh.vertices.row(k) << (3 + std::cos(v)) * std::cos(u) + 10, (3 + std::cos(v)) * std::sin(u) - 4,
          std::sin(v);
      entry.colors.row(k) << static_cast<float>(0.5 + 0.5 * std::cos(u)), static_cast<float>(0.5 + 0.5 * std::sin(v)),
          static_cast<float>(i) / static_cast<float>(around), 1.0F;
      scalar.values.push_back(static_cast<float>(std::sin(v) * 1e3 + 0.123 * k));
    }
  }
  entry.mesh.faces.resize(2 * n, 3);
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      const int a = i * across + j, b = ((i + 1) % around) * across + j;
      const int c = ((i + 1) % around) * across + (j + 1) % across, d = i * across + (j + 1) % across;
      entry.mesh.faces.row(2 * (i * across + j)) << a, b, c;
      entry.mesh.faces.row(2 * (i * across + j) + 1) << a, c, d;
    }
  }
  entry.scalars.push_back(std::move(scalar));
  return entry;
}

GltfScene scene_of(GltfTriangleMesh entry, GltfCompression compression) {
  return {.triangle_meshes = {std::move(entry)},
          .extras_json = R"({"note":"kept as written"})",
          .compression = compression};
}

// What a decoder gives back: positions (after the node's transform), normals,
// colours, the scalar and the triangles.
struct Decoded {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<float, 3>> normals;
  std::vector<std::array<float, 4>> colors;
  std::vector<float> scalar;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<float, 2>> texcoords;  ///< where written
  std::vector<std::array<float, 4>> tangents;   ///< where written
};

// The byte range of buffer 0 that a meshopt view's extension points at.
std::vector<unsigned char> meshopt_source(const Glb& glb, const json& extension) {
  EXPECT_EQ(extension["buffer"], 0);
  const std::size_t offset = extension.value("byteOffset", std::size_t{0});
  const std::size_t length = extension["byteLength"].get<std::size_t>();
  const auto* first = reinterpret_cast<const unsigned char*>(glb.bin.data() + offset);
  return {first, first + length};
}

Decoded decode_meshopt(const Glb& glb) {
  const json& doc = glb.document;
  const json& primitive = doc["meshes"][0]["primitives"][0];
  const json& node = doc["nodes"][0];
  Decoded out;
  // Decodes accessor `index` into `stride`-byte elements, checking its view's extension.
  const auto decode = [&](int index, std::size_t element_bytes) {
    const json& accessor = doc["accessors"][index];
    const json& view = doc["bufferViews"][accessor["bufferView"].get<int>()];
    const json& extension = view["extensions"]["EXT_meshopt_compression"];
    const std::size_t count = accessor["count"].get<std::size_t>();
    const std::size_t stride = extension["byteStride"].get<std::size_t>();
    EXPECT_EQ(extension["count"].get<std::size_t>(), count);
    EXPECT_EQ(view["buffer"], 1);  // the fallback buffer
    EXPECT_EQ(view["byteLength"].get<std::size_t>(), count * stride);
    EXPECT_GE(stride, element_bytes);
    const std::vector<unsigned char> source = meshopt_source(glb, extension);
    std::vector<std::byte> data(count * stride);
    const bool triangles = extension["mode"] == "TRIANGLES";
    const int rc = triangles ? meshopt_decodeIndexBuffer(data.data(), count, stride, source.data(), source.size())
                             : meshopt_decodeVertexBuffer(data.data(), count, stride, source.data(), source.size());
    EXPECT_EQ(rc, 0) << "accessor " << index;
    if (extension.value("filter", std::string("NONE")) == "OCTAHEDRAL") {
      meshopt_decodeFilterOct(data.data(), count, stride);
    } else {
      EXPECT_FALSE(extension.contains("filter"));
    }
    return std::pair{data, stride};
  };

  const json& position_accessor = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(position_accessor["componentType"], 5123);  // UNSIGNED_SHORT (KHR_mesh_quantization)
  EXPECT_FALSE(position_accessor.value("normalized", false));
  const auto [positions, position_stride] = decode(primitive["attributes"]["POSITION"].get<int>(), 6);
  const double scale = node["scale"][0].get<double>();
  EXPECT_EQ(node["scale"][1].get<double>(), scale);  // uniform: normals stay as they are
  for (std::size_t v = 0; v < positions.size() / position_stride; ++v) {
    std::array<std::uint16_t, 3> q{};
    std::memcpy(q.data(), positions.data() + v * position_stride, 6);
    std::array<double, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
      p[k] = node["translation"][k].get<double>() + scale * q[k];
      EXPECT_GE(q[k], position_accessor["min"][k].get<double>());
      EXPECT_LE(q[k], position_accessor["max"][k].get<double>());
    }
    out.positions.push_back(p);
  }
  const auto [normals, normal_stride] = decode(primitive["attributes"]["NORMAL"].get<int>(), 3);
  EXPECT_EQ(doc["bufferViews"][doc["accessors"][primitive["attributes"]["NORMAL"].get<int>()]["bufferView"].get<int>()]
               ["extensions"]["EXT_meshopt_compression"]["filter"],
            "OCTAHEDRAL");
  EXPECT_EQ(doc["accessors"][primitive["attributes"]["NORMAL"].get<int>()]["componentType"], 5120);  // BYTE
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    std::array<std::int8_t, 3> q{};
    std::memcpy(q.data(), normals.data() + v * normal_stride, 3);
    out.normals.push_back(
        {std::max(q[0] / 127.0F, -1.0F), std::max(q[1] / 127.0F, -1.0F), std::max(q[2] / 127.0F, -1.0F)});
  }
  const auto [colors, color_stride] = decode(primitive["attributes"]["COLOR_0"].get<int>(), 8);
  for (std::size_t v = 0; v < out.positions.size(); ++v) {
    std::array<std::uint16_t, 4> q{};
    std::memcpy(q.data(), colors.data() + v * color_stride, 8);
    out.colors.push_back({q[0] / 65535.0F, q[1] / 65535.0F, q[2] / 65535.0F, q[3] / 65535.0F});
  }
  const auto [scalar, scalar_stride] = decode(primitive["attributes"]["_HEIGHT"].get<int>(), 4);
  out.scalar.resize(out.positions.size());
  std::memcpy(out.scalar.data(), scalar.data(), scalar.size());
  if (primitive["attributes"].contains("TEXCOORD_0")) {  // normalised uint16 u, v
    const json& accessor = doc["accessors"][primitive["attributes"]["TEXCOORD_0"].get<int>()];
    EXPECT_EQ(accessor["componentType"], 5123);
    EXPECT_EQ(accessor["normalized"], true);
    const auto [uvs, uv_stride] = decode(primitive["attributes"]["TEXCOORD_0"].get<int>(), 4);
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
      std::array<std::uint16_t, 2> q{};
      std::memcpy(q.data(), uvs.data() + v * uv_stride, 4);
      out.texcoords.push_back({q[0] / 65535.0F, q[1] / 65535.0F});
    }
  }
  if (primitive["attributes"].contains("TANGENT")) {  // normalised int8 x, y, z, w through the octahedral filter
    const auto [tangents, tangent_stride] = decode(primitive["attributes"]["TANGENT"].get<int>(), 4);
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
      std::array<std::int8_t, 4> q{};
      std::memcpy(q.data(), tangents.data() + v * tangent_stride, 4);
      out.tangents.push_back({std::max(q[0] / 127.0F, -1.0F), std::max(q[1] / 127.0F, -1.0F),
                              std::max(q[2] / 127.0F, -1.0F), std::max(q[3] / 127.0F, -1.0F)});
    }
  }
  const json& index_accessor = doc["accessors"][primitive["indices"].get<int>()];
  const auto [indices, index_size] = decode(primitive["indices"].get<int>(), 2);
  EXPECT_EQ(index_size, index_accessor["componentType"] == 5123 ? 2u : 4u);
  for (std::size_t t = 0; 3 * t < indices.size() / index_size; ++t) {
    std::array<std::uint32_t, 3> triangle{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (index_size == 2) {
        std::uint16_t i = 0;
        std::memcpy(&i, indices.data() + (3 * t + k) * 2, 2);
        triangle[k] = i;
      } else {
        std::memcpy(&triangle[k], indices.data() + (3 * t + k) * 4, 4);
      }
    }
    out.triangles.push_back(triangle);
  }
  return out;
}

Decoded decode_draco(const Glb& glb) {
  const json& doc = glb.document;
  const json& primitive = doc["meshes"][0]["primitives"][0];
  const json& extension = primitive["extensions"]["KHR_draco_mesh_compression"];
  const json& view = doc["bufferViews"][extension["bufferView"].get<int>()];
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(glb.bin.data()) + view.value("byteOffset", std::size_t{0}),
              view["byteLength"].get<std::size_t>());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  EXPECT_TRUE(decoded.ok()) << decoded.status().error_msg_string();
  Decoded out;
  if (!decoded.ok()) return out;
  const draco::Mesh& mesh = *decoded.value();
  const auto attribute = [&](const char* name) {
    const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(extension["attributes"][name].get<std::uint32_t>());
    EXPECT_NE(a, nullptr) << name;
    const json& accessor = doc["accessors"][primitive["attributes"][name].get<int>()];
    EXPECT_FALSE(accessor.contains("bufferView")) << name;
    EXPECT_EQ(accessor["count"].get<std::size_t>(), mesh.num_points()) << name;
    return a;
  };
  const draco::PointAttribute* positions = attribute("POSITION");
  const draco::PointAttribute* normals = attribute("NORMAL");
  const draco::PointAttribute* colors = attribute("COLOR_0");
  const draco::PointAttribute* scalar = attribute("_HEIGHT");
  for (draco::PointIndex::ValueType v = 0; v < mesh.num_points(); ++v) {
    std::array<float, 3> p{};
    positions->GetMappedValue(draco::PointIndex(v), p.data());
    out.positions.push_back({p[0], p[1], p[2]});
    normals->GetMappedValue(draco::PointIndex(v), out.normals.emplace_back().data());
    colors->GetMappedValue(draco::PointIndex(v), out.colors.emplace_back().data());
    scalar->GetMappedValue(draco::PointIndex(v), &out.scalar.emplace_back());
  }
  if (primitive["attributes"].contains("TEXCOORD_0")) {
    const draco::PointAttribute* uvs = attribute("TEXCOORD_0");
    const draco::PointAttribute* tangents = attribute("TANGENT");
    for (draco::PointIndex::ValueType v = 0; v < mesh.num_points(); ++v) {
      uvs->GetMappedValue(draco::PointIndex(v), out.texcoords.emplace_back().data());
      tangents->GetMappedValue(draco::PointIndex(v), out.tangents.emplace_back().data());
    }
  }
  EXPECT_EQ(doc["accessors"][primitive["indices"].get<int>()]["count"].get<std::size_t>(), 3 * mesh.num_faces());
  for (draco::FaceIndex::ValueType f = 0; f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(f));
    out.triangles.push_back({face[0].value(), face[1].value(), face[2].value()});
  }
  return out;
}

// A triangle as a set element: rotated so that its smallest index comes first (orientation kept).
std::array<Index, 3> canonical(std::array<Index, 3> t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

struct Errors {
  double position = 0, normal = 0, color = 0, scalar = 0, texcoord = 0, tangent = 0;
};

// Matches each decoded vertex to the input vertex nearest to it; expects a
// one-to-one match within `tolerance` and the same triangles; returns the largest errors.
Errors compare(const GltfTriangleMesh& input, const Decoded& decoded, double tolerance) {
  Errors errors;
  const Index n = input.mesh.num_vertices();
  EXPECT_EQ(decoded.positions.size(), static_cast<std::size_t>(n));
  std::vector<Index> original(decoded.positions.size(), -1);
  std::vector<bool> taken(static_cast<std::size_t>(n), false);
  for (std::size_t d = 0; d < decoded.positions.size(); ++d) {
    double best = std::numeric_limits<double>::infinity();
    for (Index v = 0; v < n; ++v) {
      double distance = 0;
      for (Index k = 0; k < 3; ++k) {
        distance = std::max(distance, std::abs(decoded.positions[d][k] - input.mesh.vertices(v, k)));
      }
      if (distance < best) best = distance, original[d] = v;
    }
    errors.position = std::max(errors.position, best);
    const auto v = static_cast<std::size_t>(original[d]);
    EXPECT_FALSE(taken[v]) << "input vertex " << v << " decoded twice";
    taken[v] = true;
    for (Index k = 0; k < 3; ++k) {
      errors.color = std::max(errors.color, static_cast<double>(std::abs(decoded.colors[d][k] - input.colors(v, k))));
    }
    errors.scalar =
        std::max(errors.scalar, static_cast<double>(std::abs(decoded.scalar[d] - input.scalars[0].values[v])));
    if (input.texcoords.rows() > 0) {
      EXPECT_EQ(decoded.texcoords.size(), decoded.positions.size());
      EXPECT_EQ(decoded.tangents.size(), decoded.positions.size());
      for (Index k = 0; k < 2; ++k) {
        errors.texcoord = std::max(
            errors.texcoord, static_cast<double>(std::abs(decoded.texcoords[d][k] - input.texcoords(original[d], k))));
      }
      for (Index k = 0; k < 4; ++k) {
        errors.tangent = std::max(
            errors.tangent, static_cast<double>(std::abs(decoded.tangents[d][k] - input.tangents(original[d], k))));
      }
    }
    if (input.normals.rows() > 0) {  // given normals: to the decoded one's unit vector
      const Eigen::RowVector3d unit = input.normals.row(original[d]).normalized();
      for (Index k = 0; k < 3; ++k) {
        errors.normal = std::max(errors.normal, std::abs(static_cast<double>(decoded.normals[d][k]) - unit[k]));
      }
    }
  }
  EXPECT_LE(errors.position, tolerance);
  std::multiset<std::array<Index, 3>> expected, got;
  for (Index f = 0; f < input.mesh.num_faces(); ++f) {
    expected.insert(canonical({input.mesh.faces(f, 0), input.mesh.faces(f, 1), input.mesh.faces(f, 2)}));
  }
  for (const auto& t : decoded.triangles) {
    got.insert(canonical({original[t[0]], original[t[1]], original[t[2]]}));
  }
  EXPECT_TRUE(got == expected) << got.size() << " triangles decoded, " << expected.size() << " written";
  return errors;
}

// The largest side of the mesh's bounding box.
double extent(const TriangleMesh& mesh) {
  return (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).maxCoeff();
}

void expect_extensions(const json& doc, const std::vector<std::string>& names) {
  EXPECT_EQ(doc["extensionsUsed"].get<std::vector<std::string>>(), names);
  EXPECT_EQ(doc["extensionsRequired"].get<std::vector<std::string>>(), names);
}

TEST(GltfCompression, MeshoptDecodesToThePositionsWithinHalfAStepAndTheSameTriangles) {
  const GltfTriangleMesh input = torus(48, 40);
  const double step = extent(input.mesh) / ((1 << 14) - 1);  // 14-bit grid
  const Glb glb = split_glb(encode_gltf(scene_of(input, GltfCompression::meshopt), GltfContainer::glb));
  expect_extensions(glb.document, {"EXT_meshopt_compression", "KHR_mesh_quantization"});
  ASSERT_EQ(glb.document["buffers"].size(), 2u);
  EXPECT_EQ(glb.document["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"], true);
  EXPECT_FALSE(glb.document["buffers"][1].contains("uri"));
  EXPECT_EQ(glb.document["asset"]["extras"]["note"], "kept as written");
  const Decoded decoded = decode_meshopt(glb);
  const Errors errors = compare(input, decoded, 0.5 * step + 1e-6);
  EXPECT_LE(errors.color, 0.5 / 65535 + 1e-6);
  EXPECT_EQ(errors.scalar, 0);
  std::cout << "meshopt: position error " << errors.position << " (step " << step << "), colour error " << errors.color
            << '\n';
}

TEST(GltfCompression, NormalsComeBackWithinTheirQuantisation) {
  GltfTriangleMesh input = torus(48, 40);
  // Given normals, the torus's own (every direction), of several lengths.
  input.normals.resize(input.mesh.num_vertices(), 3);
  for (Index v = 0; v < input.mesh.num_vertices(); ++v) {
    const double x = input.mesh.vertices(v, 0) - 10, y = input.mesh.vertices(v, 1) + 4;
    const Eigen::RowVector3d centre(10 + 3 * x / std::hypot(x, y), -4 + 3 * y / std::hypot(x, y), 0);
    input.normals.row(v) = (input.mesh.vertices.row(v) - centre) * (1.0 + static_cast<double>(v % 3));
  }
  // meshopt: 8-bit octahedral, decoded to normalised int8; Draco: 10-bit octahedral.
  for (const auto& [compression, tolerance] :
       {std::pair{GltfCompression::meshopt, 0.02}, std::pair{GltfCompression::draco, 0.005}}) {
    const Glb glb = split_glb(encode_gltf(scene_of(input, compression), GltfContainer::glb));
    const Decoded decoded = compression == GltfCompression::meshopt ? decode_meshopt(glb) : decode_draco(glb);
    const Errors errors = compare(input, decoded, extent(input.mesh) / ((1 << 14) - 1));
    EXPECT_LE(errors.normal, tolerance) << gltf_compression_name(compression);
    std::cout << gltf_compression_name(compression) << ": normal component error " << errors.normal << '\n';
  }
}

TEST(GltfCompression, TextureCoordinatesAndTangentsComeBackWithinTheirQuantisation) {
  GltfTriangleMesh input = torus(48, 40);
  // The torus's (u, v) over [0, 1] and its tangent along u (w +1 and -1 in turn).
  input.texcoords.resize(input.mesh.num_vertices(), 2);
  input.tangents.resize(input.mesh.num_vertices(), 4);
  for (Index v = 0; v < input.mesh.num_vertices(); ++v) {
    const int i = v / 40, j = v % 40;
    input.texcoords.row(v) << static_cast<float>(i / 47.0), static_cast<float>(j / 39.0);
    const double u = 2 * std::numbers::pi * i / 48;
    input.tangents.row(v) << static_cast<float>(-std::sin(u)), static_cast<float>(std::cos(u)), 0.0F,
        v % 2 == 0 ? 1.0F : -1.0F;
  }
  input.base_color_texture = {.bytes = {std::byte{1}}, .mime_type = "image/png"};  // bytes as given, never decoded
  // meshopt: uint16 (half a step of 1/65535) and 8-bit octahedral; Draco: 16 bits over the range, tangents exact.
  for (const auto& [compression, texcoord_tolerance, tangent_tolerance] :
       {std::tuple{GltfCompression::meshopt, 0.5 / 65535 + 1e-7, 0.02},
        std::tuple{GltfCompression::draco, 1.0 / 65535, 0.0}}) {
    const Glb glb = split_glb(encode_gltf(scene_of(input, compression), GltfContainer::glb));
    const Decoded decoded = compression == GltfCompression::meshopt ? decode_meshopt(glb) : decode_draco(glb);
    const Errors errors = compare(input, decoded, extent(input.mesh) / ((1 << 14) - 1));
    EXPECT_LE(errors.texcoord, texcoord_tolerance) << gltf_compression_name(compression);
    EXPECT_LE(errors.tangent, tangent_tolerance) << gltf_compression_name(compression);
    const json& material = glb.document["materials"][0];
    EXPECT_EQ(glb.document["meshes"][0]["primitives"][0]["material"], 0);
    EXPECT_EQ(material["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
    EXPECT_EQ(glb.document["images"][0]["mimeType"], "image/png");
  }
}

TEST(GltfCompression, DracoDecodesToThePositionsWithinAStepAndTheSameTriangles) {
  const GltfTriangleMesh input = torus(48, 40);
  const Glb glb = split_glb(encode_gltf(scene_of(input, GltfCompression::draco), GltfContainer::glb));
  expect_extensions(glb.document, {"KHR_draco_mesh_compression"});
  ASSERT_EQ(glb.document["buffers"].size(), 1u);
  const Decoded decoded = decode_draco(glb);
  const double step = extent(input.mesh) / ((1 << 14) - 1);  // 14-bit quantisation
  const Errors errors = compare(input, decoded, step);
  EXPECT_LE(errors.color, 1.0 / 65535);
  EXPECT_EQ(errors.scalar, 0);
  std::cout << "draco: position error " << errors.position << " (step " << step << "), colour error " << errors.color
            << '\n';
  const json& position =
      glb.document["accessors"][glb.document["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  for (std::size_t k = 0; k < 3; ++k) {  // bounds of the decoded positions
    double low = std::numeric_limits<double>::infinity();
    for (const auto& p : decoded.positions) low = std::min(low, static_cast<double>(static_cast<float>(p[k])));
    EXPECT_EQ(position["min"][k].get<double>(), low);
  }
}

TEST(GltfCompression, WideIndicesAboveUint16) {
  const GltfTriangleMesh input = torus(300, 240);  // 72,000 vertices
  for (const GltfCompression compression : {GltfCompression::meshopt, GltfCompression::draco}) {
    const Glb glb = split_glb(encode_gltf(scene_of(input, compression), GltfContainer::glb));
    const json& indices = glb.document["accessors"][glb.document["meshes"][0]["primitives"][0]["indices"].get<int>()];
    EXPECT_EQ(indices["componentType"], 5125) << gltf_compression_name(compression);
    EXPECT_EQ(indices["count"], 3 * 2 * 72000);
    if (compression == GltfCompression::meshopt) {
      const Decoded decoded = decode_meshopt(glb);
      ASSERT_EQ(decoded.triangles.size(), 2u * 72000);
      for (const auto& t : decoded.triangles) {
        for (const std::uint32_t i : t) ASSERT_LT(i, 72000u);
      }
    }
  }
}

TEST(GltfCompression, SameSceneSameBytesAndTheEmbeddedGltfHoldsTheSame) {
  const GltfTriangleMesh input = torus(30, 20);
  for (const GltfCompression compression : {GltfCompression::meshopt, GltfCompression::draco}) {
    const std::vector<std::byte> first = encode_gltf(scene_of(input, compression), GltfContainer::glb);
    EXPECT_EQ(first, encode_gltf(scene_of(input, compression), GltfContainer::glb));
    const std::vector<std::byte> text = encode_gltf(scene_of(input, compression), GltfContainer::gltf_embedded);
    EXPECT_EQ(text, encode_gltf(scene_of(input, compression), GltfContainer::gltf_embedded));
    const json document = json::parse(reinterpret_cast<const char*>(text.data()),
                                      reinterpret_cast<const char*>(text.data()) + text.size());
    const Glb glb = split_glb(first);
    EXPECT_EQ(document["bufferViews"], glb.document["bufferViews"]);
    EXPECT_EQ(document["extensionsRequired"], glb.document["extensionsRequired"]);
    EXPECT_TRUE(document["buffers"][0]["uri"].get<std::string>().starts_with("data:"));
  }
}

TEST(GltfCompression, LinesAndPointsStayUncompressedBesideACompressedMesh) {
  GltfScene scene = scene_of(torus(12, 8), GltfCompression::meshopt);
  scene.line_sets.push_back(
      {.name = "lines", .points = VertexMatrix{{0, 0, 0}, {1, 0, 0}}, .segments = SegmentMatrix{{0, 1}}});
  scene.point_sets.push_back({.name = "points", .points = VertexMatrix{{0, 0, 1}}});
  const Glb glb = split_glb(encode_gltf(scene, GltfContainer::glb));
  for (int mesh = 1; mesh <= 2; ++mesh) {
    const json& accessor =
        glb.document["accessors"][glb.document["meshes"][mesh]["primitives"][0]["attributes"]["POSITION"].get<int>()];
    EXPECT_EQ(accessor["componentType"], 5126);
    const json& view = glb.document["bufferViews"][accessor["bufferView"].get<int>()];
    EXPECT_EQ(view["buffer"], 0);
    EXPECT_FALSE(view.contains("extensions"));
  }
}

TEST(GltfCompression, GeodualsReaderNamesTheFileAndTheExtension) {
  const fs::path folder = fs::temp_directory_path() / ("geodual-gltf-compression-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const GltfTriangleMesh input = torus(12, 8);
  for (const auto& [compression, extension] : {std::pair{GltfCompression::meshopt, "EXT_meshopt_compression"},
                                               std::pair{GltfCompression::draco, "KHR_draco_mesh_compression"}}) {
    for (const char* suffix : {".glb", ".gltf"}) {
      const fs::path path = folder / (std::string(gltf_compression_name(compression)) + suffix);
      write_gltf(path, input.mesh, {}, compression);
      try {
        (void)read_mesh(path);
        ADD_FAILURE() << path << " was read";
      } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_NE(message.find(extension), std::string::npos) << message;
        EXPECT_NE(message.find("decompress"), std::string::npos) << message;
      }
    }
  }
  fs::remove_all(folder);
}

TEST(GltfCompression, UncompressedOutputIsUnchangedByTheOption) {
  const GltfTriangleMesh input = torus(12, 8);
  GltfScene plain = scene_of(input, GltfCompression::none);
  const Glb glb = split_glb(encode_gltf(plain, GltfContainer::glb));
  EXPECT_FALSE(glb.document.contains("extensionsUsed"));
  EXPECT_FALSE(glb.document["nodes"][0].contains("scale"));
  EXPECT_EQ(gltf_compression_name(GltfCompression::none), "none");
}

TEST(GltfCompression, InvalidInputIsRefusedAsWithoutCompression) {
  for (const GltfCompression compression : {GltfCompression::meshopt, GltfCompression::draco}) {
    GltfTriangleMesh input = torus(6, 4);
    input.mesh.vertices(2, 1) = std::nan("");
    EXPECT_THROW((void)encode_gltf(scene_of(input, compression), GltfContainer::glb), Error);
    input = torus(6, 4);
    input.colors(1, 0) = 2.0F;
    EXPECT_THROW((void)encode_gltf(scene_of(input, compression), GltfContainer::glb), Error);
    input = torus(6, 4);
    input.scalars[0].name = "HEIGHT";
    EXPECT_THROW((void)encode_gltf(scene_of(input, compression), GltfContainer::glb), Error);
  }
}

}  // namespace
}  // namespace geodual::io
