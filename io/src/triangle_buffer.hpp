#pragma once
// Internal: collects the triangles a reader produces straight into the
// FaceMatrix it returns, growing geometrically, and fan-triangulates polygons.

#include "geodual/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace geodual::io::detail {

class TriangleBuffer {
 public:
  /// `expected` triangles are allocated at once (callers bound it by the file size).
  explicit TriangleBuffer(std::size_t expected = 0) : faces_(static_cast<Eigen::Index>(expected), 3) {}

  [[gnu::always_inline]] void add(Index a, Index b, Index c) {
    if (size_ == faces_.rows()) [[unlikely]] {
      grow();
    }
    Index* row = faces_.data() + 3 * size_;
    row[0] = a;
    row[1] = b;
    row[2] = c;
    ++size_;
  }

  /// Fan-triangulates corners (c0, c1, c2), (c0, c2, c3), ...; needs at least 3.
  /// `corner(i)` returns the i-th corner's vertex index.
  template <class CornerAt>
  void add_polygon(std::size_t corners, CornerAt&& corner) {
    const Index first = corner(0);
    Index previous = corner(1);
    for (std::size_t i = 2; i < corners; ++i) {
      const Index current = corner(i);
      add(first, previous, current);
      previous = current;
    }
    if (corners > 3) {
      ++polygons_split_;
    }
  }

  std::int64_t polygons_split() const { return polygons_split_; }
  Eigen::Index size() const { return size_; }

  /// The triangles collected, as many rows as were added.
  FaceMatrix take() {
    if (faces_.rows() != size_) {
      faces_.conservativeResize(size_, 3);
    }
    size_ = 0;
    return std::move(faces_);
  }

 private:
  [[gnu::noinline]] void grow() {
    FaceMatrix bigger(std::max<Eigen::Index>(64, 2 * faces_.rows()), 3);
    bigger.topRows(size_) = faces_.topRows(size_);
    faces_.swap(bigger);
  }

  FaceMatrix faces_;
  Eigen::Index size_ = 0;
  std::int64_t polygons_split_ = 0;
};

}  // namespace geodual::io::detail
