#include "texture/atlas_charts.hpp"

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/sharp_edges.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <utility>

namespace geodual::remesh::detail {
namespace {

/// The weight of a face's distance from the seed beside its normal's
/// deviation in the order charts grow (0.5: the best texture use of a few
/// tried on a sphere, fandisk and a bunny remesh).
constexpr double kRoundness = 0.5;

/// The angle in radians between two unit vectors.
double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// The corner (0, 1, 2) of face f at vertex v; -1 if none.
int corner_at(const TriangleMesh& mesh, Index f, Index v) {
  for (int k = 0; k < 3; ++k) {
    if (mesh.faces(f, k) == v) return k;
  }
  return -1;
}

/// A face waiting to join the chart being grown: the smallest priority
/// (ChartGrower::priority) first, then the earliest pushed.
struct Candidate {
  double deviation;
  Index order;
  Index face;
  bool operator>(const Candidate& other) const {
    return deviation != other.deviation ? deviation > other.deviation : order > other.order;
  }
};

/// Grows one chart from `seed` (see grow_charts); faces turned down are
/// appended to `rejected`, the seeds of later charts.
class ChartGrower {
 public:
  ChartGrower(const TriangleMesh& mesh, const FaceNeighbours& neighbours, double max_angle_degrees)
      : neighbours_(neighbours), max_angle_(max_angle_degrees * std::numbers::pi / 180) {
    const Index n = mesh.num_faces();
    normal_.resize(n);
    centroid_.resize(n);
    area_.resize(n);
    for (Index f = 0; f < n; ++f) {
      normal_[f] = face_unit_normal(mesh, f);
      centroid_[f] = (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
                      mesh.vertices.row(mesh.faces(f, 2))) /
                     3;
      area_[f] = face_area(mesh, f);
    }
    chart_of_.assign(n, -1);
  }

  bool assigned(Index f) const { return chart_of_[f] >= 0; }
  const std::vector<Eigen::Vector3d>& normals() const { return normal_; }
  const std::vector<double>& areas() const { return area_; }

  std::vector<Index> grow(Index seed, Index chart, std::vector<Index>& rejected) {
    std::vector<Index> faces;
    sum_ = Eigen::Vector3d::Zero();
    heap_.clear();
    order_ = 0;
    seed_ = centroid_[seed];
    chart_area_ = 0;
    add(seed, chart, faces);
    reference_ = mean();
    reference_spread_ = 0;
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
      const Index f = heap_.back().face;
      heap_.pop_back();
      if (assigned(f)) continue;
      if (fits(f, faces)) {
        add(f, chart, faces);
      } else {
        rejected.push_back(f);
      }
    }
    return faces;
  }

 private:
  Eigen::Vector3d mean() const {
    const double norm = sum_.norm();
    return norm > 0 ? Eigen::Vector3d(sum_ / norm) : Eigen::Vector3d::Zero();
  }

  void add(Index f, Index chart, std::vector<Index>& faces) {
    chart_of_[f] = chart;
    faces.push_back(f);
    sum_ += area_[f] * normal_[f];
    chart_area_ += area_[f];
    const Eigen::Vector3d m = mean();
    for (const Index g : neighbours_[f]) {
      if (g < 0 || assigned(g)) continue;
      heap_.push_back({priority(g, m), order_++, g});
      std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
    }
  }

  // Whether face f may join: with it, every face of the chart is within the
  // angle of the new mean normal. The faces are within reference_spread_ of
  // reference_, so within that plus the turn from reference_ to the new
  // mean; only when that bound is too loose are they all measured again.
  bool fits(Index f, const std::vector<Index>& faces) {
    const double norm = (sum_ + area_[f] * normal_[f]).norm();
    if (!(norm > 0)) return false;
    const Eigen::Vector3d m = (sum_ + area_[f] * normal_[f]) / norm;
    if (angle_between(normal_[f], m) > max_angle_) return false;
    if (reference_spread_ + angle_between(reference_, m) <= max_angle_) {
      reference_spread_ = std::max(reference_spread_, angle_between(normal_[f], reference_));
      return true;
    }
    double spread = angle_between(normal_[f], m);
    for (const Index g : faces) {
      spread = std::max(spread, angle_between(normal_[g], m));
      if (spread > max_angle_) return false;
    }
    reference_ = m;
    reference_spread_ = spread;
    return true;
  }

  const FaceNeighbours& neighbours_;
  const double max_angle_;
  // Normal deviation (as a share of the cone's angle) plus distance from the
  // seed (as a share of the radius of a disk of the chart's area): charts
  // grow round, which packs better, and turn as little as they can.
  double priority(Index g, const Eigen::Vector3d& mean) const {
    const double radius = std::sqrt(chart_area_ / std::numbers::pi);
    const double distance = radius > 0 ? (centroid_[g] - seed_).norm() / radius : 0;
    return angle_between(normal_[g], mean) / max_angle_ + kRoundness * distance;
  }

  std::vector<Eigen::Vector3d> normal_;
  std::vector<Eigen::Vector3d> centroid_;
  Eigen::Vector3d seed_ = Eigen::Vector3d::Zero();
  double chart_area_ = 0;
  std::vector<double> area_;
  std::vector<Index> chart_of_;
  std::vector<Candidate> heap_;
  Index order_ = 0;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d reference_ = Eigen::Vector3d::Zero();
  double reference_spread_ = 0;
};

/// Breadth-first steps from the faces in `sources` (slots) over the chart's
/// faces; per slot, the source it was reached from, and the slot reached last.
Index breadth_first(const FaceNeighbours& neighbours, const std::vector<Index>& faces,
                    const std::vector<Index>& face_slot, const std::vector<Index>& sources, std::vector<Index>& label) {
  label.assign(faces.size(), -1);
  std::deque<Index> queue;
  for (std::size_t s = 0; s < sources.size(); ++s) {
    label[sources[s]] = static_cast<Index>(s);
    queue.push_back(sources[s]);
  }
  Index last = sources.front();
  while (!queue.empty()) {
    const Index slot = queue.front();
    queue.pop_front();
    last = slot;
    for (const Index g : neighbours[faces[slot]]) {
      if (g < 0 || face_slot[g] < 0 || label[face_slot[g]] >= 0) continue;
      label[face_slot[g]] = label[slot];
      queue.push_back(face_slot[g]);
    }
  }
  return last;
}

/// Charts of fewer than `small` faces merged, in chart order, into the
/// neighbour they share most crossable edges with (then the first) whose
/// faces, with theirs, all stay within the angle of the joint mean normal;
/// charts left empty removed.
void merge_small_charts(const FaceNeighbours& neighbours, const std::vector<Eigen::Vector3d>& normals,
                        const std::vector<double>& areas, double max_angle, std::size_t small,
                        std::vector<std::vector<Index>>& charts) {
  std::vector<Index> chart_of(neighbours.size(), -1);
  std::vector<Eigen::Vector3d> sums(charts.size(), Eigen::Vector3d::Zero());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (const Index f : charts[c]) {
      chart_of[f] = static_cast<Index>(c);
      sums[c] += areas[f] * normals[f];
    }
  }
  auto within_cone = [&](const std::vector<Index>& faces, const Eigen::Vector3d& mean) {
    return std::all_of(faces.begin(), faces.end(),
                       [&](Index f) { return angle_between(normals[f], mean) <= max_angle; });
  };
  std::vector<std::pair<Index, Index>> shared;  // (neighbour chart, crossable edges shared)
  for (std::size_t c = 0; c < charts.size(); ++c) {
    if (charts[c].empty() || charts[c].size() >= small) continue;
    shared.clear();
    for (const Index f : charts[c]) {
      for (const Index g : neighbours[f]) {
        if (g < 0 || chart_of[g] == static_cast<Index>(c)) continue;
        const auto at =
            std::find_if(shared.begin(), shared.end(), [&](const auto& s) { return s.first == chart_of[g]; });
        if (at == shared.end()) {
          shared.emplace_back(chart_of[g], 1);
        } else {
          ++at->second;
        }
      }
    }
    std::stable_sort(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
      return a.second != b.second ? a.second > b.second : a.first < b.first;
    });
    for (const auto& [d, edges] : shared) {
      const Eigen::Vector3d sum = sums[c] + sums[d];
      if (!(sum.norm() > 0)) continue;
      const Eigen::Vector3d mean = sum.normalized();
      if (!within_cone(charts[c], mean) || !within_cone(charts[d], mean)) continue;
      for (const Index f : charts[c]) chart_of[f] = d;
      charts[d].insert(charts[d].end(), charts[c].begin(), charts[c].end());
      sums[d] = sum;
      charts[c].clear();
      break;
    }
  }
  std::erase_if(charts, [](const std::vector<Index>& faces) { return faces.empty(); });
}

}  // namespace

FaceNeighbours chart_neighbours(const TriangleMesh& mesh, const std::vector<std::array<Index, 2>>& seams) {
  const MeshTopology topology = build_mesh_topology(mesh);
  std::vector<std::uint8_t> is_seam(topology.num_edges(), 0);
  for (const auto& [a, b] : seams) {
    const Index e = topology.find_edge(a, b);
    if (e >= 0) is_seam[e] = 1;
  }
  std::vector<std::uint8_t> has_area(mesh.num_faces());
  for (Index f = 0; f < mesh.num_faces(); ++f) has_area[f] = has_positive_area(mesh, f) ? 1 : 0;

  FaceNeighbours neighbours(mesh.num_faces(), {-1, -1, -1});
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!has_area[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const Index e = topology.face_edges[f][k];
      if (e < 0 || is_seam[e]) continue;
      const auto faces = topology.edge_faces(e);
      if (faces.size() != 2) continue;
      const Index g = faces[0] == f ? faces[1] : faces[0];
      const Index a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (!has_area[g] || face_runs_edge(mesh, g, a, b)) continue;
      neighbours[f][k] = g;
    }
  }
  return neighbours;
}

std::vector<std::vector<Index>> grow_charts(const TriangleMesh& mesh, const FaceNeighbours& neighbours,
                                            double max_angle_degrees) {
  ChartGrower grower(mesh, neighbours, max_angle_degrees);
  std::vector<std::vector<Index>> charts;
  std::vector<Index> rejected;
  std::size_t next_rejected = 0;
  Index next_face = 0;
  for (;;) {
    while (next_rejected < rejected.size() && grower.assigned(rejected[next_rejected])) ++next_rejected;
    Index seed = -1;
    if (next_rejected < rejected.size()) {
      seed = rejected[next_rejected];
    } else {
      while (next_face < mesh.num_faces() && grower.assigned(next_face)) ++next_face;
      if (next_face == mesh.num_faces()) break;
      seed = next_face;
    }
    charts.push_back(grower.grow(seed, static_cast<Index>(charts.size()), rejected));
  }
  constexpr std::size_t small_chart = 16;
  merge_small_charts(neighbours, grower.normals(), grower.areas(), max_angle_degrees * std::numbers::pi / 180,
                     small_chart, charts);
  return charts;
}

ChartSurface chart_surface(const TriangleMesh& mesh, const FaceNeighbours& neighbours, std::vector<Index> faces,
                           std::vector<Index>& face_slot) {
  ChartSurface chart;
  chart.faces = std::move(faces);
  const Index n = static_cast<Index>(chart.faces.size());
  for (Index i = 0; i < n; ++i) face_slot[chart.faces[i]] = i;

  // Corners 3 i + k; those at one vertex joined across the chart's inner edges.
  UnionFind corners(3 * static_cast<std::size_t>(n));
  Index inner_sides = 0;
  Index boundary_sides = 0;
  for (Index i = 0; i < n; ++i) {
    const Index f = chart.faces[i];
    for (int k = 0; k < 3; ++k) {
      const Index g = neighbours[f][k];
      if (g < 0 || face_slot[g] < 0) {
        ++boundary_sides;
        continue;
      }
      ++inner_sides;
      const Index j = face_slot[g];
      const int next = (k + 1) % 3;
      corners.unite(3 * i + k, 3 * j + corner_at(mesh, g, mesh.faces(f, k)));
      corners.unite(3 * i + next, 3 * j + corner_at(mesh, g, mesh.faces(f, next)));
    }
  }
  std::vector<Index> vertex_of_root(3 * static_cast<std::size_t>(n), -1);
  chart.corners.resize(n);
  for (Index i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      Index& v = vertex_of_root[corners.find(3 * i + k)];
      if (v < 0) {
        v = static_cast<Index>(chart.source_vertex.size());
        chart.source_vertex.push_back(mesh.faces(chart.faces[i], k));
      }
      chart.corners[i][k] = v;
    }
  }
  const Index vertices = static_cast<Index>(chart.source_vertex.size());
  chart.euler_characteristic = vertices - (inner_sides / 2 + boundary_sides) + n;

  // Boundary loops: each chart vertex is one fan of corners, so a boundary
  // vertex starts exactly one boundary edge; follow them round.
  std::vector<Index> boundary_from(vertices, -1);
  std::vector<Index> boundary_to;
  bool fans = true;
  for (Index i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Index g = neighbours[chart.faces[i]][k];
      if (g >= 0 && face_slot[g] >= 0) continue;
      Index& from = boundary_from[chart.corners[i][k]];
      if (from >= 0) fans = false;
      from = static_cast<Index>(boundary_to.size());
      boundary_to.push_back(chart.corners[i][(k + 1) % 3]);
    }
  }
  std::vector<std::uint8_t> visited(boundary_to.size(), 0);
  for (std::size_t start = 0; start < boundary_to.size() && fans; ++start) {
    if (visited[start]) continue;
    ++chart.boundary_loops;
    for (Index side = static_cast<Index>(start); side >= 0 && !visited[side];) {
      visited[side] = 1;
      side = boundary_from[boundary_to[side]];
      if (side < 0) fans = false;
    }
  }
  if (!fans) chart.boundary_loops = -1;
  for (const Index f : chart.faces) face_slot[f] = -1;
  return chart;
}

std::array<std::vector<Index>, 2> split_chart(const FaceNeighbours& neighbours, const std::vector<Index>& faces,
                                              std::vector<Index>& face_slot) {
  for (std::size_t i = 0; i < faces.size(); ++i) face_slot[faces[i]] = static_cast<Index>(i);
  std::vector<Index> label;
  const Index far = breadth_first(neighbours, faces, face_slot, {0}, label);
  const Index other = breadth_first(neighbours, faces, face_slot, {far}, label);
  breadth_first(neighbours, faces, face_slot, {other, far}, label);
  std::array<std::vector<Index>, 2> parts;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    parts[label[i] == 1 ? 1 : 0].push_back(faces[i]);
    face_slot[faces[i]] = -1;
  }
  return parts;
}

}  // namespace geodual::remesh::detail
