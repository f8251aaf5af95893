#include "gltf_draco.hpp"

#include "geodual/mesh/error.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <limits>
#include <memory>

namespace geodual::io::detail::gltf {
namespace {

constexpr int normal_bits = 10;
constexpr int color_bits = 16;
constexpr int texcoord_bits = 16;  // a step of 1/65535 of the coordinates' range: 1/16 texel at 4096 texels

// Adds `components` floats per vertex as an attribute of `type`; returns its unique id.
std::uint32_t add_attribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components,
                            const std::vector<float>& values) {
  draco::GeometryAttribute attribute;
  const auto stride = static_cast<std::int64_t>(sizeof(float)) * components;
  attribute.Init(type, nullptr, static_cast<std::uint8_t>(components), draco::DT_FLOAT32, false, stride, 0);
  const int id = mesh.AddAttribute(attribute, /*identity_mapping=*/true, mesh.num_points());
  draco::PointAttribute& added = *mesh.attribute(id);
  for (draco::PointIndex::ValueType v = 0; v < mesh.num_points(); ++v) {
    added.SetAttributeValue(draco::AttributeValueIndex(v), values.data() + static_cast<std::size_t>(components) * v);
  }
  return added.unique_id();
}

}  // namespace

DracoPrimitive encode_draco(const TriangleStreams& streams, const std::string& where) {
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<draco::PointIndex::ValueType>(streams.vertex_count));
  for (std::size_t t = 0; t + 2 < streams.indices.size(); t += 3) {
    mesh.AddFace({draco::PointIndex(streams.indices[t]), draco::PointIndex(streams.indices[t + 1]),
                  draco::PointIndex(streams.indices[t + 2])});
  }
  DracoPrimitive out;
  out.attribute_ids.emplace_back("POSITION",
                                 add_attribute(mesh, draco::GeometryAttribute::POSITION, 3, streams.positions));
  out.attribute_ids.emplace_back("NORMAL", add_attribute(mesh, draco::GeometryAttribute::NORMAL, 3, streams.normals));
  if (streams.color_channels > 0) {
    out.attribute_ids.emplace_back(
        "COLOR_0", add_attribute(mesh, draco::GeometryAttribute::COLOR, streams.color_channels, streams.colors));
  }
  if (!streams.texcoords.empty()) {
    out.attribute_ids.emplace_back("TEXCOORD_0",
                                   add_attribute(mesh, draco::GeometryAttribute::TEX_COORD, 2, streams.texcoords));
  }
  if (!streams.tangents.empty()) {  // exact, as the scalars: Draco quantises GENERIC attributes only when asked
    out.attribute_ids.emplace_back("TANGENT",
                                   add_attribute(mesh, draco::GeometryAttribute::GENERIC, 4, streams.tangents));
  }
  for (const NamedScalars& scalar : streams.scalars) {
    out.attribute_ids.emplace_back(scalar.name,
                                   add_attribute(mesh, draco::GeometryAttribute::GENERIC, 1, scalar.values));
  }

  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, draco_position_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, normal_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::COLOR, color_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, texcoord_bits);
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  draco::EncoderBuffer buffer;
  if (const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer); !status.ok()) {
    throw Error(where + ": Draco could not compress the mesh: " + status.error_msg_string());
  }
  const auto* first = reinterpret_cast<const std::byte*>(buffer.data());
  out.encoded.assign(first, first + buffer.size());

  // The accessors describe the decoded mesh, so decode it once.
  draco::DecoderBuffer input;
  input.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&input);
  if (!decoded.ok()) {
    throw Error(where + ": Draco could not decode the mesh it compressed: " + decoded.status().error_msg_string());
  }
  const draco::Mesh& back = *decoded.value();
  out.decoded_vertices = back.num_points();
  out.decoded_indices = 3 * static_cast<std::size_t>(back.num_faces());
  const draco::PointAttribute* position = back.GetAttributeByUniqueId(out.attribute_ids.front().second);
  if (position == nullptr) throw Error(where + ": Draco lost the positions of the mesh it compressed");
  out.position_min.assign(3, std::numeric_limits<double>::infinity());
  out.position_max.assign(3, -std::numeric_limits<double>::infinity());
  for (draco::PointIndex::ValueType v = 0; v < back.num_points(); ++v) {
    float xyz[3];
    position->GetMappedValue(draco::PointIndex(v), xyz);
    for (std::size_t k = 0; k < 3; ++k) {
      out.position_min[k] = std::min(out.position_min[k], static_cast<double>(xyz[k]));
      out.position_max[k] = std::max(out.position_max[k], static_cast<double>(xyz[k]));
    }
  }
  return out;
}

}  // namespace geodual::io::detail::gltf
