// Binary little-endian PLY writer: float64 x y z, optional per-vertex scalar
// properties, `list uchar int vertex_indices`. The body is encoded in blocks
// into one reusable buffer, whatever the host's byte order.

#include "geodual/io/write_mesh.hpp"

#include "byte_order.hpp"
#include "file_error.hpp"
#include "mesh_checks.hpp"

#include "geodual/io/atomic_file.hpp"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace geodual::io {
namespace {

namespace fs = std::filesystem;
using detail::throw_file_error;

template <class T>
constexpr std::string_view ply_type_name() {
  if constexpr (std::is_same_v<T, double>) {
    return "double";
  } else if constexpr (std::is_same_v<T, float>) {
    return "float";
  } else {
    static_assert(std::is_same_v<T, std::int32_t>);
    return "int";
  }
}

std::size_t value_size(const VertexProperty& property) {
  return std::visit([](const auto& values) { return sizeof(values[0]); }, property.values);
}

std::size_t value_count(const VertexProperty& property) {
  return std::visit([](const auto& values) { return values.size(); }, property.values);
}

/// Names must be one PLY word, unique, and not one of the coordinates.
void check_properties(const fs::path& path, const TriangleMesh& mesh, const std::vector<VertexProperty>& properties) {
  for (std::size_t i = 0; i < properties.size(); ++i) {
    const VertexProperty& property = properties[i];
    const bool is_word = !property.name.empty() && std::all_of(property.name.begin(), property.name.end(),
                                                               [](char c) { return c > ' ' && c <= '~'; });
    if (!is_word) {
      throw_file_error(path, "vertex property name '", detail::excerpt(property.name),
                       "' must be one word of printable ASCII characters");
    }
    if (property.name == "x" || property.name == "y" || property.name == "z") {
      throw_file_error(path, "vertex property name '", property.name, "' is taken by the coordinates");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (properties[j].name == property.name) {
        throw_file_error(path, "vertex property '", property.name, "' is given twice");
      }
    }
    if (value_count(property) != static_cast<std::size_t>(mesh.vertices.rows())) {
      throw_file_error(path, "vertex property '", property.name, "' has ", value_count(property), " values for ",
                       mesh.vertices.rows(), " vertices");
    }
  }
}

std::string ply_header(const TriangleMesh& mesh, const std::vector<VertexProperty>& properties) {
  std::string header =
      detail::str_cat("ply\nformat binary_little_endian 1.0\ncomment written by geodual\n", "element vertex ",
                      mesh.vertices.rows(), "\nproperty double x\nproperty double y\nproperty double z\n");
  for (const VertexProperty& property : properties) {
    const std::string_view type = std::visit(
        [](const auto& values) { return ply_type_name<std::decay_t<decltype(values[0])>>(); }, property.values);
    header += detail::str_cat("property ", type, " ", property.name, "\n");
  }
  header +=
      detail::str_cat("element face ", mesh.faces.rows(), "\nproperty list uchar int vertex_indices\nend_header\n");
  return header;
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

void write_body(std::ostream& out, const TriangleMesh& mesh, const std::vector<VertexProperty>& properties) {
  constexpr auto le = std::endian::little;
  std::size_t vertex_record = 3 * sizeof(double);
  for (const VertexProperty& property : properties) {
    vertex_record += value_size(property);
  }
  BlockWriter vertices(out, vertex_record);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    std::byte* at = vertices.next();
    for (Eigen::Index axis = 0; axis < 3; ++axis, at += sizeof(double)) {
      detail::store<le>(at, mesh.vertices(v, axis));
    }
    for (const VertexProperty& property : properties) {
      std::visit(
          [&at, v](const auto& values) {
            detail::store<le>(at, values[static_cast<std::size_t>(v)]);
            at += sizeof(values[0]);
          },
          property.values);
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

void write_ply(const fs::path& path, const TriangleMesh& mesh, const std::vector<VertexProperty>& vertex_properties) {
  detail::check_face_indices(path, mesh);
  check_properties(path, mesh, vertex_properties);
  const std::string header = ply_header(mesh, vertex_properties);
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    write_body(out, mesh, vertex_properties);
  });
}

}  // namespace geodual::io
