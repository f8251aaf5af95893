#pragma once
// Preview pictures (`--preview OUT.png`): a small deterministic software
// rasteriser that draws a mesh -- shaded, optionally coloured per face or per
// vertex, with its wireframe -- plus extra polylines (e.g. Voronoi boundaries)
// and points (e.g. sites) into a PNG.
//
// How the picture is made:
//  - orthographic camera; the view is framed automatically on the referenced
//    mesh vertices, the polyline vertices and the points (unreferenced
//    vertices are ignored), centred, with `margin` free on every side;
//  - z-buffer on a supersampled grid (supersampling x supersampling samples
//    per pixel, box-filtered: that is the anti-aliasing of edges, lines and
//    points alike); triangles are scan-converted over their bounding box with
//    exact integer edge functions (1/256 sample) and a top-left fill rule, so
//    shared edges are neither left open nor drawn twice;
//  - two-sided headlight Lambert shading, ambient + (1 - ambient) |n . v|, so
//    back faces are lit like front faces; normals are the face's (flat) or
//    interpolated area-weighted vertex normals (smooth);
//  - the wireframe is drawn inside each visible triangle within half the width
//    of its edges (screen-space distance), so hidden edges are hidden exactly;
//    on dense meshes it fades out (see wireframe_fade_pixels);
//  - polylines (round joins) and points (discs with a dark rim) are depth
//    tested against the surface as tubes and spheres of their screen radius,
//    pulled towards the camera by overlay_depth_bias;
//  - colours are linear RGB in [0, 1] (values outside are clamped) and are
//    written sRGB-encoded, 8-bit RGB, no alpha.
// Same scene and options give the same bytes. Memory: 8 bytes per sample
// (1200 x 900 at 3 x 3: 78 MB), 24 bytes per vertex for the projection and 24
// more for smooth normals.

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

namespace geodual::io {

/// What to draw: plain data, nothing owned but the overlays.
struct PreviewScene {
  const TriangleMesh* mesh = nullptr;                   ///< may be null when only lines or points are drawn
  std::vector<Eigen::Vector3f> face_colors;             ///< optional, one per face, linear 0..1
  std::vector<Eigen::Vector3f> vertex_colors;           ///< optional, one per vertex (used if face_colors is empty)
  bool wireframe = true;                                ///< draw the mesh edges
  std::vector<std::vector<Eigen::Vector3d>> polylines;  ///< optional extra lines (e.g. Voronoi boundaries)
  Eigen::Vector3f polyline_color{0.05f, 0.05f, 0.05f};
  std::vector<Eigen::Vector3d> points;  ///< optional points (e.g. sites), drawn as small discs
};

/// How to draw it. Sizes in pixels are output pixels (not samples).
struct PreviewOptions {
  int width = 1200;  ///< picture width in pixels, at least 800
  int height = 900;  ///< picture height in pixels, at least 600

  /// Direction the camera looks in (from the camera into the scene); need not
  /// be unit length. Default: a three-quarter view from front-right-above for
  /// +Y up, +Z front models, i.e. looking along (-0.5, -0.4, -1).
  std::optional<Eigen::Vector3d> view_direction;
  /// Up direction of the picture (projected perpendicular to the view).
  /// Default +Y, or +Z when the view is (nearly) along Y. An explicit up
  /// parallel to the view direction is an error.
  std::optional<Eigen::Vector3d> up;
  /// Free border on every side, as a fraction of the picture's width and of
  /// its height, in [0, 0.4]. The scene's projection is scaled uniformly to fit
  /// the remaining (1 - 2 margin) width x (1 - 2 margin) height and centred.
  double margin = 0.05;
  /// Samples per pixel along each axis, 1 to 4 (anti-aliasing).
  int supersampling = 3;

  Eigen::Vector3f background_color{1.0f, 1.0f, 1.0f};
  /// Colour of the surface when the scene has neither face nor vertex colours.
  Eigen::Vector3f surface_color{0.62f, 0.66f, 0.74f};
  float ambient = 0.2f;        ///< in [0, 1]: light that faces turned away from the camera still get
  bool smooth_shading = true;  ///< interpolated vertex normals; false: flat per face

  Eigen::Vector3f wireframe_color{0.04f, 0.04f, 0.06f};
  float wireframe_width = 1.0f;    ///< pixels, in (0, 16]
  float wireframe_opacity = 0.6f;  ///< in [0, 1]
  /// Dense meshes would turn black under their wireframe: when the mean
  /// projected edge is shorter than this many pixels, the wireframe's opacity
  /// falls linearly, to nothing at a quarter of it. 0 keeps it always.
  float wireframe_fade_pixels = 4.0f;

  float polyline_width = 2.0f;  ///< pixels, in (0, 32]
  Eigen::Vector3f point_color{0.9f, 0.12f, 0.08f};
  float point_radius = 4.0f;  ///< pixels, in (0, 64]; the disc has a 1-pixel rim in polyline_color
  /// Polylines and points are moved this fraction of the bounding-box diagonal
  /// towards the camera before the depth test, in [0, 1].
  double overlay_depth_bias = 0.002;

  /// Asked with the fraction done in [0, 1] about every 4096 faces drawn and
  /// every 16 rows resolved; returning false stops with geodual::Cancelled.
  std::function<bool(double)> progress;
};

/// Renders the scene and returns the bytes of a PNG file (8-bit RGB).
/// Throws geodual::Error for: width < 800 or height < 600 (or more than
/// 2^26 samples in all), options out of the ranges above, nothing to draw (no
/// face, polyline vertex or point), face indices out of range, colour counts
/// that do not match the faces / vertices, non-finite coordinates or colours.
/// Degenerate faces and unreferenced vertices are fine. Throws
/// geodual::Cancelled when options.progress says stop.
std::vector<std::uint8_t> render_preview_png(const PreviewScene& scene, const PreviewOptions& options = {});

/// Renders and writes the PNG atomically (see atomic_file.hpp). The path must
/// end in .png (any case); anything else is a geodual::Error, raised before
/// rendering, and nothing is written when rendering fails.
void write_preview_png(const std::filesystem::path& path, const PreviewScene& scene,
                       const PreviewOptions& options = {});

}  // namespace geodual::io
