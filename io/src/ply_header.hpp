#pragma once
// Internal: the PLY header -- encoding, elements, their properties -- and its
// parser. Only ply_reader.cpp includes this.

#include "file_error.hpp"
#include "parse_number.hpp"
#include "text_lines.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace geodual::io::detail {

enum class PlyScalar : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

constexpr std::size_t size_of(PlyScalar type) {
  switch (type) {
    case PlyScalar::int8:
    case PlyScalar::uint8: return 1;
    case PlyScalar::int16:
    case PlyScalar::uint16: return 2;
    case PlyScalar::int32:
    case PlyScalar::uint32:
    case PlyScalar::float32: return 4;
    case PlyScalar::float64: return 8;
  }
  return 0;
}

constexpr bool is_integer(PlyScalar type) { return type != PlyScalar::float32 && type != PlyScalar::float64; }

/// The name PLY's original specification uses.
constexpr std::string_view name_of(PlyScalar type) {
  switch (type) {
    case PlyScalar::int8: return "char";
    case PlyScalar::uint8: return "uchar";
    case PlyScalar::int16: return "short";
    case PlyScalar::uint16: return "ushort";
    case PlyScalar::int32: return "int";
    case PlyScalar::uint32: return "uint";
    case PlyScalar::float32: return "float";
    case PlyScalar::float64: return "double";
  }
  return "?";
}

/// Both spellings in use: char/uchar/... and int8/uint8/... .
constexpr std::optional<PlyScalar> ply_scalar_from_name(std::string_view name) {
  struct Spelling {
    std::string_view name;
    PlyScalar type;
  };
  constexpr Spelling spellings[] = {
      {"char", PlyScalar::int8},       {"int8", PlyScalar::int8},       {"uchar", PlyScalar::uint8},
      {"uint8", PlyScalar::uint8},     {"short", PlyScalar::int16},     {"int16", PlyScalar::int16},
      {"ushort", PlyScalar::uint16},   {"uint16", PlyScalar::uint16},   {"int", PlyScalar::int32},
      {"int32", PlyScalar::int32},     {"uint", PlyScalar::uint32},     {"uint32", PlyScalar::uint32},
      {"float", PlyScalar::float32},   {"float32", PlyScalar::float32}, {"double", PlyScalar::float64},
      {"float64", PlyScalar::float64},
  };
  for (const Spelling& spelling : spellings) {
    if (spelling.name == name) {
      return spelling.type;
    }
  }
  return std::nullopt;
}

/// Calls visit(std::type_identity<T>{}) with the C++ type T of `type`, so that
/// hot loops can be instantiated per type instead of switching per value.
template <class Visitor>
decltype(auto) visit_ply_scalar(PlyScalar type, Visitor&& visit) {
  switch (type) {
    case PlyScalar::int8: return visit(std::type_identity<std::int8_t>{});
    case PlyScalar::uint8: return visit(std::type_identity<std::uint8_t>{});
    case PlyScalar::int16: return visit(std::type_identity<std::int16_t>{});
    case PlyScalar::uint16: return visit(std::type_identity<std::uint16_t>{});
    case PlyScalar::int32: return visit(std::type_identity<std::int32_t>{});
    case PlyScalar::uint32: return visit(std::type_identity<std::uint32_t>{});
    case PlyScalar::float32: return visit(std::type_identity<float>{});
    case PlyScalar::float64: break;
  }
  return visit(std::type_identity<double>{});
}

struct PlyProperty {
  std::string name;
  PlyScalar type = PlyScalar::float32;  ///< the value type; for a list, the item type
  std::optional<PlyScalar> count_type;  ///< set for a list property: the type of its length

  bool is_list() const { return count_type.has_value(); }
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t line = 0;  ///< the header line that declares it

  /// Bytes per binary record, when no property is a list.
  std::optional<std::size_t> fixed_record_size() const {
    std::size_t size = 0;
    for (const PlyProperty& property : properties) {
      if (property.is_list()) {
        return std::nullopt;
      }
      size += size_of(property.type);
    }
    return size;
  }

  std::optional<std::size_t> find_property(std::string_view property_name) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
      if (properties[i].name == property_name) {
        return i;
      }
    }
    return std::nullopt;
  }
};

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

constexpr std::string_view name_of(PlyEncoding encoding) {
  switch (encoding) {
    case PlyEncoding::ascii: return "ascii";
    case PlyEncoding::binary_little_endian: return "binary_little_endian";
    case PlyEncoding::binary_big_endian: return "binary_big_endian";
  }
  return "?";
}

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;      ///< the first byte after the end_header line
  std::size_t body_first_line = 0;  ///< the line number of that byte (ascii bodies)
};

/// Parses the header at the start of a PLY file's text, line by line.
class PlyHeaderParser {
 public:
  PlyHeaderParser(std::string_view file_text, const std::filesystem::path& file) : lines_(file_text), file_(file) {}

  /// Throws geodual::Error naming the line for anything malformed or unsupported.
  PlyHeader parse() {
    std::string_view line;
    bool is_ply = false;
    if (lines_.next(line)) {
      WordCursor words(line);
      std::string_view magic;
      is_ply = words.next(magic) && magic == "ply" && words.at_end();
    }
    if (!is_ply) {
      throw_file_error(file_, "not a PLY file (the first line is not 'ply')");
    }
    while (lines_.next(line)) {
      line_ = lines_.line_number();
      WordCursor words(line);
      std::string_view keyword;
      if (!words.next(keyword)) {
        continue;  // blank lines are harmless
      }
      if (keyword == "end_header") {
        if (!words.at_end()) {
          throw_line_error(file_, line_, "malformed end_header line (nothing may follow end_header)");
        }
        if (!have_format_) {
          throw_file_error(file_, "the PLY header has no format line");
        }
        header_.body_offset = lines_.offset();
        header_.body_first_line = line_ + 1;
        return std::move(header_);
      }
      if (keyword == "comment" || keyword == "obj_info") {
        continue;
      }
      if (keyword == "format") {
        parse_format(words);
      } else if (keyword == "element") {
        parse_element(words);
      } else if (keyword == "property") {
        parse_property(words);
      } else {
        throw_line_error(file_, line_, "malformed PLY header line: unknown keyword '", excerpt(keyword), "'");
      }
    }
    throw_file_error(file_, "the PLY header has no end_header line (truncated or not a PLY file)");
  }

 private:
  static constexpr std::string_view type_list =
      "char, uchar, short, ushort, int, uint, float, double or int8, uint8, int16, uint16, int32, "
      "uint32, float32, float64";

  PlyScalar scalar_type(std::string_view word) const {
    if (const auto type = ply_scalar_from_name(word)) {
      return *type;
    }
    throw_line_error(file_, line_, "unsupported PLY property type '", excerpt(word), "' (expected ", type_list, ")");
  }

  void parse_format(WordCursor& words) {
    if (have_format_) {
      throw_line_error(file_, line_, "a second format line");
    }
    std::string_view encoding;
    std::string_view version;
    if (!words.next(encoding) || !words.next(version) || !words.at_end()) {
      throw_line_error(file_, line_,
                       "malformed format line (expected 'format ascii 1.0', 'format "
                       "binary_little_endian 1.0' or 'format binary_big_endian 1.0')");
    }
    if (encoding == "ascii") {
      header_.encoding = PlyEncoding::ascii;
    } else if (encoding == "binary_little_endian") {
      header_.encoding = PlyEncoding::binary_little_endian;
    } else if (encoding == "binary_big_endian") {
      header_.encoding = PlyEncoding::binary_big_endian;
    } else {
      throw_line_error(file_, line_, "unknown PLY format '", excerpt(encoding),
                       "' (expected ascii, binary_little_endian or binary_big_endian)");
    }
    if (!parse_double(version)) {
      throw_line_error(file_, line_, "malformed PLY version '", excerpt(version), "' (expected 1.0)");
    }
    have_format_ = true;
  }

  void parse_element(WordCursor& words) {
    std::string_view name;
    std::string_view count_word;
    if (!words.next(name) || !words.next(count_word) || !words.at_end()) {
      throw_line_error(file_, line_, "malformed element line (expected 'element <name> <count>')");
    }
    const auto count = parse_integer<std::uint64_t>(count_word);
    if (!count) {
      throw_line_error(file_, line_, "element '", excerpt(name), "' has an invalid count '", excerpt(count_word),
                       "' (expected a non-negative integer)");
    }
    // Hash sets keep duplicate checks linear however many names a header holds.
    if (const auto [first, added] = element_lines_.emplace(name, line_); !added) {
      throw_line_error(file_, line_, "element '", excerpt(name), "' is declared twice (first on line ", first->second,
                       ")");
    }
    property_names_.clear();
    header_.elements.push_back(PlyElement{.name = std::string(name), .count = *count, .properties = {}, .line = line_});
  }

  void parse_property(WordCursor& words) {
    if (header_.elements.empty()) {
      throw_line_error(file_, line_, "property declared before any element");
    }
    PlyElement& element = header_.elements.back();
    PlyProperty property;
    std::string_view type_word;
    std::string_view name;
    if (!words.next(type_word)) {
      throw_line_error(file_, line_,
                       "malformed property line (expected 'property <type> <name>' or "
                       "'property list <count type> <item type> <name>')");
    }
    if (type_word == "list") {
      std::string_view count_word;
      std::string_view item_word;
      if (!words.next(count_word) || !words.next(item_word) || !words.next(name) || !words.at_end()) {
        throw_line_error(file_, line_,
                         "malformed list property line (expected 'property list <count type> "
                         "<item type> <name>')");
      }
      property.count_type = scalar_type(count_word);
      property.type = scalar_type(item_word);
      if (!is_integer(*property.count_type)) {
        throw_line_error(file_, line_, "list property '", excerpt(name), "' has a length of type '", count_word,
                         "'; list lengths must be of an integer type");
      }
    } else {
      if (!words.next(name) || !words.at_end()) {
        throw_line_error(file_, line_, "malformed property line (expected 'property <type> <name>')");
      }
      property.type = scalar_type(type_word);
    }
    if (!property_names_.insert(name).second) {
      throw_line_error(file_, line_, "property '", excerpt(name), "' of element '", excerpt(element.name),
                       "' is declared twice");
    }
    property.name = std::string(name);
    element.properties.push_back(std::move(property));
  }

  LineCursor lines_;
  const std::filesystem::path& file_;
  std::size_t line_ = 1;  // the line being parsed
  PlyHeader header_;
  bool have_format_ = false;
  std::unordered_map<std::string_view, std::size_t> element_lines_;  // name -> declaring line
  std::unordered_set<std::string_view> property_names_;              // of the latest element
};

/// Parses the header at the start of `file_text`; throws geodual::Error naming
/// the line for anything malformed or unsupported.
inline PlyHeader parse_ply_header(std::string_view file_text, const std::filesystem::path& file) {
  return PlyHeaderParser(file_text, file).parse();
}

}  // namespace geodual::io::detail
