// OFF reader (Object File Format): a header keyword (OFF, or COFF / NOFF /
// STOFF / CNOFF ... whose extra per-vertex values are ignored), a counts line
// "V F E", V vertex lines, F face lines "n i0 ... i(n-1) [colour]".
// Polygons are triangulated in their plane (polygon_triangulation.hpp); '#'
// starts a comment; blank lines are skipped.
// Each vertex and face is read from its own line, as every writer emits them.

#include "format_readers.hpp"

#include "file_error.hpp"
#include "parse_number.hpp"
#include "polygon_triangulation.hpp"
#include "saturating.hpp"
#include "text_lines.hpp"

#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace geodual::io::detail {
namespace {

namespace fs = std::filesystem;

/// "OFF" with any of the prefixes ST (texture coordinates), C (colours), N (normals).
bool is_off_keyword(std::string_view word) {
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") {
    return false;
  }
  for (const char c : word.substr(0, word.size() - 3)) {
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N') {
      return false;
    }
  }
  return true;
}

class OffParser {
 public:
  OffParser(std::string_view text, const fs::path& file) : text_(text), lines_(text), file_(file) {}

  LoadedMesh parse() {
    read_header();
    const std::uint64_t available = text_.size() - lines_.offset() + 1;  // the last line may lack its end
    // A vertex line holds at least "0 0 0\n", a face line "3 0 0 0\n".
    const std::uint64_t needed =
        saturating_add(saturating_mul<std::uint64_t>(vertex_count_, 6), saturating_mul<std::uint64_t>(face_count_, 8));
    if (needed > available) {
      // Too short for the counts: name the first bad line without allocating
      // (a dry run), else report the shortfall itself.
      const std::size_t body_start = lines_.offset();
      read_vertices(nullptr);
      read_faces(nullptr);
      throw_line_error(file_, counts_line_, "the counts line declares ", vertex_count_, " vertices and ", face_count_,
                       " faces, which need at least ", needed, " bytes, but only ", text_.size() - body_start,
                       " follow (file is ", text_.size(), " bytes)");
    }
    LoadedMesh loaded;
    loaded.info.format = MeshFormat::off;
    loaded.info.encoding = "ascii";
    read_vertices(&loaded.mesh.vertices);
    FaceBuffer faces(static_cast<std::size_t>(face_count_));
    faces.know_vertices(loaded.mesh.vertices);
    read_faces(&faces);
    loaded.mesh.faces = faces.take(loaded.mesh.vertices, loaded.info);
    return loaded;
  }

 private:
  /// The next line with something other than blanks and comments; false at the end.
  bool next_content_line(WordCursor& words) {
    std::string_view line;
    while (lines_.next(line)) {
      line = strip_comment(line);
      if (!is_blank_line(line)) {
        words = WordCursor(line);
        return true;
      }
    }
    return false;
  }

  [[noreturn]] void file_ends_before(std::string_view what, Index number = -1, Index count = 0) const {
    if (number < 0) {
      throw_file_error(file_, "the file ends before ", what, " (line ", lines_.line_number(), ")");
    }
    throw_file_error(file_, "the file ends before ", what, " ", number, " of ", count, " (line ", lines_.line_number(),
                     ")");
  }

  void read_header() {
    WordCursor words(std::string_view{});
    if (!next_content_line(words)) {
      file_ends_before("the OFF header");
    }
    WordCursor counts = words;
    std::string_view first;
    words.next(first);
    if (is_off_keyword(first)) {
      std::string_view after;
      WordCursor peek = words;
      if (peek.next(after) && after == "BINARY") {
        throw_line_error(file_, lines_.line_number(), "binary OFF is not supported; convert it to PLY");
      }
      if (!words.at_end()) {
        counts = words;
      } else if (!next_content_line(counts)) {
        file_ends_before("the counts line");
      }
    } else if (first.find("OFF") != std::string_view::npos) {
      throw_line_error(file_, lines_.line_number(), "unsupported OFF variant '", excerpt(first),
                       "' (4D and n-dimensional OFF are not supported)");
    } else if (!parse_integer<std::int64_t>(first)) {
      throw_line_error(file_, lines_.line_number(), "not an OFF file (expected 'OFF' or a counts line, found '",
                       excerpt(first), "')");
    }
    counts_line_ = lines_.line_number();
    vertex_count_ = read_count(counts, "vertex");
    face_count_ = read_count(counts, "face");
    std::string_view edges;  // the edge count is optional and unused
    if (counts.next(edges) && !parse_integer<std::int64_t>(edges)) {
      throw_line_error(file_, counts_line_, "malformed edge count '", excerpt(edges), "'");
    }
    if (!counts.at_end()) {
      throw_line_error(file_, counts_line_, "unexpected values after the counts 'V F E'");
    }
  }

  Index read_count(WordCursor& words, std::string_view what) {
    std::string_view word;
    if (!words.next(word)) {
      throw_line_error(file_, lines_.line_number(), "the counts line lacks the ", what,
                       " count (expected 'vertices faces edges')");
    }
    const auto count = parse_integer<std::int64_t>(word);
    if (!count || *count < 0) {
      throw_line_error(file_, lines_.line_number(), "malformed ", what, " count '", excerpt(word),
                       "' (expected a non-negative integer)");
    }
    if (*count > std::numeric_limits<Index>::max()) {
      throw_line_error(file_, lines_.line_number(), "the ", what, " count ", *count,
                       " exceeds geodual's 32-bit indices");
    }
    return static_cast<Index>(*count);
  }

  /// Reads the vertex lines into `vertices`, or only checks them when it is null.
  void read_vertices(VertexMatrix* vertices) {
    if (vertices != nullptr) {
      vertices->resize(vertex_count_, 3);
    }
    for (Index v = 0; v < vertex_count_; ++v) {
      WordCursor words(std::string_view{});
      if (!next_content_line(words)) {
        file_ends_before("vertex", v, vertex_count_);
      }
      for (Eigen::Index axis = 0; axis < 3; ++axis) {
        std::string_view word;
        if (!words.next(word)) {
          throw_line_error(file_, lines_.line_number(), "vertex ", v, " has ", axis, " coordinates; expected x y z");
        }
        const auto value = parse_double(word);
        if (!value) {
          throw_line_error(file_, lines_.line_number(), "vertex ", v, ": coordinate '", excerpt(word),
                           "' is not a number");
        }
        if (vertices != nullptr) {
          (*vertices)(v, axis) = *value;
        }
      }
      // Normals, colours or texture coordinates (NOFF, COFF, STOFF) may follow.
    }
  }

  /// Reads the face lines into `faces`, or only checks them when it is null.
  void read_faces(FaceBuffer* faces) {
    for (Index f = 0; f < face_count_; ++f) {
      WordCursor words(std::string_view{});
      if (!next_content_line(words)) {
        file_ends_before("face", f, face_count_);
      }
      std::string_view word;
      words.next(word);
      const auto corners = parse_integer<std::int64_t>(word);
      if (!corners) {
        throw_line_error(file_, lines_.line_number(), "face ", f, ": malformed corner count '", excerpt(word), "'");
      }
      if (*corners < 3) {
        throw_line_error(file_, lines_.line_number(), "face ", f, " has ", *corners,
                         " corners; a face needs at least 3");
      }
      corners_.clear();
      for (std::int64_t c = 0; c < *corners; ++c) {
        if (!words.next(word)) {
          throw_line_error(file_, lines_.line_number(), "face ", f, " declares ", *corners, " corners but lists ", c);
        }
        const auto index = parse_integer<std::int64_t>(word);
        if (!index) {
          throw_line_error(file_, lines_.line_number(), "face ", f, ": malformed vertex index '", excerpt(word), "'");
        }
        if (*index < 0 || *index >= vertex_count_) {
          throw_line_error(file_, lines_.line_number(), "face ", f, ": vertex index ", *index,
                           " is out of range (the file has ", vertex_count_, " vertices)");
        }
        corners_.push_back(static_cast<Index>(*index));
      }
      // Colour values may follow the indices.
      if (faces != nullptr) {
        faces->add_polygon(corners_.size(), [this](std::size_t corner) { return corners_[corner]; });
      }
    }
  }

  std::string_view text_;
  LineCursor lines_;
  const fs::path& file_;
  Index vertex_count_ = 0;
  Index face_count_ = 0;
  std::size_t counts_line_ = 0;
  std::vector<Index> corners_;  // reused for every face: no allocation per face
};

}  // namespace

LoadedMesh read_off(std::span<const std::byte> data, const fs::path& name) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  return OffParser(text, name).parse();
}

}  // namespace geodual::io::detail
