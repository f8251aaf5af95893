#pragma once
// Byte helpers shared by the glTF reading tests.

#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <span>
#include <string>
#include <vector>

namespace geodual::io::gltf_test {

/// Little-endian bytes of a list of values, e.g. bytes_of<float>({0, 1, 2}).
template <class T>
std::vector<std::byte> bytes_of(std::initializer_list<T> values) {
  std::vector<std::byte> out(values.size() * sizeof(T));
  std::memcpy(out.data(), std::data(values), out.size());
  return out;
}

/// The bytes of a string, as the readers take them.
inline std::span<const std::byte> as_span(const std::string& text) {
  return std::as_bytes(std::span(text.data(), text.size()));
}

}  // namespace geodual::io::gltf_test
