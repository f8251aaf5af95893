#include "gltf_meshopt.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace geodual::io::detail::gltf {
namespace {

constexpr double position_steps = (1 << meshopt_position_bits) - 1;  // stored as uint16
constexpr int normal_bits = 8;                                       // octahedral x and y
// glTF forbids 65535 in uint16 indices (primitive restart), as the uncompressed writer does.
constexpr std::size_t max_vertices_for_uint16 = 65535;

// Vertex `v` of the reordered mesh came from vertex `source[v]`.
struct VertexOrder {
  std::vector<std::uint32_t> indices;  // reordered triangles, in new vertex numbers
  std::vector<std::uint32_t> source;
};

// Triangles in vertex-cache order, then vertices in first-use (fetch) order;
// vertices no triangle uses keep their order after the others.
VertexOrder reorder(const TriangleStreams& mesh) {
  const std::size_t n = mesh.vertex_count;
  std::vector<std::uint32_t> cached(mesh.indices.size());
  meshopt_optimizeVertexCache(cached.data(), mesh.indices.data(), mesh.indices.size(), n);
  std::vector<std::uint32_t> remap(n);
  std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), cached.data(), cached.size(), n);
  for (std::uint32_t& target : remap) {
    if (target == std::numeric_limits<std::uint32_t>::max()) target = static_cast<std::uint32_t>(used++);
  }
  VertexOrder order;
  order.indices.resize(cached.size());
  meshopt_remapIndexBuffer(order.indices.data(), cached.data(), cached.size(), remap.data());
  order.source.resize(n);
  for (std::size_t v = 0; v < n; ++v) order.source[remap[v]] = static_cast<std::uint32_t>(v);
  return order;
}

std::vector<std::byte> encode_vertices(const std::vector<std::byte>& data, std::size_t count, std::size_t stride) {
  std::vector<std::byte> out(meshopt_encodeVertexBufferBound(count, stride));
  const std::size_t size =
      meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(), data.data(), count, stride);
  out.resize(size);
  return out;
}

// Packs `components` values per vertex of type T into `stride`-byte elements (zero padding).
template <class T, class Convert>
std::vector<std::byte> pack(const VertexOrder& order, std::size_t components, std::size_t stride, Convert&& value_of) {
  std::vector<std::byte> data(order.source.size() * stride);
  for (std::size_t v = 0; v < order.source.size(); ++v) {
    for (std::size_t k = 0; k < components; ++k) {
      const T value = value_of(order.source[v], k);
      std::memcpy(data.data() + v * stride + k * sizeof(T), &value, sizeof(T));
    }
  }
  return data;
}

// Unit vectors (`components` floats per vertex: x, y, z, and w kept where 4)
// as normalised int8 x, y, z, w through the 8-bit octahedral filter, which
// the codec packs tighter: a stream of `attribute`, encoded.
MeshoptStream octahedral_stream(const char* attribute, const VertexOrder& order, const std::vector<float>& values,
                                std::size_t components) {
  const std::size_t n = order.source.size();
  MeshoptStream stream;
  stream.attribute = attribute;
  stream.component_type = ComponentType::byte;
  stream.components = static_cast<int>(components);
  stream.normalized = true;
  stream.byte_stride = 4;
  stream.filter = "OCTAHEDRAL";
  std::vector<float> xyzw(4 * n, 0.0F);
  for (std::size_t v = 0; v < n; ++v) {
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(components * order.source[v]), components,
                xyzw.begin() + static_cast<std::ptrdiff_t>(4 * v));
  }
  std::vector<std::byte> filtered(4 * n);
  meshopt_encodeFilterOct(filtered.data(), n, 4, normal_bits, xyzw.data());
  stream.encoded = encode_vertices(filtered, n, 4);
  return stream;
}

template <class T>
T quantize_unit(float value, double steps) {  // [0, 1] to a normalised integer
  return static_cast<T>(std::lround(std::clamp(static_cast<double>(value), 0.0, 1.0) * steps));
}

}  // namespace

MeshoptPrimitive encode_meshopt(const TriangleStreams& mesh) {
  meshopt_encodeVertexVersion(0);  // the versions EXT_meshopt_compression specifies
  meshopt_encodeIndexVersion(1);
  const VertexOrder order = reorder(mesh);
  const std::size_t n = mesh.vertex_count;
  MeshoptPrimitive out;

  // POSITION: uint16 x, y, z and 2 bytes of padding (vertex elements are 4-byte aligned).
  std::array<float, 3> low{}, high{};
  low.fill(std::numeric_limits<float>::infinity());
  high.fill(-std::numeric_limits<float>::infinity());
  for (std::size_t v = 0; v < n; ++v) {
    for (std::size_t k = 0; k < 3; ++k) {
      low[k] = std::min(low[k], mesh.positions[3 * v + k]);
      high[k] = std::max(high[k], mesh.positions[3 * v + k]);
    }
  }
  double extent = 0;
  for (std::size_t k = 0; k < 3; ++k) extent = std::max(extent, static_cast<double>(high[k]) - low[k]);
  out.scale = extent > 0 ? extent / position_steps : 1.0;
  for (std::size_t k = 0; k < 3; ++k) out.translation[k] = low[k];
  MeshoptStream& position = out.streams.emplace_back();
  position.attribute = "POSITION";
  position.component_type = ComponentType::unsigned_short;
  position.components = 3;
  position.byte_stride = 8;
  position.min.assign(3, std::numeric_limits<double>::infinity());
  position.max.assign(3, -std::numeric_limits<double>::infinity());
  const auto grid = [&](std::uint32_t v, std::size_t k) {
    const double q = std::round((mesh.positions[3 * v + k] - out.translation[k]) / out.scale);
    return static_cast<std::uint16_t>(std::clamp(q, 0.0, position_steps));
  };
  for (std::size_t v = 0; v < n; ++v) {
    for (std::size_t k = 0; k < 3; ++k) {
      position.min[k] = std::min(position.min[k], static_cast<double>(grid(static_cast<std::uint32_t>(v), k)));
      position.max[k] = std::max(position.max[k], static_cast<double>(grid(static_cast<std::uint32_t>(v), k)));
    }
  }
  position.encoded = encode_vertices(pack<std::uint16_t>(order, 3, 8, grid), n, 8);

  // NORMAL: normalised int8 x, y, z and a byte of padding, through the octahedral filter.
  out.streams.push_back(octahedral_stream("NORMAL", order, mesh.normals, 3));

  if (mesh.color_channels > 0) {  // COLOR_0: normalised uint16, RGB padded to 8 bytes
    const auto channels = static_cast<std::size_t>(mesh.color_channels);
    MeshoptStream& color = out.streams.emplace_back();
    color.attribute = "COLOR_0";
    color.component_type = ComponentType::unsigned_short;
    color.components = mesh.color_channels;
    color.normalized = true;
    color.byte_stride = 8;
    color.encoded =
        encode_vertices(pack<std::uint16_t>(order, channels, 8,
                                            [&](std::uint32_t v, std::size_t k) {
                                              return quantize_unit<std::uint16_t>(mesh.colors[channels * v + k], 65535);
                                            }),
                        n, 8);
  }

  if (!mesh.texcoords.empty()) {
    // TEXCOORD_0: normalised uint16 where every coordinate is in [0, 1] (an
    // atlas: a step of 1/65535 is 1/16 texel at 4096 texels), float32 otherwise.
    const bool unit =
        std::all_of(mesh.texcoords.begin(), mesh.texcoords.end(), [](float c) { return c >= 0.0F && c <= 1.0F; });
    MeshoptStream& uv = out.streams.emplace_back();
    uv.attribute = "TEXCOORD_0";
    uv.components = 2;
    if (unit) {
      uv.component_type = ComponentType::unsigned_short;
      uv.normalized = true;
      uv.byte_stride = 4;
      uv.encoded =
          encode_vertices(pack<std::uint16_t>(order, 2, 4,
                                              [&](std::uint32_t v, std::size_t k) {
                                                return quantize_unit<std::uint16_t>(mesh.texcoords[2 * v + k], 65535);
                                              }),
                          n, 4);
    } else {
      uv.byte_stride = 8;
      uv.encoded = encode_vertices(
          pack<float>(order, 2, 8, [&](std::uint32_t v, std::size_t k) { return mesh.texcoords[2 * v + k]; }), n, 8);
    }
  }

  if (!mesh.tangents.empty()) {  // TANGENT: the same, w (+-1) kept
    out.streams.push_back(octahedral_stream("TANGENT", order, mesh.tangents, 4));
  }

  for (const NamedScalars& scalar : mesh.scalars) {  // float32, as written uncompressed
    MeshoptStream& stream = out.streams.emplace_back();
    stream.attribute = scalar.name;
    stream.byte_stride = 4;
    stream.encoded =
        encode_vertices(pack<float>(order, 1, 4, [&](std::uint32_t v, std::size_t) { return scalar.values[v]; }), n, 4);
  }

  MeshoptStream& indices = out.streams.emplace_back();
  indices.count = order.indices.size();
  const bool narrow = n <= max_vertices_for_uint16;
  indices.component_type = narrow ? ComponentType::unsigned_short : ComponentType::unsigned_int;
  indices.byte_stride = narrow ? 2 : 4;
  indices.encoded.resize(meshopt_encodeIndexBufferBound(order.indices.size(), n));
  indices.encoded.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(indices.encoded.data()),
                                                   indices.encoded.size(), order.indices.data(), order.indices.size()));
  for (MeshoptStream& stream : out.streams) {
    if (!stream.attribute.empty()) stream.count = n;
  }
  return out;
}

}  // namespace geodual::io::detail::gltf
