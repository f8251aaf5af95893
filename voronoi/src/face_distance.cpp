#include "face_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace geodual::voronoi::detail {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The sites' point sources that lie in `face`: face_point_sources is sorted by face.
std::pair<const FacePointSource*, const FacePointSource*> point_sources_in(const GeodesicField& field, Index face) {
  const auto range =
      std::equal_range(field.face_point_sources.begin(), field.face_point_sources.end(), FacePointSource{face},
                       [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  return {field.face_point_sources.data() + (range.first - field.face_point_sources.begin()),
          field.face_point_sources.data() + (range.second - field.face_point_sources.begin())};
}

}  // namespace

FaceLayout FaceLayout::of(const GeodesicField& field, Index face) {
  const auto& edges = field.face_edges[face];
  const double l0 = field.edge_length[edges[0]];  // corners 0-1
  const double l1 = field.edge_length[edges[1]];  // corners 1-2
  const double l2 = field.edge_length[edges[2]];  // corners 2-0
  FaceLayout layout;
  layout.corner[0] = Eigen::Vector2d::Zero();
  layout.corner[1] = Eigen::Vector2d(l0, 0);
  const double x = l0 > 0 ? (l0 * l0 + l2 * l2 - l1 * l1) / (2 * l0) : 0;
  layout.corner[2] = Eigen::Vector2d(x, std::sqrt(std::max(0.0, l2 * l2 - x * x)));
  layout.area = 0.5 * l0 * layout.corner[2].y();
  return layout;
}

Eigen::Vector3d FaceLayout::barycentric(const Eigen::Vector2d& p) const {
  const double twice_area = cross(corner[1] - corner[0], corner[2] - corner[0]);
  Eigen::Vector3d b;
  if (!(twice_area > 0)) {
    // A zero-area face: place the point along its longest side.
    int k = 0;
    double longest = -1;
    for (int i = 0; i < 3; ++i) {
      const double length = (corner[(i + 1) % 3] - corner[i]).norm();
      if (length > longest) longest = length, k = i;
    }
    const Eigen::Vector2d side = corner[(k + 1) % 3] - corner[k];
    const double t = longest > 0 ? std::clamp((p - corner[k]).dot(side) / side.squaredNorm(), 0.0, 1.0) : 0.0;
    b.setZero();
    b[k] = 1 - t;
    b[(k + 1) % 3] = t;
    return b;
  }
  b[0] = cross(corner[1] - p, corner[2] - p) / twice_area;
  b[1] = cross(corner[2] - p, corner[0] - p) / twice_area;
  b = b.cwiseMax(0.0);
  b[2] = 0;
  const double sum = b[0] + b[1];
  if (sum > 1) b /= sum;
  b[2] = std::max(0.0, 1 - b[0] - b[1]);
  return b;
}

void DistanceCone::set_rays(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  in_wedge_only = true;
  ray0 = from;
  ray1 = to;
  wedge_opens = cross(ray0, ray1) > 0;
}

bool DistanceCone::sees(const Eigen::Vector2d& p) const {
  if (!in_wedge_only) return true;
  const Eigen::Vector2d q = p - apex;
  if (!wedge_opens) return cross(ray0, q) == 0 && (q - ray0).dot(q - ray1) <= 0;
  return after_ray0(q) && before_ray1(q);
}

void ConeEnvelope::clear() {
  for (int slot = 0; slot < slot_count(); ++slot) slot_cones_[slot].clear();
  if (slot_count() > kScannedSlots) slot_index_.clear();
  slot_site_.clear();
}

std::size_t ConeEnvelope::cone_count() const {
  std::size_t cones = 0;
  for (int slot = 0; slot < slot_count(); ++slot) cones += slot_cones_[slot].size();
  return cones;
}

int ConeEnvelope::slot_of(Index site) const {
  if (site < 0) return -1;
  if (slot_count() > kScannedSlots) {
    const int* slot = slot_index_.find(site);
    return slot ? *slot : -1;
  }
  for (int slot = 0; slot < slot_count(); ++slot) {
    if (slot_site_[slot] == site) return slot;
  }
  return -1;
}

int ConeEnvelope::slot_for(Index site) {
  const int slot = slot_of(site);
  if (slot >= 0) return slot;
  slot_site_.push_back(site);
  if (slot_cones_.size() < slot_site_.size()) slot_cones_.emplace_back();
  if (slot_count() == kScannedSlots + 1) {
    for (int s = 0; s < slot_count(); ++s) slot_index_.insert(slot_site_[s], s);
  } else if (slot_count() > kScannedSlots + 1) {
    slot_index_.insert(site, slot_count() - 1);
  }
  return slot_count() - 1;
}

void ConeEnvelope::add(const Eigen::Vector2d& apex, double sigma, Index site) {
  if (site < 0 || !std::isfinite(sigma)) return;
  DistanceCone cone;
  cone.apex = apex;
  cone.sigma = sigma;
  slot_cones_[slot_for(site)].push_back(cone);
}

void ConeEnvelope::add_wedge(const Eigen::Vector2d& apex, double sigma, Index site, const Eigen::Vector2d& end0,
                             const Eigen::Vector2d& end1) {
  if (site < 0 || !std::isfinite(sigma)) return;
  DistanceCone cone;
  cone.apex = apex;
  cone.sigma = sigma;
  Eigen::Vector2d ray0 = end0 - apex, ray1 = end1 - apex;
  if (cross(ray0, ray1) < 0) std::swap(ray0, ray1);
  cone.set_rays(ray0, ray1);
  slot_cones_[slot_for(site)].push_back(cone);
  // The paths that bend at either end of the window's interval.
  add(end0, sigma + (end0 - apex).norm(), site);
  add(end1, sigma + (end1 - apex).norm(), site);
}

// The queries compute a cone's value first and test whether the cone sees p
// only where the value would change the answer: the same results as testing
// every cone, with far fewer wedge tests.

double ConeEnvelope::distance(int slot, const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const {
  double best = infinity;
  const DistanceCone* best_cone = nullptr;
  const std::span<const DistanceCone> cones =
      slot >= 0 ? std::span<const DistanceCone>(slot_cones_[slot]) : std::span<const DistanceCone>();
  for (const DistanceCone& cone : cones) {
    const double d = cone.value(p);
    if (d < best && cone.sees(p)) best = d, best_cone = &cone;
  }
  if (gradient) {
    gradient->setZero();
    if (best_cone) {
      const Eigen::Vector2d r = p - best_cone->apex;
      const double length = r.norm();
      if (length > 0) *gradient = r / length;
    }
  }
  return best;
}

Index ConeEnvelope::nearest_site(const Eigen::Vector2d& p) const {
  // The smallest value, ties to the smallest site: the same whatever order
  // the cones are read in.
  NearestCone nearest{p};
  for (int slot = 0; slot < slot_count(); ++slot) {
    for (const DistanceCone& cone : slot_cones_[slot]) nearest.consider(cone, slot_site_[slot]);
  }
  return nearest.site;
}

double ConeEnvelope::difference(Index site_a, Index site_b, const Eigen::Vector2d& p) const {
  const int a = slot_of(site_a), b = slot_of(site_b);
  // With site_a == site_b, only a's value counts (b's stays unreachable).
  const double da = distance(a, p), db = b == a ? infinity : distance(b, p);
  if (da == db) return 0;  // also both infinite
  return da - db;
}

void build_face_envelope(const GeodesicField& field, const TriangleMesh& mesh, Index face, const FaceLayout& layout,
                         ConeEnvelope& envelope) {
  envelope.clear();
  for (int c = 0; c < 3; ++c) {
    const Index v = mesh.faces(face, c);
    envelope.add(layout.corner[c], field.distance[v], field.nearest_site[v]);
  }
  const auto [first, last] = point_sources_in(field, face);
  for (const FacePointSource* source = first; source != last; ++source) {
    envelope.add(layout.point(source->barycentric), source->sigma, source->site);
  }
  for (int k = 0; k < 3; ++k) {
    const Index e = field.face_edges[face][k];
    const int side = field.edge_faces[e][0] == face ? 0 : 1;
    // The edge's frame in the face's plane: origin at the edge's v0,
    // x along the edge, and the face's side of the edge (y > 0 for side 0,
    // y < 0 for side 1) mapped into the face.
    const Index v0 = field.edge_vertices(mesh, e)[0];
    const int origin_corner = mesh.faces(face, k) == v0 ? k : (k + 1) % 3;
    const int end_corner = origin_corner == k ? (k + 1) % 3 : k;
    const Eigen::Vector2d origin = layout.corner[origin_corner];
    const Eigen::Vector2d along = layout.corner[end_corner] - origin;
    const double length = along.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector2d u = along / length;
    Eigen::Vector2d inward(-u.y(), u.x());
    if (inward.dot(layout.corner[(k + 2) % 3] - origin) < 0) inward = -inward;
    const double flip = side == 0 ? 1.0 : -1.0;
    // Windows entering the face through the edge cover the part of the face
    // beyond the edge; windows leaving through it, the part of the face on
    // their way to the edge (a path to the edge passes there first). Both
    // are the edge's own values on the edge itself.
    for (Index i = field.window_begin[e]; i < field.window_begin[e + 1]; ++i) {
      const EdgeWindow& w = field.windows[i];
      const Eigen::Vector2d source = origin + w.source_x * u + flip * w.source_y * inward;
      envelope.add_wedge(source, w.sigma, w.site, origin + w.b0 * u, origin + w.b1 * u);
    }
  }
}

void ConeEnvelope::add_moved(const ConeEnvelope& other, const Eigen::Vector2d& origin, const Eigen::Vector2d& x_axis,
                             const Eigen::Vector2d& y_axis) {
  auto move = [&](const Eigen::Vector2d& v) { return Eigen::Vector2d(v.dot(x_axis), v.dot(y_axis)); };
  const bool reflects = cross(x_axis, y_axis) < 0;
  // other's slots are numbered in order of first appearance, so taking them
  // in order numbers the new sites here as adding its cones one by one would.
  for (int other_slot = 0; other_slot < other.slot_count(); ++other_slot) {
    std::vector<DistanceCone>& cones = slot_cones_[slot_for(other.slot_site_[other_slot])];
    for (const DistanceCone& cone : other.slot_cones_[other_slot]) {
      DistanceCone moved = cone;
      moved.apex = move(cone.apex - origin);
      if (cone.in_wedge_only) {
        if (reflects) {
          moved.set_rays(move(cone.ray1), move(cone.ray0));
        } else {
          moved.set_rays(move(cone.ray0), move(cone.ray1));
        }
      }
      cones.push_back(moved);
    }
  }
}

void build_edge_envelope(const GeodesicField& field, const TriangleMesh& mesh, Index edge, ConeEnvelope& envelope,
                         ConeEnvelope& scratch) {
  envelope.clear();
  for (Index i = field.window_begin[edge]; i < field.window_begin[edge + 1]; ++i) {
    const EdgeWindow& w = field.windows[i];
    envelope.add_wedge(Eigen::Vector2d(w.source_x, w.source_y), w.sigma, w.site, Eigen::Vector2d(w.b0, 0),
                       Eigen::Vector2d(w.b1, 0));
  }
  const auto [v0, v1] = field.edge_vertices(mesh, edge);
  const std::array<Index, 2>& faces = field.edge_faces[edge];
  // Sites (and pseudo-sources seen through zero-area faces) on the edge
  // itself: the barycentric coordinate of the corner opposite it is zero.
  const double edge_length = field.edge_length[edge];
  for (const Index face : faces) {
    if (face < 0) continue;
    const auto [first, last] = point_sources_in(field, face);
    for (const FacePointSource* source = first; source != last; ++source) {
      for (int c = 0; c < 3; ++c) {
        const Index a = mesh.faces(face, (c + 1) % 3), b = mesh.faces(face, (c + 2) % 3);
        if (source->barycentric[c] != 0 || !((a == v0 && b == v1) || (a == v1 && b == v0))) continue;
        const double from_v0 = a == v0 ? source->barycentric[(c + 2) % 3] : source->barycentric[(c + 1) % 3];
        envelope.add(Eigen::Vector2d(from_v0 * edge_length, 0), source->sigma, source->site);
      }
    }
  }
  if (faces[0] >= 0 && faces[1] >= 0) {
    // Between two faces the windows cover the edge (MMP's invariant), and
    // paths that bend at an end vertex are the ends' cones.
    envelope.add(Eigen::Vector2d::Zero(), field.distance[v0], field.nearest_site[v0]);
    envelope.add(Eigen::Vector2d(field.edge_length[edge], 0), field.distance[v1], field.nearest_site[v1]);
    return;
  }
  // A boundary edge keeps only the windows that reached it last: take the
  // face's envelope (corners, sites in it, windows entering it), moved into
  // the edge's frame: origin at v0, x along the edge, the face on the y > 0
  // side for edge_faces[edge][0], y < 0 for [1].
  for (int side = 0; side < 2; ++side) {
    const Index face = faces[side];
    if (face < 0) continue;
    const FaceLayout layout = FaceLayout::of(field, face);
    build_face_envelope(field, mesh, face, layout, scratch);
    const int k = field.topology->side_of(face, edge);
    const bool forward = mesh.faces(face, k) == v0;
    const Eigen::Vector2d origin = layout.corner[forward ? k : (k + 1) % 3];
    const Eigen::Vector2d along = layout.corner[forward ? (k + 1) % 3 : k] - origin;
    const double length = along.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector2d x_axis = along / length;
    Eigen::Vector2d inward(-x_axis.y(), x_axis.x());
    if (inward.dot(layout.corner[(k + 2) % 3] - origin) < 0) inward = -inward;
    envelope.add_moved(scratch, origin, x_axis, side == 0 ? inward : Eigen::Vector2d(-inward));
  }
}

}  // namespace geodual::voronoi::detail
