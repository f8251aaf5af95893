// Wavefront OBJ writer: "v x y z" and "f a b c" lines (1-based indices).
// Coordinates are printed by std::to_chars in its shortest round-trip form:
// at most max_digits10 (17) significant digits, and reading the text back
// gives the very same double. No locale is involved.

#include "geodual/io/write_mesh.hpp"

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

/// Room for the longest line: "v " and 3 doubles of at most 24 characters with separators.
using LineBuffer = std::array<char, 96>;

template <class T>
char* put_number(char* at, LineBuffer& line, T value) {
  return std::to_chars(at, line.data() + line.size(), value).ptr;
}

void write_obj_text(std::ostream& out, const TriangleMesh& mesh) {
  TextBlockWriter text(out);
  LineBuffer line;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    char* at = line.data();
    *at++ = 'v';
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      *at++ = ' ';
      at = put_number(at, line, mesh.vertices(v, axis));
    }
    *at++ = '\n';
    text.append(line.data(), at);
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    char* at = line.data();
    *at++ = 'f';
    for (Eigen::Index corner = 0; corner < 3; ++corner) {
      *at++ = ' ';
      at = put_number(at, line, static_cast<std::int64_t>(mesh.faces(f, corner)) + 1);
    }
    *at++ = '\n';
    text.append(line.data(), at);
  }
  text.flush();
}

}  // namespace

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh) {
  detail::check_face_indices(path, mesh);
  write_file_atomically(path, [&](std::ostream& out) {
    static constexpr std::string_view header = "# written by geodual\n";
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    write_obj_text(out, mesh);
  });
}

}  // namespace geodual::io
