#pragma once
// CGAL's isotropic remeshing as the benchmarks run it: a TriangleMesh to and
// from a CGAL Surface_mesh, and the search for the target edge length that
// gives a wanted vertex count.
//
// The search: a triangle mesh of n vertices has about 2 n faces, each of
// area sqrt(3)/4 L^2 if equilateral, so L0 = sqrt(4 A / (sqrt(3) 2 n)) for a
// surface of area A. The vertex count falls like L^-2, so each next L comes
// from a secant step on (log L, log count) through the last two runs (a
// power-law step with exponent -2 after the first), kept inside the bracket
// of runs above and below the target (geometric bisection when it leaves it).

#include "bench_support.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace geodual::bench {

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<CgalKernel::Point_3>;

/// The input as a CGAL Surface_mesh: referenced vertices only, faces with a
/// repeated index left out. Throws geodual::Error when a face cannot be added
/// (the input is not an oriented 2-manifold).
inline CgalMesh to_cgal(const TriangleMesh& mesh) {
  std::vector<CgalMesh::Vertex_index> handle(static_cast<std::size_t>(mesh.num_vertices()));
  std::vector<char> referenced(handle.size(), 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) referenced[static_cast<std::size_t>(mesh.faces(f, c))] = 1;
  }
  CgalMesh out;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (referenced[static_cast<std::size_t>(v)] == 0) continue;
    handle[static_cast<std::size_t>(v)] =
        out.add_vertex(CgalKernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  }
  std::int64_t refused = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    const auto corner = [&](int c) { return handle[static_cast<std::size_t>(mesh.faces(f, c))]; };
    if (out.add_face(corner(0), corner(1), corner(2)) == CgalMesh::null_face()) ++refused;
  }
  if (refused > 0) {
    throw Error("not a valid polygon mesh for CGAL: " + std::to_string(refused) +
                " faces could not be added (non-manifold edges or vertices, or inconsistent orientation)");
  }
  return out;
}

/// A triangulated Surface_mesh back as a TriangleMesh (garbage collected
/// first, so that its indices are 0..n-1).
inline TriangleMesh from_cgal(CgalMesh& mesh) {
  mesh.collect_garbage();
  TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (const CgalMesh::Vertex_index v : mesh.vertices()) {
    const CgalKernel::Point_3& p = mesh.point(v);
    const auto row = static_cast<Eigen::Index>(v.idx());
    out.vertices(row, 0) = p.x();
    out.vertices(row, 1) = p.y();
    out.vertices(row, 2) = p.z();
  }
  out.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index row = 0;
  for (const CgalMesh::Face_index f : mesh.faces()) {
    int c = 0;
    for (const CgalMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (c == 3) throw Error("CGAL returned a face that is not a triangle");
      out.faces(row, c++) = static_cast<Index>(v.idx());
    }
    if (c != 3) throw Error("CGAL returned a face that is not a triangle");
    ++row;
  }
  return out;
}

inline double surface_area(const TriangleMesh& mesh) {
  double area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

/// The target edge lengths to try, one after the other, for a remesh of
/// `target` vertices of a surface of area `area` (see the file comment):
///   EdgeLengthSearch search(area, target);
///   while (...) { run at search.length(); search.record(vertices); }
class EdgeLengthSearch {
 public:
  EdgeLengthSearch(double area, std::int64_t target)
      : target_(target),
        log_target_(std::log(static_cast<double>(target))),
        length_(std::sqrt(4.0 * area / (std::sqrt(3.0) * 2.0 * static_cast<double>(target)))),
        best_length_(length_) {}

  /// The length to run next.
  double length() const { return length_; }

  /// Of the lengths run so far, the one whose count came closest to the target.
  double best_length() const { return best_length_; }

  /// |count / target - 1| of a count.
  double miss(std::int64_t vertices) const {
    return std::abs(static_cast<double>(vertices - target_)) / static_cast<double>(target_);
  }

  /// The vertex count of a run at length(); chooses the next length.
  void record(std::int64_t vertices) {
    if (miss(vertices) < best_miss_) {
      best_miss_ = miss(vertices);
      best_length_ = length_;
    }
    const double log_length = std::log(length_);
    const double log_count = std::log(static_cast<double>(std::max<std::int64_t>(vertices, 1)));
    if (vertices > target_) {
      too_many_log_length_ = std::max(too_many_log_length_, log_length);
    } else {
      too_few_log_length_ = std::min(too_few_log_length_, log_length);
    }
    points_.emplace_back(log_length, log_count);
    double next = log_length + 0.5 * (log_count - log_target_);  // count ~ L^-2
    if (points_.size() >= 2) {
      const auto [x0, y0] = points_[points_.size() - 2];
      const auto [x1, y1] = points_.back();
      if (y1 != y0 && x1 != x0) {
        const double slope = (y1 - y0) / (x1 - x0);
        if (slope < 0) next = x1 + (log_target_ - y1) / slope;
      }
    }
    if (std::isfinite(too_many_log_length_) && std::isfinite(too_few_log_length_) &&
        !(next > too_many_log_length_ && next < too_few_log_length_)) {
      next = 0.5 * (too_many_log_length_ + too_few_log_length_);
    }
    length_ = std::exp(next);
  }

 private:
  std::int64_t target_;
  double log_target_;
  double length_;
  double best_length_;
  double best_miss_ = std::numeric_limits<double>::infinity();
  /// Runs so far, (log L, log count); the bracket: the longest L known to
  /// give too many vertices and the shortest known to give too few.
  std::vector<std::pair<double, double>> points_;
  double too_many_log_length_ = -std::numeric_limits<double>::infinity();
  double too_few_log_length_ = std::numeric_limits<double>::infinity();
};

}  // namespace geodual::bench
