#include "face_boundary.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace geodual::voronoi::detail {
namespace {

constexpr int samples_per_inner_side = 8;
/// Every search along a segment ends within 2^-46 of it (at most a triangle's
/// side: ~1e-14 of it): bisection's number of halvings, Brent's tolerance.
constexpr int bisection_steps = 46;
constexpr int max_polyline_depth = 12;
/// A side is not split within this fraction of its length of a crossing.
constexpr double kSplitClearance = 1e-9;
/// From this many cones on an edge (about a third as many windows), its
/// nearest site is asked of an AxisNearestSite rather than of the envelope.
constexpr std::size_t min_cones_to_index = 96;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area(std::span<const Eigen::Vector2d> polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    twice += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * twice;
}

double triangle_area(const std::array<Eigen::Vector2d, 3>& c) { return 0.5 * cross(c[1] - c[0], c[2] - c[0]); }

/// Where g changes sign on [0, 1], given g(0) = g_lo and g(1) = g_hi of
/// opposite signs, to within 2^-bisection_steps, as bisection would find it.
/// Brent's method (Algorithms for Minimization without Derivatives, 1973,
/// ch. 4: secant and inverse quadratic steps kept inside a shrinking
/// bracket, bisection where they would not shrink it fast enough) converges
/// superlinearly on the smooth difference of two sites' distances: a handful
/// of evaluations instead of 46. Ends of infinite value (a site no cone of
/// which sees the point) are bisected towards.
template <typename G>
double sign_change(G&& g, double g_lo, double g_hi) {
  const double tolerance = std::ldexp(1.0, -bisection_steps - 1);
  double a = 0, b = 1, c = 0;
  double fa = g_lo, fb = g_hi, fc = g_lo;
  double d = b - a, e = d;
  for (int step = 0; step < 4 * bisection_steps; ++step) {
    if ((fb > 0) == (fc > 0)) {
      c = a;  // c is b's partner across the sign change
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {  // b is the better estimate
      a = b, b = c, c = a;
      fa = fb, fb = fc, fc = fa;
    }
    const double half = 0.5 * (c - b);
    if (std::abs(half) <= tolerance || fb == 0) return b;
    const bool finite = std::isfinite(fa) && std::isfinite(fb) && std::isfinite(fc);
    if (finite && std::abs(e) >= tolerance && std::abs(fa) > std::abs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {  // secant
        p = 2 * half * s;
        q = 1 - s;
      } else {  // inverse quadratic interpolation
        const double qa = fa / fc, r = fb / fc;
        p = s * (2 * half * qa * (qa - r) - (b - a) * (r - 1));
        q = (qa - 1) * (r - 1) * (s - 1);
      }
      if (p > 0) {
        q = -q;
      } else {
        p = -p;
      }
      if (2 * p < std::min(3 * half * q - std::abs(tolerance * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = e = half;
      }
    } else {
      d = e = half;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tolerance ? d : std::copysign(tolerance, half);
    fb = g(b);
  }
  return b;
}

double bounding_box_diagonal(const TriangleMesh& mesh) {
  if (mesh.vertices.rows() == 0) return 0;
  return (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
}

/// Where the edge lies in the face's layout: its frame's origin
/// (its end v0, see SurfaceTopology::edge_vertices) and unit direction.
struct EdgeInFace {
  Eigen::Vector2d origin;
  Eigen::Vector2d direction;
  bool forward = true;  ///< the face's side k runs from the edge's v0 to its v1
};

EdgeInFace edge_in_face(const GeodesicField& field, const TriangleMesh& mesh, const FaceLayout& layout, Index face,
                        int k) {
  const Index e = field.face_edges[face][k];
  EdgeInFace result;
  result.forward = mesh.faces(face, k) == field.edge_vertices(mesh, e)[0];
  const int origin_corner = result.forward ? k : (k + 1) % 3;
  const int end_corner = result.forward ? (k + 1) % 3 : k;
  result.origin = layout.corner[origin_corner];
  const Eigen::Vector2d along = layout.corner[end_corner] - result.origin;
  const double length = along.norm();
  result.direction = length > 0 ? Eigen::Vector2d(along / length) : Eigen::Vector2d(1, 0);
  return result;
}

}  // namespace

void TracedChunk::clear() {
  graph.nodes.clear();
  graph.vertex_sites.clear();
  graph.pieces.clear();
  graph.points.clear();
  graph.point_locations.clear();
  faces.clear();
  contributions.clear();
  stats = VoronoiStats{};
}

FaceBoundaryTracer::FaceBoundaryTracer(const TriangleMesh& mesh, const GeodesicField& field,
                                       const VoronoiOptions& options, const EdgeCrossingStore& crossings,
                                       std::span<const Eigen::Vector3d> site_normals)
    : mesh_(mesh), field_(field), options_(options), store_(crossings), moments_(mesh, field, site_normals) {
  tolerance_ = options.boundary_tolerance * bounding_box_diagonal(mesh);
  vertex_tolerance_ = 1e-11 * bounding_box_diagonal(mesh);
}

bool FaceBoundaryTracer::may_hold_boundary(Index face) const {
  if (field_.face_edges[face][0] < 0) return false;
  if (field_.valid_face[face]) return true;
  const Index s0 = field_.nearest_site[mesh_.faces(face, 0)];
  if (s0 != field_.nearest_site[mesh_.faces(face, 1)] || s0 != field_.nearest_site[mesh_.faces(face, 2)]) {
    return true;
  }
  const auto it =
      std::lower_bound(field_.face_point_sources.begin(), field_.face_point_sources.end(), FacePointSource{face},
                       [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  return it != field_.face_point_sources.end() && it->face == face;
}

BoundaryNode edge_crossing_node(const TriangleMesh& mesh, const GeodesicField& field, Index edge,
                                const EdgeCrossing& crossing) {
  const double length = field.edge_length[edge];
  const auto [v0, v1] = field.edge_vertices(mesh, edge);
  const Index face = field.edge_faces[edge][0] >= 0 ? field.edge_faces[edge][0] : field.edge_faces[edge][1];
  const double t = crossing.x / length;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) {
    if (mesh.faces(face, c) == v0) barycentric[c] = 1 - t;
    if (mesh.faces(face, c) == v1) barycentric[c] = t;
  }
  BoundaryNode node;
  node.kind = BoundaryNode::Kind::mesh_edge_crossing;
  node.location = SurfacePoint::in_face(face, barycentric[0], barycentric[1], barycentric[2]);
  node.position = (1 - t) * mesh.vertices.row(v0).transpose() + t * mesh.vertices.row(v1).transpose();
  node.distance = crossing.distance;
  return node;
}

void FaceBoundaryTracer::find_edge_crossings(Index edge, std::vector<EdgeCrossing>& crossings) {
  const double length = field_.edge_length[edge];
  const auto [v0, v1] = field_.edge_vertices(mesh_, edge);
  const Index site0 = field_.nearest_site[v0], site1 = field_.nearest_site[v1];
  build_edge_envelope(field_, mesh_, edge, edge_envelope_, face_scratch_);

  // Only one site here: no crossing. Otherwise sample the nearest site at the
  // ends of every window (where the envelope's pieces change) and between,
  // and find each change of site by bisection.
  if (edge_envelope_.slot_count() > 1 && site0 >= 0 && site1 >= 0 && length > 0) {
    const AxisNearestSite* index = nullptr;
    if (edge_envelope_.cone_count() >= min_cones_to_index) {
      edge_index_.build(edge_envelope_);
      index = &edge_index_;
    }
    samples_.clear();
    for (int i = 0; i <= 4; ++i) samples_.push_back(length * i / 4);
    for (Index i = field_.window_begin[edge]; i < field_.window_begin[edge + 1]; ++i) {
      for (const double x : {field_.windows[i].b0, field_.windows[i].b1}) {
        if (x > 0 && x < length) samples_.push_back(x);
      }
    }
    std::sort(samples_.begin(), samples_.end());
    samples_.erase(std::unique(samples_.begin(), samples_.end()), samples_.end());
    // And inside each stretch: at a window's ends its neighbours tie with it.
    const std::size_t ends = samples_.size();
    for (std::size_t i = 1; i < ends; ++i) samples_.push_back(0.5 * (samples_[i - 1] + samples_[i]));
    std::sort(samples_.begin(), samples_.end());
    changes_.clear();
    Index previous_site = site0;
    double previous_x = 0;
    auto nearest_site = [&](const Eigen::Vector2d& at) {
      return index ? index->nearest_site(at.x()) : edge_envelope_.nearest_site(at);
    };
    for (std::size_t i = 1; i < samples_.size(); ++i) {
      const double x = samples_[i];
      const Index site = i + 1 == samples_.size() ? site1 : nearest_site(Eigen::Vector2d(x, 0));
      if (site < 0 || site == previous_site) continue;
      find_site_changes(edge_envelope_, nearest_site, Eigen::Vector2d::Zero(), Eigen::Vector2d(length, 0),
                        previous_x / length, x / length, previous_site, site);
      previous_site = site;
      previous_x = x;
    }
    drop_zero_width_stretches();
    for (const SiteChange& change : changes_) {
      EdgeCrossing crossing;
      crossing.x = std::clamp(change.t * length, 0.0, length);
      crossing.distance = edge_envelope_.distance(edge_envelope_.slot_of(change.to), Eigen::Vector2d(crossing.x, 0));
      crossing.from = change.from;
      crossing.to = change.to;
      crossings.push_back(crossing);
    }
  }
}

double FaceBoundaryTracer::equal_distance_parameter(const ConeEnvelope& envelope, const Eigen::Vector2d& a,
                                                    const Eigen::Vector2d& b, Index from, Index to, double g_a,
                                                    double g_b) {
  // g = d_from - d_to changes sign between a and b.
  return sign_change([&](double u) { return envelope.difference(from, to, a + u * (b - a)); }, g_a, g_b);
}

void FaceBoundaryTracer::drop_zero_width_stretches() {
  // Where two sites tie along a stretch (a bisector running through mesh
  // vertices or along an edge), rounding can flip the nearest site back and
  // forth at one point: A -> B -> A with nothing between is no boundary.
  constexpr double zero_width = 1e-9;  // of the segment
  for (std::size_t i = 0; i + 1 < changes_.size();) {
    const SiteChange& a = changes_[i];
    const SiteChange& b = changes_[i + 1];
    if (a.from == b.to && b.t - a.t < zero_width) {
      changes_.erase(changes_.begin() + static_cast<std::ptrdiff_t>(i),
                     changes_.begin() + static_cast<std::ptrdiff_t>(i + 2));
      i = i > 0 ? i - 1 : 0;
    } else {
      ++i;
    }
  }
}

template <class NearestSite>
void FaceBoundaryTracer::find_site_changes(const ConeEnvelope& envelope, const NearestSite& nearest_site,
                                           const Eigen::Vector2d& p, const Eigen::Vector2d& q, double t0, double t1,
                                           Index site0, Index site1) {
  // Where the two sites are equally far, found on the difference of their
  // distances, is the change when they are the nearest on either side of it.
  const Eigen::Vector2d a = p + t0 * (q - p), b = p + t1 * (q - p);
  const double g_a = envelope.difference(site0, site1, a), g_b = envelope.difference(site0, site1, b);
  if (g_a < 0 && g_b > 0) {
    const double u = equal_distance_parameter(envelope, a, b, site0, site1, g_a, g_b);
    const double step = std::ldexp(t1 - t0, -bisection_steps + 2);
    const double t = t0 + u * (t1 - t0);
    if (nearest_site(p + (t - step) * (q - p)) == site0 && nearest_site(p + (t + step) * (q - p)) == site1) {
      changes_.push_back({t, site0, site1});
      return;
    }
  }
  // Otherwise bisection on the nearest site itself: a third site met at a
  // midpoint owns a stretch in between, and is split out rather than
  // stepped over.
  double lo = t0, hi = t1;
  for (int step = 0; step < bisection_steps; ++step) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const Index site = nearest_site(p + mid * (q - p));
    if (site == site1) {
      hi = mid;
    } else if (site == site0 || site < 0) {
      lo = mid;
    } else {
      find_site_changes(envelope, nearest_site, p, q, lo, mid, site0, site);
      find_site_changes(envelope, nearest_site, p, q, mid, hi, site, site1);
      return;
    }
  }
  changes_.push_back({0.5 * (lo + hi), site0, site1});
}

Eigen::Vector3d FaceBoundaryTracer::to_space(const Eigen::Vector2d& p) const {
  const Eigen::Vector3d b = layout_.barycentric(p);
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) x += b[c] * mesh_.vertices.row(mesh_.faces(face_, c)).transpose();
  return x;
}

Index FaceBoundaryTracer::add_node(const Eigen::Vector2d& p, BoundaryNode::Kind kind) {
  BoundaryNode node;
  node.kind = kind;
  const Eigen::Vector3d b = layout_.barycentric(p);
  node.location = SurfacePoint::in_face(face_, b[0], b[1], b[2]);
  node.position = to_space(p);
  graph_->nodes.push_back(node);
  return static_cast<Index>(graph_->nodes.size()) - 1;
}

void FaceBoundaryTracer::add_inner_face(Index face, Index site, TracedChunk& out) {
  const FaceLayout layout = FaceLayout::of(field_, face);
  moments_.set_face(face, layout);
  out.contributions.push_back({site, layout.area, moments_.face_from_corners(site)});
}

void FaceBoundaryTracer::trace_face(Index face, TracedChunk& out) {
  face_ = face;
  layout_ = FaceLayout::of(field_, face);
  SubTriangle root;
  for (int c = 0; c < 3; ++c) {
    root.corner[c] = layout_.corner[c];
    root.site[c] = field_.nearest_site[mesh_.faces(face, c)];
    if (root.site[c] < 0) return;  // not reached by any site
  }
  out_ = &out;
  graph_ = &out.graph;
  build_face_envelope(field_, mesh_, face, layout_, envelope_);
  face_indexed_ = envelope_.cone_count() >= min_cones_to_index;
  if (face_indexed_) face_index_.build(envelope_, layout_.corner);
  moments_.set_face(face, layout_);
  face_sites_.clear();
  const auto first =
      std::lower_bound(field_.face_point_sources.begin(), field_.face_point_sources.end(), FacePointSource{face},
                       [](const FacePointSource& a, const FacePointSource& b) { return a.face < b.face; });
  for (auto it = first; it != field_.face_point_sources.end() && it->face == face; ++it) {
    if (it->sigma == 0) {  // a site itself, not a pseudo-source seen through a neighbour
      face_sites_.push_back({layout_.point(it->barycentric), it->site});
    }
  }
  std::sort(face_sites_.begin(), face_sites_.end(), [](const FaceSite& a, const FaceSite& b) {
    return a.point.x() < b.point.x() || (a.point.x() == b.point.x() && a.site < b.site);
  });
  // Cells much smaller than the face (a coarse input remeshed finely) are
  // resolved as far below their own size as the option asks below a face's:
  // a face holding k sites is split log4(k) levels deeper.
  max_depth_ = options_.max_refinement;
  for (std::size_t k = face_sites_.size(); k >= 4; k /= 4) ++max_depth_;

  sides_.clear();
  crossings_.clear();
  for (int k = 0; k < 3; ++k) {
    const Index e = field_.face_edges[face][k];
    const std::span<const EdgeCrossing> along = store_.of(e);
    const EdgeInFace frame = edge_in_face(field_, mesh_, layout_, face, k);
    Side side;
    side.start = root.corner[k];
    side.end = root.corner[(k + 1) % 3];
    side.start_site = root.site[k];
    side.end_site = root.site[(k + 1) % 3];
    side.crossing_begin = static_cast<Index>(crossings_.size());
    auto add = [&](const EdgeCrossing& c, bool forward) {
      const auto reference = edge_crossing_reference(static_cast<Index>(&c - store_.crossings.data()));
      crossings_.push_back(
          {frame.origin + c.x * frame.direction, forward ? c.from : c.to, forward ? c.to : c.from, reference});
    };
    if (frame.forward) {
      for (const EdgeCrossing& c : along) add(c, true);
    } else {
      for (auto it = along.rbegin(); it != along.rend(); ++it) add(*it, false);
    }
    side.crossing_end = static_cast<Index>(crossings_.size());
    sides_.push_back(side);
    root.side[k] = {static_cast<Index>(k), false};
  }
  face_refined_ = false;
  ++out_->stats.boundary_faces;
  trace(root, 0);
  if (face_refined_) ++out_->stats.refined_faces;
  out.faces.push_back({face, static_cast<Index>(out.graph.nodes.size())});
}

void FaceBoundaryTracer::collect_cycle(const SubTriangle& triangle) {
  cycle_.clear();
  for (int k = 0; k < 3; ++k) {
    const SideUse use = triangle.side[k];
    const Side& side = sides_[use.side];
    if (!use.reversed) {
      for (Index i = side.crossing_begin; i < side.crossing_end; ++i) cycle_.push_back({crossings_[i], k});
    } else {
      for (Index i = side.crossing_end; i-- > side.crossing_begin;) {
        Crossing c = crossings_[i];
        std::swap(c.from, c.to);
        cycle_.push_back({c, k});
      }
    }
  }
}

bool FaceBoundaryTracer::holds_island(const SubTriangle& triangle) const {
  // Only the sites within the triangle's stretch of x (and a few units in
  // the last place, which the tests below may round across) can lie in it.
  double x_min = std::min({triangle.corner[0].x(), triangle.corner[1].x(), triangle.corner[2].x()});
  double x_max = std::max({triangle.corner[0].x(), triangle.corner[1].x(), triangle.corner[2].x()});
  const double slack = 16 * std::numeric_limits<double>::epsilon() * (std::abs(x_min) + std::abs(x_max));
  x_min -= slack;
  x_max += slack;
  const auto first = std::lower_bound(face_sites_.begin(), face_sites_.end(), x_min,
                                      [](const FaceSite& a, double x) { return a.point.x() < x; });
  for (auto it = first; it != face_sites_.end() && it->point.x() <= x_max; ++it) {
    const Eigen::Vector2d& p = it->point;
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      inside = cross(triangle.corner[(k + 1) % 3] - triangle.corner[k], p - triangle.corner[k]) >= 0;
    }
    if (!inside) continue;
    const Index site = it->site;
    bool seen = triangle.site[0] == site || triangle.site[1] == site || triangle.site[2] == site;
    for (const CycleCrossing& c : cycle_) seen = seen || c.crossing.to == site;
    if (!seen) return true;
  }
  return false;
}

void FaceBoundaryTracer::trace(const SubTriangle& triangle, int depth) {
  collect_cycle(triangle);
  const std::size_t n = cycle_.size();
  const bool at_limit = depth >= max_depth_;
  // Consistent: each crossing leaves the site the previous one entered.
  bool consistent = true;
  for (std::size_t i = 0; i < n; ++i) {
    consistent = consistent && cycle_[i].crossing.to == cycle_[(i + 1) % n].crossing.from;
  }
  if (consistent && !holds_island(triangle) && resolve(triangle, at_limit)) return;
  if (!at_limit) {
    subdivide(triangle, depth);
    return;
  }

  // Finer than the refinement limit allows: join the crossings in pairs with
  // straight pieces and give the area to the site at the centre.
  ++out_->stats.unresolved_regions;
  for (std::size_t i = 0; i + 1 < n; i += 2) {
    const Crossing& a = cycle_[i].crossing;
    const Crossing& b = cycle_[i + 1].crossing;
    BoundaryPiece piece;
    piece.from = a.node;
    piece.to = b.node;
    piece.left = a.from;
    piece.right = a.to;
    piece.point_begin = piece.point_end = static_cast<Index>(graph_->points.size());
    piece.length = (b.point - a.point).norm();
    graph_->pieces.push_back(piece);
  }
  const Eigen::Vector2d centre = (triangle.corner[0] + triangle.corner[1] + triangle.corner[2]) / 3;
  const Index site = nearest_in_face(centre);
  const Index owner = site >= 0 ? site : triangle.site[0];
  out_->contributions.push_back(
      {owner, std::max(triangle_area(triangle.corner), 0.0), moments_.polygon(owner, triangle.corner, envelope_)});
}

std::span<const Eigen::Vector2d> FaceBoundaryTracer::piece_span(std::size_t piece) const {
  return {piece_points_.data() + piece_offsets_[piece],
          static_cast<std::size_t>(piece_offsets_[piece + 1] - piece_offsets_[piece])};
}

void FaceBoundaryTracer::peel_caps() {
  // 1. Caps: a crossing into site X followed by one back out of it, where X
  //    owns no other stretch of the boundary, are joined by one bisector arc
  //    that cuts X's part off (peeled repeatedly, so nested caps work too).
  const std::size_t n = cycle_.size();
  remaining_.resize(n);
  for (std::size_t i = 0; i < n; ++i) remaining_[i] = static_cast<Index>(i);
  caps_.clear();
  for (bool peeled = true; peeled && remaining_.size() >= 2;) {
    peeled = false;
    const std::size_t m = remaining_.size();
    for (std::size_t r = 0; r < m && !peeled; ++r) {
      const Crossing& into = cycle_[remaining_[r]].crossing;
      const Crossing& out_of = cycle_[remaining_[(r + 1) % m]].crossing;
      if (into.from != out_of.to) continue;
      int stretches = 0;
      for (const Index k : remaining_) stretches += cycle_[k].crossing.to == into.to;
      if (stretches != 1) continue;
      caps_.push_back({remaining_[r], remaining_[(r + 1) % m]});
      const std::size_t second = (r + 1) % m;
      remaining_.erase(remaining_.begin() + static_cast<std::ptrdiff_t>(std::max(r, second)));
      remaining_.erase(remaining_.begin() + static_cast<std::ptrdiff_t>(std::min(r, second)));
      peeled = true;
    }
  }
}

bool FaceBoundaryTracer::at_most_one_vertex(bool at_limit) const {
  // 2. What is left must be empty or one Voronoi vertex: every stretch a
  //    different site (more than three only at the refinement limit).
  const std::size_t m = remaining_.size();
  if (m == 1 || m == 2) return false;
  for (std::size_t r = 0; r < m; ++r) {
    for (std::size_t q = 0; q < r; ++q) {
      if (cycle_[remaining_[r]].crossing.to == cycle_[remaining_[q]].crossing.to) return false;
    }
  }
  return m <= 3 || at_limit;
}

bool FaceBoundaryTracer::trace_pieces(const SubTriangle& triangle, bool at_limit, Eigen::Vector2d& vertex,
                                      double& spread) {
  const std::size_t m = remaining_.size();
  // 3. Trace everything into scratch space, checking that no third site is
  //    nearer along the way; nothing is added to the graph before all passes.
  trace_valid_ = true;
  piece_points_.clear();
  piece_offsets_.assign(1, 0);
  for (const auto& [i, j] : caps_) {
    const Crossing& into = cycle_[i].crossing;
    trace_bisector(into.point, cycle_[j].crossing.point, into.from, into.to, triangle, 0);
    piece_offsets_.push_back(static_cast<Index>(piece_points_.size()));
  }
  if (m > 0) {
    star_sites_.clear();
    Eigen::Vector2d start = Eigen::Vector2d::Zero();
    for (const Index k : remaining_) {
      star_sites_.push_back(cycle_[k].crossing.to);
      start += cycle_[k].crossing.point / static_cast<double>(m);
    }
    vertex = solve_vertex(star_sites_, triangle, start, spread);
    // Newton converges once it starts near the vertex, where every site's
    // envelope is exact; from farther away it can stall (an envelope is only
    // an upper bound outside its cell), and refining brings the start closer.
    const bool found = spread <= vertex_tolerance_ && vertex.allFinite() && inside(triangle, vertex);
    if (!found) {
      if (!at_limit) return false;
      vertex = layout_.point(layout_.barycentric(start));
      spread = 0;
    }
    for (const Index k : remaining_) {
      const Crossing& c = cycle_[k].crossing;
      trace_bisector(c.point, vertex, c.from, c.to, triangle, 0);
      piece_offsets_.push_back(static_cast<Index>(piece_points_.size()));
    }
  }
  return trace_valid_ || at_limit;
}

void FaceBoundaryTracer::commit_pieces(const Eigen::Vector2d& vertex, double spread) {
  const std::size_t m = remaining_.size();
  // 4. Commit: the vertex and the pieces.
  for (std::size_t c = 0; c < caps_.size(); ++c) {
    const Crossing& into = cycle_[caps_[c][0]].crossing;
    const Crossing& out_of = cycle_[caps_[c][1]].crossing;
    commit_piece(into.node, out_of.node, into.from, into.to, into.point, out_of.point, piece_span(c));
  }
  if (m > 0) {
    const Index node = add_node(vertex, BoundaryNode::Kind::voronoi_vertex);
    graph_->nodes[node].site_begin = static_cast<Index>(graph_->vertex_sites.size());
    graph_->nodes[node].degree = static_cast<int>(m);
    graph_->nodes[node].distance = envelope_.distance(envelope_.slot_of(star_sites_[0]), vertex);
    graph_->vertex_sites.insert(graph_->vertex_sites.end(), star_sites_.begin(), star_sites_.end());
    out_->stats.max_vertex_residual = std::max(out_->stats.max_vertex_residual, spread);
    for (std::size_t r = 0; r < m; ++r) {
      const Crossing& c = cycle_[remaining_[r]].crossing;
      commit_piece(c.node, node, c.from, c.to, c.point, vertex, piece_span(caps_.size() + r));
    }
  }
}

void FaceBoundaryTracer::add_parts(const SubTriangle& triangle, const Eigen::Vector2d& vertex) {
  // 5. Every site's part of the triangle, walked as a polygon with the part
  //    on the left: along the triangle's boundary to the crossing where the
  //    part ends, then through the inside along the piece that starts there
  //    (a cap's arc, or a star piece to the vertex and the previous star
  //    piece back out) to the crossing where the boundary is the part's again.
  const std::size_t n = cycle_.size(), m = remaining_.size();
  if (n == 0) {
    add_part(triangle.site[0], triangle.corner);
    return;
  }
  // Where the inside path from crossing k leads: its far crossing, and how.
  std::vector<std::array<Index, 3>>& jump = jump_;  // {to crossing, piece, forward (1) / reverse (0) / star (2)}
  jump.assign(n, {-1, -1, 0});
  for (std::size_t c = 0; c < caps_.size(); ++c) {
    jump[caps_[c][0]] = {caps_[c][1], static_cast<Index>(c), 1};
    jump[caps_[c][1]] = {caps_[c][0], static_cast<Index>(c), 0};
  }
  for (std::size_t r = 0; r < m; ++r) {
    jump[remaining_[r]] = {remaining_[(r + m - 1) % m], static_cast<Index>(r), 2};
  }
  visited_.assign(n, 0);
  for (std::size_t start = 0; start < n; ++start) {
    if (visited_[start]) continue;
    const Index site = cycle_[start].crossing.to;
    polygon_.clear();
    std::size_t k = start;
    for (std::size_t guard = 0; guard <= 2 * n; ++guard) {
      visited_[k] = 1;
      // Along the boundary from crossing k to the next one.
      const std::size_t next = (k + 1) % n;
      polygon_.push_back(cycle_[k].crossing.point);
      const int count = next > k ? cycle_[next].after_corner - cycle_[k].after_corner
                                 : cycle_[next].after_corner + 3 - cycle_[k].after_corner;
      for (int c = 1; c <= count; ++c) polygon_.push_back(triangle.corner[(cycle_[k].after_corner + c) % 3]);
      polygon_.push_back(cycle_[next].crossing.point);
      // Then inside, from `next`.
      const auto [to, piece, how] = jump[next];
      if (how == 1) {
        const auto line = piece_span(static_cast<std::size_t>(piece));
        polygon_.insert(polygon_.end(), line.begin(), line.end());
      } else if (how == 0) {
        const auto line = piece_span(static_cast<std::size_t>(piece));
        polygon_.insert(polygon_.end(), line.rbegin(), line.rend());
      } else {
        const auto in = piece_span(caps_.size() + static_cast<std::size_t>(piece));
        polygon_.insert(polygon_.end(), in.begin(), in.end());
        polygon_.push_back(vertex);
        const std::size_t back = (static_cast<std::size_t>(piece) + m - 1) % m;
        const auto out = piece_span(caps_.size() + back);
        polygon_.insert(polygon_.end(), out.rbegin(), out.rend());
      }
      k = static_cast<std::size_t>(to);
      if (k == start) break;
    }
    add_part(site, polygon_);
  }
}

bool FaceBoundaryTracer::resolve(const SubTriangle& triangle, bool at_limit) {
  peel_caps();
  if (!at_most_one_vertex(at_limit)) return false;
  Eigen::Vector2d vertex = Eigen::Vector2d::Zero();
  double spread = 0;
  if (!trace_pieces(triangle, at_limit, vertex, spread)) return false;
  commit_pieces(vertex, spread);
  add_parts(triangle, vertex);
  return true;
}

void FaceBoundaryTracer::add_part(Index site, std::span<const Eigen::Vector2d> polygon) {
  out_->contributions.push_back(
      {site, std::max(0.0, signed_area(polygon)), moments_.polygon(site, polygon, envelope_)});
}

bool FaceBoundaryTracer::inside(const SubTriangle& triangle, const Eigen::Vector2d& p) const {
  const double scale = (triangle.corner[1] - triangle.corner[0]).norm() +
                       (triangle.corner[2] - triangle.corner[1]).norm() +
                       (triangle.corner[0] - triangle.corner[2]).norm();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d edge = triangle.corner[(k + 1) % 3] - triangle.corner[k];
    const double length = edge.norm();
    if (length > 0 && cross(edge, p - triangle.corner[k]) / length < -1e-9 * scale) return false;
  }
  return true;
}

void FaceBoundaryTracer::commit_piece(Index from, Index to, Index left, Index right, const Eigen::Vector2d& p,
                                      const Eigen::Vector2d& q, std::span<const Eigen::Vector2d> line) {
  BoundaryPiece piece;
  piece.from = from;
  piece.to = to;
  piece.left = left;
  piece.right = right;
  piece.point_begin = static_cast<Index>(graph_->points.size());
  Eigen::Vector2d previous = p;
  for (const Eigen::Vector2d& x : line) {
    const Eigen::Vector3d b = layout_.barycentric(x);
    graph_->points.push_back(to_space(x));
    graph_->point_locations.push_back(SurfacePoint::in_face(face_, b[0], b[1], b[2]));
    piece.length += (x - previous).norm();
    previous = x;
  }
  piece.length += (q - previous).norm();
  piece.point_end = static_cast<Index>(graph_->points.size());
  graph_->pieces.push_back(piece);
}

double FaceBoundaryTracer::trace_bisector(const Eigen::Vector2d& p, const Eigen::Vector2d& q, Index left, Index right,
                                          const SubTriangle& triangle, int depth) {
  const Eigen::Vector2d chord = q - p;
  const double length = chord.norm();
  if (depth >= max_polyline_depth || !(length > tolerance_)) return 0;
  const Eigen::Vector2d middle = 0.5 * (p + q);
  const Eigen::Vector2d normal(-chord.y() / length, chord.x() / length);
  // The stretch of the line middle + s normal inside the triangle.
  double s_min = -length, s_max = length;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d a = triangle.corner[k], edge = triangle.corner[(k + 1) % 3] - a;
    const double at_middle = cross(edge, middle - a), rate = cross(edge, normal);
    if (rate > 0) {
      s_min = std::max(s_min, -at_middle / rate);
    } else if (rate < 0) {
      s_max = std::min(s_max, -at_middle / rate);
    } else if (at_middle < 0) {
      return 0;
    }
  }
  if (!(s_min < s_max)) return 0;
  const Eigen::Vector2d low = middle + s_min * normal, high = middle + s_max * normal;
  const double g_low = envelope_.difference(left, right, low), g_high = envelope_.difference(left, right, high);
  if (!((g_low <= 0) != (g_high <= 0))) return 0;
  const Eigen::Vector2d on_curve =
      low + equal_distance_parameter(envelope_, low, high, left, right, g_low, g_high) * (high - low);
  if (const Index nearest = nearest_in_face(on_curve); nearest != left && nearest != right) {
    trace_valid_ = false;  // a third site's part lies across the way
  }
  if ((on_curve - middle).norm() <= tolerance_) return 0;
  trace_bisector(p, on_curve, left, right, triangle, depth + 1);
  piece_points_.push_back(on_curve);
  trace_bisector(on_curve, q, left, right, triangle, depth + 1);
  return 0;
}

Eigen::Vector2d FaceBoundaryTracer::solve_vertex(std::span<const Index> sites, const SubTriangle& triangle,
                                                 const Eigen::Vector2d& start, double& spread) {
  // Gauss-Newton on r_i = d_i(x) - d_0(x), i = 1..k-1 (Newton for k = 3);
  // each d_i is a cone near x, so its gradient is the unit vector from the
  // active cone's apex.
  Eigen::Vector2d x = start;
  const double scale = std::max(std::sqrt(std::max(layout_.area, 0.0)), tolerance_);
  // Distances and gradients at x (`at_x_`) and at a trial point (`trial_`).
  at_x_.resize(sites.size());
  trial_.resize(sites.size());
  auto evaluate = [&](const Eigen::Vector2d& at, std::vector<VertexTerm>& terms) {
    double worst = 0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const int slot = envelope_.slot_of(sites[i]);
      terms[i].distance =
          slot >= 0 ? envelope_.distance(slot, at, &terms[i].gradient) : std::numeric_limits<double>::infinity();
      if (i > 0) worst = std::max(worst, std::abs(terms[i].distance - terms[0].distance));
    }
    return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
  };
  spread = evaluate(x, at_x_);
  for (int iteration = 0; iteration < 40 && spread > 0 && std::isfinite(spread); ++iteration) {
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    for (std::size_t i = 1; i < sites.size(); ++i) {
      const Eigen::Vector2d row = at_x_[i].gradient - at_x_[0].gradient;
      normal += row * row.transpose();
      rhs += row * (at_x_[i].distance - at_x_[0].distance);
    }
    normal += 1e-14 * Eigen::Matrix2d::Identity();
    Eigen::Vector2d step = -normal.ldlt().solve(rhs);
    if (!step.allFinite()) break;
    if (step.norm() > scale) step *= scale / step.norm();
    // Stay in the triangle: its boundary says the vertex is inside, and
    // outside it the envelopes are only upper bounds.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = triangle.corner[k], edge = triangle.corner[(k + 1) % 3] - a;
      const double now = cross(edge, x - a), rate = cross(edge, step);
      if (rate < 0 && now + rate < 0) step *= std::max(0.0, now) / -rate;
    }
    // Backtrack until the spread falls.
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      const double trial_spread = evaluate(x + step, trial_);
      if (trial_spread < spread) {
        x += step;
        spread = trial_spread;
        std::swap(at_x_, trial_);
        improved = true;
        break;
      }
      step *= 0.5;
    }
    if (!improved || step.norm() < 1e-17 * scale) break;
  }
  return x;
}

FaceBoundaryTracer::SideUse FaceBoundaryTracer::half_of(const SideUse& use, int which) {
  // Split the stored side once, at its midpoint; both triangles that share it
  // then see the same halves and the same crossings. Where a crossing lies at
  // the midpoint (two sites tie there: sites placed symmetrically about it),
  // the split moves off it: a corner on the crossing would leave the site of
  // every sub-triangle there undecided, at any depth of refinement.
  Side& side = sides_[use.side];
  if (side.halves[0] < 0) {
    const Eigen::Vector2d start = side.start, end = side.end;
    const Eigen::Vector2d along = end - start;
    const double squared_length = along.squaredNorm();
    auto at_crossing = [&](double t) {
      for (Index i = side.crossing_begin; i < side.crossing_end; ++i) {
        const double u = (crossings_[i].point - start).dot(along) / squared_length;
        if (std::abs(u - t) <= kSplitClearance) return true;
      }
      return false;
    };
    double t = 0.5;
    for (const double other : {0.5 + 1.0 / 16, 0.5 - 1.0 / 16}) {
      if (!at_crossing(t)) break;
      t = other;
    }
    const Eigen::Vector2d middle = start + t * along;
    side.split = middle;
    Index split = side.crossing_begin;
    while (split < side.crossing_end && (crossings_[split].point - start).dot(along) < t * squared_length) {
      ++split;
    }
    const Index middle_site = split > side.crossing_begin ? crossings_[split - 1].to : side.start_site;
    Side first{start, middle, side.start_site, middle_site, side.crossing_begin, split, {-1, -1}};
    Side second{middle, end, middle_site, side.end_site, split, side.crossing_end, {-1, -1}};
    const Index index = static_cast<Index>(sides_.size());
    sides_.push_back(first);
    sides_.push_back(second);
    sides_[use.side].halves = {index, index + 1};
  }
  const std::array<Index, 2> halves = sides_[use.side].halves;
  // `which` counts from the corner where the use starts.
  if (!use.reversed) return {halves[which], false};
  return {halves[1 - which], true};
}

Eigen::Vector2d FaceBoundaryTracer::split_point(const SideUse& use) {
  half_of(use, 0);
  return sides_[use.side].split;
}

Index FaceBoundaryTracer::midpoint_site(const SideUse& use) {
  const SideUse first_half = half_of(use, 0);
  const Side& side = sides_[first_half.side];
  return first_half.reversed ? side.start_site : side.end_site;
}

Index FaceBoundaryTracer::inner_side(const Eigen::Vector2d& start, const Eigen::Vector2d& end, Index start_site,
                                     Index end_site) {
  Side side;
  side.start = start;
  side.end = end;
  side.start_site = start_site;
  side.end_site = end_site;
  side.crossing_begin = static_cast<Index>(crossings_.size());
  changes_.clear();
  const auto in_face = [this](const Eigen::Vector2d& at) { return nearest_in_face(at); };
  Index previous_site = start_site;
  double previous_t = 0;
  for (int i = 1; i <= samples_per_inner_side; ++i) {
    const double t = static_cast<double>(i) / samples_per_inner_side;
    const Index site = i == samples_per_inner_side ? end_site : in_face(start + t * (end - start));
    if (site < 0 || site == previous_site) continue;
    find_site_changes(envelope_, in_face, start, end, previous_t, t, previous_site, site);
    previous_site = site;
    previous_t = t;
  }
  drop_zero_width_stretches();
  for (const SiteChange& change : changes_) {
    const Eigen::Vector2d crossing = start + change.t * (end - start);
    crossings_.push_back({crossing, change.from, change.to, add_node(crossing, BoundaryNode::Kind::inner_crossing)});
  }
  side.crossing_end = static_cast<Index>(crossings_.size());
  sides_.push_back(side);
  return static_cast<Index>(sides_.size()) - 1;
}

void FaceBoundaryTracer::subdivide(const SubTriangle& triangle, int depth) {
  face_refined_ = true;
  const auto& c = triangle.corner;
  // Where sides 0 (c0-c1), 1 (c1-c2) and 2 (c2-c0) are split: their midpoints, unless a crossing lies there.
  const std::array<Eigen::Vector2d, 3> m = {split_point(triangle.side[0]), split_point(triangle.side[1]),
                                            split_point(triangle.side[2])};
  std::array<Index, 3> m_site{};
  for (int k = 0; k < 3; ++k) m_site[k] = midpoint_site(triangle.side[k]);
  // The three new sides inside, each shared by the centre triangle and a corner one.
  const Index inner0 = inner_side(m[0], m[2], m_site[0], m_site[2]);  // corner 0's triangle
  const Index inner1 = inner_side(m[1], m[0], m_site[1], m_site[0]);  // corner 1's triangle
  const Index inner2 = inner_side(m[2], m[1], m_site[2], m_site[1]);  // corner 2's triangle

  std::array<SubTriangle, 4> children;
  children[0] = {{c[0], m[0], m[2]},
                 {triangle.site[0], m_site[0], m_site[2]},
                 {half_of(triangle.side[0], 0), SideUse{inner0, false}, half_of(triangle.side[2], 1)}};
  children[1] = {{m[0], c[1], m[1]},
                 {m_site[0], triangle.site[1], m_site[1]},
                 {half_of(triangle.side[0], 1), half_of(triangle.side[1], 0), SideUse{inner1, false}}};
  children[2] = {{m[2], m[1], c[2]},
                 {m_site[2], m_site[1], triangle.site[2]},
                 {SideUse{inner2, false}, half_of(triangle.side[1], 1), half_of(triangle.side[2], 0)}};
  children[3] = {{m[0], m[1], m[2]},
                 {m_site[0], m_site[1], m_site[2]},
                 {SideUse{inner1, true}, SideUse{inner2, true}, SideUse{inner0, true}}};
  for (const SubTriangle& child : children) trace(child, depth + 1);
}

}  // namespace geodual::voronoi::detail
