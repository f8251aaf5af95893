#include "texture/atlas_lscm.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

namespace geodual::remesh::detail {

std::vector<Eigen::Vector2d> lscm_parameterisation(const std::vector<Eigen::Vector3d>& positions,
                                                   const std::vector<std::array<Index, 3>>& triangles) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
  using VertexHandle = Surface::Vertex_index;
  namespace parameterization = CGAL::Surface_mesh_parameterization;

  Surface surface;
  surface.reserve(static_cast<Surface::size_type>(positions.size()),
                  static_cast<Surface::size_type>(3 * triangles.size()),
                  static_cast<Surface::size_type>(triangles.size()));
  std::vector<VertexHandle> handles;
  handles.reserve(positions.size());
  for (const Eigen::Vector3d& p : positions)
    handles.push_back(surface.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (const auto& [a, b, c] : triangles) {
    if (surface.add_face(handles[a], handles[b], handles[c]) == Surface::null_face()) return {};
  }
  Surface::Halfedge_index border = Surface::null_halfedge();
  for (const Surface::Halfedge_index h : surface.halfedges()) {
    if (surface.is_border(h)) {
      border = h;
      break;
    }
  }
  if (border == Surface::null_halfedge()) return {};

  auto uv = surface.add_property_map<VertexHandle, Kernel::Point_2>("v:uv").first;
  const parameterization::Error_code status =
      parameterization::parameterize(surface, parameterization::LSCM_parameterizer_3<Surface>(), border, uv);
  if (status != parameterization::OK) return {};
  std::vector<Eigen::Vector2d> result;
  result.reserve(positions.size());
  for (const VertexHandle v : handles) result.emplace_back(uv[v].x(), uv[v].y());
  return result;
}

}  // namespace geodual::remesh::detail
