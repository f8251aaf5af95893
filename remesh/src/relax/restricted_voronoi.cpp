#include "relax/restricted_voronoi.hpp"

#include "common/point_grid.hpp"
#include "common/surface_walk.hpp"
#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>

namespace geodual::remesh::detail {
namespace {

/// A polygon corner: position and density (both linear along the sides, so
/// clipping interpolates them together).
using Corner = Eigen::Vector4d;

/// What a polygon side lies on: a bisector (the other site, >= 0) or side k
/// of the face (-1 - k).
using SideLabel = Index;

/// A convex polygon being clipped: its corners, and the labels of the sides
/// that end at them, in buffers sized once for the sites searched (a clip
/// adds at most one corner), so that clipping a face allocates nothing.
struct ClipPolygon {
  std::vector<Corner> corner;
  std::vector<SideLabel> label;
  std::size_t size = 0;
  void reserve(std::size_t capacity) {
    if (corner.size() >= capacity) return;
    corner.resize(capacity);
    label.resize(capacity);
  }
  void add(const Corner& p, SideLabel side) {
    corner[size] = p;
    label[size++] = side;
  }
};

struct Scratch {
  /// The faces the cell has reached (tens: a per-face array would be
  /// touched at random across the whole mesh), emptied for each cell.
  IndexHashSet reached;
  std::vector<Index> queue;
  std::vector<std::pair<double, Index>> near;  // the sites near the current one (squared distance, site), nearest first
  std::vector<Eigen::Vector4d> planes;         // and their bisectors: normal . (x - site) <= w
  ClipPolygon polygon, clipped;
  std::vector<double> side;  // per corner of the polygon
  // The current cell's boundary segments: the other site, the density at
  // the midpoint, the ends.
  struct Segment {
    Index other;
    double density;
    Eigen::Vector3d from, to;
  };
  std::vector<Segment> segments;
  // The current block's boundaries, their segment ends numbered from 0.
  std::vector<RestrictedBoundary> boundaries;
  std::vector<Eigen::Vector3d> segment_ends;
};

/// The largest squared distance of a corner of `polygon` from `site`.
double reach_squared(const ClipPolygon& polygon, const Eigen::Vector3d& site) {
  double r = 0;
  for (std::size_t k = 0; k < polygon.size; ++k) r = std::max(r, (polygon.corner[k].head<3>() - site).squaredNorm());
  return r;
}

/// The integrals of one cell at a time (restricted_voronoi): a flood fill
/// over the faces the cell reaches from its site, each face clipped by the
/// bisector planes of the sites near it.
class CellIntegrator {
 public:
  /// `position` per site; `grid` holds them, in cells twice `spacing`
  /// wide. Each cell's integrals go into `cells`.
  CellIntegrator(const RestrictedSurface& surface, std::span<const SurfacePoint> sites,
                 std::span<const Eigen::Vector3d> position, const PointGrid& grid, double spacing,
                 RestrictedCells& cells)
      : surface_(surface), sites_(sites), position_(position), grid_(grid), spacing_(spacing), cells_(cells) {}

  /// The cell of the site in the grid's `slot`: its integrals into the
  /// cells, its boundaries appended to scratch.boundaries (their segment
  /// ends to scratch.segment_ends).
  void integrate(Index slot, Scratch& scratch) const {
    const TriangleMesh& mesh = surface_.mesh;
    const std::span<const double> density = surface_.density;
    const Index s = grid_.original(slot);
    const Eigen::Vector3d& site = position_[s];
    // A face's polygon within `reach` of the site can only be cut by sites
    // within 2 reach: the search widens when that is beyond it.
    double searched = 2 * spacing_;
    search(slot, searched, scratch);
    // Of two sites at one place, the first takes the cell.
    if (!scratch.near.empty() && scratch.near.front().first == 0 && scratch.near.front().second < s) return;
    auto& queue = scratch.queue;
    queue.clear();
    if (sites_[s].kind == SurfacePoint::Kind::face) {
      queue.push_back(sites_[s].element);
    } else {
      const std::span<const Index> around = surface_.fans.around(sites_[s].element);
      queue.insert(queue.end(), around.begin(), around.end());
    }
    scratch.reached.clear();
    for (const Index f : queue) scratch.reached.insert(f);
    scratch.segments.clear();
    const ClipPolygon& polygon = scratch.polygon;
    // The cell's integrals, summed here and stored once.
    double area = 0, mass = 0, energy = 0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (std::size_t next = 0; next < queue.size(); ++next) {
      const Index face = queue[next];
      if (next + 1 < queue.size()) {
        // Start loading the next face's corners (its row of vertex indices
        // was prefetched when it was queued, below).
        for (int c = 0; c < 3; ++c) {
          const Index v = mesh.faces(queue[next + 1], c);
          __builtin_prefetch(&mesh.vertices(v, 0));
          if (!density.empty()) __builtin_prefetch(&density[v]);
        }
      }
      while (!clip(face, site, searched, scratch)) {
        searched = 2 * std::sqrt(reach_squared(polygon, site)) * (1 + 1e-9);
        search(slot, searched, scratch);
      }
      if (polygon.size < 3) continue;
      // The three-edge-midpoint rule on the fan from polygon[0].
      for (std::size_t k = 1; k + 1 < polygon.size; ++k) {
        const Corner& a = polygon.corner[0];
        const Corner& b = polygon.corner[k];
        const Corner& c = polygon.corner[k + 1];
        const double piece = (b.head<3>() - a.head<3>()).cross(c.head<3>() - a.head<3>()).norm() / 2;
        area += piece;
        for (const Corner& m : {Corner((a + b) / 2), Corner((b + c) / 2), Corner((c + a) / 2)}) {
          const Eigen::Vector3d offset = m.head<3>() - site;
          const double weight = piece / 3 * m[3];
          mass += weight;
          moment += weight * offset;
          energy += weight * offset.squaredNorm();
        }
      }
      for (std::size_t k = 0, previous = polygon.size - 1; k < polygon.size; previous = k++) {
        const Corner& from = polygon.corner[previous];
        const Corner& to = polygon.corner[k];
        const SideLabel label = polygon.label[k];
        if (from.head<3>() == to.head<3>()) continue;
        if (label >= 0) {
          if (label > s) scratch.segments.push_back({label, (from[3] + to[3]) / 2, from.head<3>(), to.head<3>()});
          continue;
        }
        // A side on the face's side -1 - label: the cell goes on across it.
        const Index across = surface_.across[face][-1 - label];
        if (across >= 0 && scratch.reached.insert(across)) {
          queue.push_back(across);
          // Its corners and neighbours are read when its turn comes: start
          // loading them now (a face's first visit is mostly cache misses).
          __builtin_prefetch(&mesh.faces(across, 0));
          __builtin_prefetch(&surface_.across[across]);
        }
      }
    }
    cells_.area[s] = area;
    cells_.mass[s] = mass;
    cells_.moment[s] = moment;
    cells_.energy[s] = energy;
    gather_boundaries(s, scratch);
  }

 private:
  Corner corner(Index face, int c) const {
    const Index v = surface_.mesh.faces(face, c);
    Corner p;
    p.head<3>() = surface_.mesh.vertices.row(v).transpose();
    p[3] = surface_.density.empty() ? 1.0 : surface_.density[v];
    return p;
  }

  /// The sites within `searched` of the one in `slot`, nearest first (ties
  /// by index), and their bisector planes, into scratch.near and
  /// scratch.planes; the polygon buffers sized for them.
  void search(Index slot, double searched, Scratch& scratch) const {
    const Index s = grid_.original(slot);
    const Eigen::Vector3d& site = position_[s];
    auto& found = scratch.near;
    found.clear();
    auto take = [&](Index other_slot, double squared_distance) {
      const Index other = grid_.original(other_slot);
      if (other != s) found.emplace_back(squared_distance, other);
    };
    if (searched == 2 * spacing_) {
      // The first search, as wide as the grid's radius: the cells around
      // the site's own, listed in the grid, without looking them up.
      grid_.for_each_around(slot, [&](Index other_slot, double squared_distance) {
        if (squared_distance <= searched * searched) take(other_slot, squared_distance);
      });
    } else {
      grid_.for_each_within(site, searched, take);
    }
    std::sort(found.begin(), found.end());
    scratch.planes.clear();
    for (const auto& [squared_distance, other] : found) {
      const Eigen::Vector3d normal = position_[other] - site;
      scratch.planes.emplace_back(normal.x(), normal.y(), normal.z(), normal.squaredNorm() / 2);
    }
    const std::size_t most_corners = 3 + found.size();
    scratch.polygon.reserve(most_corners);
    scratch.clipped.reserve(most_corners);
    if (scratch.side.size() < most_corners) scratch.side.resize(most_corners);
  }

  /// Clips `face` to the cell of the site at `site` into scratch.polygon;
  /// false when a site beyond `searched` might cut it.
  bool clip(Index face, const Eigen::Vector3d& site, double searched, Scratch& scratch) const {
    // label[k] names the side from polygon[k - 1] to polygon[k]; face side
    // k joins corners k and k + 1.
    ClipPolygon& polygon = scratch.polygon;
    polygon.size = 0;
    polygon.add(corner(face, 0), -3);
    polygon.add(corner(face, 1), -1);
    polygon.add(corner(face, 2), -2);
    double reach2 = reach_squared(polygon, site);
    for (std::size_t n = 0; n < scratch.near.size(); ++n) {
      // Nearest first: once a bisector lies beyond the polygon's reach
      // (at half the sites' distance), so do all the others'.
      const Eigen::Vector4d& plane = scratch.planes[n];
      if (2 * plane[3] >= 4 * reach2) return true;
      // Each corner's signed offset from the plane, positive beyond it.
      double* side = scratch.side.data();
      bool cut = false;
      for (std::size_t k = 0; k < polygon.size; ++k) {
        side[k] = plane.head<3>().dot(polygon.corner[k].head<3>() - site) - plane[3];
        cut = cut || side[k] > 0;
      }
      if (!cut) continue;
      ClipPolygon& clipped = scratch.clipped;
      clipped.size = 0;
      for (std::size_t k = 0, previous = polygon.size - 1; k < polygon.size; previous = k++) {
        const Corner& from = polygon.corner[previous];
        const Corner& to = polygon.corner[k];
        const double a = side[previous], b = side[k];
        if (a <= 0 && b <= 0) {
          clipped.add(to, polygon.label[k]);
        } else if (a <= 0) {
          clipped.add(from + (a / (a - b)) * (to - from), polygon.label[k]);
        } else if (b <= 0) {
          clipped.add(from + (a / (a - b)) * (to - from), scratch.near[n].second);
          clipped.add(to, polygon.label[k]);
        }
      }
      std::swap(polygon, clipped);
      if (polygon.size < 3) return true;
      reach2 = reach_squared(polygon, site);
    }
    return 4 * reach2 <= searched * searched;
  }

  /// One boundary per other site of site `s`, from scratch.segments.
  static void gather_boundaries(Index s, Scratch& scratch) {
    // One boundary per other site, its segments together in the order they
    // were found: an insertion sort, stable and without the buffer that
    // std::stable_sort would allocate per cell (a cell has tens of segments).
    auto& segments = scratch.segments;
    for (std::size_t k = 1; k < segments.size(); ++k) {
      const Scratch::Segment segment = segments[k];
      std::size_t at = k;
      for (; at > 0 && segments[at - 1].other > segment.other; --at) segments[at] = segments[at - 1];
      segments[at] = segment;
    }
    for (std::size_t first = 0; first < segments.size();) {
      std::size_t last = first;
      double length = 0, weighted = 0;
      const auto begin = static_cast<Index>(scratch.segment_ends.size());
      for (; last < segments.size() && segments[last].other == segments[first].other; ++last) {
        const double piece = (segments[last].to - segments[last].from).norm();
        length += piece;
        weighted += piece * segments[last].density;
        scratch.segment_ends.push_back(segments[last].from);
        scratch.segment_ends.push_back(segments[last].to);
      }
      scratch.boundaries.push_back({s, segments[first].other, length > 0 ? weighted / length : segments[first].density,
                                    begin, static_cast<Index>(scratch.segment_ends.size())});
      first = last;
    }
  }

  const RestrictedSurface& surface_;
  std::span<const SurfacePoint> sites_;
  std::span<const Eigen::Vector3d> position_;
  const PointGrid& grid_;
  double spacing_;
  RestrictedCells& cells_;
};

}  // namespace

double RestrictedCells::total_energy() const { return std::accumulate(energy.begin(), energy.end(), 0.0); }

RestrictedSurface prepare_restricted_surface(const TriangleMesh& mesh, const voronoi::SurfaceTopology& topology,
                                             std::span<const double> density, bool vertex_sites) {
  RestrictedSurface surface{mesh, topology, density, 0.0, vertex_sites ? vertex_fans(mesh, topology) : VertexFans{},
                            {}};
  surface.across.resize(static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (topology.face_edges[f][0] >= 0) surface.area += face_area(mesh, f);
    for (int k = 0; k < 3; ++k) {
      const Index edge = topology.face_edges[f][k];
      if (edge < 0) {
        surface.across[f][k] = -1;
        continue;
      }
      const auto& faces = topology.edge_faces[edge];
      surface.across[f][k] = faces[0] == f ? faces[1] : faces[0];
    }
  }
  return surface;
}

RestrictedCells restricted_voronoi(const RestrictedSurface& surface, std::span<const SurfacePoint> sites,
                                   std::span<const std::uint8_t> only) {
  const TriangleMesh& mesh = surface.mesh;
  const std::size_t site_count = sites.size();
  if (surface.fans.begin.empty() && any_at_vertex(sites)) {
    throw Error("restricted_voronoi: a site at a vertex, on a surface prepared without vertex sites");
  }
  if (!only.empty() && only.size() != site_count) {
    throw Error("restricted_voronoi: " + std::to_string(only.size()) + " flags for " + std::to_string(site_count) +
                " sites");
  }
  std::vector<Eigen::Vector3d> position(site_count);
  for (std::size_t s = 0; s < site_count; ++s) position[s] = sites[s].position(mesh);
  // Grid cells twice as wide as the sites' spacing: the first search (twice
  // the spacing) looks at 27 of them. (The cells found do not depend on the
  // spacing: a search that falls short is widened.)
  const double spacing =
      surface.area > 0 ? std::sqrt(surface.area / static_cast<double>(std::max<std::size_t>(site_count, 1))) : 1.0;
  const PointGrid grid(position, 2 * spacing);

  RestrictedCells cells;
  cells.area.assign(site_count, 0.0);
  cells.mass.assign(site_count, 0.0);
  cells.moment.assign(site_count, Eigen::Vector3d::Zero());
  cells.energy.assign(site_count, 0.0);
  tbb::enumerable_thread_specific<Scratch> scratches;
  const CellIntegrator cell(surface, sites, position, grid, spacing, cells);
  // Each cell is integrated by one thread on its own, the cells taken in
  // the grid's Z-order so that neighbouring cells, which share faces, run
  // close together in time (the faces and their corners are then still in
  // the cache). Each block of cells keeps its boundary pieces apart; they are
  // gathered in the order of the sites at the end, so the sums and the order
  // of the pieces do not depend on the threads.
  constexpr std::size_t kBlock = 256;
  struct Block {
    std::vector<Index> cell_begin;  // per slot of the block, its first boundary
    std::vector<RestrictedBoundary> boundaries;
    std::vector<Eigen::Vector3d> segment_ends;
  };
  std::vector<Block> blocks((site_count + kBlock - 1) / kBlock);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Scratch& scratch = scratches.local();
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        Block& block = blocks[b];
                        scratch.boundaries.clear();
                        scratch.segment_ends.clear();
                        for (std::size_t slot = b * kBlock; slot < std::min(site_count, (b + 1) * kBlock); ++slot) {
                          block.cell_begin.push_back(static_cast<Index>(scratch.boundaries.size()));
                          if (only.empty() || only[grid.original(static_cast<Index>(slot))] != 0) {
                            cell.integrate(static_cast<Index>(slot), scratch);
                          }
                        }
                        block.cell_begin.push_back(static_cast<Index>(scratch.boundaries.size()));
                        block.boundaries = scratch.boundaries;
                        block.segment_ends = scratch.segment_ends;
                      }
                    });
  // The boundaries in the order of the sites: each cell's place in the
  // output from the counts before it, then the copies on all threads.
  std::vector<Index> slot_of(site_count);
  for (Index slot = 0; slot < static_cast<Index>(site_count); ++slot) slot_of[grid.original(slot)] = slot;
  auto block_of = [&](std::size_t s) -> const Block& { return blocks[static_cast<std::size_t>(slot_of[s]) / kBlock]; };
  std::vector<Index> boundary_begin(site_count + 1, 0), end_begin(site_count + 1, 0);
  for (std::size_t s = 0; s < site_count; ++s) {
    const Block& block = block_of(s);
    const std::size_t k = static_cast<std::size_t>(slot_of[s]) % kBlock;
    const Index first = block.cell_begin[k], last = block.cell_begin[k + 1];
    boundary_begin[s + 1] = boundary_begin[s] + (last - first);
    end_begin[s + 1] =
        end_begin[s] + (last > first ? block.boundaries[last - 1].end - block.boundaries[first].begin : 0);
  }
  cells.boundaries.resize(static_cast<std::size_t>(boundary_begin[site_count]));
  cells.segment_ends.resize(static_cast<std::size_t>(end_begin[site_count]));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, site_count, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s) {
                        const Block& block = block_of(s);
                        const std::size_t k = static_cast<std::size_t>(slot_of[s]) % kBlock;
                        const Index first = block.cell_begin[k], last = block.cell_begin[k + 1];
                        if (first == last) continue;
                        const Index shift = end_begin[s] - block.boundaries[first].begin;
                        std::copy(block.segment_ends.begin() + block.boundaries[first].begin,
                                  block.segment_ends.begin() + block.boundaries[last - 1].end,
                                  cells.segment_ends.begin() + end_begin[s]);
                        for (Index b = first; b < last; ++b) {
                          RestrictedBoundary boundary = block.boundaries[b];
                          boundary.begin += shift;
                          boundary.end += shift;
                          cells.boundaries[static_cast<std::size_t>(boundary_begin[s] + (b - first))] = boundary;
                        }
                      }
                    });
  return cells;
}

}  // namespace geodual::remesh::detail
