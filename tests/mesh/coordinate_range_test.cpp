// require_computable_range: the limits of double-precision geometry, checked
// on the vertices that faces use.

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace geodual {
namespace {

TriangleMesh triangle(double scale, double offset = 0) {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << offset, 0, 0, offset + scale, 0, 0, offset, scale, 0, 1e300, 1e300, 1e300;  // the last unused
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;
  return mesh;
}

std::string message_of(const TriangleMesh& mesh) {
  try {
    require_computable_range(mesh, "m.obj");
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

TEST(CoordinateRange, OrdinaryScalesPassAndUnusedVerticesDoNotCount) {
  for (const double scale : {1e-60, 1e-3, 1.0, 1e6, 1e60}) EXPECT_EQ(message_of(triangle(scale)), "") << scale;
  EXPECT_EQ(message_of(triangle(1, 1e69)), "");
}

TEST(CoordinateRange, HugeAndTinyMeshesAreRefusedByName) {
  const std::string huge = message_of(triangle(1e71));
  EXPECT_EQ(huge.rfind("m.obj: ", 0), 0U) << huge;
  EXPECT_NE(huge.find("scale the mesh down"), std::string::npos) << huge;
  const std::string tiny = message_of(triangle(1e-71));
  EXPECT_NE(tiny.find("scale the mesh up"), std::string::npos) << tiny;
}

TEST(CoordinateRange, ASinglePointIsLeftToTheZeroAreaChecks) { EXPECT_EQ(message_of(triangle(0)), ""); }

}  // namespace
}  // namespace geodual
