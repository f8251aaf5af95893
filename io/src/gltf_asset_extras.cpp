#include "gltf_asset_extras.hpp"

#include "geodual/mesh/error.hpp"

#include <nlohmann/json.hpp>

namespace geodual::io::detail::gltf {
namespace {

// The placeholder is {"":"###...#"}: 7 bytes plus the filler.
constexpr std::size_t placeholder_overhead = 7;
constexpr char filler = '#';

std::string placeholder_text(std::size_t length) {
  return "{\"\":\"" + std::string(length - placeholder_overhead, filler) + "\"}";
}

}  // namespace

AssetExtras::AssetExtras(std::string_view json, const std::string& where) {
  if (json.empty()) return;
  using Json = nlohmann::ordered_json;  // keeps the members in the caller's order
  Json extras;
  try {
    extras = Json::parse(json);
  } catch (const Json::parse_error& e) {
    throw Error(where + ": asset extras are not valid JSON: " + e.what());
  }
  if (!extras.is_object()) throw Error(where + ": asset extras must be a JSON object");
  text_ = extras.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text_.size() < placeholder_overhead) text_.resize(placeholder_overhead, ' ');  // JSON white space
}

tinygltf::Value AssetExtras::placeholder() const {
  if (text_.empty()) return {};
  tinygltf::Value::Object object;
  object.emplace("", tinygltf::Value(std::string(text_.size() - placeholder_overhead, filler)));
  return tinygltf::Value(std::move(object));
}

void AssetExtras::fill_in(std::string& file) const {
  if (text_.empty()) return;
  // The first match is asset.extras: only "accessors", which hold no strings of
  // this form, precede "asset" in tinygltf's alphabetical member order.
  const std::size_t at = file.find(placeholder_text(text_.size()));
  if (at == std::string::npos) throw Error("glTF output: tinygltf did not write the asset extras placeholder");
  file.replace(at, text_.size(), text_);
}

}  // namespace geodual::io::detail::gltf
