// Vertex attributes at points of the surface: barycentric interpolation, exact
// for linear fields; normals renormalised; integer scalars rounded and clamped.

#include "geodual/mesh/vertex_attributes.hpp"

#include "mesh/small_meshes.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace geodual {
namespace {

// Two triangles of the unit square in the plane z = 0.
TriangleMesh unit_square() {
  return test::make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

TEST(VertexAttributes, ALinearFieldIsReproducedExactlyAtEveryPoint) {
  const TriangleMesh mesh = unit_square();
  VertexAttributes attributes;
  attributes.colors.resize(4, 3);
  attributes.scalars.push_back({"height", ValueType::float64, {}});
  for (Index v = 0; v < 4; ++v) {
    const double x = mesh.vertices(v, 0), y = mesh.vertices(v, 1);
    attributes.colors.row(v) << static_cast<float>(0.2 + 0.5 * x), static_cast<float>(0.1 + 0.8 * y), 0.5f;
    attributes.scalars[0].values.push_back(3 * x - 2 * y + 1);
  }
  const std::vector<SurfacePoint> points = {SurfacePoint::in_face(0, 0.2, 0.3, 0.5),
                                            SurfacePoint::in_face(1, 0.6, 0.1, 0.3), SurfacePoint::at_vertex(2)};
  const VertexAttributes at = interpolate_attributes(mesh, attributes, points);
  ASSERT_EQ(at.colors.rows(), 3);
  ASSERT_EQ(at.scalars.size(), 1u);
  EXPECT_EQ(at.scalars[0].name, "height");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i].position(mesh);
    const auto row = static_cast<Eigen::Index>(i);
    EXPECT_NEAR(at.colors(row, 0), 0.2 + 0.5 * p.x(), 1e-6);
    EXPECT_NEAR(at.colors(row, 1), 0.1 + 0.8 * p.y(), 1e-6);
    EXPECT_FLOAT_EQ(at.colors(row, 2), 0.5f);
    EXPECT_NEAR(at.scalars[0].values[i], 3 * p.x() - 2 * p.y() + 1, 1e-12);
  }
}

TEST(VertexAttributes, NormalsAreRenormalisedAndIntegersRoundedIntoTheirType) {
  const TriangleMesh mesh = unit_square();
  VertexAttributes attributes;
  attributes.normals.resize(4, 3);
  attributes.normals << 1, 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0;
  attributes.scalars.push_back({"label", ValueType::uint8, {0, 255, 255, 10}});
  const std::vector<SurfacePoint> points = {SurfacePoint::in_face(0, 0.5, 0.5, 0.0),
                                            SurfacePoint::in_face(0, 0.3, 0.35, 0.35)};
  const VertexAttributes at = interpolate_attributes(mesh, attributes, points);
  EXPECT_NEAR(at.normals.row(0).norm(), 1.0, 1e-12);
  EXPECT_NEAR(at.normals(0, 0), std::sqrt(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(at.scalars[0].values[0], 128.0);  // 127.5 rounds away from zero
  EXPECT_DOUBLE_EQ(at.scalars[0].values[1], 179.0);  // 0.7 * 255 = 178.5
  EXPECT_EQ(at.scalars[0].type, ValueType::uint8);
}

TEST(VertexAttributes, SizeProblemsNameTheAttribute) {
  VertexAttributes attributes;
  EXPECT_EQ(attribute_size_problem(attributes, 4), "");
  attributes.colors.resize(3, 3);
  EXPECT_EQ(attribute_size_problem(attributes, 4), "colors: 3 rows for 4 vertices");
  attributes.colors.resize(4, 2);
  EXPECT_EQ(attribute_size_problem(attributes, 4), "colors: 2 columns (3 or 4 expected)");
  attributes.colors.resize(0, 0);
  attributes.scalars.push_back({"q", ValueType::float32, {1.0}});
  EXPECT_EQ(attribute_size_problem(attributes, 4), "scalar 'q': 1 rows for 4 vertices");
}

TEST(VertexAttributes, SrgbEncodingRoundTripsAndMatchesTheStandardsKnee) {
  EXPECT_FLOAT_EQ(srgb_from_linear(0.0f), 0.0f);
  EXPECT_EQ(srgb_from_linear(1.0f), 1.0f);  // exactly: white stays white
  EXPECT_EQ(linear_from_srgb(1.0f), 1.0f);
  EXPECT_NEAR(srgb_from_linear(0.18f), 0.4613f, 1e-4);  // middle grey
  for (int i = 0; i <= 255; ++i) {
    const float encoded = static_cast<float>(i) / 255.0f;
    EXPECT_NEAR(srgb_from_linear(linear_from_srgb(encoded)), encoded, 1e-6f);
  }
}

}  // namespace
}  // namespace geodual
