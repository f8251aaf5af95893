#pragma once
// Whole-token number parsing for the text files the command line reads.

#include <charconv>
#include <string_view>
#include <system_error>

namespace geodual::detail {

/// Whether `token` is exactly one number of type T (no sign or space around it
/// beyond what std::from_chars takes), stored in `value`.
template <typename T>
bool parse_token(std::string_view token, T& value) {
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

}  // namespace geodual::detail
