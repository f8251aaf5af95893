// geodesic and voronoi: the exact geodesic engine (window-VTP with redundant
// window removal) and the Voronoi diagram extracted from it.

#include "arrays.hpp"
#include "bindings.hpp"
#include "cancellation.hpp"

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "geodual/voronoi/voronoi_diagram.hpp"

#include <utility>
#include <vector>

namespace geodual::python {
namespace {

py::tuple geodesic(const py::handle& vertices, const py::handle& faces, const py::handle& sites,
                   const py::object& progress) {
  const TriangleMesh mesh = mesh_from_arrays(vertices, faces);
  const std::vector<SurfacePoint> points = sites_from_object(sites, mesh);
  ProgressBridge bridge(progress);
  voronoi::GeodesicOptions options;
  options.progress = [&bridge](double fraction) { return bridge("geodesics", fraction); };
  const voronoi::GeodesicField field = bridge.run([&] {
    require_computable_range(mesh, "V");
    return voronoi::compute_geodesic_field(mesh, points, options);
  });
  return py::make_tuple(vector_to_array<double>(field.distance), vector_to_array<Index>(field.nearest_site));
}

py::dict voronoi_diagram(const py::handle& vertices, const py::handle& faces, const py::handle& sites,
                         const py::object& progress) {
  const TriangleMesh mesh = mesh_from_arrays(vertices, faces);
  const std::vector<SurfacePoint> points = sites_from_object(sites, mesh);
  ProgressBridge bridge(progress);
  voronoi::VoronoiOptions options;
  options.geodesic.progress = [&bridge](double fraction) { return bridge("geodesics", fraction); };
  const voronoi::VoronoiDiagram diagram = bridge.run([&] {
    require_computable_range(mesh, "V");
    return voronoi::compute_voronoi(mesh, points, options);
  });

  py::dict result;
  result["distance"] = vector_to_array<double>(diagram.field.distance);
  result["nearest_site"] = vector_to_array<Index>(diagram.field.nearest_site);
  std::vector<Eigen::Vector3d> site_positions;
  for (const SurfacePoint& point : points) site_positions.push_back(point.position(mesh));
  result["sites"] = points_to_array(site_positions);

  std::vector<Eigen::Vector3d> vertex_positions;
  std::vector<double> vertex_distance;
  py::list vertex_sites;
  for (const voronoi::VoronoiVertex& vertex : diagram.vertices) {
    vertex_positions.push_back(vertex.position);
    vertex_distance.push_back(vertex.distance);
    vertex_sites.append(vector_to_array<Index>(diagram.sites_of(vertex)));
  }
  result["vertices"] = points_to_array(vertex_positions);
  result["vertex_distance"] = vector_to_array<double>(vertex_distance);
  result["vertex_sites"] = std::move(vertex_sites);

  const auto arcs = static_cast<py::ssize_t>(diagram.arcs.size());
  py::list polylines;
  py::array_t<Index> polyline_sites({arcs, py::ssize_t{2}});
  py::array_t<Index> polyline_vertices({arcs, py::ssize_t{2}});
  py::array_t<bool> polyline_closed(arcs);
  py::array_t<double> polyline_length(arcs);
  for (py::ssize_t a = 0; a < arcs; ++a) {
    const voronoi::VoronoiArc& arc = diagram.arcs[static_cast<std::size_t>(a)];
    polylines.append(points_to_array(diagram.polyline(arc)));
    polyline_sites.mutable_at(a, 0) = arc.left_site;
    polyline_sites.mutable_at(a, 1) = arc.right_site;
    polyline_vertices.mutable_at(a, 0) = arc.start_vertex;
    polyline_vertices.mutable_at(a, 1) = arc.end_vertex;
    polyline_closed.mutable_at(a) = arc.closed;
    polyline_length.mutable_at(a) = arc.length;
  }
  result["polylines"] = std::move(polylines);
  result["polyline_sites"] = std::move(polyline_sites);
  result["polyline_vertices"] = std::move(polyline_vertices);
  result["polyline_closed"] = std::move(polyline_closed);
  result["polyline_length"] = std::move(polyline_length);
  result["cell_area"] = vector_to_array<double>(diagram.cell_area);
  return result;
}

}  // namespace

void add_geodesics(py::module_& module) {
  module.def("geodesic", &geodesic, py::arg("V"), py::arg("F"), py::arg("sites"), py::kw_only(),
             py::arg("progress") = py::none(),
             R"(Exact geodesic distance from the nearest site, at every vertex.

V, F: the mesh (n x 3 positions, m x 3 triangles). sites: a sequence of vertex
indices (a list or 1-D integer array) and/or points inside faces given as
(face, u, v, w) tuples with barycentric coordinates u + v + w = 1 (a k x 4
array works too).

Returns (distance, nearest_site): float64 and int32 arrays of length n, the
exact geodesic distance (window propagation, no approximation) and the index
in `sites` of the nearest site; inf and -1 where no site can be reached
(another component, an unreferenced vertex).

progress: None or progress(stage, fraction), called now and then; return
False to cancel (geodual.Cancelled). Ctrl-C raises KeyboardInterrupt.
Raises geodual.Error for bad sites (out of range, two at one point, on a
degenerate face).

Example:
    distance, nearest = geodual.geodesic(V, F, [0, 100, (5, 0.2, 0.3, 0.5)])
)");
  module.def("voronoi", &voronoi_diagram, py::arg("V"), py::arg("F"), py::arg("sites"), py::kw_only(),
             py::arg("progress") = py::none(),
             R"(The exact geodesic Voronoi diagram of sites on the mesh.

V, F, sites and progress as for geodesic(). Returns a dict of numpy arrays:
  distance, nearest_site  per mesh vertex, as geodesic() returns them
  sites                   k x 3, the sites' positions
  vertices                Voronoi vertices (points equidistant to three or more
                          sites), p x 3 positions
  vertex_distance         p, their geodesic distance to each of their sites
  vertex_sites            list of p int32 arrays: each vertex's sites,
                          counter-clockwise (3 unless sites are co-circular)
  polylines               list of a arrays (m_i x 3): the cell boundaries, each
                          a maximal piece of boundary between two cells, traced
                          within 1e-5 of the bounding-box diagonal of the exact
                          bisector
  polyline_sites          a x 2 int32: the (left, right) sites each separates
                          (left as seen walking from its first point with the
                          mesh's orientation)
  polyline_vertices       a x 2 int32: the Voronoi vertex each starts and ends
                          at, -1 on the mesh boundary or for a closed loop
  polyline_closed         a, bool; polyline_length: a, float64
  cell_area               k, the area of each site's cell
)");
}

}  // namespace geodual::python
