#pragma once
// Internal: base64 decoding (RFC 4648, standard alphabet) for glTF data URIs.

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace geodual::io::detail {

/// Decodes standard base64. Padding is optional; any character outside the
/// alphabet (whitespace included) or a dangling sixth bit group gives nullopt.
std::optional<std::vector<std::byte>> decode_base64(std::string_view text);

}  // namespace geodual::io::detail
