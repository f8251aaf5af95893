#pragma once

#include <string_view>

namespace geodual {

/// geodual's version, "MAJOR.MINOR.PATCH".
std::string_view version();

}  // namespace geodual
