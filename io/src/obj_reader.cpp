// Wavefront OBJ reader: `v` lines give vertices, `f` lines faces (any of the
// forms v, v/vt, v//vn, v/vt/vn; negative indices count back from the latest
// vertex), polygons are triangulated in their plane (polygon_triangulation.hpp).
// Vertex colours written as `v x y z r g b` (in [0, 1], or 0-255) are kept
// when every vertex has one. A textured scan -- `vt` at every face corner,
// and every face under a `usemtl` material whose `map_Kd` image (PNG or
// JPEG) the `mtllib` files beside it name -- keeps its texture
// (LoadedMesh::texture) and gets vertex colours sampled from it where it has
// none; a texture that cannot be read is left out with a note. Everything
// else -- normals, groups, objects, smoothing, lines, points -- is ignored,
// as are comments. Lines end in "\n" or "\r\n".

#include "format_readers.hpp"

#include "file_error.hpp"
#include "gltf_buffers.hpp"
#include "gltf_texture.hpp"
#include "parse_number.hpp"
#include "polygon_triangulation.hpp"
#include "str_cat.hpp"
#include "text_lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail {
namespace {

namespace fs = std::filesystem;

/// `text` without trailing blanks (a name at the end of a line).
std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

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
      } else if (keyword == "vt") {
        read_texcoord(words);
      } else if (keyword == "usemtl") {
        material_ = material_index(trimmed(words.rest()));
      } else if (keyword == "mtllib") {
        for (std::string_view library; words.next(library);) libraries_.emplace_back(library);
      }
      // vn, vp, g, o, s, l, p, ...: not geometry geodual uses.
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
    take_texture(loaded);
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

  /// "vt u [v [w]]": glTF's coordinates kept, (u, 1 - v) (OBJ's v points up).
  void read_texcoord(WordCursor& words) {
    std::array<double, 2> uv{0, 0};
    std::string_view word;
    for (int k = 0; k < 2 && words.next(word); ++k) {
      const auto value = parse_double(word);
      if (!value || !std::isfinite(*value)) {
        throw_line_error(file_, lines_.line_number(), "texture coordinate '", excerpt(word), "' is not a number");
      }
      uv[static_cast<std::size_t>(k)] = *value;
    }
    texcoords_.insert(texcoords_.end(), {uv[0], 1 - uv[1]});
  }

  int material_index(std::string_view name) {
    return materials_.emplace(std::string(name), static_cast<int>(materials_.size())).first->second;
  }

  /// The texture (LoadedMesh::texture) where every corner has a `vt` and every
  /// face a material with an image; otherwise nothing, with a note saying why.
  void take_texture(LoadedMesh& loaded) const {
    if (texcoords_.empty() || libraries_.empty()) return;
    const auto note = [&](const std::string& why) { loaded.info.notes.push_back("texture ignored: " + why); };
    if (file_.empty()) return note("read from memory without a name, its material library cannot be found");
    if (face_sizes_.size() != face_count_) return note("some faces come before the first 'vt'");
    if (std::find(corner_texcoords_.begin(), corner_texcoords_.end(), -1) != corner_texcoords_.end()) {
      return note("some face corners have no 'vt'");
    }
    if (std::find(face_material_.begin(), face_material_.end(), -1) != face_material_.end()) {
      return note("some faces have no material ('usemtl')");
    }
    // Each material's image (map_Kd), from the libraries beside the file.
    std::map<std::string, fs::path, std::less<>> image_of_material;
    for (const std::string& library : libraries_) {
      loaded.info.companion_files.push_back(file_.parent_path() / library);
      try {
        read_material_library(file_.parent_path() / library, image_of_material);
      } catch (const std::exception& error) {
        return note(error.what());
      }
    }
    std::vector<std::string> names(materials_.size());
    for (const auto& [name, index] : materials_) names[static_cast<std::size_t>(index)] = name;
    std::vector<std::uint8_t> used(materials_.size(), 0);  // materials no face uses need no image
    for (const int m : face_material_) used[static_cast<std::size_t>(m)] = 1;
    SurfaceTexture texture;
    std::vector<gltf::DecodedImage> decoded;                       // the images as decoded, for the vertex colours
    std::map<std::string, std::int32_t, std::less<>> image_index;  // by image path
    std::vector<std::int32_t> image_of(materials_.size(), -1);
    for (std::size_t m = 0; m < names.size(); ++m) {
      if (!used[m]) continue;
      const auto found = image_of_material.find(names[m]);
      if (found == image_of_material.end()) return note("material '" + names[m] + "' has no image ('map_Kd')");
      const auto [at, added] =
          image_index.emplace(found->second.string(), static_cast<std::int32_t>(texture.images.size()));
      image_of[m] = at->second;
      if (!added) continue;
      try {
        loaded.info.companion_files.push_back(found->second);
        const std::string what = "image '" + found->second.string() + "' of material '" + names[m] + "'";
        decoded.push_back(gltf::decode_image(gltf::read_external_file(found->second, what, file_.string()), what));
        texture.images.push_back(gltf::texture_image(decoded.back()));
      } catch (const std::exception& error) {
        return note(error.what());
      }
    }
    // Per triangle, its polygon's corners: each of its vertices at the polygon's corner with that vertex.
    const FaceMatrix& faces = loaded.mesh.faces;
    std::size_t expected = 0;
    for (const std::size_t size : face_sizes_) expected += size - 2;
    if (expected != static_cast<std::size_t>(faces.rows())) return note("a polygon was not split into triangles");
    texture.corner_uvs.resize(3 * faces.rows(), 2);
    texture.face_image.resize(static_cast<std::size_t>(faces.rows()));
    Eigen::Index triangle = 0;
    std::size_t first_corner = 0;
    for (std::size_t polygon = 0; polygon < face_sizes_.size(); ++polygon) {
      const std::size_t size = face_sizes_[polygon];
      for (std::size_t t = 0; t + 2 < size; ++t, ++triangle) {
        texture.face_image[static_cast<std::size_t>(triangle)] =
            image_of[static_cast<std::size_t>(face_material_[polygon])];
        for (int c = 0; c < 3; ++c) {
          const auto begin = corner_vertices_.begin() + static_cast<std::ptrdiff_t>(first_corner);
          const auto at = std::find(begin, begin + static_cast<std::ptrdiff_t>(size), faces(triangle, c));
          const auto corner =
              static_cast<std::size_t>(at == begin + static_cast<std::ptrdiff_t>(size) ? 0 : at - begin);
          const auto vt = static_cast<std::size_t>(corner_texcoords_[first_corner + corner]);
          texture.corner_uvs.row(3 * triangle + c) << texcoords_[2 * vt], texcoords_[2 * vt + 1];
        }
      }
      first_corner += size;
    }
    if (texture.images.size() == 1) texture.face_image.clear();
    if (loaded.attributes.colors.rows() == 0) sample_vertex_colors(loaded, texture, decoded);
    loaded.info.notes.push_back(str_cat("texture: ", texture.images.size(),
                                        texture.images.size() == 1 ? " image" : " images",
                                        " (map_Kd) kept for baking, with the vt of every face corner"));
    loaded.texture = std::move(texture);
  }

  /// Adds each material's `map_Kd` image from the library at `path`: the
  /// file named after the statement's options (each `-name` with the words
  /// that follow it that are numbers or on/off), spaces kept, '\\' read as
  /// '/', relative to the library's folder.
  static void read_material_library(const fs::path& path,
                                    std::map<std::string, fs::path, std::less<>>& image_of_material) {
    const std::vector<std::byte> bytes = gltf::read_external_file(path, "material library", path.string());
    LineCursor lines(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    std::string material;
    std::string_view line;
    while (lines.next(line)) {
      WordCursor words(strip_comment(line));
      std::string_view keyword;
      if (!words.next(keyword)) continue;
      if (keyword == "newmtl") {
        material = std::string(trimmed(words.rest()));
      } else if (keyword == "map_Kd" && !material.empty()) {
        std::string_view rest = trimmed(words.rest());
        while (rest.starts_with('-')) {  // an option and its values
          WordCursor option(rest);
          std::string_view word;
          option.next(word);
          for (std::string_view value = option.rest(); !value.empty(); value = option.rest()) {
            WordCursor peek(value);
            peek.next(word);
            if (!parse_double(word) && word != "on" && word != "off") break;
            option.next(word);
          }
          rest = option.rest();
        }
        std::string file(rest);
        std::replace(file.begin(), file.end(), '\\', '/');
        if (!file.empty()) image_of_material[material] = path.parent_path() / file;
      }
    }
  }

  /// The vertices' colours sampled from the texture (its images as
  /// `decoded`) at each vertex's first corner, as glTF's default sampler does.
  static void sample_vertex_colors(LoadedMesh& loaded, const SurfaceTexture& texture,
                                   const std::vector<gltf::DecodedImage>& decoded) {
    const FaceMatrix& faces = loaded.mesh.faces;
    ColorMatrix colors = ColorMatrix::Zero(loaded.mesh.num_vertices(), 3);
    std::vector<std::uint8_t> done(static_cast<std::size_t>(loaded.mesh.num_vertices()), 0);
    for (Eigen::Index corner = 0; corner < faces.size(); ++corner) {
      const Index v = faces(corner / 3, corner % 3);
      if (done[static_cast<std::size_t>(v)]) continue;
      done[static_cast<std::size_t>(v)] = 1;
      const std::size_t image =
          texture.face_image.empty()
              ? 0
              : static_cast<std::size_t>(texture.face_image[static_cast<std::size_t>(corner / 3)]);
      const std::array<float, 4> linear =
          gltf::sample_texture(decoded[image], {}, texture.corner_uvs(corner, 0), texture.corner_uvs(corner, 1));
      for (int k = 0; k < 3; ++k) colors(v, k) = srgb_from_linear(linear[static_cast<std::size_t>(k)]);
    }
    loaded.attributes.colors = std::move(colors);
    loaded.attributes.color_type = ValueType::uint8;
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
    const bool textured = !texcoords_.empty();  // a face before any vt: no texture (take_texture says so)
    while (words.next(word)) {
      corners_.push_back(vertex_of_corner(word));
      if (textured) corner_texcoords_.push_back(texcoord_of_corner(word));
    }
    if (textured) {
      corner_vertices_.insert(corner_vertices_.end(), corners_.begin(), corners_.end());
      face_sizes_.push_back(corners_.size());
      face_material_.push_back(material_);
    }
    if (corners_.size() < 3) {
      throw_line_error(file_, lines_.line_number(), "face ", face_count_, " has ", corners_.size(),
                       " corners; a face needs at least 3");
    }
    faces_.know_vertices(coordinates_);
    faces_.add_polygon(corners_.size(), [this](std::size_t corner) { return corners_[corner]; });
  }

  /// The 0-based `vt` index of a corner written "v/vt" or "v/vt/vn", or -1
  /// (none, or one out of range: the texture is then not kept).
  std::int64_t texcoord_of_corner(std::string_view corner) const {
    const std::size_t slash = corner.find('/');
    if (slash == std::string_view::npos) return -1;
    std::string_view vt = corner.substr(slash + 1);
    vt = vt.substr(0, vt.find('/'));
    const auto index = parse_integer<std::int64_t>(vt);
    const auto count = static_cast<std::int64_t>(texcoords_.size() / 2);
    if (!index || *index == 0 || *index > count || *index < -count) return -1;
    return *index < 0 ? count + *index : *index - 1;
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
  // The texture: coordinates (glTF's), and per face corner its vertex and vt, per face its size and material.
  std::vector<double> texcoords_;
  std::vector<Index> corner_vertices_;
  std::vector<std::int64_t> corner_texcoords_;
  std::vector<std::size_t> face_sizes_;
  std::vector<int> face_material_;
  int material_ = -1;
  std::map<std::string, int, std::less<>> materials_;
  std::vector<std::string> libraries_;
};

}  // namespace

LoadedMesh read_obj(std::span<const std::byte> data, const fs::path& name) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  return ObjParser(text, name).parse();
}

}  // namespace geodual::io::detail
