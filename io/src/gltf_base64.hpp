#pragma once
// Internal: base64 (RFC 4648, standard alphabet) for glTF data URIs.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::io::detail {

/// Standard alphabet with '=' padding.
std::string encode_base64(std::span<const std::byte> data);

/// Decodes standard base64. Padding is optional; any character outside the
/// alphabet (whitespace included) or a dangling sixth bit group gives nullopt.
std::optional<std::vector<std::byte>> decode_base64(std::string_view text);

}  // namespace geodual::io::detail
