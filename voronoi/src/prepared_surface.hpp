#pragma once
// What a GeodesicSurface holds for the engine: the propagation mesh and the
// locality numbering that maps between it and the caller's mesh.

#include "locality_order.hpp"
#include "propagation_mesh.hpp"

namespace geodual::voronoi::detail {

struct PreparedSurface {
  /// Faces and vertices in locality order (see locality_order.hpp).
  PropagationMesh propagation;
  /// The numbering between the two (its renumbered mesh copy is not kept).
  LocalityOrder order;
};

}  // namespace geodual::voronoi::detail
