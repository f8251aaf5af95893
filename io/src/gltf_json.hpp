#pragma once
// Internal: typed, checked access to the JSON of a glTF file. Every helper
// takes `where` (e.g. "scan.gltf: accessor 3") and throws
// geodual::Error("<where>: <what is wrong>") when the value is missing, has
// the wrong type or is out of range.

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace geodual::io::detail::gltf {

using Json = nlohmann::json;

/// Integers above 2^53 are not exactly representable in JSON readers that use
/// doubles; glTF sizes and indices never come near, so larger values are errors.
/// Keeping all sizes below 2^53 also makes offset + count * stride overflow-free.
inline constexpr std::uint64_t max_json_integer = std::uint64_t{1} << 53;

[[noreturn]] void fail(std::string_view where, std::string_view what);

/// Member `key` of `object`, or nullptr when absent (or when `object` is not an object).
const Json* find_member(const Json& object, std::string_view key);

/// The JSON object `object[key]`; nullptr when absent; throws when not an object.
const Json* optional_object(const Json& object, std::string_view key, std::string_view where);

/// The array `object[key]`; an empty array when absent; throws when not an array.
const Json& array_member(const Json& object, std::string_view key, std::string_view where);

/// A non-negative integer (at most 2^53); nullopt when absent.
std::optional<std::uint64_t> optional_uint(const Json& object, std::string_view key, std::string_view where);
std::uint64_t required_uint(const Json& object, std::string_view key, std::string_view where);

/// A non-negative integer JSON value (not a member), e.g. an element of "children".
std::uint64_t uint_value(const Json& value, std::string_view what, std::string_view where);

/// An index into an array of `count` elements (`kind` names them in messages,
/// e.g. "accessor").
std::size_t index_value(const Json& value, std::size_t count, std::string_view kind, std::string_view where);
std::optional<std::size_t> optional_index(const Json& object, std::string_view key, std::size_t count,
                                          std::string_view kind, std::string_view where);

std::size_t required_index(const Json& object, std::string_view key, std::size_t count, std::string_view kind,
                           std::string_view where);

std::optional<std::string> optional_string(const Json& object, std::string_view key, std::string_view where);
bool optional_bool(const Json& object, std::string_view key, bool fallback, std::string_view where);

/// Exactly N numbers, e.g. a node's "translation"; nullopt when absent.
template <std::size_t N>
std::optional<std::array<double, N>> optional_numbers(const Json& object, std::string_view key,
                                                      std::string_view where) {
  const Json* value = find_member(object, key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_array() || value->size() != N) {
    fail(where, "'" + std::string(key) + "' must be an array of " + std::to_string(N) + " numbers");
  }
  std::array<double, N> numbers{};
  for (std::size_t i = 0; i < N; ++i) {
    const Json& element = (*value)[i];
    if (!element.is_number()) {
      fail(where, "'" + std::string(key) + "' must be an array of " + std::to_string(N) + " numbers");
    }
    numbers[i] = element.get<double>();
  }
  return numbers;
}

/// "mesh 2 'Body'": the kind, the index and, when the object has one, its
/// name (control characters replaced, long names shortened) for messages.
std::string describe(std::string_view kind, std::size_t index, const Json& object);

}  // namespace geodual::io::detail::gltf
