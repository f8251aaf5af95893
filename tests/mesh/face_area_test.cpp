// face_area and has_positive_area against hand-computed triangles, and the
// defect report counting as degenerate exactly the faces without an area.

#include "mesh/small_meshes.hpp"

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

namespace geodual {
namespace {

using test::make_mesh;

TEST(FaceArea, RightTriangleAndItsHeronTwin) {
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}, {{0, 1, 2}});
  EXPECT_DOUBLE_EQ(face_area(mesh, 0), 6.0);
  EXPECT_DOUBLE_EQ(twice_area_from_lengths(3, 4, 5), 12.0);
  EXPECT_DOUBLE_EQ(twice_area_from_lengths(5, 3, 4), 12.0);  // any order
  EXPECT_TRUE(has_positive_area(mesh, 0));
}

TEST(FaceArea, ImpossibleAndNanLengthsHaveNoArea) {
  EXPECT_EQ(twice_area_from_lengths(1, 1, 3), 0.0);  // breaks the triangle inequality
  EXPECT_EQ(twice_area_from_lengths(1, 1, 2), 0.0);  // flat
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(has_area_from_lengths({1, 1, nan}));
  EXPECT_TRUE(has_area_from_lengths({1, 1, 1}));
}

TEST(FaceArea, RepeatedCornersAndCollinearCornersHaveNoArea) {
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 1}, {0, 1, 2}, {0, 1, 3}});
  EXPECT_TRUE(has_repeated_corner(mesh, 0));
  EXPECT_FALSE(has_repeated_corner(mesh, 1));
  EXPECT_FALSE(has_positive_area(mesh, 0));
  EXPECT_FALSE(has_positive_area(mesh, 1));
  EXPECT_TRUE(has_positive_area(mesh, 2));
  EXPECT_EQ(face_area(mesh, 1), 0.0);
}

TEST(FaceArea, NeedleBelowTheRoundingOfItsLengthsHasNone) {
  // The cross product of two edges is (0, 0, 1e-17), not zero; but the two
  // short sides round to exactly 0.5, so the lengths say it is flat, and the
  // geodesic engine, which lays faces out from their lengths, sees no area.
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1e-17, 0}}, {{0, 1, 2}});
  EXPECT_GT(face_area(mesh, 0), 0.0);
  EXPECT_FALSE(has_positive_area(mesh, 0));
  EXPECT_EQ(analyze_mesh(mesh).degenerate_faces, 1);
  // A needle that is thin but above that rounding keeps its area.
  const TriangleMesh thin = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1e-6, 0}}, {{0, 1, 2}});
  EXPECT_TRUE(has_positive_area(thin, 0));
  EXPECT_EQ(analyze_mesh(thin).degenerate_faces, 0);
}

TEST(FaceArea, OverflowGivesZeroNotInfinity) {
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1e200, 0, 0}, {0, 1e200, 0}}, {{0, 1, 2}});
  EXPECT_EQ(face_area(mesh, 0), 0.0);
}

}  // namespace
}  // namespace geodual
