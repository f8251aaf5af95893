#pragma once
// Sorting a mesh's half-edges by vertex pair in linear time: every stage
// does it once per mesh (to find twins and boundaries), and on a scan of
// millions of faces a comparison sort of the 3F half-edges is a noticeable
// part of the stage.

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstddef>
#include <vector>

namespace geodual {

/// Sorts `items` by (low(item), high(item)), vertex indices in
/// [0, num_vertices), keeping the order of items with equal pairs: a
/// counting sort by `low` (the items of one vertex land together, and with
/// vertices in locality order mostly near each other), then an insertion
/// sort by `high` within each vertex's few items. Takes a buffer the size of
/// `items` and one counter per vertex.
template <class T, class Low, class High>
void sort_by_vertex_pair(std::vector<T>& items, Index num_vertices, Low low, High high) {
  std::vector<std::size_t> start(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const T& item : items) ++start[static_cast<std::size_t>(low(item)) + 1];
  for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
  std::vector<T> sorted(items.size());
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const T& item : items) sorted[next[static_cast<std::size_t>(low(item))]++] = item;
  }
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    for (std::size_t i = start[v] + 1; i < start[v + 1]; ++i) {
      const T item = sorted[i];
      std::size_t j = i;
      for (; j > start[v] && high(sorted[j - 1]) > high(item); --j) sorted[j] = sorted[j - 1];
      sorted[j] = item;
    }
  }
  items.swap(sorted);
}

}  // namespace geodual
