// The preview renderer, checked on pictures decoded with stb_image (an
// independent PNG decoder) against hand-computed framing: with the camera
// looking along -Z, up +Y and margin m, a scene whose projection spans
// ex x ey is scaled by s = min(W (1 - 2m) / ex, H (1 - 2m) / ey) pixels per
// unit and its extent's centre lands on the picture's centre.

#include "io_test_files.hpp"

#include "geodual/io/preview.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb/stb_image.h>

namespace geodual::test {
namespace {

using io::PreviewOptions;
using io::PreviewScene;

struct Rgb {
  int r = 0;
  int g = 0;
  int b = 0;
  bool operator==(const Rgb&) const = default;
  int sum() const { return r + g + b; }
};

std::ostream& operator<<(std::ostream& out, const Rgb& c) {
  return out << "(" << c.r << ", " << c.g << ", " << c.b << ")";
}

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  Rgb at(int x, int y) const {
    const std::size_t k =
        (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
  int count_not(const Rgb& color) const {
    int count = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        count += at(x, y) == color ? 0 : 1;
      }
    }
    return count;
  }
  /// Pixels within `tolerance` of `color` in every channel.
  int count_near(const Rgb& color, int tolerance) const {
    int count = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const Rgb c = at(x, y);
        count += (std::abs(c.r - color.r) <= tolerance && std::abs(c.g - color.g) <= tolerance &&
                  std::abs(c.b - color.b) <= tolerance)
                     ? 1
                     : 0;
      }
    }
    return count;
  }
};

Image decode(const std::vector<std::uint8_t>& png) {
  int width = 0;
  int height = 0;
  int channels = 0;
  unsigned char* data = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &width, &height, &channels, 3);
  if (data == nullptr) {
    ADD_FAILURE() << "stb_image cannot decode the PNG: " << stbi_failure_reason();
    return {};
  }
  Image image{width, height, std::vector<std::uint8_t>(data, data + static_cast<std::size_t>(width) * height * 3)};
  stbi_image_free(data);
  return image;
}

// The sRGB transfer function (IEC 61966-2-1), written out independently.
int srgb_byte(double linear) {
  const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * s));
}

Rgb srgb(const Eigen::Vector3f& linear) {
  return {srgb_byte(linear.x()), srgb_byte(linear.y()), srgb_byte(linear.z())};
}

void expect_near(const Rgb& actual, const Rgb& expected, int tolerance, const std::string& where) {
  EXPECT_LE(std::abs(actual.r - expected.r), tolerance) << where << ": " << actual << " vs " << expected;
  EXPECT_LE(std::abs(actual.g - expected.g), tolerance) << where << ": " << actual << " vs " << expected;
  EXPECT_LE(std::abs(actual.b - expected.b), tolerance) << where << ": " << actual << " vs " << expected;
}

TriangleMesh make_mesh(std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3i> faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    mesh.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  }
  return mesh;
}

// The unit right triangle in z = 0.
TriangleMesh unit_triangle() { return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}); }

// Camera along -Z, +Y up: x to the right, y up on the picture.
PreviewOptions front_view() {
  PreviewOptions options;
  options.view_direction = Eigen::Vector3d(0, 0, -1);
  options.up = Eigen::Vector3d(0, 1, 0);
  return options;
}

// Framing of a scene spanning [0, 1] x [0, 1] in a 1200 x 900 picture with
// margin 0.05: s = min(1080 / 1, 810 / 1) = 810, centre (0.5, 0.5) -> (600, 450).
constexpr double kUnitScale = 810.0;
double unit_pixel_x(double x) { return 600.0 + (x - 0.5) * kUnitScale; }
double unit_pixel_y(double y) { return 450.0 - (y - 0.5) * kUnitScale; }

// The pixel whose area contains the picture point (X, Y).
int pixel(double coordinate) { return static_cast<int>(std::floor(coordinate)); }

const Rgb kWhite{255, 255, 255};

TEST(Preview, PngSignatureAndHeaderGiveTheRequestedSize) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  PreviewOptions options;
  options.width = 1003;
  options.height = 677;
  const std::vector<std::uint8_t> png = io::render_preview_png(scene, options);
  ASSERT_GT(png.size(), 33u);
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(png[static_cast<std::size_t>(i)], signature[i]) << "signature byte " << i;
  }
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t{png[at]} << 24) | (std::uint32_t{png[at + 1]} << 16) | (std::uint32_t{png[at + 2]} << 8) |
           std::uint32_t{png[at + 3]};
  };
  EXPECT_EQ(be32(8), 13u) << "IHDR chunk length";
  EXPECT_EQ(std::string(png.begin() + 12, png.begin() + 16), "IHDR");
  EXPECT_EQ(be32(16), 1003u);
  EXPECT_EQ(be32(20), 677u);
  EXPECT_EQ(png[24], 8) << "bit depth";
  EXPECT_EQ(png[25], 2) << "colour type RGB";
  const Image image = decode(png);
  EXPECT_EQ(image.width, 1003);
  EXPECT_EQ(image.height, 677);
}

TEST(Preview, TriangleFacingTheCameraCoversItsAreaInItsColour) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  const Eigen::Vector3f color(0.8f, 0.3f, 0.1f);
  scene.face_colors = {color};
  const Image image = decode(io::render_preview_png(scene, front_view()));
  ASSERT_EQ(image.width, 1200);
  ASSERT_EQ(image.height, 900);

  // Area 810^2 / 2 pixels; partly covered pixels lie along the perimeter.
  const double area = 0.5 * kUnitScale * kUnitScale;
  const double perimeter = kUnitScale * (2.0 + std::sqrt(2.0));
  const int drawn = image.count_not(kWhite);
  EXPECT_NEAR(drawn, area, perimeter);
  EXPECT_GT(drawn, 0.3 * 1200 * 900);  // the fraction, 0.30375, to first order
  // Lit head-on by the headlight: exactly its colour inside.
  const Rgb face = srgb(color);
  EXPECT_NEAR(image.count_near(face, 1), area, perimeter);
  EXPECT_GE(image.count_near(face, 1), area - perimeter);
  expect_near(image.at(pixel(unit_pixel_x(1.0 / 3)), pixel(unit_pixel_y(1.0 / 3))), face, 1, "centroid");
  // Corners land where the framing puts them: just inside is face, just outside white.
  expect_near(image.at(pixel(unit_pixel_x(0.0)) + 3, pixel(unit_pixel_y(0.0)) - 3), face, 1, "corner");
  EXPECT_EQ(image.at(pixel(unit_pixel_x(0.0)) - 3, pixel(unit_pixel_y(0.0)) + 3), kWhite);
  EXPECT_EQ(image.at(pixel(unit_pixel_x(1.0)) + 3, pixel(unit_pixel_y(0.0)) - 3), kWhite);
  EXPECT_EQ(image.at(pixel(unit_pixel_x(0.0)) + 3, pixel(unit_pixel_y(1.0)) - 3), kWhite);
  // The margin is background.
  EXPECT_EQ(image.at(10, 10), kWhite);
  EXPECT_EQ(image.at(1190, 890), kWhite);
}

TEST(Preview, BackFacesAreLitLikeFrontFaces) {
  const TriangleMesh front = unit_triangle();
  const TriangleMesh back = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 2, 1}});
  PreviewScene scene;
  scene.wireframe = false;
  scene.mesh = &front;
  const Image front_image = decode(io::render_preview_png(scene, front_view()));
  scene.mesh = &back;
  const Image back_image = decode(io::render_preview_png(scene, front_view()));
  const int x = pixel(unit_pixel_x(0.3));
  const int y = pixel(unit_pixel_y(0.3));
  EXPECT_EQ(back_image.at(x, y), front_image.at(x, y));
  expect_near(front_image.at(x, y), srgb(PreviewOptions{}.surface_color), 1, "default surface colour");
}

TEST(Preview, ObliqueFacesAreDarkerByLambertsLaw) {
  // A triangle tilted 60 degrees from the view: |n . v| = 1/2.
  const double c = std::cos(M_PI / 3);
  const double s = std::sin(M_PI / 3);
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, c, s}}, {{0, 1, 2}});
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  const Eigen::Vector3f color(0.9f, 0.9f, 0.9f);
  scene.face_colors = {color};
  PreviewOptions options = front_view();
  options.ambient = 0.2f;
  const Image image = decode(io::render_preview_png(scene, options));
  // Projected extent 1 x 0.5: s = min(1080, 810 / 0.5) = 1080, centre (0.5, 0.25) -> (600, 450).
  const int x = pixel(600.0 + (0.25 - 0.5) * 1080.0);
  const int y = pixel(450.0 - (0.25 * c - 0.25) * 1080.0);
  expect_near(image.at(x, y), srgb(color * (0.2f + 0.8f * 0.5f)), 1, "tilted face");
}

TEST(Preview, VertexColoursAreInterpolated) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  scene.vertex_colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Image image = decode(io::render_preview_png(scene, front_view()));
  for (const auto& [x, y] : {std::pair{0.2, 0.2}, std::pair{0.6, 0.1}, std::pair{0.1, 0.7}}) {
    const int px = pixel(unit_pixel_x(x));
    const int py = pixel(unit_pixel_y(y));
    // The pixel centre's position on the triangle, and its barycentric colour.
    const double cx = (px + 0.5 - 600.0) / kUnitScale + 0.5;
    const double cy = 0.5 - (py + 0.5 - 450.0) / kUnitScale;
    const Rgb expected{srgb_byte(1.0 - cx - cy), srgb_byte(cx), srgb_byte(cy)};
    expect_near(image.at(px, py), expected, 2,
                "vertex colours at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
  }
}

TEST(Preview, WireframeDarkensEdgePixelsOnly) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  const Image plain = decode(io::render_preview_png(scene, front_view()));
  scene.wireframe = true;
  const Image wired = decode(io::render_preview_png(scene, front_view()));

  // Points on the three edges (the bottom edge y = 0 is the pixel boundary
  // at Y = 855: the row above it is inside).
  const int bottom_y = pixel(unit_pixel_y(0.0)) - 1;
  const int left_x = pixel(unit_pixel_x(0.0));
  struct Probe {
    int x;
    int y;
  };
  for (const Probe probe : {Probe{pixel(unit_pixel_x(0.5)), bottom_y}, Probe{left_x, pixel(unit_pixel_y(0.5))},
                            Probe{pixel(unit_pixel_x(0.5)), pixel(unit_pixel_y(0.5))}}) {
    EXPECT_LT(wired.at(probe.x, probe.y).sum() + 30, plain.at(probe.x, probe.y).sum())
        << "edge pixel (" << probe.x << ", " << probe.y << ") " << wired.at(probe.x, probe.y) << " vs "
        << plain.at(probe.x, probe.y);
  }
  // The interior and the background are untouched; about a perimeter's worth
  // of pixels (1 pixel wide lines) changes.
  const int cx = pixel(unit_pixel_x(0.3));
  const int cy = pixel(unit_pixel_y(0.3));
  EXPECT_EQ(wired.at(cx, cy), plain.at(cx, cy));
  EXPECT_EQ(wired.at(100, 100), kWhite);
  int changed = 0;
  for (int y = 0; y < plain.height; ++y) {
    for (int x = 0; x < plain.width; ++x) {
      changed += wired.at(x, y) == plain.at(x, y) ? 0 : 1;
    }
  }
  const double perimeter = kUnitScale * (2.0 + std::sqrt(2.0));
  EXPECT_GT(changed, perimeter);
  EXPECT_LT(changed, 3.0 * perimeter);
}

TEST(Preview, NearerTriangleHidesFartherOneWhateverTheOrder) {
  // Two triangles with the same outline (symmetric under x -> -x), one at z = 0, one at z = -1.
  const std::vector<Eigen::Vector3d> vertices = {{-1, -1, 0},  {1, -1, 0},  {0, 1, 0},
                                                 {-1, -1, -1}, {1, -1, -1}, {0, 1, -1}};
  const TriangleMesh near_first = make_mesh(vertices, {{0, 1, 2}, {3, 4, 5}});
  const TriangleMesh far_first = make_mesh(vertices, {{3, 4, 5}, {0, 1, 2}});
  const Eigen::Vector3f red(0.9f, 0.05f, 0.05f);
  const Eigen::Vector3f blue(0.05f, 0.05f, 0.9f);
  // Extent 2 x 2: s = 405, centre (0, 0) -> (600, 450); the centroid (0, -1/3) -> (600, 585).
  const int x = 600;
  const int y = pixel(450.0 + 405.0 / 3.0);

  PreviewScene scene;
  scene.wireframe = false;
  scene.mesh = &near_first;
  scene.face_colors = {red, blue};
  expect_near(decode(io::render_preview_png(scene, front_view())).at(x, y), srgb(red), 1, "near drawn first");
  scene.mesh = &far_first;
  scene.face_colors = {blue, red};
  expect_near(decode(io::render_preview_png(scene, front_view())).at(x, y), srgb(red), 1, "near drawn last");
  // Seen from behind, the other one is in front.
  PreviewOptions behind = front_view();
  behind.view_direction = Eigen::Vector3d(0, 0, 1);
  expect_near(decode(io::render_preview_png(scene, behind)).at(x, y), srgb(blue), 1, "seen from behind");
}

TEST(Preview, HiddenEdgesAreHidden) {
  // A small triangle behind a big one: its wireframe must not show through.
  const TriangleMesh mesh =
      make_mesh({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {-0.3, -0.5, -0.2}, {0.3, -0.5, -0.2}, {0, 0.2, -0.2}},
                {{0, 1, 2}, {3, 4, 5}});
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = true;
  const Image image = decode(io::render_preview_png(scene, front_view()));
  // The back triangle's bottom edge y = -0.5 -> Y = 652.5; sample its middle.
  const Rgb inside = image.at(600, pixel(450.0 + 405.0 / 3.0));
  for (const int y : {652, 653}) {
    EXPECT_EQ(image.at(600, y), inside) << "hidden edge shows at row " << y;
  }
  // Seen from behind, the small triangle is in front and its edge shows.
  PreviewOptions behind = front_view();
  behind.view_direction = Eigen::Vector3d(0, 0, 1);
  const Image from_behind = decode(io::render_preview_png(scene, behind));
  EXPECT_LT(std::min(from_behind.at(600, 652).sum(), from_behind.at(600, 653).sum()) + 30, inside.sum());
}

TEST(Preview, SharedEdgesLeaveNoCracks) {
  // A square of two triangles at one sample per pixel: the diagonal is covered exactly once.
  const TriangleMesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  scene.face_colors = {{0.2f, 0.4f, 0.6f}, {0.2f, 0.4f, 0.6f}};
  PreviewOptions options = front_view();
  options.supersampling = 1;
  const Image image = decode(io::render_preview_png(scene, options));
  const Rgb face = srgb(scene.face_colors[0]);
  // The square spans X in [195, 1005), Y in [45, 855): 810 x 810 pixel centres.
  // (The diagonal runs exactly through pixel centres (195 + i + 0.5, 854 - i + 0.5).)
  EXPECT_EQ(image.count_near(face, 1), 810 * 810);
  EXPECT_EQ(image.count_not(kWhite), 810 * 810);
  for (int i = 0; i < 810; ++i) {
    const Rgb c = image.at(195 + i, 854 - i);
    ASSERT_TRUE(std::abs(c.r - face.r) <= 1 && std::abs(c.g - face.g) <= 1 && std::abs(c.b - face.b) <= 1)
        << "diagonal pixel " << i << ": " << c;
  }
}

TEST(Preview, PointsAndPolylinesAreDrawnWhereTheyProjectAndDepthTested) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  scene.points = {{0.25, 0.25, 0.0}, {0.1, 0.5, -0.5}};      // on the surface; behind it
  scene.polylines = {{{0.1, 0.6, 0.0}, {0.3, 0.6, 0.0}},     // on the surface
                     {{0.5, 0.1, -0.5}, {0.5, 0.3, -0.5}}};  // behind it
  scene.polyline_color = {0.0f, 0.5f, 0.0f};
  PreviewOptions options = front_view();
  options.point_color = {0.0f, 0.0f, 1.0f};
  const Image image = decode(io::render_preview_png(scene, options));
  const Rgb surface = srgb(options.surface_color);

  // The visible point: a disc of radius 4 around (397.5, 652.5) in point_color.
  expect_near(image.at(397, 652), srgb(options.point_color), 1, "point centre");
  expect_near(image.at(398, 653), srgb(options.point_color), 1, "point disc");
  expect_near(image.at(397 + 8, 652), surface, 1, "beside the point");
  // The visible polyline: 2 pixels wide around Y = 450 - 0.1 * 810 = 369.
  for (const double x : {0.15, 0.2, 0.25}) {
    expect_near(image.at(pixel(unit_pixel_x(x)), 368), srgb(scene.polyline_color), 1, "polyline");
    expect_near(image.at(pixel(unit_pixel_x(x)), 369), srgb(scene.polyline_color), 1, "polyline");
    expect_near(image.at(pixel(unit_pixel_x(x)), 372), surface, 1, "beside the polyline");
  }
  // Behind the surface: hidden.
  expect_near(image.at(pixel(unit_pixel_x(0.1)), pixel(unit_pixel_y(0.5))), surface, 1, "hidden point");
  expect_near(image.at(pixel(unit_pixel_x(0.5)), pixel(unit_pixel_y(0.2))), surface, 1, "hidden polyline");
}

TEST(Preview, DegenerateFacesAndUnreferencedVerticesChangeNothing) {
  const TriangleMesh clean = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}}, {{0, 1, 2}});
  // A far unreferenced vertex (not framed), a repeated index and a zero-area face.
  const TriangleMesh messy =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {1e6, -1e6, 3e5}}, {{0, 1, 2}, {1, 1, 2}, {0, 3, 1}});
  PreviewScene scene;
  scene.mesh = &clean;
  const std::vector<std::uint8_t> expected = io::render_preview_png(scene);
  scene.mesh = &messy;
  EXPECT_EQ(io::render_preview_png(scene), expected);
}

TEST(Preview, BunnyIsFramedAndDeterministic) {
  const io::LoadedMesh bunny = io::read_mesh(test_mesh("bunny.ply"));
  PreviewScene scene;
  scene.mesh = &bunny.mesh;
  const std::vector<std::uint8_t> png = io::render_preview_png(scene);
  const Image image = decode(png);
  const int drawn = image.count_not(kWhite);
  const double fraction = static_cast<double>(drawn) / (1200.0 * 900.0);
  EXPECT_GT(fraction, 0.10);
  EXPECT_LT(fraction, 0.9);
  // Framed: the drawing touches the margin (5 %) on two opposite sides and
  // stays inside it everywhere.
  int min_x = image.width, max_x = -1, min_y = image.height, max_y = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!(image.at(x, y) == kWhite)) {
        min_x = std::min(min_x, x);
        max_x = std::max(max_x, x);
        min_y = std::min(min_y, y);
        max_y = std::max(max_y, y);
      }
    }
  }
  EXPECT_GE(min_x, 58);
  EXPECT_LE(max_x, 1141);
  EXPECT_GE(min_y, 43);
  EXPECT_LE(max_y, 856);
  const bool spans_width = min_x <= 61 && max_x >= 1138;
  const bool spans_height = min_y <= 46 && max_y >= 853;
  EXPECT_TRUE(spans_width || spans_height) << "x " << min_x << ".." << max_x << ", y " << min_y << ".." << max_y;
  // Centred on the axis it does not fill.
  EXPECT_NEAR(0.5 * (min_x + max_x), 599.5, 2.0);
  EXPECT_NEAR(0.5 * (min_y + max_y), 449.5, 2.0);
  // Shaded: many distinct grey levels, not one flat colour.
  std::vector<bool> seen(256 * 3, false);
  int levels = 0;
  for (int y = 0; y < image.height; y += 3) {
    for (int x = 0; x < image.width; x += 3) {
      const int s = image.at(x, y).sum();
      if (!seen[static_cast<std::size_t>(s)]) {
        seen[static_cast<std::size_t>(s)] = true;
        ++levels;
      }
    }
  }
  EXPECT_GT(levels, 100);

  EXPECT_EQ(io::render_preview_png(scene), png) << "same scene, different bytes";
}

TEST(Preview, OverlayScenesAreDeterministicToo) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  scene.vertex_colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  scene.points = {{0.2, 0.2, 0.0}, {0.4, 0.1, 0.0}};
  scene.polylines = {{{0.0, 0.0, 0.0}, {0.3, 0.4, 0.0}, {0.5, 0.5, 0.0}}};
  const std::vector<std::uint8_t> first = io::render_preview_png(scene);
  EXPECT_EQ(io::render_preview_png(scene), first);
  // Lines and points alone (no mesh) draw too.
  PreviewScene overlays_only;
  overlays_only.polylines = scene.polylines;
  overlays_only.points = scene.points;
  EXPECT_GT(decode(io::render_preview_png(overlays_only)).count_not(kWhite), 1000);
}

TEST(Preview, BadRequestsAreErrors) {
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  PreviewOptions options;
  options.width = 799;
  EXPECT_NE(error_message([&] { io::render_preview_png(scene, options); }).find("at least 800 x 600"),
            std::string::npos);
  options.width = 800;
  options.height = 599;
  EXPECT_NE(error_message([&] { io::render_preview_png(scene, options); }).find("(got 800 x 599)"), std::string::npos);
  options.height = 600;
  EXPECT_EQ(decode(io::render_preview_png(scene, options)).width, 800);

  options = {};
  options.supersampling = 0;
  EXPECT_THROW(io::render_preview_png(scene, options), Error);
  options = {};
  options.width = 30000;
  options.height = 30000;
  EXPECT_THROW(io::render_preview_png(scene, options), Error);
  options = {};
  options.margin = std::nan("");
  EXPECT_THROW(io::render_preview_png(scene, options), Error);
  options = {};
  options.up = Eigen::Vector3d(0, 0, 2);
  options.view_direction = Eigen::Vector3d(0, 0, -1);
  EXPECT_NE(error_message([&] { io::render_preview_png(scene, options); }).find("parallel"), std::string::npos);
  options = {};
  options.view_direction = Eigen::Vector3d::Zero();
  EXPECT_THROW(io::render_preview_png(scene, options), Error);

  const TriangleMesh bad_index = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}});
  scene.mesh = &bad_index;
  EXPECT_NE(error_message([&] { io::render_preview_png(scene); }).find("face 0 refers to vertex 3"), std::string::npos);
  scene.mesh = &mesh;
  scene.face_colors = {{1, 0, 0}, {0, 1, 0}};
  EXPECT_NE(error_message([&] { io::render_preview_png(scene); }).find("2 face colours for 1 faces"),
            std::string::npos);
  scene.face_colors.clear();
  scene.vertex_colors = {{1, 0, 0}};
  EXPECT_THROW(io::render_preview_png(scene), Error);
  scene.vertex_colors.clear();
  scene.points = {{std::nan(""), 0, 0}};
  EXPECT_THROW(io::render_preview_png(scene), Error);
  scene.points = {{1e308, 0, 0}, {-1e308, 0, 0}};
  EXPECT_NE(error_message([&] { io::render_preview_png(scene); }).find("too large"), std::string::npos);
  scene.points.clear();

  EXPECT_NE(error_message([] { io::render_preview_png(PreviewScene{}); }).find("nothing to draw"), std::string::npos);
  const TriangleMesh no_faces = make_mesh({{0, 0, 0}}, {});
  PreviewScene empty;
  empty.mesh = &no_faces;
  EXPECT_THROW(io::render_preview_png(empty), Error);
}

TEST(Preview, WritesPngFilesAtomicallyAndOnlyThose) {
  const TempDir dir;
  const TriangleMesh mesh = unit_triangle();
  PreviewScene scene;
  scene.mesh = &mesh;
  io::write_preview_png(dir / "view.PNG", scene);
  const std::string written = read_file(dir / "view.PNG");
  const std::vector<std::uint8_t> expected = io::render_preview_png(scene);
  EXPECT_EQ(written, std::string(expected.begin(), expected.end()));

  for (const char* name : {"view.jpg", "view", "view.png.tmp", ".png"}) {
    EXPECT_NE(error_message([&] { io::write_preview_png(dir / name, scene); }).find(".png"), std::string::npos) << name;
  }
  // A failed render writes nothing.
  PreviewOptions too_small;
  too_small.width = 100;
  EXPECT_THROW(io::write_preview_png(dir / "small.png", scene, too_small), Error);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"view.PNG"});
}

TEST(Preview, ProgressIsReportedAndCanCancel) {
  // A 100 x 100 grid: 20,000 faces, so the faces are asked about several times.
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> faces;
  const int n = 100;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) points.emplace_back(i, j, 0.1 * std::sin(0.3 * i));
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + n + 1;
      faces.emplace_back(a, a + 1, b + 1);
      faces.emplace_back(a, b + 1, b);
    }
  }
  const TriangleMesh mesh = make_mesh(points, faces);
  PreviewScene scene;
  scene.mesh = &mesh;

  PreviewOptions watched;
  std::vector<double> fractions;
  watched.progress = [&fractions](double fraction) {
    fractions.push_back(fraction);
    return true;
  };
  EXPECT_EQ(io::render_preview_png(scene, watched), io::render_preview_png(scene));
  ASSERT_GT(fractions.size(), 50U);  // 5 face blocks, 900 / 16 row blocks
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GT(std::count_if(fractions.begin(), fractions.end(), [](double f) { return f > 0.0 && f < 0.5; }), 2);

  // Refused while the faces are drawn: Cancelled, and no file.
  const TempDir dir;
  PreviewOptions cancelling;
  int calls = 0;
  cancelling.progress = [&calls](double) { return ++calls < 3; };
  EXPECT_THROW(io::write_preview_png(dir / "grid.png", scene, cancelling), Cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace geodual::test
