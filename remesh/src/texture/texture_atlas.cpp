#include "geodual/remesh/texture_atlas.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "texture/atlas_charts.hpp"
#include "texture/atlas_lscm.hpp"
#include "texture/atlas_packing.hpp"
#include "texture/texel_raster.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace geodual::remesh {
namespace {

using detail::ChartSurface;

/// A chart flattened: per chart vertex its point, triangles counter-clockwise (y up).
struct FlatChart {
  ChartSurface surface;
  std::vector<Eigen::Vector2d> points;
};

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * cross(b - a, c - a);
}

void check_mesh(const TriangleMesh& mesh) {
  if (mesh.num_faces() == 0) throw Error("make_texture_atlas: the mesh has no faces");
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.faces(f, k);
      if (v < 0 || v >= mesh.num_vertices()) {
        throw Error("make_texture_atlas: face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                    ", but the mesh has " + std::to_string(mesh.num_vertices()) + " vertices");
      }
      if (!mesh.vertices.row(v).allFinite()) {
        throw Error("make_texture_atlas: vertex " + std::to_string(v) + " of face " + std::to_string(f) +
                    " has a coordinate that is not finite");
      }
    }
  }
}

/// A chart of one face laid out from its side lengths; a face without an
/// area gets a small right triangle instead, so that no point is NaN and no
/// triangle is degenerate.
std::vector<Eigen::Vector2d> lay_out_face(const TriangleMesh& mesh, Index f) {
  const Eigen::Vector3d p0 = mesh.vertices.row(mesh.faces(f, 0));
  const Eigen::Vector3d p1 = mesh.vertices.row(mesh.faces(f, 1));
  const Eigen::Vector3d p2 = mesh.vertices.row(mesh.faces(f, 2));
  const double base = (p1 - p0).norm();
  const double side = (p2 - p0).norm();
  if (has_positive_area(mesh, f) && base > 0) {
    const double x = (p2 - p0).dot(p1 - p0) / base;
    const double y = std::sqrt(std::max(0.0, side * side - x * x));
    if (y > 0) return {{0, 0}, {base, 0}, {x, y}};
  }
  const double longest = std::max({base, side, (p2 - p1).norm()});
  const double leg = longest > 0 ? longest : 1.0;
  return {{0, 0}, {leg, 0}, {0, leg}};
}

/// Whether every triangle is counter-clockwise with an area that is not
/// negligible beside the chart's mean, and every point finite.
bool keeps_orientation(const ChartSurface& chart, const std::vector<Eigen::Vector2d>& points) {
  double total = 0;
  for (const auto& [a, b, c] : chart.corners) total += signed_area(points[a], points[b], points[c]);
  if (!std::isfinite(total) || !(total > 0)) return false;
  const double smallest = 1e-9 * total / static_cast<double>(chart.corners.size());
  for (const auto& [a, b, c] : chart.corners) {
    if (!(signed_area(points[a], points[b], points[c]) > smallest)) return false;
  }
  return true;
}

/// Whether the chart's boundary is a simple polygon: no two boundary edges
/// meet but at a shared end. With every triangle counter-clockwise, that
/// makes the flattening one to one. A sweep over the edges sorted by their
/// leftmost x.
bool boundary_is_simple(const ChartSurface& chart, const std::vector<Eigen::Vector2d>& points) {
  // Boundary edges: chart sides (vertex pairs) that only one face has.
  std::vector<std::array<Index, 2>> sides;
  sides.reserve(3 * chart.corners.size());
  for (const auto& corners : chart.corners) {
    for (int k = 0; k < 3; ++k) {
      sides.push_back({std::min(corners[k], corners[(k + 1) % 3]), std::max(corners[k], corners[(k + 1) % 3])});
    }
  }
  std::sort(sides.begin(), sides.end());
  std::vector<std::array<Index, 2>> edges;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    if (j - i == 1) edges.push_back(sides[i]);
    i = j;
  }
  auto left = [&](const std::array<Index, 2>& e) { return std::min(points[e[0]].x(), points[e[1]].x()); };
  auto right = [&](const std::array<Index, 2>& e) { return std::max(points[e[0]].x(), points[e[1]].x()); };
  std::sort(edges.begin(), edges.end(), [&](const auto& a, const auto& b) { return left(a) < left(b); });
  auto orient = [&](Index a, Index b, Index c) {
    const double value = cross(points[b] - points[a], points[c] - points[a]);
    return (value > 0) - (value < 0);
  };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [p, q] = edges[i];
    const double end = right(edges[i]);
    for (std::size_t j = i + 1; j < edges.size() && left(edges[j]) <= end; ++j) {
      const auto [r, s] = edges[j];
      if (p == r || p == s || q == r || q == s) continue;
      const double low = std::max(std::min(points[p].y(), points[q].y()), std::min(points[r].y(), points[s].y()));
      const double high = std::min(std::max(points[p].y(), points[q].y()), std::max(points[r].y(), points[s].y()));
      if (low > high) continue;
      if (orient(p, q, r) * orient(p, q, s) <= 0 && orient(r, s, p) * orient(r, s, q) <= 0) return false;
    }
  }
  return true;
}

/// The chart flattened without flips or overlaps; empty where LSCM cannot.
std::vector<Eigen::Vector2d> flatten(const TriangleMesh& mesh, const ChartSurface& chart) {
  if (chart.faces.size() == 1) return lay_out_face(mesh, chart.faces.front());
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(chart.source_vertex.size());
  for (const Index v : chart.source_vertex) positions.emplace_back(mesh.vertices.row(v));
  std::vector<Eigen::Vector2d> points = detail::lscm_parameterisation(positions, chart.corners);
  if (points.empty()) return {};
  if (!keeps_orientation(chart, points) || !boundary_is_simple(chart, points)) return {};
  return points;
}

/// Charts grown, split until each is a disk that LSCM flattens one to one.
std::vector<FlatChart> flat_charts(const TriangleMesh& mesh, const AtlasOptions& options) {
  const detail::FaceNeighbours neighbours = detail::chart_neighbours(mesh, options.seams);
  std::vector<std::vector<Index>> pending = detail::grow_charts(mesh, neighbours, options.max_chart_angle);
  std::reverse(pending.begin(), pending.end());  // taken from the back, in growing order
  std::vector<Index> face_slot(mesh.num_faces(), -1);
  std::vector<FlatChart> charts;
  while (!pending.empty()) {
    ChartSurface surface = detail::chart_surface(mesh, neighbours, std::move(pending.back()), face_slot);
    pending.pop_back();
    if (surface.is_disk()) {
      std::vector<Eigen::Vector2d> points = flatten(mesh, surface);
      if (!points.empty()) {
        charts.push_back({std::move(surface), std::move(points)});
        continue;
      }
    }
    if (surface.faces.size() < 2) {  // a single face is a disk and always laid out
      throw Error("make_texture_atlas: face " + std::to_string(surface.faces.front()) + " cannot be flattened");
    }
    auto parts = detail::split_chart(neighbours, surface.faces, face_slot);
    pending.push_back(std::move(parts[1]));
    pending.push_back(std::move(parts[0]));
  }
  return charts;
}

/// Each chart scaled to one density (flattened area = 3D area) and turned to
/// image orientation: y down, so counter-clockwise triangles stay
/// counter-clockwise as seen in the image.
void to_image_density(const TriangleMesh& mesh, std::vector<FlatChart>& charts) {
  for (FlatChart& chart : charts) {
    double area = 0, flat_area = 0;
    for (std::size_t i = 0; i < chart.surface.faces.size(); ++i) {
      const auto& [a, b, c] = chart.surface.corners[i];
      area += face_area(mesh, chart.surface.faces[i]);
      flat_area += signed_area(chart.points[a], chart.points[b], chart.points[c]);
    }
    const double scale = area > 0 ? std::sqrt(area / flat_area) : 1.0;
    for (Eigen::Vector2d& p : chart.points) p = Eigen::Vector2d(scale * p.x(), -scale * p.y());
  }
}

double space_angle(const Eigen::Vector3d& at, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - at, w = c - at;
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

double flat_angle(const Eigen::Vector2d& at, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - at, w = c - at;
  return std::atan2(std::abs(cross(u, w)), u.dot(w));
}

/// The figures of TextureAtlas: distortions, and the texels used, by
/// testing the centre of every texel in each triangle's bounding box.
void measure(const TriangleMesh& mesh, int texture_size, TextureAtlas& atlas) {
  const Index n = mesh.num_faces();
  std::vector<double> area(n), uv_area(n);
  double total_area = 0, total_uv_area = 0;
  for (Index f = 0; f < n; ++f) {
    area[f] = face_area(mesh, f);
    uv_area[f] = std::abs(signed_area(atlas.uvs.row(atlas.faces(f, 0)), atlas.uvs.row(atlas.faces(f, 1)),
                                      atlas.uvs.row(atlas.faces(f, 2))));
    if (area[f] > 0) {
      total_area += area[f];
      total_uv_area += uv_area[f];
    }
  }
  const double density = total_area > 0 ? total_uv_area / total_area : 1.0;
  double area_sum = 0, angle_sum = 0;
  for (Index f = 0; f < n; ++f) {
    if (!(area[f] > 0)) continue;
    const double ratio = uv_area[f] / area[f] / density;
    const double area_distortion = ratio > 0 ? std::max(ratio, 1 / ratio) - 1 : 0;
    double angle_distortion = 0;
    for (int k = 0; k < 3; ++k) {
      const Index a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3), c = mesh.faces(f, (k + 2) % 3);
      const Index ua = atlas.faces(f, k), ub = atlas.faces(f, (k + 1) % 3), uc = atlas.faces(f, (k + 2) % 3);
      const double in_space = space_angle(mesh.vertices.row(a), mesh.vertices.row(b), mesh.vertices.row(c));
      const double flat = flat_angle(atlas.uvs.row(ua), atlas.uvs.row(ub), atlas.uvs.row(uc));
      angle_distortion = std::max(angle_distortion, std::abs(in_space - flat) * 180 / std::numbers::pi);
    }
    area_sum += area[f] * area_distortion;
    angle_sum += area[f] * angle_distortion;
    atlas.max_area_distortion = std::max(atlas.max_area_distortion, area_distortion);
    atlas.max_angle_distortion = std::max(atlas.max_angle_distortion, angle_distortion);
  }
  if (total_area > 0) {
    atlas.mean_area_distortion = area_sum / total_area;
    atlas.mean_angle_distortion = angle_sum / total_area;
  }

  const int size = texture_size;
  std::vector<std::uint8_t> used(static_cast<std::size_t>(size) * size, 0);
  for (Index f = 0; f < n; ++f) {
    std::array<Eigen::Vector2d, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = size * atlas.uvs.row(atlas.faces(f, k)).transpose();
    detail::for_each_texel_in(
        p, size, [&](int x, int y, const Eigen::Vector3d&) { used[static_cast<std::size_t>(y) * size + x] = 1; });
  }
  const auto count = std::count(used.begin(), used.end(), std::uint8_t{1});
  atlas.texture_used = static_cast<double>(count) / static_cast<double>(used.size());
}

}  // namespace

TextureAtlas make_texture_atlas(const TriangleMesh& mesh, const AtlasOptions& options) {
  check_options(options);
  check_mesh(mesh);
  std::vector<FlatChart> charts = flat_charts(mesh, options);
  to_image_density(mesh, charts);

  std::vector<std::vector<Eigen::Vector2d>> points(charts.size());
  std::vector<std::vector<std::array<Index, 3>>> triangles(charts.size());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    points[c] = charts[c].points;
    triangles[c] = charts[c].surface.corners;
  }
  const std::vector<detail::ChartPlacement> placements =
      detail::pack_charts(points, triangles, options.texture_size, options.gutter);

  TextureAtlas atlas;
  atlas.charts = static_cast<Index>(charts.size());
  atlas.faces.resize(mesh.num_faces(), 3);
  atlas.chart_of_face.assign(mesh.num_faces(), -1);
  std::size_t vertices = 0;
  for (const FlatChart& chart : charts) vertices += chart.points.size();
  atlas.uvs.resize(static_cast<Eigen::Index>(vertices), 2);
  atlas.source_vertex.reserve(vertices);
  const double size = options.texture_size;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const Index first = static_cast<Index>(atlas.source_vertex.size());
    const FlatChart& chart = charts[c];
    for (std::size_t v = 0; v < chart.points.size(); ++v) {
      const Eigen::Vector2d texel = placements[c].transform * chart.points[v] + placements[c].offset;
      atlas.uvs.row(first + static_cast<Index>(v)) = (texel / size).transpose();
      atlas.source_vertex.push_back(chart.surface.source_vertex[v]);
    }
    for (std::size_t i = 0; i < chart.surface.faces.size(); ++i) {
      const Index f = chart.surface.faces[i];
      for (int k = 0; k < 3; ++k) atlas.faces(f, k) = first + chart.surface.corners[i][k];
      atlas.chart_of_face[f] = static_cast<Index>(c);
    }
  }
  measure(mesh, options.texture_size, atlas);
  return atlas;
}

}  // namespace geodual::remesh
