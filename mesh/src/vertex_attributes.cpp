#include "geodual/mesh/vertex_attributes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace geodual {
namespace {

// The corners of `point` and their weights: one corner of weight 1 at a vertex.
struct Corners {
  Index vertex[3] = {0, 0, 0};
  double weight[3] = {1, 0, 0};
  int count = 1;
};

Corners corners_of(const TriangleMesh& mesh, const SurfacePoint& point) {
  Corners corners;
  if (point.kind == SurfacePoint::Kind::vertex) {
    corners.vertex[0] = point.element;
    return corners;
  }
  corners.count = 3;
  for (int c = 0; c < 3; ++c) {
    corners.vertex[c] = mesh.faces(point.element, c);
    corners.weight[c] = point.barycentric[c];
  }
  return corners;
}

struct IntegerRange {
  double lowest = 0;
  double highest = 0;
};

IntegerRange integer_range(ValueType type) {
  switch (type) {
    case ValueType::int8: return {-128.0, 127.0};
    case ValueType::uint8: return {0.0, 255.0};
    case ValueType::int16: return {-32768.0, 32767.0};
    case ValueType::uint16: return {0.0, 65535.0};
    case ValueType::int32: return {-2147483648.0, 2147483647.0};
    case ValueType::uint32: return {0.0, 4294967295.0};
    case ValueType::float32:
    case ValueType::float64: break;
  }
  return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
}

bool is_integer(ValueType type) { return type != ValueType::float32 && type != ValueType::float64; }

}  // namespace

std::string_view ply_type_name(ValueType type) {
  switch (type) {
    case ValueType::int8: return "char";
    case ValueType::uint8: return "uchar";
    case ValueType::int16: return "short";
    case ValueType::uint16: return "ushort";
    case ValueType::int32: return "int";
    case ValueType::uint32: return "uint";
    case ValueType::float32: return "float";
    case ValueType::float64: return "double";
  }
  return "?";
}

VertexAttributes interpolate_attributes(const TriangleMesh& mesh, const VertexAttributes& attributes,
                                        std::span<const SurfacePoint> points) {
  const auto n = static_cast<Eigen::Index>(points.size());
  VertexAttributes out;
  out.color_type = attributes.color_type;
  out.normal_type = attributes.normal_type;
  if (attributes.colors.rows() > 0) out.colors.setZero(n, attributes.colors.cols());
  if (attributes.normals.rows() > 0) out.normals.setZero(n, 3);
  out.scalars.reserve(attributes.scalars.size());
  for (const VertexScalar& scalar : attributes.scalars) {
    out.scalars.push_back({scalar.name, scalar.type, std::vector<double>(points.size(), 0.0)});
  }

  for (Eigen::Index i = 0; i < n; ++i) {
    const Corners corners = corners_of(mesh, points[static_cast<std::size_t>(i)]);
    for (int c = 0; c < corners.count; ++c) {
      const Index v = corners.vertex[c];
      const double w = corners.weight[c];
      if (out.colors.rows() > 0) out.colors.row(i) += static_cast<float>(w) * attributes.colors.row(v);
      if (out.normals.rows() > 0) out.normals.row(i) += w * attributes.normals.row(v);
      for (std::size_t s = 0; s < out.scalars.size(); ++s) {
        out.scalars[s].values[static_cast<std::size_t>(i)] +=
            w * attributes.scalars[s].values[static_cast<std::size_t>(v)];
      }
    }
    if (out.colors.rows() > 0) out.colors.row(i) = out.colors.row(i).cwiseMax(0.0f).cwiseMin(1.0f);
    if (out.normals.rows() > 0) {
      const double length = out.normals.row(i).norm();
      if (length > 0) out.normals.row(i) /= length;
    }
  }
  for (VertexScalar& scalar : out.scalars) {
    if (!is_integer(scalar.type)) continue;
    const IntegerRange range = integer_range(scalar.type);
    for (double& value : scalar.values) value = std::clamp(std::round(value), range.lowest, range.highest);
  }
  return out;
}

std::string attribute_size_problem(const VertexAttributes& attributes, Index vertex_count) {
  const auto rows_for = [&](std::string_view what, Eigen::Index rows) {
    return std::string(what) + ": " + std::to_string(rows) + " rows for " + std::to_string(vertex_count) + " vertices";
  };
  if (attributes.colors.rows() > 0 && attributes.colors.rows() != vertex_count) {
    return rows_for("colors", attributes.colors.rows());
  }
  if (attributes.colors.rows() > 0 && attributes.colors.cols() != 3 && attributes.colors.cols() != 4) {
    return "colors: " + std::to_string(attributes.colors.cols()) + " columns (3 or 4 expected)";
  }
  if (attributes.normals.rows() > 0 && attributes.normals.rows() != vertex_count) {
    return rows_for("normals", attributes.normals.rows());
  }
  for (const VertexScalar& scalar : attributes.scalars) {
    if (scalar.values.size() != static_cast<std::size_t>(vertex_count)) {
      return rows_for("scalar '" + scalar.name + "'", static_cast<Eigen::Index>(scalar.values.size()));
    }
  }
  return {};
}

// IEC 61966-2-1: linear below the knee, a 2.4 power above it.
// Evaluated in double, so that 0 and 1 map to exactly 0 and 1.
float srgb_from_linear(float linear) {
  const double c = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  return static_cast<float>(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

float linear_from_srgb(float encoded) {
  const double c = std::clamp(static_cast<double>(encoded), 0.0, 1.0);
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

}  // namespace geodual
