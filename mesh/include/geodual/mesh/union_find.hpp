#pragma once
// Disjoint sets over the integers 0..n-1 (union-find).

#include "geodual/mesh/triangle_mesh.hpp"

#include <cstddef>
#include <numeric>
#include <vector>

namespace geodual {

/// The root of every set is its smallest element, whatever the order of the
/// unions, so results built on roots are deterministic. Path halving keeps
/// finds near constant time.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }

  /// n singletons again, reusing the storage.
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), Index{0});
    merges_ = 0;
  }

  /// The smallest element of x's set. \pre 0 <= x < size()
  Index find(Index x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Joins the sets of a and b; true if they were apart.
  bool unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (a < b) {
      parent_[b] = a;
    } else {
      parent_[a] = b;
    }
    ++merges_;
    return true;
  }

  std::size_t size() const { return parent_.size(); }
  /// Unions that joined two sets since construction or reset.
  std::size_t merges() const { return merges_; }
  std::size_t sets() const { return parent_.size() - merges_; }

 private:
  std::vector<Index> parent_;
  std::size_t merges_ = 0;
};

}  // namespace geodual
