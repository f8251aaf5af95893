#pragma once
// What a GeodesicSurface holds for the engine: the propagation mesh and the
// locality numbering that maps between it and the caller's mesh.

#include "geodual/voronoi/geodesic_surface.hpp"
#include "locality_order.hpp"
#include "propagation_mesh.hpp"

namespace geodual::voronoi::detail {

struct PreparedSurface {
  /// Faces and vertices in locality order (see locality_order.hpp).
  PropagationMesh propagation;
  /// The numbering between the two: old_face and old_vertex alone (its
  /// renumbered mesh copy and the inverse maps are not kept).
  LocalityOrder order;
};

/// The propagation mesh and numbering of `mesh`, without the caller's topology.
PreparedSurface prepare_surface(const TriangleMesh& mesh);

/// The propagation's topology in the caller's numbering of vertices and
/// faces (edges keep the propagation's numbering). The edge lengths move
/// over from the propagation mesh, which views them there from then on.
SurfaceTopology caller_topology(PropagationMesh& pm, const LocalityOrder& order);

}  // namespace geodual::voronoi::detail
