#pragma once
// Internal: builds messages from text and numbers without iostreams or
// locales; numbers are formatted by std::to_chars.

#include <charconv>
#include <concepts>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace geodual::io::detail {

inline void append_piece(std::string& out, std::string_view text) { out += text; }

inline void append_piece(std::string& out, char c) { out += c; }

// A template, so that strings do not convert to paths implicitly.
template <std::same_as<std::filesystem::path> Path>
void append_piece(std::string& out, const Path& path) {
  out += path.string();
}

template <std::integral T>
requires(!std::same_as<T, bool> && !std::same_as<T, char>) void append_piece(std::string& out, T value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

template <std::floating_point T>
void append_piece(std::string& out, T value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// Concatenates strings, characters, paths and numbers into one string.
template <class... Pieces>
std::string str_cat(const Pieces&... pieces) {
  std::string out;
  (append_piece(out, pieces), ...);
  return out;
}

}  // namespace geodual::io::detail
