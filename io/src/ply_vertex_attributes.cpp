#include "ply_vertex_attributes.hpp"

#include "file_error.hpp"
#include "str_cat.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace geodual::io::detail {
namespace {

ValueType value_type_of(PlyScalar type) {
  switch (type) {
    case PlyScalar::int8: return ValueType::int8;
    case PlyScalar::uint8: return ValueType::uint8;
    case PlyScalar::int16: return ValueType::int16;
    case PlyScalar::uint16: return ValueType::uint16;
    case PlyScalar::int32: return ValueType::int32;
    case PlyScalar::uint32: return ValueType::uint32;
    case PlyScalar::float32: return ValueType::float32;
    case PlyScalar::float64: break;
  }
  return ValueType::float64;
}

/// The scalar properties named, all of one type, or nothing.
template <std::size_t N>
std::optional<std::array<std::size_t, N>> find_group(const PlyElement& vertex,
                                                     const std::array<std::string_view, N>& names) {
  std::array<std::size_t, N> found{};
  for (std::size_t i = 0; i < N; ++i) {
    const auto property = vertex.find_property(names[i]);
    if (!property || vertex.properties[*property].is_list()) return std::nullopt;
    found[i] = *property;
    if (vertex.properties[found[i]].type != vertex.properties[found[0]].type) return std::nullopt;
  }
  return found;
}

/// Integer colours in [0, max]: their scale to [0, 1]; floats 1; other types none.
std::optional<double> color_scale(PlyScalar type) {
  switch (type) {
    case PlyScalar::uint8: return 1.0 / 255.0;
    case PlyScalar::uint16: return 1.0 / 65535.0;
    case PlyScalar::float32:
    case PlyScalar::float64: return 1.0;
    default: return std::nullopt;
  }
}

}  // namespace

PlyVertexAttributes::PlyVertexAttributes(const PlyElement& vertex, const std::array<std::size_t, 3>& xyz)
    : column_of_(vertex.properties.size(), -1) {
  const auto rows = static_cast<Eigen::Index>(vertex.count);
  const auto taken = [&](std::size_t p) { return p == xyz[0] || p == xyz[1] || p == xyz[2]; };
  std::vector<std::uint8_t> assigned(vertex.properties.size(), 0);

  if (const auto rgb = find_group<3>(vertex, {"red", "green", "blue"})) {
    const PlyScalar type = vertex.properties[(*rgb)[0]].type;
    if (const auto scale = color_scale(type)) {
      std::vector<std::size_t> channels(rgb->begin(), rgb->end());
      if (const auto alpha = vertex.find_property("alpha");
          alpha && !vertex.properties[*alpha].is_list() && vertex.properties[*alpha].type == type) {
        channels.push_back(*alpha);
      }
      attributes_.colors.resize(rows, static_cast<Eigen::Index>(channels.size()));
      attributes_.color_type = value_type_of(type);
      for (std::size_t k = 0; k < channels.size(); ++k) {
        add_column(channels[k],
                   {.to_float = attributes_.colors.data() + k, .stride = channels.size(), .scale = *scale});
        assigned[channels[k]] = 1;
      }
    }
  }
  if (const auto normal = find_group<3>(vertex, {"nx", "ny", "nz"})) {
    const PlyScalar type = vertex.properties[(*normal)[0]].type;
    if (type == PlyScalar::float32 || type == PlyScalar::float64) {
      attributes_.normals.resize(rows, 3);
      attributes_.normal_type = value_type_of(type);
      for (std::size_t k = 0; k < 3; ++k) {
        add_column((*normal)[k], {.to_double = attributes_.normals.data() + k, .stride = 3});
        assigned[(*normal)[k]] = 1;
      }
    }
  }
  // Every other scalar property, in the file's order. Reserved first: the
  // columns point into the vectors.
  std::size_t scalar_count = 0;
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    scalar_count += !taken(p) && assigned[p] == 0 && !vertex.properties[p].is_list();
  }
  attributes_.scalars.reserve(scalar_count);
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    if (taken(p) || assigned[p] != 0 || vertex.properties[p].is_list()) continue;
    attributes_.scalars.push_back({vertex.properties[p].name, value_type_of(vertex.properties[p].type),
                                   std::vector<double>(static_cast<std::size_t>(vertex.count))});
    add_column(p, {.to_double = attributes_.scalars.back().values.data()});
  }
}

VertexAttributes PlyVertexAttributes::take(std::vector<std::string>& notes) {
  VertexAttributes attributes = std::move(attributes_);
  ColorMatrix& colors = attributes.colors;
  const bool float_colors = attributes.color_type == ValueType::float32 || attributes.color_type == ValueType::float64;
  if (float_colors && colors.size() > 0 &&
      (!colors.allFinite() || colors.minCoeff() < 0.0f || colors.maxCoeff() > 1.0f)) {
    // Not colours in [0, 1]: carried as the plain scalars they are.
    constexpr std::array<std::string_view, 4> names = {"red", "green", "blue", "alpha"};
    std::vector<VertexScalar> channels;
    for (Eigen::Index k = 0; k < colors.cols(); ++k) {
      VertexScalar channel{std::string(names[static_cast<std::size_t>(k)]), attributes.color_type, {}};
      channel.values.reserve(static_cast<std::size_t>(colors.rows()));
      for (Eigen::Index v = 0; v < colors.rows(); ++v) channel.values.push_back(colors(v, k));
      channels.push_back(std::move(channel));
    }
    attributes.scalars.insert(attributes.scalars.begin(), std::make_move_iterator(channels.begin()),
                              std::make_move_iterator(channels.end()));
    colors.resize(0, 0);
    notes.push_back("vertex properties red, green, blue hold values outside [0, 1]: kept as scalars, not colours");
  }
  if (attributes.normals.size() > 0 && !attributes.normals.allFinite()) {
    attributes.normals.resize(0, 3);
    notes.push_back("vertex normals nx, ny, nz ignored: not all finite");
  }
  std::erase_if(attributes.scalars, [&](const VertexScalar& scalar) {
    const bool finite =
        std::all_of(scalar.values.begin(), scalar.values.end(), [](double x) { return std::isfinite(x); });
    if (!finite) notes.push_back(str_cat("vertex property '", excerpt(scalar.name), "' ignored: not all finite"));
    return !finite;
  });
  return attributes;
}

}  // namespace geodual::io::detail
