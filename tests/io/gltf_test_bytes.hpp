#pragma once
// Byte helpers shared by the glTF reading tests: raw values, base64 data URIs
// and GLB containers around hand-written JSON.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
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

/// Standard base64 with '=' padding.
inline std::string base64(std::span<const std::byte> data) {
  constexpr std::string_view alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, data.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k)
      group = (group << 8) | (k < n ? std::to_integer<std::uint32_t>(data[i + k]) : 0);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

/// "data:application/octet-stream;base64,..." holding `bytes`.
inline std::string data_uri(std::span<const std::byte> bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

/// A GLB file: `json` padded with spaces, then (if `bin` is not empty) `bin` padded with zeros.
inline std::vector<std::byte> glb_of(std::string_view json, std::span<const std::byte> bin) {
  const auto padded = [](std::size_t n) { return (n + 3) / 4 * 4; };
  std::vector<std::byte> out;
  const auto put_u32 = [&](std::size_t value) {
    const auto v = static_cast<std::uint32_t>(value);
    const auto* bytes = reinterpret_cast<const std::byte*>(&v);
    out.insert(out.end(), bytes, bytes + 4);
  };
  const std::size_t total = 20 + padded(json.size()) + (bin.empty() ? 0 : 8 + padded(bin.size()));
  out.insert(out.end(), {std::byte{'g'}, std::byte{'l'}, std::byte{'T'}, std::byte{'F'}});
  put_u32(2);
  put_u32(total);
  put_u32(padded(json.size()));
  put_u32(0x4E4F534A);  // "JSON"
  const std::span<const std::byte> text = std::as_bytes(std::span(json.data(), json.size()));
  out.insert(out.end(), text.begin(), text.end());
  out.resize(20 + padded(json.size()), std::byte{' '});
  if (!bin.empty()) {
    put_u32(padded(bin.size()));
    put_u32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    out.resize(total, std::byte{0});
  }
  return out;
}

}  // namespace geodual::io::gltf_test
