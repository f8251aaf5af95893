#pragma once
// Internal: the vertex properties of a PLY file besides x, y, z, read into
// VertexAttributes -- red/green/blue[/alpha] as colours, nx/ny/nz as normals,
// every other scalar property under its own name and type. Only ply_reader.cpp
// includes this.

#include "ply_header.hpp"

#include "geodual/mesh/vertex_attributes.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace geodual::io::detail {

/// Where each attribute property of the vertex element goes.
class PlyVertexAttributes {
 public:
  /// Sorts the scalar properties of `vertex` other than those at `xyz` into
  /// colours, normals and named scalars, and allocates them for its records.
  PlyVertexAttributes(const PlyElement& vertex, const std::array<std::size_t, 3>& xyz);

  /// Whether `property` (an index into the vertex element's properties) is read.
  bool reads(std::size_t property) const { return column_of_[property] >= 0; }

  /// Stores `value`, the file's value of `property` in `record`.
  void put(std::size_t property, std::uint64_t record, double value) {
    const Column& column = columns_[static_cast<std::size_t>(column_of_[property])];
    const auto at = static_cast<std::size_t>(record) * column.stride;
    if (column.to_float != nullptr) {
      column.to_float[at] = static_cast<float>(value * column.scale);
    } else {
      column.to_double[at] = value;
    }
  }

  /// The attributes read. Colours stored as floats outside [0, 1] become
  /// scalars under their own names, and scalars or normals with a value that
  /// is not finite are dropped; `notes` says so.
  VertexAttributes take(std::vector<std::string>& notes);

 private:
  struct Column {
    float* to_float = nullptr;
    double* to_double = nullptr;
    std::size_t stride = 1;
    double scale = 1;  ///< integer colours to [0, 1]
  };

  void add_column(std::size_t property, Column column) {
    column_of_[property] = static_cast<int>(columns_.size());
    columns_.push_back(column);
  }

  VertexAttributes attributes_;
  std::vector<int> column_of_;  ///< per property of the vertex element: its column, or -1
  std::vector<Column> columns_;
};

}  // namespace geodual::io::detail
