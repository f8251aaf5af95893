#include "geodual/mesh/error.hpp"
#include "geodual/remesh/texture_atlas.hpp"

#include <string>

namespace geodual::remesh {

void check_options(const AtlasOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("make_texture_atlas: " + what);
  };
  require(options.texture_size >= 64, "texture_size must be >= 64, got " + std::to_string(options.texture_size));
  require(options.gutter >= 1, "gutter must be >= 1, got " + std::to_string(options.gutter));
  require(options.gutter * 8 < options.texture_size, "gutter must be below an eighth of texture_size, got " +
                                                         std::to_string(options.gutter) + " for " +
                                                         std::to_string(options.texture_size));
  require(options.max_chart_angle > 0 && options.max_chart_angle <= 90,
          "max_chart_angle must be in (0, 90] degrees, got " + std::to_string(options.max_chart_angle));
}

}  // namespace geodual::remesh
