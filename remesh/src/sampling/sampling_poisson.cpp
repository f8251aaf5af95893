// Blue noise by weighted sample elimination (C. Yuksel, "Sample Elimination
// for Generating Poisson Disk Sample Sets", Computer Graphics Forum 2015).
//
// Draw M = 5 n candidates uniformly by area, give each the weight
//   w_i = sum over neighbours j with d_ij < 2 r_max of (1 - d^_ij / (2 r_max))^8,
// d^_ij = max(d_ij, r_min), and repeatedly remove the candidate of largest
// weight (updating its neighbours) until n remain. r_max is the radius of n
// disks packed hexagonally on the component's area A counting every site of
// the component (boundary ones included): r_max = s / 2 with
// s = sqrt(2 A / (sqrt(3) N)); r_min = r_max (1 - (n / M)^1.5) 0.65 (Yuksel's
// weight limiting, which keeps close pairs from dominating). Distances are 3D
// Euclidean, a good stand-in for geodesic ones at the scale of the spacing.
// Boundary sites are neighbours that add weight but are never removed.

#include "common/point_grid.hpp"
#include "sampling/sampling_strategies.hpp"

#include <algorithm>

namespace geodual::remesh::detail {
namespace {

constexpr std::int64_t kCandidatesPerSite = 5;

/// Max-heap of items (indices into `weight`) by weight, ties to the smaller
/// index, whose weights only ever decrease.
class EliminationHeap {
 public:
  EliminationHeap(const std::vector<double>& weight, std::vector<Index> items)
      : weight_(weight), heap_(std::move(items)), position_(weight.size(), -1) {
    const auto size = static_cast<Index>(heap_.size());
    for (Index slot = 0; slot < size; ++slot) position_[heap_[slot]] = slot;
    for (Index slot = size / 2; slot-- > 0;) sift_down(slot);
  }
  Index pop() {
    const Index top = heap_[0];
    place(0, heap_.back());
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0);
    position_[top] = -1;
    return top;
  }
  /// Restores the order after weight[i] decreased.
  void decreased(Index i) { sift_down(position_[i]); }

 private:
  bool above(Index a, Index b) const { return weight_[a] > weight_[b] || (weight_[a] == weight_[b] && a < b); }
  void place(Index slot, Index item) {
    heap_[slot] = item;
    position_[item] = slot;
  }
  void sift_down(Index slot) {
    const Index item = heap_[slot];
    const auto size = static_cast<Index>(heap_.size());
    for (;;) {
      Index child = 2 * slot + 1;
      if (child >= size) break;
      if (child + 1 < size && above(heap_[child + 1], heap_[child])) ++child;
      if (!above(heap_[child], item)) break;
      place(slot, heap_[child]);
      slot = child;
    }
    place(slot, item);
  }

  const std::vector<double>& weight_;
  std::vector<Index> heap_;
  std::vector<Index> position_;
};

}  // namespace

void sample_interior_poisson(const SamplingSurface& surface, const ComponentTask& task, Rng& rng,
                             std::vector<SurfacePoint>& out) {
  const std::int64_t n = task.interior;
  if (n <= 0) return;
  const TriangleMesh& mesh = *surface.mesh;
  const std::int64_t m = kCandidatesPerSite * n;
  const auto num_candidates = static_cast<std::size_t>(m);

  std::vector<SurfacePoint> candidates(num_candidates);
  std::vector<Eigen::Vector3d> points(num_candidates + task.boundary_sites.size());
  for (std::size_t i = 0; i < num_candidates; ++i) {
    candidates[i] = random_point_in_face(surface.random_face(task.component, rng), rng);
    points[i] = site_position(mesh, candidates[i]);
  }
  for (std::size_t j = 0; j < task.boundary_sites.size(); ++j) {
    points[num_candidates + j] = site_position(mesh, task.boundary_sites[j]);
  }

  const double r_max = 0.5 * hexagonal_spacing(surface.component_area[task.component], task.total);
  const double reach = 2 * r_max;
  const double ratio = static_cast<double>(n) / static_cast<double>(m);
  const double r_min = r_max * (1 - ratio * std::sqrt(ratio)) * 0.65;  // sqrt, not pow: correctly rounded everywhere
  auto weight_of = [&](double squared_distance) {
    const double x = 1 - std::max(std::sqrt(squared_distance), r_min) / reach;
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  };

  // Everything below is indexed by grid slot: neighbours sit next to each
  // other in memory.
  const PointGrid grid(points, reach);
  const Index num_points = grid.size();
  auto is_candidate = [&](Index slot) { return static_cast<std::size_t>(grid.original(slot)) < num_candidates; };
  std::vector<double> weight(static_cast<std::size_t>(num_points), 0.0);
  std::vector<Index> candidate_slots;
  candidate_slots.reserve(num_candidates);
  for (Index slot = 0; slot < num_points; ++slot) {
    if (!is_candidate(slot)) continue;
    candidate_slots.push_back(slot);
    double sum = 0;
    grid.for_each_near(slot, [&](Index other, double d2) {
      if (other != slot) sum += weight_of(d2);
    });
    weight[slot] = sum;
  }

  EliminationHeap heap(weight, std::move(candidate_slots));
  std::vector<std::uint8_t> removed(static_cast<std::size_t>(num_points), 0);
  for (std::int64_t k = 0; k < m - n; ++k) {
    const Index slot = heap.pop();
    removed[slot] = 1;
    grid.for_each_near(slot, [&](Index other, double d2) {
      if (removed[other] || !is_candidate(other)) return;
      weight[other] -= weight_of(d2);
      heap.decreased(other);
    });
  }
  // The survivors, in the order they were drawn.
  std::vector<Index> kept;
  for (Index slot = 0; slot < num_points; ++slot) {
    if (!removed[slot] && is_candidate(slot)) kept.push_back(grid.original(slot));
  }
  std::sort(kept.begin(), kept.end());
  for (const Index i : kept) out.push_back(candidates[i]);
}

}  // namespace geodual::remesh::detail
