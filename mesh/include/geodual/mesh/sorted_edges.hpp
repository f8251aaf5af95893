#pragma once
// Edges kept as vertex pairs, smaller index first, in sorted order: the
// lookup every such list needs.

#include "geodual/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <array>
#include <span>

namespace geodual {

/// The index in `edges` (sorted vertex pairs, smaller first) of the edge
/// between vertices a and b, either order; -1 where it is not there.
inline Index find_sorted_edge(std::span<const std::array<Index, 2>> edges, Index a, Index b) {
  const std::array<Index, 2> edge{std::min(a, b), std::max(a, b)};
  const auto at = std::lower_bound(edges.begin(), edges.end(), edge);
  return at != edges.end() && *at == edge ? static_cast<Index>(at - edges.begin()) : -1;
}

}  // namespace geodual
