#pragma once
// Internal: whole-word decimal numbers through std::from_chars (no locale, no
// allocation). A leading '+' is accepted, as text writers sometimes emit one.
// "nan" and "inf" parse as doubles: read_mesh rejects them naming the vertex.

#include <charconv>
#include <concepts>
#include <optional>
#include <string_view>
#include <system_error>

namespace geodual::io::detail {

/// Drops one leading '+' unless a sign follows it ("+-1" stays invalid).
constexpr std::string_view without_plus(std::string_view word) {
  if (word.size() >= 2 && word[0] == '+' && word[1] != '-' && word[1] != '+') {
    word.remove_prefix(1);
  }
  return word;
}

/// The double the whole word spells, or nothing (also for out-of-range values).
inline std::optional<double> parse_double(std::string_view word) {
  word = without_plus(word);
  double value = 0.0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, value);
  if (ec != std::errc{} || ptr != end) {
    return std::nullopt;
  }
  return value;
}

/// The integer the whole word spells in base 10, or nothing (also when it does not fit T).
template <std::integral T>
std::optional<T> parse_integer(std::string_view word) {
  word = without_plus(word);
  T value = 0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, value);
  if (ec != std::errc{} || ptr != end) {
    return std::nullopt;
  }
  return value;
}

}  // namespace geodual::io::detail
