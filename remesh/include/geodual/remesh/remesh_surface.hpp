#pragma once
// A surface prepared once for the sampling stages of a remesh, in the manner
// of voronoi::GeodesicSurface: the mesh and its topology (edges, faces round
// each edge, components, boundary loops), which sizing, feature detection,
// the cut along the features, the chains' sites, the pins and the sampling
// read instead of each building it again. The functions that take a
// TriangleMesh prepare one for that call.
//
//   const geodual::remesh::RemeshSurface surface(cut.mesh);  // refers to cut.mesh: keep it alive
//   auto creases = geodual::remesh::sample_features(surface, 2000);
//   auto sites = geodual::remesh::sample_remesh_sites(surface, 2000, creases);

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <utility>

namespace geodual::remesh {

class RemeshSurface {
 public:
  explicit RemeshSurface(const TriangleMesh& mesh) : mesh_(&mesh), topology_(build_mesh_topology(mesh)) {}
  /// With the mesh's topology built already (cut_to_manifold gives it).
  /// \pre topology is build_mesh_topology(mesh).
  RemeshSurface(const TriangleMesh& mesh, MeshTopology topology) : mesh_(&mesh), topology_(std::move(topology)) {}

  const TriangleMesh& mesh() const { return *mesh_; }
  const MeshTopology& topology() const { return topology_; }

 private:
  const TriangleMesh* mesh_;
  MeshTopology topology_;
};

}  // namespace geodual::remesh
