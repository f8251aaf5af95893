// Wavefront OBJ reader: `v` lines give vertices, `f` lines faces (any of the
// forms v, v/vt, v//vn, v/vt/vn; negative indices count back from the latest
// vertex), polygons are triangulated in their plane (polygon_triangulation.hpp).
// Vertex colours written as `v x y z r g b` (in [0, 1], or 0-255) are kept
// when every vertex has one. Everything else -- texture coordinates, normals, groups, objects, materials,
// smoothing, lines, points -- is ignored, as are comments. Lines end in "\n"
// or "\r\n".

#include "format_readers.hpp"

#include "file_error.hpp"
#include "parse_number.hpp"
#include "polygon_triangulation.hpp"
#include "str_cat.hpp"
#include "text_lines.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace geodual::io::detail {
namespace {

namespace fs = std::filesystem;

/// The first face that names a vertex beyond those read so far. OBJ allows a
/// face before the vertices it uses, so the check waits for the end of the file.
struct ForwardReference {
  std::int64_t index = 0;  ///< 1-based, as written
  std::size_t face = 0;    ///< 1-based, counting 'f' lines
  std::size_t line = 0;
};

class ObjParser {
 public:
  ObjParser(std::string_view text, const fs::path& file) : lines_(text), file_(file) {}

  LoadedMesh parse() {
    std::string_view line;
    while (lines_.next(line)) {
      WordCursor words(strip_comment(line));
      std::string_view keyword;
      if (!words.next(keyword)) {
        continue;
      }
      if (keyword == "v") {
        read_vertex(words);
      } else if (keyword == "f") {
        read_face(words);
      }
      // vt, vn, vp, g, o, s, usemtl, mtllib, l, p, ...: not geometry geodual uses.
    }
    const auto vertex_count = static_cast<std::int64_t>(coordinates_.size() / 3);
    if (forward_.index > vertex_count) {
      throw_line_error(file_, forward_.line, "face ", forward_.face, " refers to vertex ", forward_.index,
                       ", but the file has only ", vertex_count, " vertices");
    }
    LoadedMesh loaded;
    loaded.info.format = MeshFormat::obj;
    loaded.info.encoding = "ascii";
    loaded.mesh.vertices = Eigen::Map<const VertexMatrix>(coordinates_.data(), vertex_count, 3);
    loaded.mesh.faces = faces_.take(loaded.mesh.vertices, loaded.info);
    take_colors(loaded);
    return loaded;
  }

 private:
  void read_vertex(WordCursor& words) {
    if (coordinates_.size() / 3 >= static_cast<std::size_t>(std::numeric_limits<Index>::max())) {
      throw_line_error(file_, lines_.line_number(), "more vertices than geodual's 32-bit indices can address");
    }
    for (int axis = 0; axis < 3; ++axis) {
      std::string_view word;
      if (!words.next(word)) {
        throw_line_error(file_, lines_.line_number(), "vertex has ", axis, " coordinates; 'v' needs x y z");
      }
      const auto value = parse_double(word);
      if (!value) {
        throw_line_error(file_, lines_.line_number(), "vertex coordinate '", excerpt(word), "' is not a number");
      }
      coordinates_.push_back(*value);
    }
    // An optional w, or r g b colour values, may follow.
    std::array<double, 3> rgb{};
    int extra = 0;
    for (std::string_view word; extra < 4 && words.next(word); ++extra) {
      const auto value = parse_double(word);
      if (!value) {
        throw_line_error(file_, lines_.line_number(), "vertex value '", excerpt(word), "' is not a number");
      }
      if (extra < 3) rgb[static_cast<std::size_t>(extra)] = *value;
    }
    if (extra == 3) {
      colored_vertices_ += 1;
      colors_.resize(coordinates_.size(), 0.0f);  // vertices before the first colour stay black
      for (std::size_t k = 0; k < 3; ++k) colors_[coordinates_.size() - 3 + k] = static_cast<float>(rgb[k]);
    }
  }

  /// The colours, when every vertex has one: in [0, 1], or all within 0-255 (scaled).
  void take_colors(LoadedMesh& loaded) const {
    const std::int64_t vertices = loaded.mesh.num_vertices();
    if (colored_vertices_ == 0) return;
    if (colored_vertices_ < vertices) {
      loaded.info.notes.push_back(
          str_cat("vertex colours ignored: only ", colored_vertices_, " of ", vertices, " vertices have one"));
      return;
    }
    ColorMatrix colors = Eigen::Map<const ColorMatrix>(colors_.data(), vertices, 3);
    if (!colors.allFinite() || colors.minCoeff() < 0.0f || colors.maxCoeff() > 255.0f) {
      loaded.info.notes.push_back("vertex colours ignored: not all within [0, 1] or 0-255");
      return;
    }
    if (colors.maxCoeff() > 1.0f) {
      colors /= 255.0f;
      loaded.info.notes.push_back("vertex colours read as 0-255 (some exceed 1)");
    }
    loaded.attributes.colors = std::move(colors);
    loaded.attributes.color_type = ValueType::float32;
  }

  void read_face(WordCursor& words) {
    ++face_count_;
    corners_.clear();
    std::string_view word;
    while (words.next(word)) {
      corners_.push_back(vertex_of_corner(word));
    }
    if (corners_.size() < 3) {
      throw_line_error(file_, lines_.line_number(), "face ", face_count_, " has ", corners_.size(),
                       " corners; a face needs at least 3");
    }
    faces_.know_vertices(coordinates_);
    faces_.add_polygon(corners_.size(), [this](std::size_t corner) { return corners_[corner]; });
  }

  /// The 0-based vertex index of a corner written "v", "v/vt", "v//vn" or "v/vt/vn".
  Index vertex_of_corner(std::string_view corner) {
    const std::string_view vertex = corner.substr(0, corner.find('/'));
    const auto index = parse_integer<std::int64_t>(vertex);
    const std::size_t line = lines_.line_number();
    if (!index) {
      throw_line_error(file_, line, "malformed face corner '", excerpt(corner),
                       "' (expected v, v/vt, v//vn or v/vt/vn with integer indices)");
    }
    const auto vertex_count = static_cast<std::int64_t>(coordinates_.size() / 3);
    if (*index == 0) {
      throw_line_error(file_, line, "vertex index 0 in face corner '", excerpt(corner),
                       "' (OBJ indices start at 1; negative ones count back from the latest vertex)");
    }
    if (*index < 0) {
      // -1 is the latest vertex read.
      if (*index < -vertex_count) {
        throw_line_error(file_, line, "relative vertex index ", *index, " reaches before the first vertex (",
                         vertex_count, " vertices read so far)");
      }
      return static_cast<Index>(vertex_count + *index);
    }
    if (*index > std::numeric_limits<Index>::max()) {
      throw_line_error(file_, line, "vertex index ", *index, " exceeds geodual's 32-bit indices");
    }
    if (*index > vertex_count && *index > forward_.index) {
      forward_ = ForwardReference{.index = *index, .face = face_count_, .line = line};
    }
    return static_cast<Index>(*index - 1);
  }

  LineCursor lines_;
  const fs::path& file_;
  std::vector<double> coordinates_;
  std::vector<float> colors_;  ///< r g b per vertex once one has a colour
  std::int64_t colored_vertices_ = 0;
  FaceBuffer faces_;
  std::vector<Index> corners_;  // reused for every face: no allocation per face
  std::size_t face_count_ = 0;
  ForwardReference forward_;
};

}  // namespace

LoadedMesh read_obj(std::span<const std::byte> data, const fs::path& name) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  return ObjParser(text, name).parse();
}

}  // namespace geodual::io::detail
