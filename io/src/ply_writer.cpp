// Binary little-endian PLY writer: float64 x y z, the vertex attributes as
// properties of the types they carry, `list uchar int vertex_indices`. The body is encoded in blocks
// into one reusable buffer, whatever the host's byte order.

#include "geodual/io/write_mesh.hpp"

#include "byte_order.hpp"
#include "file_error.hpp"
#include "mesh_checks.hpp"

#include "geodual/io/atomic_file.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace geodual::io {
namespace {

namespace fs = std::filesystem;
using detail::throw_file_error;

std::size_t size_of(ValueType type) {
  switch (type) {
    case ValueType::int8:
    case ValueType::uint8: return 1;
    case ValueType::int16:
    case ValueType::uint16: return 2;
    case ValueType::int32:
    case ValueType::uint32:
    case ValueType::float32: return 4;
    case ValueType::float64: break;
  }
  return 8;
}

/// One vertex property of the file: its name, type, and where its values come from.
struct PlyColumn {
  std::string name;
  ValueType type = ValueType::float64;
  const float* floats = nullptr;  ///< colours, scaled by `scale` to the type's range
  const double* doubles = nullptr;
  std::size_t stride = 1;
  double scale = 1;
};

/// The attributes as PLY vertex properties: nx ny nz, red green blue [alpha], then the scalars.
std::vector<PlyColumn> ply_columns(const VertexAttributes& attributes) {
  std::vector<PlyColumn> columns;
  if (attributes.normals.rows() > 0) {
    const char* names[] = {"nx", "ny", "nz"};
    for (std::size_t k = 0; k < 3; ++k) {
      columns.push_back(
          {.name = names[k], .type = attributes.normal_type, .doubles = attributes.normals.data() + k, .stride = 3});
    }
  }
  if (attributes.colors.rows() > 0) {
    const char* names[] = {"red", "green", "blue", "alpha"};
    const auto channels = static_cast<std::size_t>(attributes.colors.cols());
    const double scale = attributes.color_type == ValueType::uint8    ? 255.0
                         : attributes.color_type == ValueType::uint16 ? 65535.0
                                                                      : 1.0;
    const ValueType type =
        scale == 1.0 && attributes.color_type != ValueType::float64 ? ValueType::float32 : attributes.color_type;
    for (std::size_t k = 0; k < channels; ++k) {
      columns.push_back(
          {.name = names[k], .type = type, .floats = attributes.colors.data() + k, .stride = channels, .scale = scale});
    }
  }
  for (const VertexScalar& scalar : attributes.scalars) {
    columns.push_back({.name = scalar.name, .type = scalar.type, .doubles = scalar.values.data()});
  }
  return columns;
}

/// Names must be one PLY word, unique, and not one of the coordinates; sizes must match.
std::string column_problem(const std::vector<PlyColumn>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const std::string& name = columns[i].name;
    const bool is_word =
        !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return c > ' ' && c <= '~'; });
    if (!is_word) {
      return detail::str_cat("vertex property name '", detail::excerpt(name),
                             "' must be one word of printable ASCII characters");
    }
    if (name == "x" || name == "y" || name == "z") {
      return detail::str_cat("vertex property name '", name, "' is taken by the coordinates");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (columns[j].name == name) return detail::str_cat("vertex property '", name, "' is given twice");
    }
  }
  return {};
}

void check_columns(const fs::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes,
                   const std::vector<PlyColumn>& columns) {
  if (const std::string problem = attribute_size_problem(attributes, mesh.num_vertices()); !problem.empty()) {
    throw_file_error(path, "vertex attributes do not fit the mesh: ", problem);
  }
  if (const std::string problem = column_problem(columns); !problem.empty()) throw_file_error(path, problem);
  // An integer type holds no NaN or infinity.
  for (const VertexScalar& scalar : attributes.scalars) {
    if (scalar.type == ValueType::float32 || scalar.type == ValueType::float64) continue;
    if (!std::all_of(scalar.values.begin(), scalar.values.end(), [](double x) { return std::isfinite(x); })) {
      throw_file_error(path, "vertex property '", detail::excerpt(scalar.name), "' of type ",
                       ply_type_name(scalar.type), " has a value that is not finite");
    }
  }
}

std::string ply_header(const TriangleMesh& mesh, const std::vector<PlyColumn>& columns,
                       const std::string& texture_file) {
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by geodual\n";
  if (!texture_file.empty()) header += detail::str_cat("comment TextureFile ", texture_file, "\n");
  header += detail::str_cat("element vertex ", mesh.vertices.rows(),
                            "\nproperty double x\nproperty double y\nproperty double z\n");
  for (const PlyColumn& column : columns) {
    header += detail::str_cat("property ", ply_type_name(column.type), " ", column.name, "\n");
  }
  header +=
      detail::str_cat("element face ", mesh.faces.rows(), "\nproperty list uchar int vertex_indices\nend_header\n");
  return header;
}

/// Stores `value` as `type` (little-endian); integer types get the nearest value they hold.
std::byte* store_value(std::byte* at, ValueType type, double value) {
  constexpr auto le = std::endian::little;
  const auto integer = [&](auto tag) {
    using T = typename decltype(tag)::type;
    const double clamped = std::clamp(std::round(value), static_cast<double>(std::numeric_limits<T>::lowest()),
                                      static_cast<double>(std::numeric_limits<T>::max()));
    detail::store<le>(at, static_cast<T>(clamped));
    return at + sizeof(T);
  };
  switch (type) {
    case ValueType::int8: return integer(std::type_identity<std::int8_t>{});
    case ValueType::uint8: return integer(std::type_identity<std::uint8_t>{});
    case ValueType::int16: return integer(std::type_identity<std::int16_t>{});
    case ValueType::uint16: return integer(std::type_identity<std::uint16_t>{});
    case ValueType::int32: return integer(std::type_identity<std::int32_t>{});
    case ValueType::uint32: return integer(std::type_identity<std::uint32_t>{});
    case ValueType::float32: detail::store<le>(at, static_cast<float>(value)); return at + sizeof(float);
    case ValueType::float64: break;
  }
  detail::store<le>(at, value);
  return at + sizeof(double);
}

/// Encodes records block by block into one buffer and hands full blocks to the stream.
class BlockWriter {
 public:
  BlockWriter(std::ostream& out, std::size_t record_size)
      : out_(out), record_size_(record_size), buffer_(record_size * records_per_block) {}

  /// Room for the next record.
  std::byte* next() {
    if (used_ + record_size_ > buffer_.size()) {
      flush();
    }
    std::byte* record = buffer_.data() + used_;
    used_ += record_size_;
    return record;
  }

  void flush() {
    out_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(used_));
    used_ = 0;
  }

 private:
  static constexpr std::size_t records_per_block = 8192;
  std::ostream& out_;
  std::size_t record_size_;
  std::vector<std::byte> buffer_;
  std::size_t used_ = 0;
};

void write_body(std::ostream& out, const TriangleMesh& mesh, const std::vector<PlyColumn>& columns) {
  constexpr auto le = std::endian::little;
  std::size_t vertex_record = 3 * sizeof(double);
  for (const PlyColumn& column : columns) {
    vertex_record += size_of(column.type);
  }
  BlockWriter vertices(out, vertex_record);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    std::byte* at = vertices.next();
    for (Eigen::Index axis = 0; axis < 3; ++axis, at += sizeof(double)) {
      detail::store<le>(at, mesh.vertices(v, axis));
    }
    const auto row = static_cast<std::size_t>(v);
    for (const PlyColumn& column : columns) {
      const double value = column.floats != nullptr ? column.scale * column.floats[row * column.stride]
                                                    : column.doubles[row * column.stride];
      at = store_value(at, column.type, value);
    }
  }
  vertices.flush();

  constexpr std::size_t face_record = 1 + 3 * sizeof(std::int32_t);
  BlockWriter faces(out, face_record);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    std::byte* at = faces.next();
    at[0] = std::byte{3};
    for (Eigen::Index corner = 0; corner < 3; ++corner) {
      detail::store<le>(at + 1 + corner * 4, static_cast<std::int32_t>(mesh.faces(f, corner)));
    }
  }
  faces.flush();
}

}  // namespace

std::string ply_attribute_problem(const VertexAttributes& attributes) {
  return column_problem(ply_columns(attributes));
}

void write_ply(const fs::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes,
               const std::string& texture_file) {
  detail::check_face_indices(path, mesh);
  if (texture_file.find_first_of("\r\n") != std::string::npos) {
    throw_file_error(path, "the texture file name may not hold a line break");
  }
  const std::vector<PlyColumn> columns = ply_columns(attributes);
  check_columns(path, mesh, attributes, columns);
  const std::string header = ply_header(mesh, columns, texture_file);
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    write_body(out, mesh, columns);
  });
}

}  // namespace geodual::io
