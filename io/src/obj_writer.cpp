// Wavefront OBJ writer: "v x y z" (or "v x y z r g b" with colours) and
// "f a b c" lines (1-based indices).
// Coordinates are printed by std::to_chars in its shortest round-trip form:
// at most max_digits10 (17) significant digits, and reading the text back
// gives the very same double. No locale is involved.

#include "geodual/io/write_mesh.hpp"

#include "file_error.hpp"
#include "mesh_checks.hpp"

#include "geodual/io/atomic_file.hpp"

#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace geodual::io {
namespace {

/// Collects text in a buffer and hands it to the stream in large blocks.
class TextBlockWriter {
 public:
  explicit TextBlockWriter(std::ostream& out) : out_(out) { buffer_.reserve(2 * block_size); }

  void append(const char* begin, const char* end) {
    buffer_.append(begin, end);
    if (buffer_.size() >= block_size) {
      flush();
    }
  }

  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr std::size_t block_size = 1 << 20;
  std::ostream& out_;
  std::string buffer_;
};

/// Room for the longest line: "v " and 3 doubles of at most 24 characters,
/// 3 floats of at most 15, with separators.
using LineBuffer = std::array<char, 160>;

template <class T>
char* put_number(char* at, LineBuffer& line, T value) {
  return std::to_chars(at, line.data() + line.size(), value).ptr;
}

void write_obj_text(std::ostream& out, const TriangleMesh& mesh, const ColorMatrix& colors,
                    const ObjTexturing* texturing) {
  TextBlockWriter text(out);
  LineBuffer line;
  if (texturing != nullptr) {
    const std::string library = "mtllib " + texturing->material_library + "\n";
    text.append(library.data(), library.data() + library.size());
  }
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    char* at = line.data();
    *at++ = 'v';
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      *at++ = ' ';
      at = put_number(at, line, mesh.vertices(v, axis));
    }
    for (Eigen::Index k = 0; colors.rows() > 0 && k < 3; ++k) {
      *at++ = ' ';
      at = put_number(at, line, colors(v, k));
    }
    *at++ = '\n';
    text.append(line.data(), at);
  }
  if (texturing != nullptr) {
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
      char* at = line.data();
      *at++ = 'v';
      *at++ = 't';
      *at++ = ' ';
      at = put_number(at, line, texturing->texcoords(v, 0));
      *at++ = ' ';
      at = put_number(at, line, 1 - texturing->texcoords(v, 1));
      *at++ = '\n';
      text.append(line.data(), at);
    }
    const std::string use = "usemtl " + texturing->material + "\n";
    text.append(use.data(), use.data() + use.size());
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    char* at = line.data();
    *at++ = 'f';
    for (Eigen::Index corner = 0; corner < 3; ++corner) {
      *at++ = ' ';
      const auto index = static_cast<std::int64_t>(mesh.faces(f, corner)) + 1;
      at = put_number(at, line, index);
      if (texturing != nullptr) {
        *at++ = '/';
        at = put_number(at, line, index);
      }
    }
    *at++ = '\n';
    text.append(line.data(), at);
  }
  text.flush();
}

void write_obj_file(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors,
                    const ObjTexturing* texturing) {
  detail::check_face_indices(path, mesh);
  if (colors.rows() > 0 && (colors.rows() != mesh.vertices.rows() || colors.cols() < 3)) {
    detail::throw_file_error(path, "vertex colours: ", colors.rows(), " rows of ", colors.cols(), " channels for ",
                             mesh.vertices.rows(), " vertices");
  }
  if (texturing != nullptr) {
    if (texturing->texcoords.rows() != mesh.vertices.rows() || !texturing->texcoords.allFinite()) {
      detail::throw_file_error(path, "texture coordinates: ", texturing->texcoords.rows(),
                               " finite rows needed, one per vertex, for ", mesh.vertices.rows(), " vertices");
    }
    for (const std::string* name : {&texturing->material_library, &texturing->material}) {
      if (name->empty() || name->find_first_of("\r\n") != std::string::npos) {
        detail::throw_file_error(path, "material names must be one non-empty line");
      }
    }
  }
  write_file_atomically(path, [&](std::ostream& out) {
    static constexpr std::string_view header = "# written by geodual\n";
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    write_obj_text(out, mesh, colors, texturing);
  });
}

}  // namespace

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors) {
  write_obj_file(path, mesh, colors, nullptr);
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors,
               const ObjTexturing& texturing) {
  write_obj_file(path, mesh, colors, &texturing);
}

}  // namespace geodual::io
