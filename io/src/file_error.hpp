#pragma once
// Internal: the one way readers and writers report a bad file. Every message
// starts with the file's path, then (for text formats) the line, then what is
// wrong.

#include "str_cat.hpp"

#include "geodual/mesh/error.hpp"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace geodual::io::detail {

/// The file's name as messages show it; "<memory>" for an unnamed buffer.
inline std::string display_name(const std::filesystem::path& file) {
  return file.empty() ? std::string("<memory>") : file.string();
}

/// A word from the file as messages quote it: at most 40 characters, bytes
/// outside printable ASCII shown as '?', so random bytes make a readable message.
inline std::string excerpt(std::string_view word) {
  constexpr std::size_t max_length = 40;
  std::string out;
  for (const char c : word.substr(0, max_length)) {
    out += (c >= ' ' && c <= '~') ? c : '?';
  }
  if (word.size() > max_length) {
    out += "...";
  }
  return out;
}

/// Throws geodual::Error("<file>: <pieces...>").
template <class... Pieces>
[[noreturn]] void throw_file_error(const std::filesystem::path& file, const Pieces&... pieces) {
  throw Error(str_cat(display_name(file), ": ", pieces...));
}

/// Throws geodual::Error("<file>: line <line>: <pieces...>").
template <class... Pieces>
[[noreturn]] void throw_line_error(const std::filesystem::path& file, std::size_t line, const Pieces&... pieces) {
  throw Error(str_cat(display_name(file), ": line ", line, ": ", pieces...));
}

}  // namespace geodual::io::detail
