#include "geodual/pipeline/version.hpp"

// GEODUAL_VERSION comes from pipeline/CMakeLists.txt; GEODUAL_GIT_DESCRIBE
// from the header it generates at every build (cmake/GeodualGitDescribe.cmake).
#include "geodual_git_describe.hpp"

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
