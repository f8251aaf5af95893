// Sizing: the site count for a target edge length or face count, from the
// surface's area A, boundary length P and Euler characteristic chi:
// V = (F + P / L) / 2 + chi with F = A / ((sqrt(3)/4) L^2).

#include "analytic_surfaces.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/remesh/sizing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace geodual::remesh {
namespace {

TEST(Sizing, TheUnitSquareGetsTheFormulasCount) {
  const TriangleMesh square = test::unit_square(8);
  const SizingMeasures measures = sizing_measures(square);
  EXPECT_NEAR(measures.area, 1.0, 1e-12);
  EXPECT_NEAR(measures.boundary_length, 4.0, 1e-12);
  EXPECT_EQ(measures.euler_characteristic, 1);
  // L = 0.1: F = 1 / (0.4330127 * 0.01) = 230.94, B = 40, V = 135.47 + 1.
  EXPECT_EQ(sites_for_edge_length(square, 0.1), 136);
  // L = 0.05: F = 923.76, B = 80, V = 501.88 + 1.
  EXPECT_EQ(sites_for_edge_length(square, 0.05), 503);
  // 200 faces: L = sqrt(1 / (0.4330127 * 200)) = 0.10746, B = 37.22, V = 118.61 + 1.
  EXPECT_EQ(sites_for_faces(square, 200), 120);
  // A huge edge length: at least one site.
  EXPECT_EQ(sites_for_edge_length(square, 1e6), 1);
}

TEST(Sizing, AClosedSphereHasHalfTheFacesPlusTwo) {
  const TriangleMesh sphere = test::icosphere(4);
  const SizingMeasures measures = sizing_measures(sphere);
  EXPECT_EQ(measures.euler_characteristic, 2);
  EXPECT_EQ(measures.boundary_length, 0.0);
  EXPECT_NEAR(measures.area, 4 * std::numbers::pi, 0.01 * 4 * std::numbers::pi);  // inscribed: a little less
  // No boundary: V = F / 2 + 2, whatever the area.
  EXPECT_EQ(sites_for_faces(sphere, 4000), 2002);
  EXPECT_EQ(sites_for_faces(sphere, 40001), 20003);  // 20002.5 rounds up
  // L = 0.1 on area ~4 pi: F = 4 pi / (0.4330127 * 0.01) = 2902.0, V = 1453.0 (less 1 %).
  const double expected = 4 * std::numbers::pi / (std::sqrt(3.0) / 4 * 0.01) / 2 + 2;
  const std::int64_t sites = sites_for_edge_length(sphere, 0.1);
  EXPECT_LE(sites, std::llround(expected));
  EXPECT_GE(sites, std::llround(0.99 * expected));
  // Exactly the formula on the mesh's own area.
  EXPECT_EQ(sites, std::llround(measures.area / (std::sqrt(3.0) / 4 * 0.01) / 2 + 2));
}

TEST(Sizing, FacesWithARepeatedCornerTakeNoPart) {
  TriangleMesh square = test::unit_square(8);
  const Index far = square.num_vertices();
  square.vertices.conservativeResize(far + 1, 3);
  square.vertices.row(far) = Eigen::RowVector3d(5, 5, 0);
  square.faces.conservativeResize(square.num_faces() + 1, 3);
  square.faces.row(square.num_faces() - 1) << 0, far, far;
  const SizingMeasures measures = sizing_measures(square);
  EXPECT_NEAR(measures.area, 1.0, 1e-12);
  EXPECT_NEAR(measures.boundary_length, 4.0, 1e-12);
  EXPECT_EQ(measures.euler_characteristic, 1);
  EXPECT_EQ(sites_for_edge_length(square, 0.1), 136);
}

TEST(Sizing, BadTargetsAreUsageErrors) {
  const TriangleMesh square = test::unit_square(4);
  for (const double length :
       {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(sites_for_edge_length(square, length), UsageError) << length;
  }
  EXPECT_THROW(sites_for_faces(square, 0), UsageError);
  // 10^-6 on the unit square: 2.3e12 faces, more sites than allowed.
  EXPECT_THROW(sites_for_edge_length(square, 1e-6), UsageError);
  EXPECT_THROW(sites_for_faces(square, 4 * max_sized_sites), UsageError);
}

}  // namespace
}  // namespace geodual::remesh
