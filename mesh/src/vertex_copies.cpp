#include "geodual/mesh/vertex_copies.hpp"

namespace geodual {

VertexCopies group_vertex_copies(std::span<const Index> original, Index num_originals,
                                 std::span<const std::uint8_t> keep) {
  const auto kept = [&](std::size_t w) { return keep.empty() || keep[w] != 0; };
  VertexCopies result;
  result.begin.assign(static_cast<std::size_t>(num_originals) + 1, 0);
  for (std::size_t w = 0; w < original.size(); ++w) {
    if (kept(w)) ++result.begin[static_cast<std::size_t>(original[w]) + 1];
  }
  for (std::size_t v = 0; v + 1 < result.begin.size(); ++v) result.begin[v + 1] += result.begin[v];
  result.copies.resize(static_cast<std::size_t>(result.begin.back()));
  std::vector<Index> next(result.begin.begin(), result.begin.end() - 1);
  for (std::size_t w = 0; w < original.size(); ++w) {
    if (kept(w))
      result.copies[static_cast<std::size_t>(next[static_cast<std::size_t>(original[w])]++)] = static_cast<Index>(w);
  }
  return result;
}

}  // namespace geodual
