#include "common/surface_walk.hpp"

#include "geodual/mesh/face_area.hpp"

#include <Eigen/Geometry>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace geodual::remesh::detail {
namespace {

Eigen::Vector3d corner(const TriangleMesh& mesh, Index face, int c) {
  return mesh.vertices.row(mesh.faces(face, c)).transpose();
}

/// Barycentric coordinates of p (in the face's plane) with respect to the face.
Eigen::Vector3d barycentric_in(const TriangleMesh& mesh, Index face, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = corner(mesh, face, 0), b = corner(mesh, face, 1), c = corner(mesh, face, 2);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double twice = n.squaredNorm();
  Eigen::Vector3d w(n.dot((c - b).cross(p - b)), n.dot((a - c).cross(p - c)), 0.0);
  w /= twice;
  w = w.cwiseMax(0.0);
  w[2] = std::max(0.0, 1.0 - w[0] - w[1]);
  return w / w.sum();
}

}  // namespace

bool on_surface_boundary(const voronoi::SurfaceTopology& topology, const SurfacePoint& point) {
  if (point.kind != SurfacePoint::Kind::face) return false;
  for (int c = 0; c < 3; ++c) {
    if (point.barycentric[c] != 0) continue;
    const Index edge = topology.face_edges[point.element][(c + 1) % 3];  // the side opposite corner c
    if (edge >= 0 && (topology.edge_faces[edge][0] < 0 || topology.edge_faces[edge][1] < 0)) return true;
  }
  return false;
}

SurfacePoint walk_on_surface(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                             const SurfacePoint& start, const Eigen::Vector3d& direction, double length) {
  if (start.kind != SurfacePoint::Kind::face || !(length > 0) || !direction.allFinite()) return start;
  Index face = start.element;
  Eigen::Vector3d p = start.position(mesh);
  Eigen::Vector3d normal =
      (corner(mesh, face, 1) - corner(mesh, face, 0)).cross(corner(mesh, face, 2) - corner(mesh, face, 0));
  if (!(normal.norm() > 0)) return start;
  normal.normalize();
  Eigen::Vector3d v = direction - normal * normal.dot(direction);
  if (!(v.norm() > 0)) return start;
  v.normalize();
  double remaining = length;
  Index entry_edge = -1;
  // A face without area (as the geodesic engine sees it, which refuses a
  // site there) is crossed flat but never ended in: a walk ending in one
  // stops where it entered it, on the last face with area.
  bool flat = false;
  Index last_face = face;
  Eigen::Vector3d last_point = p;
  auto stop = [&] {
    const Index at = flat ? last_face : face;
    const Eigen::Vector3d b = barycentric_in(mesh, at, flat ? last_point : p);
    return SurfacePoint::in_face(at, b[0], b[1], b[2]);
  };
  for (int step = 0; step < 1'000'000; ++step) {
    // The nearest side the ray leaves through (not the one it came in by).
    double exit_t = INFINITY;
    int exit_side = -1;
    for (int k = 0; k < 3; ++k) {
      if (topology.face_edges[face][k] == entry_edge) continue;
      const Eigen::Vector3d a = corner(mesh, face, k), b = corner(mesh, face, (k + 1) % 3);
      const Eigen::Vector3d side = b - a;
      // p + t v = a + u side, within the face's plane.
      const double denominator = normal.dot(v.cross(side));
      if (!(std::abs(denominator) > 0)) continue;
      const double t = normal.dot((a - p).cross(side)) / denominator;
      const double u = normal.dot((a - p).cross(v)) / denominator;
      if (t > 0 && u >= -1e-12 && u <= 1 + 1e-12 && t < exit_t) exit_t = t, exit_side = k;
    }
    if (exit_side < 0 || exit_t >= remaining) {
      p += std::min(remaining, exit_side < 0 ? 0.0 : remaining) * v;
      return stop();
    }
    p += exit_t * v;
    remaining -= exit_t;
    const Index edge = topology.face_edges[face][exit_side];
    const Index next =
        topology.edge_faces[edge][0] == face ? topology.edge_faces[edge][1] : topology.edge_faces[edge][0];
    if (next < 0) return stop();  // the mesh boundary: stop on it
    // Unfold about the edge: keep the component along it, and turn the rest
    // into the next face's plane, pointing into that face.
    const Eigen::Vector3d a = corner(mesh, face, exit_side), b = corner(mesh, face, (exit_side + 1) % 3);
    const Eigen::Vector3d along = (b - a).normalized();
    Eigen::Vector3d next_normal =
        (corner(mesh, next, 1) - corner(mesh, next, 0)).cross(corner(mesh, next, 2) - corner(mesh, next, 0));
    if (!flat) last_face = face, last_point = p;
    flat = !has_positive_area(mesh, next);
    if (flat) next_normal = normal;  // cross it flat
    next_normal.normalize();
    Eigen::Vector3d inward = next_normal.cross(along);
    // `inward` must point from the edge into the next face.
    Eigen::Vector3d opposite = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      const Index vertex = mesh.faces(next, c);
      if (vertex != mesh.faces(face, exit_side) && vertex != mesh.faces(face, (exit_side + 1) % 3)) {
        opposite = mesh.vertices.row(vertex).transpose();
      }
    }
    if (inward.dot(opposite - a) < 0) inward = -inward;
    const double tangential = v.dot(along);
    const double across = std::sqrt(std::max(0.0, 1 - tangential * tangential));
    v = (tangential * along + across * inward).normalized();
    face = next;
    normal = next_normal;
    entry_edge = edge;
  }
  return stop();
}

namespace {

/// The fans round the vertices of the faces `kept` keeps.
template <class Kept>
VertexFans fans_of(const TriangleMesh& mesh, Kept kept) {
  VertexFans fans;
  fans.begin.assign(static_cast<std::size_t>(mesh.num_vertices()) + 1, 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!kept(f)) continue;
    for (int c = 0; c < 3; ++c) ++fans.begin[mesh.faces(f, c) + 1];
  }
  std::partial_sum(fans.begin.begin(), fans.begin.end(), fans.begin.begin());
  fans.face.resize(static_cast<std::size_t>(fans.begin.back()));
  std::vector<Index> fill(fans.begin.begin(), fans.begin.end() - 1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!kept(f)) continue;
    for (int c = 0; c < 3; ++c) fans.face[fill[mesh.faces(f, c)]++] = f;
  }
  return fans;
}

}  // namespace

VertexFans vertex_fans(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology) {
  return fans_of(mesh, [&](Index f) { return topology.face_edges[f][0] >= 0; });
}

VertexFans vertex_fans(const TriangleMesh& mesh) {
  return fans_of(mesh, [](Index) { return true; });
}

bool any_at_vertex(std::span<const SurfacePoint> sites) {
  return std::any_of(sites.begin(), sites.end(),
                     [](const SurfacePoint& p) { return p.kind == SurfacePoint::Kind::vertex; });
}

/// Every site walked along the surface by its step (a tangent vector at the
/// site); a pair landing on one point keeps its old places.
std::vector<SurfacePoint> move_sites(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                     std::span<const SurfacePoint> sites, std::span<const Eigen::Vector3d> steps) {
  std::vector<SurfacePoint> moved(sites.begin(), sites.end());
  // A vertex site steps from the corner of the face around it whose angle
  // holds the step's direction.
  VertexFans fans;
  if (any_at_vertex(sites)) fans = vertex_fans(mesh, topology);
  auto as_face_point = [&](const SurfacePoint& site, const Eigen::Vector3d& step) {
    if (site.kind == SurfacePoint::Kind::face || fans.begin.empty()) return site;
    const Index v = site.element;
    SurfacePoint best = site;
    for (const Index f : fans.around(v)) {
      if (!has_positive_area(mesh, f)) continue;  // a walk cannot start in a flat face
      int c = 0;
      while (mesh.faces(f, c) != v) ++c;
      const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
      const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, (c + 1) % 3)).transpose() - p;
      const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, (c + 2) % 3)).transpose() - p;
      const Eigen::Vector3d n = a.cross(b);
      Eigen::Vector3d b3 = Eigen::Vector3d::Zero();
      b3[c] = 1;
      if (best.kind == SurfacePoint::Kind::vertex) best = SurfacePoint::in_face(f, b3[0], b3[1], b3[2]);
      if (n.dot(a.cross(step)) >= 0 && n.dot(step.cross(b)) >= 0) return SurfacePoint::in_face(f, b3[0], b3[1], b3[2]);
    }
    return best;
  };
  // Each site's step is independent of the others: bit-identical for any
  // number of threads.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, moved.size()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Eigen::Vector3d& step = steps[i];
                        const double length = step.norm();
                        if (!(length > 0)) continue;
                        const SurfacePoint site = as_face_point(sites[i], step);
                        if (site.kind != SurfacePoint::Kind::face) continue;
                        moved[i] = walk_on_surface(mesh, topology, site, step, length);
                      }
                    });
  // The sites by their places, each place with its site: a site goes back
  // when its place is another's too, whatever the order among equal places.
  struct Placed {
    double x, y, z;
    std::size_t site;
    auto key() const { return std::tie(x, y, z); }
  };
  std::vector<Placed> placed(moved.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, moved.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Eigen::Vector3d p = moved[i].position(mesh);
                        placed[i] = {p.x(), p.y(), p.z(), i};
                      }
                    });
  tbb::parallel_sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) { return a.key() < b.key(); });
  for (std::size_t k = 1; k < placed.size(); ++k) {
    if (placed[k].key() == placed[k - 1].key()) {
      moved[placed[k].site] = sites[placed[k].site];
      moved[placed[k - 1].site] = sites[placed[k - 1].site];
    }
  }
  return moved;
}

}  // namespace geodual::remesh::detail
