// PLY reader: ascii, binary_little_endian and binary_big_endian bodies.
//
// The whole file is in memory. The header says where every element lives;
// the vertex and face elements are decoded into the mesh, every other element
// and property is stepped over. Binary decoding is instantiated per scalar
// type and byte order, so the hot loops are plain loads without per-value
// dispatch; the common layouts (fixed-size vertex records, face records that
// hold nothing but the index list) take a dedicated fast path.

#include "format_readers.hpp"

#include "byte_order.hpp"
#include "file_error.hpp"
#include "parse_number.hpp"
#include "ply_header.hpp"
#include "ply_vertex_attributes.hpp"
#include "polygon_triangulation.hpp"
#include "saturating.hpp"
#include "text_lines.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t max_index_count = static_cast<std::uint64_t>(std::numeric_limits<Index>::max());

/// Where the mesh lives among the header's elements.
struct PlyMeshLayout {
  const PlyElement* vertex = nullptr;
  std::array<std::size_t, 3> xyz{};  ///< property indices of x, y, z in *vertex
  const PlyElement* face = nullptr;
  std::size_t corner_list = 0;  ///< property index of vertex_indices in *face
};

PlyMeshLayout find_mesh_layout(const PlyHeader& header, const fs::path& file) {
  PlyMeshLayout layout;
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") {
      layout.vertex = &element;
      constexpr std::array<std::string_view, 3> axes = {"x", "y", "z"};
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const auto property = element.find_property(axes[axis]);
        if (!property) {
          throw_line_error(file, element.line, "element 'vertex' has no property '", axes[axis], "'");
        }
        if (element.properties[*property].is_list()) {
          throw_line_error(file, element.line, "vertex property '", axes[axis],
                           "' is a list; coordinates must be scalars");
        }
        layout.xyz[axis] = *property;
      }
      if (element.count > max_index_count) {
        throw_line_error(file, element.line, "the header declares ", element.count,
                         " vertices, more than geodual's 32-bit indices can address");
      }
    } else if (element.name == "face") {
      layout.face = &element;
      auto list = element.find_property("vertex_indices");
      if (!list) {
        list = element.find_property("vertex_index");
      }
      if (!list) {
        throw_line_error(file, element.line, "element 'face' has no property 'vertex_indices' (or 'vertex_index')");
      }
      const PlyProperty& property = element.properties[*list];
      if (!property.is_list()) {
        throw_line_error(file, element.line, "face property '", property.name,
                         "' is not a list; expected 'property list <count type> <index type> ", property.name, "'");
      }
      if (!is_integer(property.type)) {
        throw_line_error(file, element.line, "face property '", property.name, "' holds items of type ",
                         name_of(property.type), "; vertex indices must be of an integer type");
      }
      if (element.count > max_index_count) {
        throw_line_error(file, element.line, "the header declares ", element.count,
                         " faces, more than geodual's 32-bit indices can address");
      }
      layout.corner_list = *list;
    }
  }
  return layout;
}

/// A lower bound on the bytes one record of `element` takes: per value its
/// binary size, or 2 characters of text (a digit and a separator). Index lists
/// need at least 3 items.
std::uint64_t minimum_record_bytes(const PlyElement& element, const PlyMeshLayout& layout, bool ascii) {
  std::uint64_t bytes = 0;
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    if (!property.is_list()) {
      bytes += ascii ? 2 : size_of(property.type);
      continue;
    }
    bytes += ascii ? 2 : size_of(*property.count_type);
    if (&element == layout.face && p == layout.corner_list) {
      bytes += 3 * (ascii ? 2 : size_of(property.type));
    }
  }
  return bytes;
}

/// The first element whose records the file cannot hold.
struct Shortfall {
  const PlyElement* element = nullptr;
  std::uint64_t needed = 0;     ///< bytes up to and including that element, at least
  std::uint64_t available = 0;  ///< bytes after the header
};

/// Whether the file can hold the records the header declares, judged by the
/// least bytes each record can take. Checked before anything is allocated for
/// them: a 100-byte file may claim 10^8 vertices.
std::optional<Shortfall> find_shortfall(const PlyHeader& header, const PlyMeshLayout& layout, std::size_t file_size) {
  const bool ascii = header.encoding == PlyEncoding::ascii;
  const std::uint64_t available = file_size - header.body_offset;
  // The last line of an ascii body may lack its line end.
  const std::uint64_t allowance = ascii ? 1 : 0;
  std::uint64_t needed = 0;
  for (const PlyElement& element : header.elements) {
    needed = saturating_add(needed, saturating_mul(element.count, minimum_record_bytes(element, layout, ascii)));
    if (needed > available + allowance) {
      return Shortfall{.element = &element, .needed = needed, .available = available};
    }
  }
  return std::nullopt;
}

[[noreturn]] void throw_shortfall(const Shortfall& shortfall, std::size_t file_size, const fs::path& file) {
  throw_file_error(file, "the header declares ", shortfall.element->count, " '", excerpt(shortfall.element->name),
                   "' records, which need at least ", shortfall.needed,
                   " bytes after the header, but the file has only ", shortfall.available, " (file is ", file_size,
                   " bytes)");
}

/// "float32", "int16", ... as ReadInfo::encoding spells coordinate types.
std::string_view sized_name_of(PlyScalar type) {
  constexpr std::array<std::string_view, 8> names = {"int8",  "uint8",  "int16",   "uint16",
                                                     "int32", "uint32", "float32", "float64"};
  return names[static_cast<std::size_t>(type)];
}

/// Checks one corner's vertex index against the vertex count the header
/// declares. The checks inline into the hot loops; the throwing is kept apart.
class CornerCheck {
 public:
  CornerCheck(const PlyElement& face, std::uint64_t vertex_count, const fs::path& file)
      : face_(face), vertex_count_(vertex_count), file_(file) {}

  Index operator()(std::int64_t value, std::uint64_t record) const {
    if (value < 0 || static_cast<std::uint64_t>(value) >= vertex_count_) [[unlikely]] {
      index_out_of_range(value, record);
    }
    return static_cast<Index>(value);
  }

  void corner_count(std::int64_t count, std::uint64_t record) const {
    if (count < 3) [[unlikely]] {
      too_few_corners(count, record);
    }
  }

 private:
  [[noreturn, gnu::cold, gnu::noinline]] void index_out_of_range(std::int64_t value, std::uint64_t record) const {
    throw_file_error(file_, "face ", record, " of ", face_.count, ": vertex index ", value,
                     " is out of range (the file has ", vertex_count_, " vertices)");
  }

  [[noreturn, gnu::cold, gnu::noinline]] void too_few_corners(std::int64_t count, std::uint64_t record) const {
    throw_file_error(file_, "face ", record, " of ", face_.count, " has ", count, " corners; a face needs at least 3");
  }

  const PlyElement& face_;
  std::uint64_t vertex_count_;
  const fs::path& file_;
};

// ---------------------------------------------------------------------------
// Binary bodies

template <std::endian Order>
class BinaryPlyBody {
 public:
  BinaryPlyBody(std::span<const std::byte> data, std::size_t offset, const fs::path& file)
      : data_(data), at_(offset), file_(file) {}

  std::size_t remaining() const { return data_.size() - at_; }

  void skip(const PlyElement& element) {
    if (const auto record_size = element.fixed_record_size()) {
      require_records(element, *record_size);
      at_ += element.count * *record_size;
      return;
    }
    for (std::uint64_t record = 0; record < element.count; ++record) {
      walk_record(
          element, record, [](std::size_t, const std::byte*) {}, [](std::size_t, std::uint64_t, const std::byte*) {});
    }
  }

  void read_vertices(const PlyElement& element, const std::array<std::size_t, 3>& xyz, VertexMatrix& vertices,
                     PlyVertexAttributes& attributes) {
    const PlyScalar type = element.properties[xyz[0]].type;
    const bool same_type = element.properties[xyz[1]].type == type && element.properties[xyz[2]].type == type;
    const auto record_size = element.fixed_record_size();
    if (record_size) {
      require_records(element, *record_size);
    }
    vertices.resize(static_cast<Eigen::Index>(element.count), 3);
    if (record_size && same_type) {
      std::array<std::size_t, 3> offsets{};
      for (std::size_t axis = 0; axis < 3; ++axis) {
        offsets[axis] = property_offset(element, xyz[axis]);
      }
      visit_ply_scalar(type, [&](auto tag) {
        copy_coordinates<typename decltype(tag)::type>(element.count, *record_size, offsets, vertices);
      });
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        if (!attributes.reads(p)) continue;
        visit_ply_scalar(element.properties[p].type, [&](auto tag) {
          copy_attribute<typename decltype(tag)::type>(element.count, *record_size, p, property_offset(element, p),
                                                       attributes);
        });
      }
      at_ += element.count * *record_size;
      return;
    }
    double* out = vertices.data();
    for (std::uint64_t record = 0; record < element.count; ++record, out += 3) {
      walk_record(
          element, record,
          [&](std::size_t property, const std::byte* value) {
            for (std::size_t axis = 0; axis < 3; ++axis) {
              if (property == xyz[axis]) {
                out[axis] = load_real(element.properties[property].type, value);
              }
            }
            if (attributes.reads(property)) {
              attributes.put(property, record, load_real(element.properties[property].type, value));
            }
          },
          [](std::size_t, std::uint64_t, const std::byte*) {});
    }
  }

  void read_faces(const PlyElement& element, std::size_t corner_list, const CornerCheck& check, FaceBuffer& triangles) {
    const PlyProperty& list = element.properties[corner_list];
    if (element.properties.size() == 1) {
      visit_ply_scalar(*list.count_type, [&](auto count_tag) {
        visit_ply_scalar(list.type, [&](auto item_tag) {
          using Count = typename decltype(count_tag)::type;
          using Item = typename decltype(item_tag)::type;
          if constexpr (std::is_integral_v<Count> && std::is_integral_v<Item>) {
            read_index_lists<Count, Item>(element, check, triangles);
          }
        });
      });
      return;
    }
    const std::size_t item_size = size_of(list.type);
    for (std::uint64_t record = 0; record < element.count; ++record) {
      walk_record(
          element, record, [](std::size_t, const std::byte*) {},
          [&](std::size_t property, std::uint64_t count, const std::byte* items) {
            if (property != corner_list) {
              return;
            }
            check.corner_count(static_cast<std::int64_t>(count), record);
            triangles.add_polygon(count, [&](std::size_t corner) {
              return check(load_integer(list.type, items + corner * item_size), record);
            });
          });
    }
  }

 private:
  [[noreturn, gnu::cold, gnu::noinline]] void truncated(const PlyElement& element, std::uint64_t record) const {
    throw_file_error(file_, "truncated binary data: ", excerpt(element.name), " ", record, " of ", element.count,
                     " ends past the end of the file (file is ", data_.size(), " bytes)");
  }

  /// Throws unless `bytes` more are there, naming `record` as the one cut off.
  void require(std::uint64_t bytes, const PlyElement& element, std::uint64_t record) const {
    if (bytes > remaining()) {
      truncated(element, record);
    }
  }

  /// Throws unless all records of a fixed-size element are there, naming the first one cut off.
  void require_records(const PlyElement& element, std::size_t record_size) const {
    if (saturating_mul<std::uint64_t>(element.count, record_size) > remaining()) {
      truncated(element, remaining() / record_size);
    }
  }

  static std::size_t property_offset(const PlyElement& element, std::size_t property) {
    std::size_t offset = 0;
    for (std::size_t p = 0; p < property; ++p) {
      offset += size_of(element.properties[p].type);
    }
    return offset;
  }

  static double load_real(PlyScalar type, const std::byte* at) {
    return visit_ply_scalar(
        type, [at](auto tag) { return static_cast<double>(load<typename decltype(tag)::type, Order>(at)); });
  }

  /// Loads an integer-typed value (types were checked when the layout was found).
  static std::int64_t load_integer(PlyScalar type, const std::byte* at) {
    return visit_ply_scalar(type, [at](auto tag) -> std::int64_t {
      using T = typename decltype(tag)::type;
      if constexpr (std::is_integral_v<T>) {
        return static_cast<std::int64_t>(load<T, Order>(at));
      } else {
        return -1;
      }
    });
  }

  /// Steps over one record, calling on_scalar(property, value bytes) and
  /// on_list(property, item count, first item bytes).
  template <class OnScalar, class OnList>
  void walk_record(const PlyElement& element, std::uint64_t record, OnScalar&& on_scalar, OnList&& on_list) {
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      const std::size_t value_size = size_of(property.type);
      if (!property.is_list()) {
        require(value_size, element, record);
        on_scalar(p, data_.data() + at_);
        at_ += value_size;
        continue;
      }
      const std::size_t count_size = size_of(*property.count_type);
      require(count_size, element, record);
      const std::int64_t count = load_integer(*property.count_type, data_.data() + at_);
      at_ += count_size;
      if (count < 0) {
        throw_file_error(file_, excerpt(element.name), " ", record, " of ", element.count, ": list '",
                         excerpt(property.name), "' has a negative length ", count);
      }
      const auto items = static_cast<std::uint64_t>(count);
      if (items > remaining() / value_size) {
        truncated(element, record);
      }
      on_list(p, items, data_.data() + at_);
      at_ += items * value_size;
    }
  }

  template <class T>
  void copy_coordinates(std::uint64_t count, std::size_t record_size, const std::array<std::size_t, 3>& offsets,
                        VertexMatrix& vertices) const {
    const std::byte* record = data_.data() + at_;
    double* out = vertices.data();
    for (std::uint64_t i = 0; i < count; ++i, record += record_size, out += 3) {
      out[0] = static_cast<double>(load<T, Order>(record + offsets[0]));
      out[1] = static_cast<double>(load<T, Order>(record + offsets[1]));
      out[2] = static_cast<double>(load<T, Order>(record + offsets[2]));
    }
  }

  template <class T>
  void copy_attribute(std::uint64_t count, std::size_t record_size, std::size_t property, std::size_t offset,
                      PlyVertexAttributes& attributes) const {
    const std::byte* value = data_.data() + at_ + offset;
    for (std::uint64_t i = 0; i < count; ++i, value += record_size) {
      attributes.put(property, i, static_cast<double>(load<T, Order>(value)));
    }
  }

  /// The fast path for face records that hold nothing but the index list.
  template <class Count, class Item>
  void read_index_lists(const PlyElement& element, const CornerCheck& check, FaceBuffer& triangles) {
    const std::byte* at = data_.data() + at_;
    const std::byte* const end = data_.data() + data_.size();
    for (std::uint64_t record = 0; record < element.count; ++record) {
      if (static_cast<std::size_t>(end - at) < sizeof(Count)) {
        truncated(element, record);
      }
      const auto count = static_cast<std::int64_t>(load<Count, Order>(at));
      at += sizeof(Count);
      check.corner_count(count, record);
      if (static_cast<std::uint64_t>(count) > static_cast<std::size_t>(end - at) / sizeof(Item)) {
        truncated(element, record);
      }
      if (count == 3) {
        triangles.add(check(static_cast<std::int64_t>(load<Item, Order>(at)), record),
                      check(static_cast<std::int64_t>(load<Item, Order>(at + sizeof(Item))), record),
                      check(static_cast<std::int64_t>(load<Item, Order>(at + 2 * sizeof(Item))), record));
      } else {
        triangles.add_polygon(static_cast<std::size_t>(count), [&](std::size_t corner) {
          return check(static_cast<std::int64_t>(load<Item, Order>(at + corner * sizeof(Item))), record);
        });
      }
      at += static_cast<std::size_t>(count) * sizeof(Item);
    }
    at_ = static_cast<std::size_t>(at - data_.data());
  }

  std::span<const std::byte> data_;
  std::size_t at_;
  const fs::path& file_;
};

template <std::endian Order>
std::size_t read_binary_body(std::span<const std::byte> data, const PlyHeader& header, const PlyMeshLayout& layout,
                             const fs::path& file, TriangleMesh& mesh, PlyVertexAttributes& attributes,
                             FaceBuffer& triangles) {
  BinaryPlyBody<Order> body(data, header.body_offset, file);
  const std::uint64_t vertex_count = layout.vertex ? layout.vertex->count : 0;
  for (const PlyElement& element : header.elements) {
    if (&element == layout.vertex) {
      body.read_vertices(element, layout.xyz, mesh.vertices, attributes);
      triangles.know_vertices(mesh.vertices);
    } else if (&element == layout.face) {
      body.read_faces(element, layout.corner_list, CornerCheck(element, vertex_count, file), triangles);
    } else {
      body.skip(element);
    }
  }
  return body.remaining();
}

/// Steps over every record without allocating, to throw the error that names
/// the record cut off; called when the file is too short for the header.
template <std::endian Order>
[[noreturn]] void name_truncated_record(std::span<const std::byte> data, const PlyHeader& header,
                                        const Shortfall& shortfall, const fs::path& file) {
  BinaryPlyBody<Order> body(data, header.body_offset, file);
  for (const PlyElement& element : header.elements) {
    body.skip(element);
  }
  throw_shortfall(shortfall, data.size(), file);
}

// ---------------------------------------------------------------------------
// ASCII bodies: one record per line, values separated by blanks.

class AsciiPlyBody {
 public:
  AsciiPlyBody(std::string_view text, const PlyHeader& header, const fs::path& file)
      : lines_(text.substr(header.body_offset), header.body_first_line), file_(file) {}

  /// Reads every record of `element`: scalar values go to on_scalar(property,
  /// record, value); the list `corner_list` (if any) is checked and, unless
  /// `triangles` is null, becomes triangles.
  template <class OnScalar>
  void read(const PlyElement& element, OnScalar&& on_scalar, std::optional<std::size_t> corner_list,
            const CornerCheck* check, FaceBuffer* triangles) {
    for (std::uint64_t record = 0; record < element.count; ++record) {
      WordCursor words(next_record_line(element, record));
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (!property.is_list()) {
          on_scalar(p, record, value_as_double(next_word(words, element, record), property.type));
          continue;
        }
        const std::int64_t count = value_as_integer(next_word(words, element, record), *property.count_type);
        if (count < 0) {
          throw_line_error(file_, lines_.line_number(), "list '", excerpt(property.name), "' has a negative length ",
                           count);
        }
        if (corner_list && p == *corner_list) {
          check->corner_count(count, record);
          corners_.clear();
          for (std::int64_t i = 0; i < count; ++i) {
            corners_.push_back((*check)(value_as_integer(next_word(words, element, record), property.type), record));
          }
          if (triangles != nullptr) {
            triangles->add_polygon(corners_.size(), [this](std::size_t corner) { return corners_[corner]; });
          }
        } else {
          for (std::int64_t i = 0; i < count; ++i) {
            value_as_double(next_word(words, element, record), property.type);
          }
        }
      }
      if (!words.at_end()) {
        throw_line_error(file_, lines_.line_number(), "more values than the ", element.properties.size(),
                         " properties of element '", excerpt(element.name), "' declare (", excerpt(element.name), " ",
                         record, ")");
      }
    }
  }

  /// True when non-blank lines follow the last element.
  bool has_trailing_text() {
    std::string_view line;
    while (lines_.next(line)) {
      if (!is_blank_line(line)) {
        return true;
      }
    }
    return false;
  }

 private:
  std::string_view next_record_line(const PlyElement& element, std::uint64_t record) {
    std::string_view line;
    while (lines_.next(line)) {
      if (!is_blank_line(line)) {
        return line;
      }
    }
    throw_file_error(file_, "the file ends after ", record, " of ", element.count, " '", excerpt(element.name),
                     "' records (line ", lines_.line_number(), ")");
  }

  std::string_view next_word(WordCursor& words, const PlyElement& element, std::uint64_t record) {
    std::string_view word;
    if (!words.next(word)) {
      throw_line_error(file_, lines_.line_number(), "too few values for ", excerpt(element.name), " ", record,
                       " (its element declares ", element.properties.size(), " properties)");
    }
    return word;
  }

  double value_as_double(std::string_view word, PlyScalar type) const {
    if (is_integer(type)) {
      return static_cast<double>(value_as_integer(word, type));
    }
    const auto value = parse_double(word);
    if (!value) {
      throw_line_error(file_, lines_.line_number(), "'", excerpt(word), "' is not a number");
    }
    if (type == PlyScalar::float32) {
      // Read the value as the float the header declares, as a binary file would hold it.
      if (std::isfinite(*value) && std::fabs(*value) > static_cast<double>(std::numeric_limits<float>::max())) {
        throw_line_error(file_, lines_.line_number(), "value ", excerpt(word), " does not fit the type float");
      }
      return static_cast<double>(static_cast<float>(*value));
    }
    return *value;
  }

  std::int64_t value_as_integer(std::string_view word, PlyScalar type) const {
    const auto value = parse_integer<std::int64_t>(word);
    if (!value) {
      throw_line_error(file_, lines_.line_number(), "'", excerpt(word), "' is not an integer (type ", name_of(type),
                       ")");
    }
    const bool fits = visit_ply_scalar(type, [v = *value](auto tag) {
      using T = typename decltype(tag)::type;
      if constexpr (std::is_integral_v<T>) {
        return v >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
               v <= static_cast<std::int64_t>(std::numeric_limits<T>::max());
      } else {
        return true;
      }
    });
    if (!fits) {
      throw_line_error(file_, lines_.line_number(), "value ", *value, " does not fit the type ", name_of(type));
    }
    return *value;
  }

  LineCursor lines_;
  const fs::path& file_;
  std::vector<Index> corners_;  // reused for every face: no allocation per record
};

/// Reads an ascii body into `mesh`, `attributes` and `triangles`; with all
/// null, only checks every record (a dry run: nothing sized by the header's
/// counts is allocated). Returns whether text follows the last element.
bool read_ascii_body(std::span<const std::byte> data, const PlyHeader& header, const PlyMeshLayout& layout,
                     const fs::path& file, TriangleMesh* mesh, PlyVertexAttributes* attributes, FaceBuffer* triangles) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  AsciiPlyBody body(text, header, file);
  const std::uint64_t vertex_count = layout.vertex ? layout.vertex->count : 0;
  const auto ignore = [](std::size_t, std::uint64_t, double) {};
  for (const PlyElement& element : header.elements) {
    if (&element == layout.vertex && mesh != nullptr) {
      mesh->vertices.resize(static_cast<Eigen::Index>(element.count), 3);
      body.read(
          element,
          [&](std::size_t property, std::uint64_t record, double value) {
            for (Eigen::Index axis = 0; axis < 3; ++axis) {
              if (property == layout.xyz[static_cast<std::size_t>(axis)]) {
                mesh->vertices(static_cast<Eigen::Index>(record), axis) = value;
              }
            }
            if (attributes != nullptr && attributes->reads(property)) attributes->put(property, record, value);
          },
          std::nullopt, nullptr, nullptr);
      if (triangles != nullptr) {
        triangles->know_vertices(mesh->vertices);
      }
    } else if (&element == layout.face) {
      const CornerCheck check(element, vertex_count, file);
      body.read(element, ignore, layout.corner_list, &check, triangles);
    } else {
      body.read(element, ignore, std::nullopt, nullptr, nullptr);
    }
  }
  return body.has_trailing_text();
}

/// What the reader stepped over, for ReadInfo::notes: the first few parts by
/// name, then how many more.
std::string ignored_parts(const PlyHeader& header, const PlyMeshLayout& layout) {
  constexpr std::size_t max_named = 12;
  std::string named;
  std::size_t count = 0;
  const auto add = [&](const auto&... pieces) {
    if (count++ < max_named) {
      named += str_cat(named.empty() ? "" : ", ", pieces...);
    }
  };
  for (const PlyElement& element : header.elements) {
    if (&element != layout.vertex && &element != layout.face) {
      add("element '", excerpt(element.name), "' (", element.count, " records)");
      continue;
    }
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      // Every scalar vertex property is read: coordinates, or attributes.
      const bool used = (&element == layout.vertex && !element.properties[p].is_list()) ||
                        (&element == layout.face && p == layout.corner_list);
      if (!used) {
        add(excerpt(element.name), " property '", excerpt(element.properties[p].name), "'");
      }
    }
  }
  if (count > max_named) {
    named += str_cat(" and ", count - max_named, " more");
  }
  return named;
}

}  // namespace

LoadedMesh read_ply(std::span<const std::byte> data, const fs::path& name) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  const PlyHeader header = parse_ply_header(text, name);
  const PlyMeshLayout layout = find_mesh_layout(header, name);
  if (const auto shortfall = find_shortfall(header, layout, data.size())) {
    // Too short for what the header declares: find the first bad record
    // without allocating, to name it, else report the shortfall itself.
    switch (header.encoding) {
      case PlyEncoding::ascii:
        read_ascii_body(data, header, layout, name, nullptr, nullptr, nullptr);
        throw_shortfall(*shortfall, data.size(), name);
      case PlyEncoding::binary_little_endian:
        name_truncated_record<std::endian::little>(data, header, *shortfall, name);
      case PlyEncoding::binary_big_endian: name_truncated_record<std::endian::big>(data, header, *shortfall, name);
    }
  }

  LoadedMesh loaded;
  loaded.info.format = MeshFormat::ply;
  loaded.info.file_bytes = data.size();
  loaded.info.encoding = std::string(name_of(header.encoding));
  if (layout.vertex) {
    loaded.info.encoding += str_cat(" ", sized_name_of(layout.vertex->properties[layout.xyz[0]].type));
  }

  FaceBuffer triangles(layout.face ? static_cast<std::size_t>(layout.face->count) : 0);
  // No vertex element: no attributes either (and no vertices for the faces to use).
  const PlyElement no_vertices;
  PlyVertexAttributes attributes(layout.vertex ? *layout.vertex : no_vertices, layout.xyz);
  switch (header.encoding) {
    case PlyEncoding::ascii:
      if (read_ascii_body(data, header, layout, name, &loaded.mesh, &attributes, &triangles)) {
        loaded.info.notes.push_back("text after the last element was ignored");
      }
      break;
    case PlyEncoding::binary_little_endian:
    case PlyEncoding::binary_big_endian: {
      const std::size_t trailing =
          header.encoding == PlyEncoding::binary_little_endian
              ? read_binary_body<std::endian::little>(data, header, layout, name, loaded.mesh, attributes, triangles)
              : read_binary_body<std::endian::big>(data, header, layout, name, loaded.mesh, attributes, triangles);
      if (trailing > 0) {
        loaded.info.notes.push_back(str_cat(trailing, " bytes after the last element were ignored"));
      }
      break;
    }
  }
  loaded.mesh.faces = triangles.take(loaded.mesh.vertices, loaded.info);
  loaded.attributes = attributes.take(loaded.info.notes);
  if (const std::string ignored = ignored_parts(header, layout); !ignored.empty()) {
    loaded.info.notes.push_back("ignored: " + ignored);
  }
  return loaded;
}

}  // namespace geodual::io::detail
