#include "geodual/pipeline/version.hpp"

// GEODUAL_VERSION and GEODUAL_GIT_DESCRIBE come from pipeline/CMakeLists.txt.

namespace geodual {

std::string_view version() { return GEODUAL_VERSION; }

std::string_view build_version() {
  constexpr std::string_view describe = GEODUAL_GIT_DESCRIBE;
  if constexpr (describe.empty()) {
    return GEODUAL_VERSION;
  } else {
    return GEODUAL_VERSION " (" GEODUAL_GIT_DESCRIBE ")";
  }
}

}  // namespace geodual
