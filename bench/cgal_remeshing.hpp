#pragma once
// CGAL's isotropic remeshing as the benchmarks run it: a TriangleMesh to and
// from a CGAL Surface_mesh, one isotropic remesh, and the search for the
// target edge length that gives a wanted vertex count.
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
#include "geodual/quality/quality_stats.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
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

/// How the remesh treats the input's borders. keep: CGAL's own handling
/// (border edges are constrained: split and collapsed along the border but
/// never flipped, their vertices not smoothed). protect: CGAL's example
/// (border edges first split to at most L, then kept as they are).
enum class CgalBorder { keep, protect };

struct CgalRemeshOptions {
  unsigned iterations = 3;  ///< number_of_iterations
  CgalBorder border = CgalBorder::keep;
};

/// CGAL::Polygon_mesh_processing::isotropic_remeshing of `input` (as
/// to_cgal builds it) with target edge length `length`, read back.
inline TriangleMesh cgal_isotropic_remesh(const TriangleMesh& input, double length, const CgalRemeshOptions& options) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  CgalMesh mesh = to_cgal(input);
  if (options.border == CgalBorder::protect) {
    std::vector<CgalMesh::Halfedge_index> border;
    PMP::border_halfedges(mesh.faces(), mesh, std::back_inserter(border));
    std::vector<CgalMesh::Edge_index> border_edges;
    for (const auto h : border) border_edges.push_back(mesh.edge(h));
    PMP::split_long_edges(border_edges, length, mesh);
  }
  PMP::isotropic_remeshing(mesh.faces(), length, mesh,
                           CGAL::parameters::number_of_iterations(options.iterations)
                               .protect_constraints(options.border == CgalBorder::protect));
  return from_cgal(mesh);
}

/// What the benchmarks that set CGAL beside geodual share, and their options.
struct ComparisonOptions {
  CgalRemeshOptions cgal;      ///< --cgal-iterations N (default 3)
  double tolerance_pct = 3.0;  ///< --tolerance PCT: CGAL's vertex count within this % of geodual's
  int max_runs = 8;            ///< --max-runs R: remeshes to find CGAL's edge length
  std::int64_t samples = quality::QualityOptions{}.samples_per_side;  ///< --samples S: per side, for the distances
  unsigned time_limit_seconds = 1800;                                 ///< --time-limit S: per run
};

/// Reads `word` (and its value) into `options` when it is one of
/// ComparisonOptions' options; false when it is not.
inline bool parse_comparison_option(const std::string& word, const NextValue& value, ComparisonOptions& options) {
  if (word == "--cgal-iterations") {
    options.cgal.iterations = static_cast<unsigned>(parse_integer(word, value(), 1, 1000));
  } else if (word == "--tolerance") {
    options.tolerance_pct = parse_number(word, value());
    if (!(options.tolerance_pct > 0)) throw UsageError("--tolerance must be > 0");
  } else if (word == "--max-runs") {
    options.max_runs = static_cast<int>(parse_integer(word, value(), 1, 100));
  } else if (word == "--samples") {
    options.samples = parse_integer(word, value(), 0, quality::max_samples_per_side);
  } else if (word == "--time-limit") {
    options.time_limit_seconds = static_cast<unsigned>(parse_integer(word, value(), 1, 1'000'000));
  } else {
    return false;
  }
  return true;
}

/// 100 * |vertices / target - 1|.
inline double miss_pct(std::int64_t vertices, std::int64_t target) {
  return 100.0 * std::abs(static_cast<double>(vertices - target)) / static_cast<double>(target);
}

/// What search_edge_length found.
template <class Run>
struct EdgeLengthSearchResult {
  std::optional<Run> result;          ///< the run reported (with figures)
  double length = 0;                  ///< its target edge length
  int runs = 0;                       ///< remeshes done, the reported one included
  double search_seconds = 0;          ///< wall time of all of them
  std::string failure;                ///< why there is no result
  std::int64_t failed_child_rss = 0;  ///< the failed run's peak RSS
};

/// The remesh whose vertex count is within the tolerance of `target`: runs
/// `run_at(length, force_figures)` at the lengths EdgeLengthSearch proposes
/// for a surface of area `area`, at most `max_runs` times, until a run comes
/// back with figures; if none does, the closest length once more with
/// force_figures. `run_at` runs one remesh in a forked child and returns its
/// outcome, whose payload is a Run (trivially copyable, with `vertices`,
/// `seconds` and `has_figures`; the child measures the figures when the count
/// lands within the tolerance, or when forced). The first failed run ends the
/// search. Each run is logged on stderr after `log_prefix`.
template <class Run>
EdgeLengthSearchResult<Run> search_edge_length(double area, std::int64_t target, int max_runs,
                                               std::string_view log_prefix,
                                               const std::function<ChildOutcome(double, bool)>& run_at) {
  EdgeLengthSearchResult<Run> search;
  const auto start = Clock::now();
  const auto run_once = [&](double length, bool force_figures) -> std::optional<Run> {
    const ChildOutcome outcome = run_at(length, force_figures);
    ++search.runs;
    search.search_seconds = seconds_since(start);
    if (outcome.status != ChildOutcome::Status::ok) {
      search.failure = outcome.message;
      search.failed_child_rss = outcome.child_max_rss_bytes;
      return std::nullopt;
    }
    const Run result = from_bytes<Run>(outcome.payload);
    std::cerr << log_prefix << "CGAL L = " << scientific(length, 4) << ": " << result.vertices << " vertices ("
              << fixed(100 * (static_cast<double>(result.vertices) / static_cast<double>(target) - 1), 2) << " %), "
              << fixed(result.seconds, 2) << " s\n";
    return result;
  };
  EdgeLengthSearch lengths(area, target);
  for (int run = 0; run < max_runs; ++run) {
    const double length = lengths.length();
    const std::optional<Run> result = run_once(length, false);
    if (!result) return search;
    if (result->has_figures) {
      search.result = result;
      search.length = length;
      return search;
    }
    lengths.record(result->vertices);
  }
  search.length = lengths.best_length();
  search.result = run_once(search.length, true);
  return search;
}

}  // namespace geodual::bench
