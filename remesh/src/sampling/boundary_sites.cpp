#include "sampling/boundary_sites.hpp"

#include "common/point_grid.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <tuple>
#include <utility>

namespace geodual::remesh::detail {

LoopWalk::LoopWalk(const TriangleMesh& mesh, const BoundaryLoop& loop) : mesh_(mesh), loop_(loop) {
  start_.reserve(loop.edges.size());
  double at = 0;
  for (const BoundaryEdge& e : loop.edges) {
    start_.push_back(at);
    at += e.length;
  }
}

std::size_t LoopWalk::locate(double at, double& fraction) const {
  if (closed()) {
    at = std::fmod(at, length());
    if (at < 0) at += length();
  } else {
    at = std::clamp(at, 0.0, length());
  }
  const auto after = std::upper_bound(start_.begin(), start_.end(), at);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(std::distance(start_.begin(), after) - 1, 0));
  const BoundaryEdge& e = loop_.edges[i];
  fraction = std::clamp((at - start_[i]) / e.length, 0.0, 1.0);
  return i;
}

Eigen::Vector3d LoopWalk::point(double at) const {
  double t = 0;
  const BoundaryEdge& e = loop_.edges[locate(at, t)];
  Eigen::Vector3d a = mesh_.vertices.row(mesh_.faces(e.face, e.corner));
  Eigen::Vector3d b = mesh_.vertices.row(mesh_.faces(e.face, (e.corner + 1) % 3));
  if (e.reversed) std::swap(a, b);
  return a + t * (b - a);
}

SurfacePoint LoopWalk::site(double at) const {
  double t = 0;
  const BoundaryEdge& e = loop_.edges[locate(at, t)];
  return point_on_face_edge(e.face, e.corner, e.reversed ? 1 - t : t);
}

std::vector<std::vector<std::size_t>> slit_ends(std::span<const LoopWalk> walks, double spacing,
                                                std::span<const std::int64_t> limits) {
  // cos 20 degrees: the chords from v leave it together.
  constexpr double kTogether = 0.93969262078590838;
  struct Candidate {
    double negative_cosine;  // the sharpest first once sorted
    std::size_t loop, edge;
    double r;
    Eigen::Vector3d point;
  };
  std::vector<Candidate> candidates;
  for (std::size_t l = 0; l < walks.size(); ++l) {
    const LoopWalk& walk = walks[l];
    if (!walk.closed()) continue;
    const double r = std::min(spacing / 2, walk.length() / 6);
    for (std::size_t i = 0; i < walk.num_edges(); ++i) {
      const double at = walk.start(i);
      const Eigen::Vector3d v = walk.point(at), before = walk.point(at - r), after = walk.point(at + r);
      // Cosines, not angles: correctly rounded operations only, so the ends
      // do not depend on the maths library. false for NaN (a chord of length 0).
      const double cosine = (before - v).dot(after - v) / ((before - v).norm() * (after - v).norm());
      if (cosine > kTogether && (before - after).norm() < r / 4) candidates.push_back({-cosine, l, i, r, v});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.negative_cosine, a.loop, a.edge) < std::tie(b.negative_cosine, b.loop, b.edge);
  });
  std::vector<std::vector<std::size_t>> ends(walks.size());
  if (candidates.empty()) return ends;
  // Taken greedily: a candidate is kept unless one kept before it lies within
  // its 2 r, found among the candidates near it.
  std::vector<Eigen::Vector3d> points;
  points.reserve(candidates.size());
  for (const Candidate& candidate : candidates) points.push_back(candidate.point);
  const PointGrid grid(points, spacing);
  std::vector<std::uint8_t> kept(candidates.size(), 0);  // by candidate
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const Candidate& candidate = candidates[c];
    if (static_cast<std::int64_t>(ends[candidate.loop].size()) >= limits[candidate.loop]) continue;
    const double reach = 2 * candidate.r;
    bool near = false;
    grid.for_each_within(candidate.point, reach, [&](Index slot, double squared_distance) {
      near = near || (kept[static_cast<std::size_t>(grid.original(slot))] && squared_distance < reach * reach);
    });
    if (near) continue;
    kept[c] = 1;
    ends[candidate.loop].push_back(candidate.edge);
  }
  for (std::vector<std::size_t>& edges : ends) std::sort(edges.begin(), edges.end());
  return ends;
}

namespace {

/// Whether the loop of `walk` runs straight from arc length `at` (the
/// start of edge i) for `r` in the direction `step` (+1 or -1): the
/// vertices it passes lie within `tolerance` of the chord.
bool runs_straight(const LoopWalk& walk, std::size_t i, double r, int step, double tolerance) {
  const double at = walk.start(i);
  const Eigen::Vector3d v = walk.point(at), end = walk.point(at + step * r);
  const Eigen::Vector3d direction = (end - v).normalized();
  const auto n = static_cast<std::ptrdiff_t>(walk.num_edges());
  for (std::ptrdiff_t k = 1; k < n; ++k) {
    // The vertex k edges on, its arc length unwrapped past the loop's start.
    const std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) + step * k;
    const double wrap = j >= n ? walk.length() : (j < 0 ? -walk.length() : 0.0);
    const double there = walk.start(static_cast<std::size_t>((j % n + n) % n)) + wrap;
    if (step * (there - at) >= r) break;
    const Eigen::Vector3d offset = walk.point(there) - v;
    if ((offset - offset.dot(direction) * direction).norm() > tolerance) return false;
  }
  return true;
}

}  // namespace

std::vector<std::vector<std::size_t>> loop_corners(std::span<const LoopWalk> walks, double spacing,
                                                   std::span<const std::int64_t> limits,
                                                   const std::vector<std::vector<std::size_t>>& taken) {
  // cos 135 degrees: the chords from v meet at this angle or less.
  constexpr double kCorner = -0.70710678118654752;
  struct Candidate {
    double negative_cosine;  // the sharpest first once sorted
    std::size_t loop, edge;
    Eigen::Vector3d point;
  };
  std::vector<Candidate> candidates;
  std::vector<Eigen::Vector3d> held;  // the slit ends
  for (std::size_t l = 0; l < walks.size(); ++l) {
    const LoopWalk& walk = walks[l];
    for (const std::size_t edge : taken[l]) held.push_back(walk.point(walk.start(edge)));
    if (!walk.closed() || walk.length() < 4 * spacing) continue;
    const double r = spacing / 2;
    for (std::size_t i = 0; i < walk.num_edges(); ++i) {
      const double at = walk.start(i);
      const Eigen::Vector3d v = walk.point(at), before = walk.point(at - r), after = walk.point(at + r);
      // As in slit_ends: false for NaN.
      const double cosine = (before - v).dot(after - v) / ((before - v).norm() * (after - v).norm());
      if (!(cosine >= kCorner)) continue;
      if (runs_straight(walk, i, 4 * r, -1, r / 10) && runs_straight(walk, i, 4 * r, 1, r / 10)) {
        candidates.push_back({-cosine, l, i, v});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.negative_cosine, a.loop, a.edge) < std::tie(b.negative_cosine, b.loop, b.edge);
  });
  std::vector<std::vector<std::size_t>> corners(walks.size());
  if (candidates.empty()) return corners;
  // Taken greedily, as the slit ends: a candidate is kept unless a slit end
  // or a corner kept before it lies within 2 r (the spacing).
  std::vector<Eigen::Vector3d> points = held;
  for (const Candidate& candidate : candidates) points.push_back(candidate.point);
  const PointGrid grid(points, spacing);
  std::vector<std::uint8_t> kept(points.size(), 0);
  std::fill(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(held.size()), 1);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const Candidate& candidate = candidates[c];
    const auto room = limits[candidate.loop] - static_cast<std::int64_t>(taken[candidate.loop].size());
    if (static_cast<std::int64_t>(corners[candidate.loop].size()) >= room) continue;
    bool near = false;
    grid.for_each_within(candidate.point, spacing, [&](Index slot, double squared_distance) {
      near = near || (kept[static_cast<std::size_t>(grid.original(slot))] && squared_distance < spacing * spacing);
    });
    if (near) continue;
    kept[held.size() + c] = 1;
    corners[candidate.loop].push_back(candidate.edge);
  }
  for (std::vector<std::size_t>& edges : corners) std::sort(edges.begin(), edges.end());
  return corners;
}

namespace {

/// Arc lengths of k sites on the loop of `walk`: one at each of `ends`, the
/// others evenly between them (see place_boundary_sites).
std::vector<double> site_arc_lengths(const LoopWalk& walk, std::int64_t k, const std::vector<std::size_t>& ends) {
  std::vector<double> at;
  at.reserve(static_cast<std::size_t>(k));
  if (ends.empty()) {
    for (std::int64_t j = 0; j < k; ++j) {
      at.push_back((static_cast<double>(j) + 0.5) * walk.length() / static_cast<double>(k));
    }
    return at;
  }
  const std::size_t m = ends.size();
  std::vector<double> from(m), length(m);
  for (std::size_t c = 0; c < m; ++c) {
    from[c] = walk.start(ends[c]);
    at.push_back(from[c]);
    const double to = c + 1 < m ? walk.start(ends[c + 1]) : walk.start(ends[0]) + walk.length();
    length[c] = to - from[c];
  }
  const std::vector<std::int64_t> between =
      proportional_split(length, std::vector<std::int64_t>(m, 0), k - static_cast<std::int64_t>(m));
  for (std::size_t c = 0; c < m; ++c) {
    for (std::int64_t j = 1; j <= between[c]; ++j) {
      at.push_back(from[c] + static_cast<double>(j) * length[c] / static_cast<double>(between[c] + 1));
    }
  }
  return at;
}

/// Arc lengths of k sites on a loop smaller than the remesh's spacing (a
/// pinhole, or a loop made of copies of one short edge where a cut opened a
/// non-manifold edge): spread as far apart in space as the loop allows, by
/// farthest-point selection among its vertices and edge midpoints, starting
/// at its ends. Evenly by arc length, two of its sites would meet where the
/// loop runs back over itself. Empty where there are fewer candidates than k.
std::vector<double> spread_arc_lengths(const LoopWalk& walk, std::int64_t k, const std::vector<std::size_t>& ends) {
  std::vector<double> candidates;
  for (std::size_t i = 0; i < walk.num_edges(); ++i) {
    const double end = i + 1 < walk.num_edges() ? walk.start(i + 1) : walk.length();
    candidates.push_back(walk.start(i));
    candidates.push_back((walk.start(i) + end) / 2);
  }
  if (static_cast<std::int64_t>(candidates.size()) < k) return {};
  std::vector<Eigen::Vector3d> points;
  points.reserve(candidates.size());
  for (const double at : candidates) points.push_back(walk.point(at));
  // Per candidate, its squared distance to the nearest chosen one.
  std::vector<double> nearest(candidates.size(), std::numeric_limits<double>::infinity());
  std::vector<double> at;
  auto choose = [&](std::size_t c) {
    at.push_back(candidates[c]);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      nearest[i] = std::min(nearest[i], (points[i] - points[c]).squaredNorm());
    }
  };
  for (const std::size_t end : ends) {
    if (static_cast<std::int64_t>(at.size()) < k) choose(2 * end);
  }
  if (at.empty()) choose(0);
  while (static_cast<std::int64_t>(at.size()) < k) {
    choose(static_cast<std::size_t>(std::distance(nearest.begin(), std::max_element(nearest.begin(), nearest.end()))));
  }
  std::sort(at.begin(), at.end());
  return at;
}

/// The smallest distance in space between the walk's points at `at`.
double closest_pair(const LoopWalk& walk, std::span<const double> at) {
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < at.size(); ++i) {
    for (std::size_t j = i + 1; j < at.size(); ++j) {
      closest = std::min(closest, (walk.point(at[i]) - walk.point(at[j])).norm());
    }
  }
  return closest;
}

/// The extent of the loop: its bounding box's diagonal.
double loop_extent(const LoopWalk& walk) {
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < walk.num_edges(); ++i) box.extend(walk.point(walk.start(i)));
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

}  // namespace

void place_boundary_sites(const TriangleMesh& mesh, std::span<const BoundaryLoop* const> loops,
                          std::span<const std::int64_t> sites, double spacing, std::vector<SurfacePoint>& out) {
  std::vector<LoopWalk> walks;
  walks.reserve(loops.size());
  for (const BoundaryLoop* loop : loops) walks.emplace_back(mesh, *loop);
  std::vector<std::vector<std::size_t>> ends = slit_ends(walks, spacing, sites);
  const std::vector<std::vector<std::size_t>> corners = loop_corners(walks, spacing, sites, ends);
  for (std::size_t l = 0; l < walks.size(); ++l) {
    ends[l].insert(ends[l].end(), corners[l].begin(), corners[l].end());
    std::sort(ends[l].begin(), ends[l].end());
  }
  for (std::size_t l = 0; l < walks.size(); ++l) {
    std::vector<double> at = site_arc_lengths(walks[l], sites[l], ends[l]);
    // A loop below the spacing whose sites come far closer in space than
    // along it (it runs back over itself): spread instead, if that is better.
    if (walks[l].closed() && loop_extent(walks[l]) < spacing) {
      const double arc_spacing = walks[l].length() / static_cast<double>(std::max<std::int64_t>(sites[l], 1));
      const double closest = closest_pair(walks[l], at);
      if (closest < arc_spacing / 4) {
        std::vector<double> spread = spread_arc_lengths(walks[l], sites[l], ends[l]);
        if (!spread.empty() && closest_pair(walks[l], spread) > closest) at = std::move(spread);
      }
    }
    for (const double a : at) out.push_back(walks[l].site(a));
  }
}

}  // namespace geodual::remesh::detail
