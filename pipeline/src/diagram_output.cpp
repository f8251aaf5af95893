#include "geodual/pipeline/diagram_output.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/io/mesh_format.hpp"
#include "geodual/io/preview.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/field_output.hpp"
#include "geodual/pipeline/version.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace geodual {
void write_voronoi_diagram(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const voronoi::VoronoiDiagram& diagram, const std::string& extras_json) {
  const std::string extension = io::lowercase_extension(path);
  if (extension != ".glb" && extension != ".gltf") {
    throw Error(path.string() + ": a Voronoi diagram is written as .glb or .gltf");
  }
  const voronoi::GeodesicField& field = diagram.field;
  io::GltfScene scene;
  scene.generator = "geodual " + std::string(build_version());
  scene.extras_json = extras_json;

  io::GltfTriangleMesh surface;
  surface.name = "cells";
  surface.mesh = mesh;
  surface.colors.resize(mesh.vertices.rows(), 3);
  io::GltfVertexScalar distance{"_DISTANCE", std::vector<float>(static_cast<std::size_t>(mesh.vertices.rows()))};
  for (Index v = 0; v < mesh.vertices.rows(); ++v) {
    const std::array<float, 3> color = site_color(field.nearest_site[v]);
    for (int c = 0; c < 3; ++c) surface.colors(v, c) = color[c];
    distance.values[v] = std::isfinite(field.distance[v]) ? static_cast<float>(field.distance[v]) : -1.0f;
  }
  surface.scalars.push_back(std::move(distance));
  scene.triangle_meshes.push_back(std::move(surface));

  if (!diagram.arcs.empty()) {
    io::GltfLineSet lines;
    lines.name = "voronoi_boundaries";
    lines.points.resize(static_cast<Index>(diagram.points.size()), 3);
    for (std::size_t i = 0; i < diagram.points.size(); ++i)
      lines.points.row(static_cast<Index>(i)) = diagram.points[i].transpose();
    Index segments = 0;
    for (const voronoi::VoronoiArc& arc : diagram.arcs) segments += arc.point_end - arc.point_begin - 1;
    lines.segments.resize(segments, 2);
    Index row = 0;
    for (const voronoi::VoronoiArc& arc : diagram.arcs) {
      for (Index i = arc.point_begin; i + 1 < arc.point_end; ++i, ++row) lines.segments.row(row) << i, i + 1;
    }
    scene.line_sets.push_back(std::move(lines));
  }
  io::GltfPointSet sites;
  sites.name = "sites";
  sites.points.resize(static_cast<Index>(field.sites.size()), 3);
  for (std::size_t s = 0; s < field.sites.size(); ++s) {
    sites.points.row(static_cast<Index>(s)) = field.sites[s].position(mesh).transpose();
  }
  scene.point_sets.push_back(std::move(sites));
  if (!diagram.vertices.empty()) {
    io::GltfPointSet vertices;
    vertices.name = "voronoi_vertices";
    vertices.points.resize(static_cast<Index>(diagram.vertices.size()), 3);
    for (std::size_t i = 0; i < diagram.vertices.size(); ++i) {
      vertices.points.row(static_cast<Index>(i)) = diagram.vertices[i].position.transpose();
    }
    scene.point_sets.push_back(std::move(vertices));
  }
  io::write_gltf(path, scene);
}

void write_remesh_gltf(const std::filesystem::path& path, io::GltfTriangleMesh entry, const std::string& extras_json,
                       io::GltfCompression compression) {
  io::GltfScene scene;
  scene.generator = "geodual " + std::string(build_version());
  scene.extras_json = extras_json;
  scene.compression = compression;
  scene.triangle_meshes.push_back(std::move(entry));
  io::write_gltf(path, scene);
}

void write_remesh(const std::filesystem::path& path, const TriangleMesh& mesh, const VertexAttributes& attributes,
                  const std::string& extras_json, io::GltfCompression compression) {
  const std::string extension = io::lowercase_extension(path);
  if (extension == ".glb" || extension == ".gltf") {
    write_remesh_gltf(path, io::gltf_triangle_mesh("remesh", mesh, attributes), extras_json, compression);
    return;
  }
  if (extension == ".ply" || extension == ".obj") {
    if (compression != io::GltfCompression::none) {
      throw Error(path.string() + ": " + std::string(io::gltf_compression_name(compression)) +
                  " compression is for glTF; write .glb or .gltf");
    }
    io::write_mesh(path, mesh, attributes);
    return;
  }
  throw Error(path.string() + ": a remesh is written as .glb, .gltf, .ply or .obj");
}

void write_voronoi_preview(const std::filesystem::path& path, const TriangleMesh& mesh,
                           const voronoi::VoronoiDiagram& diagram, const std::function<bool(double)>& progress) {
  io::PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = false;
  scene.vertex_colors.resize(static_cast<std::size_t>(mesh.vertices.rows()));
  for (Index v = 0; v < mesh.vertices.rows(); ++v) {
    const std::array<float, 3> color = site_color(diagram.field.nearest_site[v]);
    scene.vertex_colors[v] = Eigen::Vector3f(color[0], color[1], color[2]);
  }
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    const auto line = diagram.polyline(arc);
    scene.polylines.emplace_back(line.begin(), line.end());
  }
  for (const SurfacePoint& site : diagram.field.sites) scene.points.push_back(site.position(mesh));
  io::PreviewOptions options;
  options.progress = progress;
  io::write_preview_png(path, scene, options);
}

ColorMatrix quality_colors(const TriangleMesh& mesh) {
  // Q per triangle (quality::face_quality), averaged at vertices.
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.vertices.rows()), count = sum;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const double q = quality::face_quality(mesh, f);
    for (int k = 0; k < 3; ++k) sum[mesh.faces(f, k)] += q, count[mesh.faces(f, k)] += 1;
  }
  ColorMatrix colors(mesh.vertices.rows(), 3);
  for (Index v = 0; v < mesh.vertices.rows(); ++v) {
    const double q = count[v] > 0 ? std::clamp(sum[v] / count[v], 0.0, 1.0) : 0.0;
    // red -> yellow at 0.5 -> green
    colors.row(v) << static_cast<float>(q < 0.5 ? 1.0 : 2 * (1 - q)), static_cast<float>(q < 0.5 ? 2 * q : 1.0), 0.1f;
  }
  return colors;
}

void write_mesh_preview(const std::filesystem::path& path, const TriangleMesh& mesh, const ColorMatrix& colors,
                        const std::function<bool(double)>& progress,
                        std::span<const std::vector<Eigen::Vector3d>> lines) {
  io::PreviewScene scene;
  scene.mesh = &mesh;
  scene.wireframe = true;
  scene.polylines.assign(lines.begin(), lines.end());
  scene.polyline_color = Eigen::Vector3f(0.55f, 0.0f, 0.0f);
  if (colors.rows() == mesh.vertices.rows() && colors.cols() >= 3) {
    // The preview shades in linear light.
    for (Index v = 0; v < colors.rows(); ++v) {
      scene.vertex_colors.emplace_back(linear_from_srgb(colors(v, 0)), linear_from_srgb(colors(v, 1)),
                                       linear_from_srgb(colors(v, 2)));
    }
  }
  io::PreviewOptions options;
  options.progress = progress;
  io::write_preview_png(path, scene, options);
}

std::int64_t peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::int64_t>(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

}  // namespace geodual
