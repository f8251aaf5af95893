#include "gltf_json.hpp"

#include "geodual/mesh/error.hpp"

#include <cmath>

namespace geodual::io::detail::gltf {
namespace {

std::string quoted(std::string_view key) { return "'" + std::string(key) + "'"; }

// A short rendering of a JSON value for messages. Never dumps arrays or
// objects: they can be huge or deeply nested (and dump() recurses).
std::string short_text(const Json& value) {
  if (value.is_number() || value.is_boolean() || value.is_null()) return value.dump();
  if (value.is_string()) return "a string";
  return std::string("an ") + (value.is_array() ? "array" : "object");
}

// nullopt when `value` is not an integer in [0, 2^53]. Integral floats such
// as 3.0 are accepted, as the glTF validator does.
std::optional<std::uint64_t> as_uint(const Json& value) {
  if (value.is_number_unsigned()) {
    const auto v = value.get<std::uint64_t>();
    return v <= max_json_integer ? std::optional(v) : std::nullopt;
  }
  if (value.is_number_integer()) return std::nullopt;  // negative
  if (value.is_number_float()) {
    const double v = value.get<double>();
    if (v >= 0.0 && v <= static_cast<double>(max_json_integer) && std::floor(v) == v) {
      return static_cast<std::uint64_t>(v);
    }
  }
  return std::nullopt;
}

}  // namespace

void fail(std::string_view where, std::string_view what) { throw Error(std::string(where) + ": " + std::string(what)); }

const Json* find_member(const Json& object, std::string_view key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(std::string(key));
  return it == object.end() ? nullptr : &*it;
}

const Json* optional_object(const Json& object, std::string_view key, std::string_view where) {
  const Json* value = find_member(object, key);
  if (value != nullptr && !value->is_object()) fail(where, quoted(key) + " must be a JSON object");
  return value;
}

const Json& array_member(const Json& object, std::string_view key, std::string_view where) {
  static const Json empty_array = Json::array();
  const Json* value = find_member(object, key);
  if (value == nullptr) return empty_array;
  if (!value->is_array()) fail(where, quoted(key) + " must be an array");
  return *value;
}

std::uint64_t uint_value(const Json& value, std::string_view what, std::string_view where) {
  const std::optional<std::uint64_t> v = as_uint(value);
  if (!v) {
    fail(where, std::string(what) + " must be a non-negative integer (at most 2^53), found " + short_text(value));
  }
  return *v;
}

std::optional<std::uint64_t> optional_uint(const Json& object, std::string_view key, std::string_view where) {
  const Json* value = find_member(object, key);
  if (value == nullptr) return std::nullopt;
  return uint_value(*value, quoted(key), where);
}

std::uint64_t required_uint(const Json& object, std::string_view key, std::string_view where) {
  const std::optional<std::uint64_t> v = optional_uint(object, key, where);
  if (!v) fail(where, "required " + quoted(key) + " is missing");
  return *v;
}

std::size_t index_value(const Json& value, std::size_t count, std::string_view kind, std::string_view where) {
  const std::uint64_t index = uint_value(value, std::string(kind) + " index", where);
  if (index >= count) {
    fail(where, "refers to " + std::string(kind) + " " + std::to_string(index) + ", but the file has " +
                    std::to_string(count));
  }
  return static_cast<std::size_t>(index);
}

std::optional<std::size_t> optional_index(const Json& object, std::string_view key, std::size_t count,
                                          std::string_view kind, std::string_view where) {
  const Json* value = find_member(object, key);
  if (value == nullptr) return std::nullopt;
  return index_value(*value, count, kind, where);
}

std::size_t required_index(const Json& object, std::string_view key, std::size_t count, std::string_view kind,
                           std::string_view where) {
  const std::optional<std::size_t> index = optional_index(object, key, count, kind, where);
  if (!index) fail(where, "required " + quoted(key) + " is missing");
  return *index;
}

std::optional<std::string> optional_string(const Json& object, std::string_view key, std::string_view where) {
  const Json* value = find_member(object, key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_string()) fail(where, quoted(key) + " must be a string");
  return value->get<std::string>();
}

bool optional_bool(const Json& object, std::string_view key, bool fallback, std::string_view where) {
  const Json* value = find_member(object, key);
  if (value == nullptr) return fallback;
  if (!value->is_boolean()) fail(where, quoted(key) + " must be true or false");
  return value->get<bool>();
}

std::string describe(std::string_view kind, std::size_t index, const Json& object) {
  std::string text = std::string(kind) + " " + std::to_string(index);
  const Json* name = find_member(object, "name");
  if (name == nullptr || !name->is_string()) return text;
  constexpr std::size_t max_length = 60;
  const auto& full = name->get_ref<const std::string&>();
  std::string shown;
  for (const char c : full.substr(0, max_length)) {
    shown += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? '?' : c;
  }
  if (full.size() > max_length) shown += "...";
  return text + " '" + shown + "'";
}

}  // namespace geodual::io::detail::gltf
