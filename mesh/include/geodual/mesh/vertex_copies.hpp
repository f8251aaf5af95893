#pragma once
// The copies of each vertex after a cut that splits vertices (a cut to a
// manifold, a cut along creases): from the map copy -> original, the copies
// of each original, grouped.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace geodual {

/// Per original vertex v, its copies copies[begin[v] .. begin[v + 1]), increasing.
struct VertexCopies {
  std::vector<Index> begin;
  std::vector<Index> copies;
  std::span<const Index> of(Index v) const {
    return std::span<const Index>(copies).subspan(static_cast<std::size_t>(begin[v]),
                                                  static_cast<std::size_t>(begin[v + 1] - begin[v]));
  }
};

/// `original[w]` (in 0 .. num_originals - 1) is the vertex copy w stands
/// for; a copy w with keep[w] == 0 is left out (keep empty: every copy is kept).
VertexCopies group_vertex_copies(std::span<const Index> original, Index num_originals,
                                 std::span<const std::uint8_t> keep = {});

}  // namespace geodual
