// The preview renderer: checks the request, frames an orthographic camera on
// the scene, fills the visibility buffer (faces, then polylines and points),
// shades every visible sample, box-filters the samples to pixels and encodes
// the PNG. See preview.hpp for what the picture shows.

#include "geodual/io/preview.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include "preview_png.hpp"
#include "preview_raster.hpp"
#include "str_cat.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/mesh/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace geodual::io {
namespace {

using detail::ScreenVertex;
using detail::str_cat;

constexpr int kMinWidth = 800;
constexpr int kMinHeight = 600;
constexpr int kMaxSupersampling = 4;
constexpr double kMaxSamples = static_cast<double>(std::int64_t{1} << 26);  // 512 MB of buffer

template <class... Pieces>
[[noreturn]] void fail(const Pieces&... pieces) {
  throw Error(str_cat("preview: ", pieces...));
}

bool in_range(double value, double low, double high) { return value >= low && value <= high; }  // false for NaN

bool finite_color(const Eigen::Vector3f& c) { return c.allFinite(); }

void check_range(const char* name, double value, double low, double high) {
  if (!in_range(value, low, high)) {
    fail(name, " must be in [", low, ", ", high, "] (got ", value, ")");
  }
}

void check_positive(const char* name, double value, double high) {
  if (!(value > 0.0 && value <= high)) {
    fail(name, " must be in (0, ", high, "] (got ", value, ")");
  }
}

void check_color(const char* name, const Eigen::Vector3f& c) {
  if (!finite_color(c)) {
    fail(name, " has a non-finite component");
  }
}

void check_options(const PreviewOptions& options) {
  if (options.width < kMinWidth || options.height < kMinHeight) {
    fail("the picture must be at least ", kMinWidth, " x ", kMinHeight, " pixels (got ", options.width, " x ",
         options.height, ")");
  }
  if (options.supersampling < 1 || options.supersampling > kMaxSupersampling) {
    fail("supersampling must be 1 to ", kMaxSupersampling, " (got ", options.supersampling, ")");
  }
  const double samples = static_cast<double>(options.width) * static_cast<double>(options.height) *
                         static_cast<double>(options.supersampling * options.supersampling);
  if (samples > kMaxSamples) {
    fail(options.width, " x ", options.height, " pixels at ", options.supersampling, " x ", options.supersampling,
         " supersampling is more than 2^26 samples; choose a smaller picture or less "
         "supersampling");
  }
  check_range("margin", options.margin, 0.0, 0.4);
  check_range("ambient", options.ambient, 0.0, 1.0);
  check_positive("wireframe_width", options.wireframe_width, 16.0);
  check_range("wireframe_opacity", options.wireframe_opacity, 0.0, 1.0);
  check_range("wireframe_fade_pixels", options.wireframe_fade_pixels, 0.0, 1000.0);
  check_positive("polyline_width", options.polyline_width, 32.0);
  check_positive("point_radius", options.point_radius, 64.0);
  check_range("overlay_depth_bias", options.overlay_depth_bias, 0.0, 1.0);
  check_color("background_color", options.background_color);
  check_color("surface_color", options.surface_color);
  check_color("wireframe_color", options.wireframe_color);
  check_color("point_color", options.point_color);
  if (options.view_direction && !(options.view_direction->allFinite() && options.view_direction->norm() > 0.0)) {
    fail("view_direction must be a finite, non-zero vector");
  }
  if (options.up && !(options.up->allFinite() && options.up->norm() > 0.0)) {
    fail("up must be a finite, non-zero vector");
  }
}

void check_scene(const PreviewScene& scene) {
  check_color("polyline_color", scene.polyline_color);
  const TriangleMesh* mesh = scene.mesh;
  if (mesh == nullptr && (!scene.face_colors.empty() || !scene.vertex_colors.empty())) {
    fail("face or vertex colours given without a mesh");
  }
  std::size_t face_count = 0;
  if (mesh != nullptr) {
    const Index vertex_count = mesh->num_vertices();
    face_count = static_cast<std::size_t>(mesh->num_faces());
    for (Index v = 0; v < vertex_count; ++v) {
      if (!mesh->vertices.row(v).allFinite()) {
        fail("vertex ", v, " has a non-finite coordinate");
      }
    }
    for (Index f = 0; f < mesh->num_faces(); ++f) {
      for (int corner = 0; corner < 3; ++corner) {
        const Index v = mesh->faces(f, corner);
        if (v < 0 || v >= vertex_count) {
          fail("face ", f, " refers to vertex ", v, ", but the mesh has ", vertex_count, " vertices");
        }
      }
    }
    if (!scene.face_colors.empty() && scene.face_colors.size() != face_count) {
      fail(scene.face_colors.size(), " face colours for ", face_count, " faces");
    }
    if (!scene.vertex_colors.empty() && scene.vertex_colors.size() != static_cast<std::size_t>(vertex_count)) {
      fail(scene.vertex_colors.size(), " vertex colours for ", vertex_count, " vertices");
    }
    for (std::size_t i = 0; i < scene.face_colors.size(); ++i) {
      if (!finite_color(scene.face_colors[i])) {
        fail("face colour ", i, " has a non-finite component");
      }
    }
    for (std::size_t i = 0; i < scene.vertex_colors.size(); ++i) {
      if (!finite_color(scene.vertex_colors[i])) {
        fail("vertex colour ", i, " has a non-finite component");
      }
    }
  }
  std::size_t polyline_vertices = 0;
  for (std::size_t l = 0; l < scene.polylines.size(); ++l) {
    for (std::size_t i = 0; i < scene.polylines[l].size(); ++i) {
      if (!scene.polylines[l][i].allFinite()) {
        fail("polyline ", l, " vertex ", i, " has a non-finite coordinate");
      }
    }
    polyline_vertices += scene.polylines[l].size();
  }
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    if (!scene.points[i].allFinite()) {
      fail("point ", i, " has a non-finite coordinate");
    }
  }
  if (face_count == 0 && polyline_vertices == 0 && scene.points.empty()) {
    fail("nothing to draw (no face, polyline vertex or point)");
  }
}

/// Orthographic camera, world -> sample grid. Depth is measured along the view
/// direction from the nearest framed point, in units of the framed bounding
/// box's diagonal, so that it lies in [0, 1].
struct Camera {
  Eigen::Vector3d right;
  Eigen::Vector3d up;
  Eigen::Vector3d view;           // unit, into the scene
  double samples_per_unit = 1.0;  // world length -> samples
  double center_u = 0.0;
  double center_v = 0.0;
  double near_depth = 0.0;
  double diagonal = 1.0;
  double half_width = 0.0;   // samples
  double half_height = 0.0;  // samples

  ScreenVertex project(const Eigen::Vector3d& p) const {
    return {half_width + (p.dot(right) - center_u) * samples_per_unit,
            half_height - (p.dot(up) - center_v) * samples_per_unit,
            static_cast<float>((p.dot(view) - near_depth) / diagonal)};
  }
};

Eigen::Vector3d default_view_direction() { return Eigen::Vector3d(-0.5, -0.4, -1.0); }

Camera frame_scene(const PreviewScene& scene, const PreviewOptions& options) {
  Camera camera;
  camera.view = options.view_direction.value_or(default_view_direction()).stableNormalized();
  Eigen::Vector3d up = options.up.value_or(Eigen::Vector3d::UnitY()).stableNormalized();
  constexpr double kParallel = 1.0 - 1.0e-9;
  if (std::abs(up.dot(camera.view)) > kParallel) {
    if (options.up) {
      fail("up is parallel to view_direction");
    }
    up = Eigen::Vector3d::UnitZ();
  }
  camera.right = camera.view.cross(up).normalized();
  camera.up = camera.right.cross(camera.view);

  // Extent of everything framed: referenced vertices, polyline vertices, points.
  constexpr double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(inf);  // in (u, v, depth)
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-inf);
  Eigen::Vector3d world_lo = Eigen::Vector3d::Constant(inf);
  Eigen::Vector3d world_hi = Eigen::Vector3d::Constant(-inf);
  const auto include = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q(p.dot(camera.right), p.dot(camera.up), p.dot(camera.view));
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
    world_lo = world_lo.cwiseMin(p);
    world_hi = world_hi.cwiseMax(p);
  };
  if (scene.mesh != nullptr && scene.mesh->num_faces() > 0) {
    const TriangleMesh& mesh = *scene.mesh;
    std::vector<bool> referenced(static_cast<std::size_t>(mesh.num_vertices()), false);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      for (int corner = 0; corner < 3; ++corner) {
        referenced[static_cast<std::size_t>(mesh.faces(f, corner))] = true;
      }
    }
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      if (referenced[static_cast<std::size_t>(v)]) {
        include(mesh.vertices.row(v).transpose());
      }
    }
  }
  for (const auto& polyline : scene.polylines) {
    for (const Eigen::Vector3d& p : polyline) {
      include(p);
    }
  }
  for (const Eigen::Vector3d& p : scene.points) {
    include(p);
  }

  if (!(hi - lo).allFinite() || !(world_hi - world_lo).allFinite()) {
    fail("the scene's coordinates are too large to frame (their extent overflows a double)");
  }

  const int ss = options.supersampling;
  const double usable_width = options.width * (1.0 - 2.0 * options.margin);
  const double usable_height = options.height * (1.0 - 2.0 * options.margin);
  const double extent_u = hi.x() - lo.x();
  const double extent_v = hi.y() - lo.y();
  double pixels_per_unit = inf;
  if (extent_u > 0.0) {
    pixels_per_unit = std::min(pixels_per_unit, usable_width / extent_u);
  }
  if (extent_v > 0.0) {
    pixels_per_unit = std::min(pixels_per_unit, usable_height / extent_v);
  }
  if (!std::isfinite(pixels_per_unit)) {
    pixels_per_unit = 1.0;  // a single point: any scale frames it
  }
  camera.samples_per_unit = pixels_per_unit * ss;
  camera.center_u = 0.5 * (lo.x() + hi.x());
  camera.center_v = 0.5 * (lo.y() + hi.y());
  camera.near_depth = lo.z();
  const double diagonal = (world_hi - world_lo).norm();
  camera.diagonal = diagonal > 0.0 && std::isfinite(diagonal) ? diagonal : 1.0;
  camera.half_width = 0.5 * options.width * ss;
  camera.half_height = 0.5 * options.height * ss;
  return camera;
}

/// Unit area-weighted vertex normals (zero where no face with area touches).
std::vector<Eigen::Vector3d> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> normals(static_cast<std::size_t>(mesh.num_vertices()), Eigen::Vector3d::Zero());
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const Eigen::Vector3d n = (b - a).cross(c - a);  // twice the area times the unit normal
    for (int corner = 0; corner < 3; ++corner) {
      normals[static_cast<std::size_t>(mesh.faces(f, corner))] += n;
    }
  }
  for (Eigen::Vector3d& n : normals) {
    const double length = n.norm();
    n = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }
  return normals;
}

/// Mean length of the drawn faces' edges on screen, in pixels (0 if none).
double mean_edge_pixels(const TriangleMesh& mesh, const std::vector<ScreenVertex>& screen, int ss) {
  double sum = 0.0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const ScreenVertex& p = screen[static_cast<std::size_t>(mesh.faces(f, corner))];
      const ScreenVertex& q = screen[static_cast<std::size_t>(mesh.faces(f, (corner + 1) % 3))];
      sum += std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y));
    }
  }
  return mesh.num_faces() > 0 ? sum / (3.0 * static_cast<double>(mesh.num_faces()) * ss) : 0.0;
}

/// Shading of the visible face samples. Per-face quantities are cached while
/// consecutive samples show the same face (the common case).
class FaceShader {
 public:
  FaceShader(const PreviewScene& scene, const PreviewOptions& options, const Camera& camera,
             const std::vector<ScreenVertex>& screen, const std::vector<Eigen::Vector3d>& normals, float wire_alpha)
      : mesh_(*scene.mesh),
        scene_(scene),
        options_(options),
        camera_(camera),
        screen_(screen),
        normals_(normals),
        wire_alpha_(wire_alpha),
        wire_half_width_(0.5 * options.wireframe_width * options.supersampling) {}

  Eigen::Vector3f shade(Index face, double x, double y) {
    if (face != face_) {
      set_up(face);
    }
    // Barycentric coordinates of the sample centre (clamped: snapping can put
    // a sample a hair outside the unsnapped triangle).
    double l[3];
    if (degenerate_) {
      l[0] = l[1] = l[2] = 1.0 / 3.0;
    } else {
      for (int i = 0; i < 3; ++i) {
        const ScreenVertex& p = corner_[(i + 1) % 3];
        const ScreenVertex& q = corner_[(i + 2) % 3];
        l[i] = std::max(((p.x - x) * (q.y - y) - (p.y - y) * (q.x - x)) * inverse_area_, 0.0);
      }
      const double sum = l[0] + l[1] + l[2];
      for (double& value : l) {
        value /= sum;
      }
    }

    Eigen::Vector3f albedo = options_.surface_color;
    if (!scene_.face_colors.empty()) {
      albedo = scene_.face_colors[static_cast<std::size_t>(face)];
    } else if (!scene_.vertex_colors.empty()) {
      albedo = static_cast<float>(l[0]) * scene_.vertex_colors[vertex_[0]] +
               static_cast<float>(l[1]) * scene_.vertex_colors[vertex_[1]] +
               static_cast<float>(l[2]) * scene_.vertex_colors[vertex_[2]];
    }
    albedo = albedo.cwiseMax(0.0f).cwiseMin(1.0f);

    Eigen::Vector3d normal = face_normal_;
    if (options_.smooth_shading) {
      const Eigen::Vector3d n = l[0] * normals_[vertex_[0]] + l[1] * normals_[vertex_[1]] + l[2] * normals_[vertex_[2]];
      const double length = n.norm();
      if (length > 1.0e-6) {
        normal = n / length;
      }
    }
    const double lambert = std::abs(normal.dot(camera_.view));  // two-sided headlight
    const auto light = static_cast<float>(options_.ambient + (1.0 - options_.ambient) * lambert);
    Eigen::Vector3f color = albedo * light;

    if (wire_alpha_ > 0.0f) {
      double distance = 0.0;  // to the nearest edge, in samples
      if (!degenerate_) {
        distance = std::min({l[0] * height_[0], l[1] * height_[1], l[2] * height_[2]});
      }
      // Coverage ramps over one sample so that the band integrates to its width.
      const double coverage = std::clamp(wire_half_width_ + 0.5 - distance, 0.0, 1.0);
      const auto alpha = static_cast<float>(coverage) * wire_alpha_;
      color = (1.0f - alpha) * color + alpha * options_.wireframe_color.cwiseMax(0.0f).cwiseMin(1.0f);
    }
    return color;
  }

 private:
  void set_up(Index face) {
    face_ = face;
    for (int i = 0; i < 3; ++i) {
      vertex_[i] = static_cast<std::size_t>(mesh_.faces(face, i));
      corner_[i] = screen_[vertex_[i]];
    }
    const double area2 = (corner_[1].x - corner_[0].x) * (corner_[2].y - corner_[0].y) -
                         (corner_[1].y - corner_[0].y) * (corner_[2].x - corner_[0].x);
    degenerate_ = !(std::abs(area2) > 1.0e-12);
    inverse_area_ = degenerate_ ? 0.0 : 1.0 / area2;
    for (int i = 0; i < 3; ++i) {
      const ScreenVertex& p = corner_[(i + 1) % 3];
      const ScreenVertex& q = corner_[(i + 2) % 3];
      const double edge = std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y));
      height_[i] = edge > 0.0 ? std::abs(area2) / edge : 0.0;  // corner i's distance to its opposite edge
    }
    const Eigen::Vector3d a = mesh_.vertices.row(static_cast<Index>(vertex_[0])).transpose();
    const Eigen::Vector3d b = mesh_.vertices.row(static_cast<Index>(vertex_[1])).transpose();
    const Eigen::Vector3d c = mesh_.vertices.row(static_cast<Index>(vertex_[2])).transpose();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    face_normal_ = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d(-camera_.view);
  }

  const TriangleMesh& mesh_;
  const PreviewScene& scene_;
  const PreviewOptions& options_;
  const Camera& camera_;
  const std::vector<ScreenVertex>& screen_;
  const std::vector<Eigen::Vector3d>& normals_;
  float wire_alpha_;
  double wire_half_width_;

  Index face_ = -1;
  std::size_t vertex_[3] = {0, 0, 0};
  ScreenVertex corner_[3];
  bool degenerate_ = true;
  double inverse_area_ = 0.0;
  double height_[3] = {0.0, 0.0, 0.0};
  Eigen::Vector3d face_normal_ = Eigen::Vector3d::UnitZ();
};

/// Linear [0, 1] -> 8-bit sRGB through a table of 2^16 + 1 entries (the
/// quantisation moves no byte by more than one; the table is built once).
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (std::size_t i = 0; i < table_.size(); ++i) {
      const double s = srgb_from_linear(static_cast<float>(i) / kSteps);
      table_[i] = static_cast<std::uint8_t>(std::lround(s * 255.0));
    }
  }
  std::uint8_t operator()(float linear) const {
    const float c = linear > 0.0f ? std::min(linear, 1.0f) : 0.0f;  // NaN -> 0: never index out of range
    return table_[static_cast<std::size_t>(std::lround(c * static_cast<float>(kSteps)))];
  }

 private:
  static constexpr int kSteps = 65536;
  std::array<std::uint8_t, kSteps + 1> table_{};
};

const SrgbEncoder& srgb_encoder() {
  static const SrgbEncoder encoder;
  return encoder;
}

void draw_overlays(const PreviewScene& scene, const PreviewOptions& options, const Camera& camera,
                   detail::SampleBuffer& buffer) {
  const int ss = options.supersampling;
  // Overlays are tubes and spheres of their screen radius: pull them towards
  // the camera by that radius plus the bias before testing depth.
  const auto pulled = [&](const Eigen::Vector3d& p, double radius_samples) {
    ScreenVertex v = camera.project(p);
    const double pull = options.overlay_depth_bias + radius_samples / camera.samples_per_unit / camera.diagonal;
    v.depth = static_cast<float>(v.depth - pull);
    return v;
  };
  const double line_radius = 0.5 * options.polyline_width * ss;
  for (const auto& polyline : scene.polylines) {
    for (std::size_t i = 0; i < polyline.size(); ++i) {
      const ScreenVertex a = pulled(polyline[i], line_radius);
      detail::rasterise_disc(buffer, a.x, a.y, a.depth, line_radius, 0.0, detail::kPolylineId,
                             detail::kPolylineId);  // round join
      if (i + 1 < polyline.size()) {
        detail::rasterise_thick_segment(buffer, a, pulled(polyline[i + 1], line_radius), line_radius,
                                        detail::kPolylineId);
      }
    }
  }
  const double point_radius = static_cast<double>(options.point_radius) * ss;
  const double rim = std::min(1.0 * ss, 0.5 * point_radius);
  for (const Eigen::Vector3d& p : scene.points) {
    const ScreenVertex v = pulled(p, point_radius);
    detail::rasterise_disc(buffer, v.x, v.y, v.depth, point_radius, rim, detail::kPointFillId, detail::kPointRimId);
  }
}

std::vector<std::uint8_t> render_rgb(const PreviewScene& scene, const PreviewOptions& options) {
  const Camera camera = frame_scene(scene, options);
  const int ss = options.supersampling;
  detail::SampleBuffer buffer(options.width * ss, options.height * ss);

  // Drawing the faces is the first half of the work, resolving the rows the second.
  const auto ask = [&options](double done) {
    if (options.progress && !options.progress(done)) throw Cancelled("preview cancelled");
  };
  ask(0.0);

  std::vector<ScreenVertex> screen;
  std::vector<Eigen::Vector3d> normals;
  float wire_alpha = 0.0f;
  const bool has_faces = scene.mesh != nullptr && scene.mesh->num_faces() > 0;
  if (has_faces) {
    const TriangleMesh& mesh = *scene.mesh;
    screen.resize(static_cast<std::size_t>(mesh.num_vertices()));
    for (Index v = 0; v < mesh.num_vertices(); ++v) {
      screen[static_cast<std::size_t>(v)] = camera.project(mesh.vertices.row(v).transpose());
    }
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (f % 4096 == 0) ask(0.5 * static_cast<double>(f) / static_cast<double>(mesh.num_faces()));
      detail::rasterise_triangle(buffer, screen[static_cast<std::size_t>(mesh.faces(f, 0))],
                                 screen[static_cast<std::size_t>(mesh.faces(f, 1))],
                                 screen[static_cast<std::size_t>(mesh.faces(f, 2))], f);
    }
    if (options.smooth_shading) {
      normals = vertex_normals(mesh);
    }
    if (scene.wireframe) {
      double fade = 1.0;
      if (options.wireframe_fade_pixels > 0.0f) {
        const double full = options.wireframe_fade_pixels;
        fade = std::clamp((mean_edge_pixels(mesh, screen, ss) - 0.25 * full) / (0.75 * full), 0.0, 1.0);
      }
      wire_alpha = static_cast<float>(fade * options.wireframe_opacity);
    }
  }
  draw_overlays(scene, options, camera, buffer);

  // Resolve: shade each sample, average each pixel's samples in linear light.
  const auto clamp01 = [](const Eigen::Vector3f& c) -> Eigen::Vector3f { return c.cwiseMax(0.0f).cwiseMin(1.0f); };
  const Eigen::Vector3f background = clamp01(options.background_color);
  const Eigen::Vector3f polyline = clamp01(scene.polyline_color);
  const Eigen::Vector3f point = clamp01(options.point_color);
  const SrgbEncoder& encode_srgb = srgb_encoder();
  const std::uint8_t background_bytes[3] = {encode_srgb(background.x()), encode_srgb(background.y()),
                                            encode_srgb(background.z())};
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height) * 3);
  std::optional<FaceShader> shader;
  if (has_faces) {
    shader.emplace(scene, options, camera, screen, normals, wire_alpha);
  }
  const float inverse_count = 1.0f / static_cast<float>(ss * ss);
  for (int py = 0; py < options.height; ++py) {
    if (py % 16 == 0) ask(0.5 + 0.5 * py / options.height);
    for (int px = 0; px < options.width; ++px) {
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      bool all_background = true;
      for (int sy = py * ss; sy < (py + 1) * ss; ++sy) {
        for (int sx = px * ss; sx < (px + 1) * ss; ++sx) {
          const std::int32_t id = buffer.id[buffer.index(sx, sy)];
          if (id >= 0) {
            sum += shader->shade(id, sx + 0.5, sy + 0.5);
          } else if (id == detail::kBackgroundId) {
            sum += background;
            continue;
          } else if (id == detail::kPolylineId || id == detail::kPointRimId) {
            sum += polyline;
          } else {
            sum += point;
          }
          all_background = false;
        }
      }
      std::uint8_t* out =
          &rgb[(static_cast<std::size_t>(py) * static_cast<std::size_t>(options.width) + static_cast<std::size_t>(px)) *
               3];
      if (all_background) {
        std::copy(background_bytes, background_bytes + 3, out);
      } else {
        const Eigen::Vector3f mean = sum * inverse_count;
        out[0] = encode_srgb(mean.x());
        out[1] = encode_srgb(mean.y());
        out[2] = encode_srgb(mean.z());
      }
    }
  }
  ask(1.0);
  return rgb;
}

}  // namespace

std::vector<std::uint8_t> render_preview_png(const PreviewScene& scene, const PreviewOptions& options) {
  check_options(options);
  check_scene(scene);
  const std::vector<std::uint8_t> rgb = render_rgb(scene, options);
  return detail::encode_png_rgb(rgb, options.width, options.height);
}

void write_preview_png(const std::filesystem::path& path, const PreviewScene& scene, const PreviewOptions& options) {
  if (!path.has_filename() || lowercase_extension(path) != ".png") {
    throw Error(str_cat(path.string(), ": a preview is written as PNG; give a path ending in .png"));
  }
  const std::vector<std::uint8_t> png = render_preview_png(scene, options);
  write_file_atomically(path, [&png](std::ostream& stream) {
    stream.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  });
}

}  // namespace geodual::io
