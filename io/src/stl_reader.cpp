// STL reader, binary and ASCII. STL has no shared vertices: every triangle
// lists its three corner positions, so corners at exactly the same position
// are welded into one vertex (first occurrence order); ReadInfo says how many.
//
// Telling the encodings apart: binary files may begin with "solid" too, so the
// size decides first -- a binary STL is exactly 84 + 50 n bytes, n being the
// count at byte 80. Otherwise a file that begins with "solid" and looks like
// text is ASCII; anything else is a binary file of the wrong size.

#include "format_readers.hpp"

#include "byte_order.hpp"
#include "file_error.hpp"
#include "geodual/mesh/detail/position_welder.hpp"
#include "parse_number.hpp"
#include "polygon_triangulation.hpp"
#include "text_lines.hpp"
#include "triangle_buffer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace geodual::io::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t binary_header_bytes = 84;    // 80-byte comment + uint32 triangle count
constexpr std::size_t binary_triangle_bytes = 50;  // normal, 3 corners (float32 x 3 each), uint16 attribute

/// No control characters other than blanks and line ends in the first KiB.
bool looks_like_text(std::span<const std::byte> data) {
  const auto head = data.first(std::min<std::size_t>(data.size(), 1024));
  return std::all_of(head.begin(), head.end(), [](std::byte b) {
    const auto c = std::to_integer<unsigned char>(b);
    return c >= 0x20 || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  });
}

bool starts_with_solid(std::string_view text) {
  WordCursor words(text.substr(0, std::min<std::size_t>(text.size(), 256)));
  std::string_view first;
  return words.next(first) && first.starts_with("solid");
}

void describe_welding(const PositionWelder& welder, LoadedMesh& loaded) {
  loaded.info.welded_corners = welder.welded_corners();
  loaded.info.notes.push_back(str_cat("STL stores every triangle corner separately: ", welder.corner_count(),
                                      " corners were welded into ", welder.vertex_count(),
                                      " vertices by exact position (first occurrence order; ", welder.welded_corners(),
                                      " corners repeated an earlier position)"));
}

LoadedMesh read_binary_stl(std::span<const std::byte> data, std::uint64_t triangle_count, const fs::path& file) {
  const std::uint64_t expected = binary_header_bytes + binary_triangle_bytes * triangle_count;
  if (expected > data.size()) {
    const std::uint64_t complete = (data.size() - binary_header_bytes) / binary_triangle_bytes;
    throw_file_error(file, "truncated binary data: triangle ", complete, " of ", triangle_count,
                     " ends past the end of the file (file is ", data.size(), " bytes; ", triangle_count,
                     " triangles need ", expected, ")");
  }
  if (triangle_count > static_cast<std::uint64_t>(std::numeric_limits<Index>::max()) / 3) {
    throw_file_error(file, "the header declares ", triangle_count,
                     " triangles, more corners than geodual's 32-bit indices can address");
  }
  LoadedMesh loaded;
  loaded.info.format = MeshFormat::stl;
  loaded.info.encoding = "binary";
  PositionWelder welder(3 * static_cast<std::size_t>(triangle_count));
  TriangleBuffer triangles(static_cast<std::size_t>(triangle_count));
  const std::byte* record = data.data() + binary_header_bytes;
  for (std::uint64_t t = 0; t < triangle_count; ++t, record += binary_triangle_bytes) {
    std::array<Index, 3> corners{};
    for (std::size_t c = 0; c < 3; ++c) {
      const std::byte* xyz = record + 12 * (c + 1);  // after the 12-byte normal
      corners[c] = welder.weld(load<float, std::endian::little>(xyz), load<float, std::endian::little>(xyz + 4),
                               load<float, std::endian::little>(xyz + 8));
    }
    triangles.add(corners[0], corners[1], corners[2]);
  }
  if (expected < data.size()) {
    loaded.info.notes.push_back(str_cat(data.size() - expected, " bytes after the last triangle were ignored"));
  }
  loaded.mesh.vertices = welder.vertices();
  loaded.mesh.faces = triangles.take();
  describe_welding(welder, loaded);
  return loaded;
}

/// solid / facet normal / outer loop / vertex x y z ... / endloop / endfacet / endsolid
class AsciiStlParser {
 public:
  AsciiStlParser(std::string_view text, const fs::path& file)
      : lines_(text), file_(file), welder_(text.size() / 40), facets_(text.size() / 250) {}

  LoadedMesh parse() {
    std::string_view line;
    while (lines_.next(line)) {
      WordCursor words(line);
      std::string_view keyword;
      if (words.next(keyword)) {
        handle(keyword, words);
      }
    }
    if (facet_line_ != 0) {
      throw_file_error(file_, "the file ends inside the facet that begins on line ", facet_line_);
    }
    LoadedMesh loaded;
    loaded.info.format = MeshFormat::stl;
    loaded.info.encoding = "ascii";
    loaded.mesh.vertices = welder_.vertices();
    loaded.mesh.faces = facets_.take(loaded.mesh.vertices, loaded.info);
    describe_welding(welder_, loaded);
    return loaded;
  }

 private:
  void handle(std::string_view keyword, WordCursor& words) {
    const bool in_facet = facet_line_ != 0;
    if (keyword == "solid" && !in_facet) {
      in_solid_ = true;  // the rest of the line is the solid's name
    } else if (keyword == "endsolid" && !in_facet) {
      in_solid_ = false;
    } else if (keyword == "facet" && in_solid_ && !in_facet) {
      facet_line_ = lines_.line_number();  // "normal nx ny nz" follows; unused
      corners_.clear();
    } else if ((keyword == "outer" || keyword == "endloop") && in_facet) {
      // "outer loop" and "endloop" only bracket the vertices.
    } else if (keyword == "vertex" && in_facet) {
      std::array<double, 3> xyz{};
      for (double& value : xyz) {
        std::string_view word;
        if (!words.next(word)) {
          throw_line_error(file_, lines_.line_number(), "vertex has fewer than 3 coordinates");
        }
        const auto parsed = parse_double(word);
        if (!parsed) {
          throw_line_error(file_, lines_.line_number(), "vertex coordinate '", excerpt(word), "' is not a number");
        }
        value = *parsed;
      }
      corners_.push_back(welder_.weld(xyz[0], xyz[1], xyz[2]));
    } else if (keyword == "endfacet" && in_facet) {
      if (corners_.size() < 3) {
        throw_line_error(file_, lines_.line_number(), "facet has ", corners_.size(),
                         " vertices; a facet needs at least 3");
      }
      facets_.add_polygon(corners_.size(), [this](std::size_t corner) { return corners_[corner]; });
      facet_line_ = 0;
    } else {
      throw_line_error(file_, lines_.line_number(), "unexpected '", excerpt(keyword), "' in ASCII STL",
                       in_facet    ? " (inside a facet)"
                       : in_solid_ ? ""
                                   : " (outside 'solid ... endsolid')");
    }
  }

  LineCursor lines_;
  const fs::path& file_;
  PositionWelder welder_;
  FaceBuffer facets_;
  std::vector<Index> corners_;  // reused for every facet: no allocation per facet
  bool in_solid_ = false;
  std::size_t facet_line_ = 0;  // line where the open facet began; 0 outside facets
};

}  // namespace

LoadedMesh read_stl(std::span<const std::byte> data, const fs::path& name) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  if (data.size() >= binary_header_bytes) {
    const std::uint64_t triangle_count = load<std::uint32_t, std::endian::little>(data.data() + 80);
    const bool size_matches = binary_header_bytes + binary_triangle_bytes * triangle_count == data.size();
    if (size_matches || !starts_with_solid(text) || !looks_like_text(data)) {
      return read_binary_stl(data, triangle_count, name);
    }
  } else if (!starts_with_solid(text)) {
    throw_file_error(name, "not an STL file: it neither begins with 'solid' nor is long enough for a binary STL (",
                     data.size(), " bytes, at least ", binary_header_bytes, " needed)");
  }
  return AsciiStlParser(text, name).parse();
}

}  // namespace geodual::io::detail
