#include "site_groups.hpp"

#include "geodual/mesh/detail/morton_code.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>

namespace geodual::voronoi::detail {

int site_group_count(std::size_t num_sites, int requested) {
  constexpr std::size_t kSitesPerGroup = 256;
  // Two groups at least, so that a second core has work on small inputs:
  // splitting costs one group's propagation a band beyond its cells.
  constexpr std::size_t kMinGroups = 2;
  constexpr std::size_t kMaxGroups = 16;
  if (num_sites == 0) return 1;
  const std::size_t groups = requested > 0 ? static_cast<std::size_t>(requested)
                                           : std::clamp(num_sites / kSitesPerGroup, kMinGroups, kMaxGroups);
  return static_cast<int>(std::min(groups, num_sites));
}

std::vector<int> partition_sites(std::span<const Eigen::Vector3d> positions, int groups) {
  const std::size_t n = positions.size();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& p : positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = n > 0 ? (hi - lo).maxCoeff() : 0.0;
  constexpr double kCells = (1 << 21) - 1;
  const double scale = extent > 0 && std::isfinite(extent) ? kCells / extent : 0.0;
  std::vector<std::uint64_t> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<std::uint64_t, 3> cell{};
    for (int axis = 0; axis < 3; ++axis) {
      const double q = (positions[i][axis] - lo[axis]) * scale;
      cell[static_cast<std::size_t>(axis)] = static_cast<std::uint64_t>(q > 0 ? std::min(q, kCells) : 0.0);
    }
    code[i] = morton_code(cell[0], cell[1], cell[2]);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return code[a] != code[b] ? code[a] < code[b] : a < b; });
  std::vector<int> group(n, 0);
  for (std::size_t rank = 0; rank < n; ++rank) {
    group[order[rank]] = static_cast<int>(rank * static_cast<std::size_t>(groups) / n);
  }
  return group;
}

namespace {

/// The diagonal from corner c of `face` to the far corner w of the face
/// across its opposite edge: the straight line in the two faces unfolded
/// into one plane, where it crosses that edge inside. {w, length}, or w = -1
/// where there is none.
std::pair<Index, double> diagonal_across(const PropagationMesh& pm, Index face, int c) {
  const FaceRecord& record = pm.face_records[face];
  const int opposite = (c + 1) % 3;  // local edge from corner c + 1 to c + 2
  const Index edge = record.edge(opposite);
  const std::array<Index, 2> faces = pm.edge_faces[edge];
  const Index other = faces[0] == face ? faces[1] : faces[0];
  if (other < 0 || other == face) return {-1, 0.0};
  const FaceRecord& across = pm.face_records[other];
  const int k = pm.local_edge(across, edge);
  const Index w = across.vertex[(k + 2) % 3];
  if (w == record.vertex[c]) return {-1, 0.0};
  // Both apexes in the frame of the edge from corner c + 1 (x = 0): c above
  // it, w below (its own layout runs the other way where it starts at c + 2).
  const EdgeLayout near = pm.layout(face, opposite), far = pm.layout(other, k);
  if (!(near.length > 0 && near.apex.y() > 0 && far.apex.y() > 0)) return {-1, 0.0};
  const double xc = near.apex.x(), yc = near.apex.y(), yw = far.apex.y();
  const double xw = across.vertex[k] == record.vertex[opposite] ? far.apex.x() : near.length - far.apex.x();
  const double crossing = xc + (xw - xc) * (yc / (yc + yw));
  if (!(crossing > 0 && crossing < near.length)) return {-1, 0.0};
  return {w, std::hypot(xc - xw, yc + yw)};
}

}  // namespace

std::vector<double> surface_path_upper_bound(const PropagationMesh& pm, std::span<const SurfacePoint> local_sites) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<double> bound(static_cast<std::size_t>(pm.num_vertices()), kInfinity);
  // Label-correcting shortest paths with a bucket queue (Dial's algorithm on
  // buckets two mean edges long), each bucket's vertices expanded in
  // parallel, in vertex order (locality order: in the order they came, a
  // bucket's vertices lie all over the mesh, a cache miss each); a vertex is
  // expanded again if it is lowered later. Whatever the order, a vertex ends
  // at the smallest over all graph paths of the lengths summed along the path
  // (each value it takes is such a sum, and each lowering is passed on), so
  // the result is Dijkstra's, and the same on any number of threads. The
  // graph: the edges, and across each edge the straight line between the
  // opposite corners of its two faces unfolded into one plane, where it
  // crosses the edge (a path on the surface too); these diagonals make the
  // bound about three times as close to d as edges alone.
  double total_length = 0;
  for (const double length : pm.edge_lengths) total_length += length;
  const double width = pm.num_edges() > 0 ? 2 * total_length / static_cast<double>(pm.num_edges()) : 1.0;
  // Beyond the last bucket everything goes in it (then a FIFO: still exact).
  const std::size_t max_buckets = 4 * static_cast<std::size_t>(pm.num_vertices()) + 1;
  auto bucket_of = [&](double d) {
    const double slot = width > 0 ? d / width : 0.0;
    return slot < static_cast<double>(max_buckets - 1) ? static_cast<std::size_t>(slot) : max_buckets - 1;
  };
  using Entry = std::pair<double, Index>;
  struct Reached {
    std::size_t bucket;
    Entry entry;
  };
  /// Lowers bound[v] to d if d is lower (from any thread); true if it did.
  auto lower = [&](Index v, double d) {
    std::atomic_ref<double> slot(bound[static_cast<std::size_t>(v)]);
    double old = slot.load(std::memory_order_relaxed);
    while (d < old) {
      if (slot.compare_exchange_weak(old, d, std::memory_order_relaxed)) return true;
    }
    return false;
  };
  std::vector<std::vector<Entry>> buckets;
  auto add = [&](const Reached& r) {
    if (r.bucket >= buckets.size()) buckets.resize(r.bucket + 1);
    buckets[r.bucket].push_back(r.entry);
  };
  for (const SurfacePoint& site : local_sites) {
    std::array<std::pair<Index, double>, 3> starts{};
    int count = 0;
    if (site.kind == SurfacePoint::Kind::vertex) {
      starts[static_cast<std::size_t>(count++)] = {site.element, 0.0};
    } else {
      // The same straight lines window-VTP's add_face_site measures.
      const FaceInPlane plane = lay_out_face(pm, site.element, 0);
      const Eigen::Vector2d p = site.barycentric[0] * plane.corner[0] + site.barycentric[1] * plane.corner[1] +
                                site.barycentric[2] * plane.corner[2];
      for (int c = 0; c < 3; ++c) {
        starts[static_cast<std::size_t>(count++)] = {pm.vertex(site.element, c), (p - plane.corner[c]).norm()};
      }
    }
    for (int i = 0; i < count; ++i) {
      const auto [v, d] = starts[static_cast<std::size_t>(i)];
      if (lower(v, d)) add({bucket_of(d), {d, v}});
    }
  }
  tbb::enumerable_thread_specific<std::vector<Reached>> reached;
  tbb::enumerable_thread_specific<std::vector<Index>> fans;
  for (std::size_t b = 0; b < buckets.size(); ++b) {
    while (!buckets[b].empty()) {
      std::vector<Entry> current = std::move(buckets[b]);
      buckets[b] = std::vector<Entry>();
      std::sort(current.begin(), current.end(), [](const Entry& x, const Entry& y) {
        return x.second != y.second ? x.second < y.second : x.first < y.first;
      });
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, current.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
            std::vector<Reached>& out = reached.local();
            std::vector<Index>& fan = fans.local();
            for (std::size_t i = range.begin(); i < range.end(); ++i) {
              const auto [d, v] = current[i];
              if (d > std::atomic_ref<double>(bound[static_cast<std::size_t>(v)]).load(std::memory_order_relaxed)) {
                continue;  // lowered since
              }
              pm.faces_around(v, fan);
              for (const Index f : fan) {
                const FaceRecord& face = pm.face_records[f];
                const int c = pm.corner_of(f, v);
                // Local edge c joins corners c and c + 1, local edge c + 2 corners c + 2 and c.
                const Index u1 = face.vertex[(c + 1) % 3], u2 = face.vertex[(c + 2) % 3];
                const double d1 = d + pm.edge_length(face.edge(c));
                const double d2 = d + pm.edge_length(face.edge((c + 2) % 3));
                if (lower(u1, d1)) out.push_back({bucket_of(d1), {d1, u1}});
                if (lower(u2, d2)) out.push_back({bucket_of(d2), {d2, u2}});
                const auto [w, diagonal] = diagonal_across(pm, f, c);
                if (w >= 0 && lower(w, d + diagonal)) out.push_back({bucket_of(d + diagonal), {d + diagonal, w}});
              }
            }
          });
      for (std::vector<Reached>& out : reached) {
        for (const Reached& r : out) add(r);
        out.clear();
      }
    }
  }
  double longest = 0;
  for (const double length : pm.edge_lengths) longest = std::max(longest, length);
  for (double& b : bound) b = b * (1 + 1e-9) + 1e-12 * longest;
  return bound;
}

SiteTree::SiteTree(std::span<const Eigen::Vector3d> positions, std::span<const int> groups)
    : points_(positions.begin(), positions.end()), group_(groups.begin(), groups.end()), axis_(positions.size(), 0) {
  build(0, static_cast<int>(points_.size()));
}

void SiteTree::build(int lo, int hi) {
  if (hi - lo <= kLeafSize) return;
  Eigen::Vector3d low = points_[static_cast<std::size_t>(lo)], high = low;
  for (int i = lo; i < hi; ++i) {
    low = low.cwiseMin(points_[static_cast<std::size_t>(i)]);
    high = high.cwiseMax(points_[static_cast<std::size_t>(i)]);
  }
  int axis = 0;
  (high - low).maxCoeff(&axis);
  const int mid = (lo + hi) / 2;
  // Sort a permutation of [lo, hi) by the axis (ties by position in the
  // array, so that the tree is the same on every run), then apply it.
  std::vector<int> order(static_cast<std::size_t>(hi - lo));
  std::iota(order.begin(), order.end(), lo);
  std::nth_element(order.begin(), order.begin() + (mid - lo), order.end(), [&](int a, int b) {
    const double pa = points_[static_cast<std::size_t>(a)][axis], pb = points_[static_cast<std::size_t>(b)][axis];
    return pa != pb ? pa < pb : a < b;
  });
  std::vector<Eigen::Vector3d> points(order.size());
  std::vector<int> group(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    points[i] = points_[static_cast<std::size_t>(order[i])];
    group[i] = group_[static_cast<std::size_t>(order[i])];
  }
  std::copy(points.begin(), points.end(), points_.begin() + lo);
  std::copy(group.begin(), group.end(), group_.begin() + lo);
  axis_[static_cast<std::size_t>(mid)] = static_cast<std::uint8_t>(axis);
  build(lo, mid);
  build(mid + 1, hi);
}

bool SiteTree::other_group_within(const Eigen::Vector3d& p, double radius, int group) const {
  const double r2 = radius * radius;
  struct Range {
    int lo, hi;
  };
  std::array<Range, 128> stack{};
  int top = 0;
  stack[top++] = {0, static_cast<int>(points_.size())};
  while (top > 0) {
    const Range r = stack[--top];
    if (r.hi - r.lo <= kLeafSize) {
      for (int i = r.lo; i < r.hi; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (group_[k] != group && (points_[k] - p).squaredNorm() <= r2) return true;
      }
      continue;
    }
    const int mid = (r.lo + r.hi) / 2;
    const auto m = static_cast<std::size_t>(mid);
    if (group_[m] != group && (points_[m] - p).squaredNorm() <= r2) return true;
    const double delta = p[axis_[m]] - points_[m][axis_[m]];
    // The far side only where the ball reaches across the splitting plane.
    if (delta < 0) {
      if (-delta <= radius) stack[top++] = {mid + 1, r.hi};
      stack[top++] = {r.lo, mid};
    } else {
      if (delta <= radius) stack[top++] = {r.lo, mid};
      stack[top++] = {mid + 1, r.hi};
    }
  }
  return false;
}

}  // namespace geodual::voronoi::detail
