#pragma once
// Test support for the mesh reader and writer suites: a private temporary
// folder per test, writing and reading whole files, catching the message of a
// geodual::Error, and the shared real-scan folder.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace geodual::test {

namespace fs = std::filesystem;

/// A fresh folder under the system's temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "geodual-io-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::system_error(errno, std::generic_category(), "mkdtemp");
    }
    path_ = pattern;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }

  const fs::path& path() const { return path_; }
  fs::path operator/(std::string_view name) const { return path_ / name; }

  /// The names of the entries in the folder, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

inline fs::path write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    throw std::runtime_error("cannot write test file " + path.string());
  }
  return path;
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error("cannot read test file " + path.string());
  }
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Writes `bytes` to `name` in a new folder and reads it with read_mesh.
inline io::LoadedMesh read_text(const TempDir& dir, std::string_view name, std::string_view bytes) {
  return io::read_mesh(write_file(dir / name, bytes));
}

/// The message of the geodual::Error `action` throws; a test failure (and "")
/// when it throws nothing.
template <class Action>
std::string error_message(Action&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected a geodual::Error, but nothing was thrown";
  return {};
}

/// The real scans the tests read: tests/data relative to the repository root,
/// where the tests run.
inline fs::path test_mesh(std::string_view name) { return fs::path("tests/data") / name; }

/// Builds binary file contents value by value in a chosen byte order.
class ByteWriter {
 public:
  explicit ByteWriter(std::endian order = std::endian::little) : order_(order) {}

  template <class T>
  ByteWriter& put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (order_ != std::endian::native) {
      std::reverse(bytes, bytes + sizeof(T));
    }
    data_.append(bytes, sizeof(T));
    return *this;
  }

  /// Writes `value` as the PLY scalar type named `type` (char ... double).
  ByteWriter& put_as(std::string_view type, double value) {
    if (type == "char" || type == "int8") return put(static_cast<std::int8_t>(value));
    if (type == "uchar" || type == "uint8") return put(static_cast<std::uint8_t>(value));
    if (type == "short" || type == "int16") return put(static_cast<std::int16_t>(value));
    if (type == "ushort" || type == "uint16") return put(static_cast<std::uint16_t>(value));
    if (type == "int" || type == "int32") return put(static_cast<std::int32_t>(value));
    if (type == "uint" || type == "uint32") return put(static_cast<std::uint32_t>(value));
    if (type == "float" || type == "float32") return put(static_cast<float>(value));
    if (type == "double" || type == "float64") return put(value);
    throw std::invalid_argument("unknown PLY type in test: " + std::string(type));
  }

  ByteWriter& text(std::string_view text) {
    data_ += text;
    return *this;
  }

  const std::string& str() const { return data_; }

 private:
  std::endian order_;
  std::string data_;
};

/// Row-major triangles as a flat list, for compact comparisons.
inline std::vector<Index> face_list(const TriangleMesh& mesh) {
  return std::vector<Index>(mesh.faces.data(), mesh.faces.data() + mesh.faces.size());
}

inline std::vector<double> vertex_list(const TriangleMesh& mesh) {
  return std::vector<double>(mesh.vertices.data(), mesh.vertices.data() + mesh.vertices.size());
}

}  // namespace geodual::test
