#include "geodual/voronoi/geodesic_surface.hpp"

#include "prepared_surface.hpp"

#include <chrono>
#include <utility>

namespace geodual::voronoi {
namespace detail {

PreparedSurface prepare_surface(const TriangleMesh& mesh) {
  PreparedSurface prepared;
  prepared.order = locality_order(mesh);
  prepared.propagation = build_propagation_mesh(prepared.order.mesh);
  // Only the maps back to the caller's numbering are held from here on (each
  // field inverts them for its sites). Assigning {} would keep the memory.
  prepared.order.mesh = TriangleMesh{};
  std::vector<Index>().swap(prepared.order.new_face);
  std::vector<Index>().swap(prepared.order.new_vertex);
  return prepared;
}

SurfaceTopology caller_topology(PropagationMesh& pm, const LocalityOrder& order) {
  SurfaceTopology topology;
  const auto num_edges = static_cast<std::size_t>(pm.num_edges());
  topology.edge_faces.resize(num_edges);
  for (std::size_t e = 0; e < num_edges; ++e) {
    for (int side = 0; side < 2; ++side) {
      const Index f = pm.edge_faces[e][side];
      topology.edge_faces[e][side] = f >= 0 ? order.old_face[f] : -1;
    }
  }
  topology.edge_length = std::move(pm.edge_length_storage);
  topology.face_edges.resize(pm.face_records.size());
  for (std::size_t f = 0; f < pm.face_records.size(); ++f) {
    topology.face_edges[order.old_face[f]] = pm.face_edges(static_cast<Index>(f));
  }
  return topology;
}

}  // namespace detail

namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& values) {
  return values.capacity() * sizeof(T);
}

}  // namespace

GeodesicSurface::GeodesicSurface(const TriangleMesh& mesh) : mesh_(&mesh) {
  const auto start = std::chrono::steady_clock::now();
  auto prepared = std::make_shared<detail::PreparedSurface>(detail::prepare_surface(mesh));
  topology_ = std::make_shared<const SurfaceTopology>(detail::caller_topology(prepared->propagation, prepared->order));
  prepared_ = std::move(prepared);
  preparation_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::size_t GeodesicSurface::memory_bytes() const {
  const detail::PropagationMesh& pm = prepared_->propagation;
  const detail::LocalityOrder& order = prepared_->order;
  return bytes_of(pm.face_records) + bytes_of(pm.edge_faces) + bytes_of(pm.edge_length_storage) +
         bytes_of(pm.vertex_face) + bytes_of(pm.fan_offsets) + bytes_of(pm.extra_fans) + bytes_of(pm.is_pseudo_source) +
         bytes_of(order.old_face) + bytes_of(order.old_vertex) + bytes_of(topology_->edge_faces) +
         bytes_of(topology_->edge_length) + bytes_of(topology_->face_edges);
}

}  // namespace geodual::voronoi
