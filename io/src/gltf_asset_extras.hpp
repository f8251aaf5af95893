#pragma once
// Internal: asset.extras, written verbatim. tinygltf's Value drops JSON nulls
// and turns empty arrays and objects into null, so tinygltf writes a
// placeholder exactly as long as the caller's JSON text, which is put in its
// place in the finished file; equal lengths keep GLB chunk lengths valid.

#include <tiny_gltf.h>

#include <string>
#include <string_view>

namespace geodual::io::detail::gltf {

class AssetExtras {
 public:
  /// `json`: empty, or the text of a JSON object; anything else throws
  /// geodual::Error("<where>: ...").
  AssetExtras(std::string_view json, const std::string& where);

  /// What to give tinygltf as asset.extras: the placeholder, or a null Value when there are no extras.
  tinygltf::Value placeholder() const;

  /// Replaces the placeholder in the file tinygltf wrote (compact JSON) with the extras.
  void fill_in(std::string& file) const;

 private:
  std::string text_;  ///< compact JSON, padded with spaces to at least the placeholder's minimum length
};

}  // namespace geodual::io::detail::gltf
