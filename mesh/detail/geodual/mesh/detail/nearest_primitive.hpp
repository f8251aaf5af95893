#pragma once
// Nearest-primitive search in a CGAL AABB tree (triangles or segments), for
// the translation units that include CGAL: the quality statistics and the
// texture baker.

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace geodual {

/// The kernel and the AABB tree of triangles (held in a vector) that both search.
namespace aabb {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;
}  // namespace aabb

/// Traversal traits for the exact squared distance from a point to the
/// primitives (triangles or segments) of an AABB tree: children are visited
/// nearest box first, and a box no nearer than the best primitive so far is
/// skipped. It starts from the distance to a given primitive (the previous
/// query's nearest, for queries in spatial order) instead of the tree's k-d
/// tree hint (costly for points far from the surface). The result is the
/// minimum over the primitives, so it depends on the query alone, not on the
/// start, the order of queries or the thread.
template <typename Kernel, typename Primitive,
          double (*squared_distance_to)(const typename Kernel::Point_3&, const typename Primitive::Datum&)>
class NearestPrimitive {
 public:
  using Point = typename Kernel::Point_3;
  using Iterator = typename Primitive::Id;

  /// `first`: the tree's first primitive, to number the primitives from.
  NearestPrimitive(Iterator first, double start_squared, std::size_t start_primitive)
      : first_(first), best_(start_squared), best_primitive_(start_primitive) {}

  using Node = CGAL::AABB_node<CGAL::AABB_traits<Kernel, Primitive>>;
  using Priority = double;  ///< higher first: minus the squared distance to the box

  bool go_further() const { return true; }

  void intersection(const Point& query, const Primitive& primitive) {
    const double d2 = squared_distance_to(query, primitive.datum());
    if (d2 < best_) {
      best_ = d2;
      best_primitive_ = static_cast<std::size_t>(primitive.id() - first_);
    }
  }

  bool do_intersect(const Point& query, const Node& node) const { return box_distance(query, node) < best_; }

  std::pair<bool, Priority> do_intersect_with_priority(const Point& query, const Node& node) const {
    const double d2 = box_distance(query, node);
    return {d2 < best_, -d2};
  }

  double squared_distance() const { return best_; }
  std::size_t nearest_primitive() const { return best_primitive_; }

 private:
  static double box_distance(const Point& q, const Node& node) {
    const CGAL::Bbox_3& box = node.bbox();
    double d2 = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double below = box.min(axis) - q[axis];
      const double above = q[axis] - box.max(axis);
      const double gap = std::max({below, above, 0.0});
      d2 += gap * gap;
    }
    return d2;
  }

  Iterator first_;
  double best_;
  std::size_t best_primitive_;
};

}  // namespace geodual
