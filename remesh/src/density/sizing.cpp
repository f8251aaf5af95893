#include "geodual/remesh/sizing.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace geodual::remesh {
namespace {

// An equilateral triangle of side L has area (sqrt(3)/4) L^2, so a remesh of
// such triangles covering area A has F = A / ((sqrt(3)/4) L^2) faces. Its
// boundary, of length P, is split into B = P / L edges. A triangle mesh has
// 3F = 2E - B (each face has three edges, each interior edge two faces) and
// V - E + F = chi, so V = chi + E - F = (F + B) / 2 + chi.
constexpr double equilateral_area_factor = 0.4330127018922193;  // sqrt(3) / 4

std::int64_t vertices_from(double faces, double boundary_edges, std::int64_t euler_characteristic,
                           const std::string& what) {
  const double vertices = std::round((faces + boundary_edges) / 2 + static_cast<double>(euler_characteristic));
  if (!(vertices <= static_cast<double>(max_sized_sites))) {
    throw UsageError(what + " asks for more than " + std::to_string(max_sized_sites) + " sites");
  }
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(vertices));
}

}  // namespace

SizingMeasures sizing_measures(const TriangleMesh& surface) { return sizing_measures(RemeshSurface(surface)); }

SizingMeasures sizing_measures(const RemeshSurface& prepared) {
  const TriangleMesh& surface = prepared.mesh();
  SizingMeasures measures;
  for (Index f = 0; f < surface.num_faces(); ++f) {
    if (!has_repeated_corner(surface, f)) measures.area += face_area(surface, f);
  }
  const MeshTopology& topology = prepared.topology();
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_boundary_edge(e)) continue;
    const auto& ends = topology.edge_vertices[static_cast<std::size_t>(e)];
    measures.boundary_length += (surface.vertices.row(ends[1]) - surface.vertices.row(ends[0])).norm();
  }
  for (const ComponentCounts& component : topology.components) {
    measures.euler_characteristic += component.euler_characteristic();
  }
  return measures;
}

std::int64_t sites_for_edge_length(const TriangleMesh& surface, double edge_length) {
  return sites_for_edge_length(RemeshSurface(surface), edge_length);
}

std::int64_t sites_for_edge_length(const RemeshSurface& surface, double edge_length) {
  std::ostringstream what_text;
  what_text << "edge length " << edge_length;
  const std::string what = what_text.str();
  if (!(std::isfinite(edge_length) && edge_length > 0)) throw UsageError(what + ": must be a finite number > 0");
  const SizingMeasures measures = sizing_measures(surface);
  const double faces = measures.area / (equilateral_area_factor * edge_length * edge_length);
  return vertices_from(faces, measures.boundary_length / edge_length, measures.euler_characteristic, what);
}

std::int64_t sites_for_faces(const TriangleMesh& surface, std::int64_t faces) {
  return sites_for_faces(RemeshSurface(surface), faces);
}

std::int64_t sites_for_faces(const RemeshSurface& surface, std::int64_t faces) {
  const std::string what = std::to_string(faces) + " faces";
  if (faces < 1) throw UsageError(what + ": must be at least 1");
  const SizingMeasures measures = sizing_measures(surface);
  // The edge length of `faces` equilateral triangles covering the area.
  const double edge_length = std::sqrt(measures.area / (equilateral_area_factor * static_cast<double>(faces)));
  const double boundary_edges = edge_length > 0 ? measures.boundary_length / edge_length : 0;
  return vertices_from(static_cast<double>(faces), boundary_edges, measures.euler_characteristic, what);
}

}  // namespace geodual::remesh
