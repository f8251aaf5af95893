// triangle_quality: element shape, valence and topology figures of one mesh
// (no CGAL here; the distances between meshes live in quality_stats.cpp).

#include "geodual/quality/quality_stats.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/mesh/triangle_shape.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace geodual::quality {
namespace {

constexpr double degrees_per_radian = 180.0 / std::numbers::pi;
constexpr double thirty_degrees = std::numbers::pi / 6.0;

/// Shape of one face: Q, its three angles (radians) and area.
struct FaceShape {
  double q = 0.0;
  std::array<double, 3> angles{0.0, 0.0, std::numbers::pi};  ///< a degenerate face's
  double area = 0.0;
  bool degenerate = true;
};

FaceShape face_shape(const TriangleMesh& mesh, Index f) {
  FaceShape shape;
  if (!has_positive_area(mesh, f)) return shape;  // as analyze_mesh says
  const TriangleShape triangle = triangle_shape(
      mesh.vertices.row(mesh.faces(f, 0)), mesh.vertices.row(mesh.faces(f, 1)), mesh.vertices.row(mesh.faces(f, 2)));
  shape.q = triangle.q;
  shape.angles = triangle.angles;
  shape.area = triangle.area;
  shape.degenerate = false;
  return shape;
}

void check_mesh(const TriangleMesh& mesh) {
  if (mesh.num_faces() == 0) throw Error("the mesh has no faces");
  const Index n = mesh.num_vertices();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.faces(f, k);
      if (v < 0 || v >= n) {
        throw Error("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + ", but the mesh has " +
                    std::to_string(n) + " vertices");
      }
    }
  }
  for (Index v = 0; v < n; ++v) {
    if (!mesh.vertices.row(v).allFinite()) {
      throw Error("vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
}

/// Valences of the interior vertices (see TriangleQuality::valence_histogram):
/// every face side joining two different indices, sorted as (min, max) keys,
/// so that the sides of each undirected edge come together.
void count_valences(const TriangleMesh& mesh, TriangleQuality& quality) {
  std::vector<std::uint64_t> sides;
  sides.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint32_t>(mesh.faces(f, k));
      const auto w = static_cast<std::uint32_t>(mesh.faces(f, (k + 1) % 3));
      if (u == w) continue;
      sides.push_back(std::uint64_t{std::min(u, w)} << 32 | std::max(u, w));
    }
  }
  std::sort(sides.begin(), sides.end());

  const auto n = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<std::int32_t> valence(n, 0);
  std::vector<char> interior(n, 1);  // cleared by a boundary or non-manifold edge
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    const auto u = static_cast<std::size_t>(sides[i] >> 32);
    const auto w = static_cast<std::size_t>(sides[i] & 0xffff'ffffU);
    ++valence[u];
    ++valence[w];
    if (j - i != 2) interior[u] = interior[w] = 0;
    i = j;
  }

  for (std::size_t v = 0; v < n; ++v) {
    if (valence[v] == 0 || !interior[v]) continue;  // unreferenced, or touches no edge
    const auto k = static_cast<std::size_t>(valence[v]);
    if (quality.valence_histogram.size() <= k) quality.valence_histogram.resize(k + 1, 0);
    ++quality.valence_histogram[k];
    ++quality.interior_vertices;
  }
  if (quality.interior_vertices > 0) {
    const std::int64_t six = quality.valence_histogram.size() > 6 ? quality.valence_histogram[6] : 0;
    quality.pct_valence6 = 100.0 * static_cast<double>(six) / static_cast<double>(quality.interior_vertices);
  }
}

}  // namespace

double face_quality(const TriangleMesh& mesh, Index face) { return face_shape(mesh, face).q; }

TriangleQuality triangle_quality(const TriangleMesh& mesh) {
  check_mesh(mesh);
  const MeshReport report = analyze_mesh(mesh);

  TriangleQuality quality;
  quality.vertices = mesh.num_vertices();
  quality.faces = mesh.num_faces();
  quality.euler_characteristic = report.euler_characteristic;
  quality.genus = report.genus;
  quality.components = report.components;
  quality.boundary_loops = report.boundary_loops;
  quality.nonmanifold_edges = report.nonmanifold_edges;
  quality.bbox_diagonal = report.bbox_diagonal;

  // Volume relative to the bounding-box centre: the same value as from the
  // origin for a closed mesh, with far less cancellation for a scan placed
  // away from the origin.
  const Eigen::Vector3d centre = 0.5 * (report.bbox_min + report.bbox_max);
  double q_sum = 0.0;
  double min_angle_sum = 0.0;
  std::int64_t angles_lt30 = 0;
  std::int64_t faces_lt30 = 0;
  quality.q_min = std::numeric_limits<double>::infinity();
  double theta_min = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const FaceShape shape = face_shape(mesh, f);
    quality.q_min = std::min(quality.q_min, shape.q);
    q_sum += shape.q;
    const double smallest = std::min({shape.angles[0], shape.angles[1], shape.angles[2]});
    theta_min = std::min(theta_min, smallest);
    min_angle_sum += smallest;
    for (const double angle : shape.angles) angles_lt30 += angle < thirty_degrees ? 1 : 0;
    faces_lt30 += smallest < thirty_degrees ? 1 : 0;
    if (shape.degenerate) {
      ++quality.degenerate_faces;
      continue;
    }
    quality.area += shape.area;
    const Eigen::Vector3d p0 = mesh.vertices.row(mesh.faces(f, 0)).transpose() - centre;
    const Eigen::Vector3d p1 = mesh.vertices.row(mesh.faces(f, 1)).transpose() - centre;
    const Eigen::Vector3d p2 = mesh.vertices.row(mesh.faces(f, 2)).transpose() - centre;
    quality.volume += p0.dot(p1.cross(p2)) / 6.0;
  }
  const auto faces = static_cast<double>(quality.faces);
  quality.q_avg = q_sum / faces;
  quality.theta_min_deg = theta_min * degrees_per_radian;
  quality.theta_min_avg_deg = min_angle_sum / faces * degrees_per_radian;
  quality.pct_angles_lt30 = 100.0 * static_cast<double>(angles_lt30) / (3.0 * faces);
  quality.p30 = 100.0 * static_cast<double>(faces_lt30) / (3.0 * faces);

  count_valences(mesh, quality);
  return quality;
}

}  // namespace geodual::quality
