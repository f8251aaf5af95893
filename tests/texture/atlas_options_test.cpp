#include "geodual/mesh/error.hpp"
#include "geodual/remesh/texture_atlas.hpp"

#include <gtest/gtest.h>

namespace geodual::remesh {
namespace {

TEST(AtlasOptions, RefusesSizesAndAnglesOutOfRange) {
  EXPECT_NO_THROW(check_options(AtlasOptions{}));
  EXPECT_THROW(check_options(AtlasOptions{.texture_size = 32}), UsageError);
  EXPECT_THROW(check_options(AtlasOptions{.gutter = 0}), UsageError);
  EXPECT_THROW(check_options(AtlasOptions{.texture_size = 64, .gutter = 8}), UsageError);
  EXPECT_THROW(check_options(AtlasOptions{.max_chart_angle = 0}), UsageError);
  EXPECT_THROW(check_options(AtlasOptions{.max_chart_angle = 91}), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
