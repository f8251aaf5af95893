#include "window_vtp.hpp"

#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace geodual::voronoi::detail {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Relative tolerance (of an edge's length) for "a window reaches this end
/// point" and "this vertex is visible through the window".
constexpr double kEndpointTolerance = 1e-12;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

WindowVtp::WindowVtp(const PropagationMesh& mesh, const GeodesicOptions& options, const GroupLimits* limits)
    : pm_(mesh),
      options_(options),
      limits_(limits),
      distance_(static_cast<std::size_t>(mesh.num_vertices())),
      label_plus_one_(static_cast<std::size_t>(mesh.num_vertices())),
      vertex_flags_(static_cast<std::size_t>(mesh.num_vertices())),
      face_flags_(static_cast<std::size_t>(mesh.num_faces())),
      store_(mesh.num_edges(), options.release_memory_between_phases),
      events_(mesh.num_vertices()) {
  window_bytes_limit_ = static_cast<std::int64_t>(
      std::min<std::size_t>(options.window_memory_limit_bytes, std::numeric_limits<std::int64_t>::max()));
  // Room for every face at once: reserved address space costs no memory until
  // used, whereas a doubling array leaves its outgrown copies in the heap.
  std::vector<FaceEvent> face_events;
  if (options.remove_redundant_windows) face_events.reserve(static_cast<std::size_t>(mesh.num_faces()));
  face_events_ = decltype(face_events_)(std::greater<>(), std::move(face_events));
  // With limits, a path longer than the bound is not a shortest path to any
  // site: starting from it (distance()), relax() and Xin & Wang's filter in
  // submit() drop such paths.
}

std::vector<double> WindowVtp::distances() const {
  std::vector<double> d(static_cast<std::size_t>(pm_.num_vertices()));
  for (Index v = 0; v < pm_.num_vertices(); ++v) d[static_cast<std::size_t>(v)] = distance(v);
  return d;
}

std::vector<Index> WindowVtp::labels() const {
  std::vector<Index> l(static_cast<std::size_t>(pm_.num_vertices()));
  for (Index v = 0; v < pm_.num_vertices(); ++v) l[static_cast<std::size_t>(v)] = label(v);
  return l;
}

// ---------------------------------------------------------------- seeding --

void WindowVtp::add_sites(const std::vector<SurfacePoint>& sites, std::span<const Index> labels) {
  // Each pseudo-source emits once (again only if its distance falls after),
  // a face site up to twice: room for that, rather than a doubling array's.
  const auto pseudo_sources = std::count(pm_.is_pseudo_source.begin(), pm_.is_pseudo_source.end(), std::uint8_t{1});
  store_.reserve_sources(static_cast<std::size_t>(pseudo_sources) + 2 * sites.size());
  for (Index i = 0; i < static_cast<Index>(sites.size()); ++i) {
    const SurfacePoint& site = sites[i];
    const Index label = labels.empty() ? i : labels[static_cast<std::size_t>(i)];
    if (site.kind == SurfacePoint::Kind::vertex) {
      add_vertex_site(site.element, label);
    } else {
      add_face_site(site.element, site.barycentric, label);
    }
  }
}

void WindowVtp::add_vertex_site(Index vertex, Index site) {
  relax(vertex, 0.0, site);
  vertex_flags_[vertex] |= kEmitted;
  emit_from_vertex(vertex, 0.0, site);
}

void WindowVtp::add_face_site(Index face, const Eigen::Vector3d& barycentric, Index site) {
  const FaceInPlane plane = lay_out_face(pm_, face, 0);
  const Eigen::Vector2d p =
      barycentric[0] * plane.corner[0] + barycentric[1] * plane.corner[1] + barycentric[2] * plane.corner[2];
  for (int c = 0; c < 3; ++c) relax(pm_.vertex(face, c), (p - plane.corner[c]).norm(), site);

  int zero_corner = -1;
  for (int c = 0; c < 3; ++c) {
    if (barycentric[c] == 0) zero_corner = c;
  }
  point_sources_.push_back({face, site, 0.0, barycentric});
  if (zero_corner < 0) {
    emit_from_point_in_face(face, plane, p, -1, 0.0, site, 0);
    return;
  }
  // On the edge opposite `zero_corner`: the site lies in both faces of it.
  const int k = (zero_corner + 1) % 3;
  emit_from_point_in_face(face, plane, p, k, 0.0, site, 0);
  emit_across_edge(face, k, to_local_edge_frame(plane, k, p).x(), 0.0, site, 0);
}

void WindowVtp::emit_across_edge(Index face, int k, double x_face, double sigma, Index site, int depth) {
  const Index e = pm_.face_edges(face)[k];
  const int side = pm_.side_of(e, face);
  const Index other = pm_.edge_faces[e][1 - side];
  if (other < 0) return;
  const double x_edge = face_frame_to_edge_frame(pm_, e, side, {x_face, 0.0}).x();
  const int other_k = pm_.local_edge(other, e);
  const bool flip = (1 - side) == 1 && pm_.edge_reversed_in_face1(e);
  const Eigen::Vector2d p_other(flip ? pm_.edge_length(e) - x_edge : x_edge, 0.0);
  const FaceInPlane other_plane = lay_out_face(pm_, other, other_k);
  const int apex = (other_k + 2) % 3;
  relax(pm_.vertex(other, apex), sigma + (p_other - other_plane.corner[apex]).norm(), site);
  // Remember the point for queries inside `other`, where no window shows it.
  const double t = pm_.edge_length(e) > 0 ? p_other.x() / pm_.edge_length(e) : 0.0;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  barycentric[other_k] = 1 - t;
  barycentric[(other_k + 1) % 3] = t;
  point_sources_.push_back({other, site, sigma, barycentric});
  emit_from_point_in_face(other, other_plane, p_other, other_k, sigma, site, depth + 1);
}

void WindowVtp::emit_from_point_in_face(Index face, const FaceInPlane& plane, const Eigen::Vector2d& source,
                                        int skip_local_edge, double sigma, Index site, int depth) {
  // Chains of zero-area faces are crossed, but never without end.
  constexpr int kMaxZeroAreaCrossings = 16;
  const std::uint32_t source_id = store_.add_source(sigma, site);
  const WindowSource window_source{sigma, site};
  for (int j = 0; j < 3; ++j) {
    if (j == skip_local_edge) continue;
    const Index e = pm_.face_edges(face)[j];
    const Eigen::Vector2d local = to_local_edge_frame(plane, j, source);
    if (!(local.y() > 0)) {
      // On the edge's line (a zero-area face): where the point lies inside
      // the edge, it is a point of the edge and reaches the face beyond.
      if (local.x() > 0 && local.x() < pm_.edge_length(e) && depth < kMaxZeroAreaCrossings) {
        emit_across_edge(face, j, local.x(), sigma, site, depth);
      }
      continue;
    }
    const Eigen::Vector2d s = face_frame_to_edge_frame(pm_, e, pm_.side_of(e, face), local);
    submit(e, {0.0, pm_.edge_length(e), s.x(), s.y(), source_id, 0}, window_source);
  }
}

void WindowVtp::emit_from_vertex(Index v, double sigma, Index site) {
  const std::uint32_t source_id = store_.add_source(sigma, site);
  const WindowSource window_source{sigma, site};
  // Its own list: relaxing the far corners walks round them meanwhile.
  pm_.faces_around(v, emit_faces_);
  for (const Index f : emit_faces_) {
    const FaceRecord& face = pm_.face_records[f];
    const int k = (pm_.corner_of(f, v) + 1) % 3;  // the edge opposite v
    const EdgeLayout l = layout_on_edge(pm_.face_lengths(face), k);
    if (!(l.apex.y() > 0) || !(l.length > 0)) {
      // A zero-area face: v lies on the line of its opposite edge. Its end
      // points are reached along the line; where v lies inside the edge, v is
      // a point of that edge and sends windows into the face beyond it.
      relax(pm_.vertex(f, k), sigma + l.apex.norm(), site);
      relax(pm_.vertex(f, (k + 1) % 3), sigma + (l.apex - Eigen::Vector2d(l.length, 0)).norm(), site);
      if (l.apex.x() > 0 && l.apex.x() < l.length) emit_across_edge(f, k, l.apex.x(), sigma, site, 0);
      continue;
    }
    // The apex in the frame of the opposite edge (see face_frame_to_edge_frame).
    const double x = face.flipped(k) ? l.length - l.apex.x() : l.apex.x();
    const double y = face.side(k) == 0 ? l.apex.y() : -l.apex.y();
    submit(face.edge(k), l.length, face.edge_start(k), face.edge_end(k), {0.0, l.length, x, y, source_id, 0},
           window_source);
  }
}

// ------------------------------------------------------------ propagation --

void WindowVtp::submit(Index e, const Window& w, const WindowSource& source) {
  const std::array<Index, 2> ends = pm_.edge_vertices(e);
  submit(e, pm_.edge_length(e), ends[0], ends[1], w, source);
}

void WindowVtp::submit(Index e, double length, Index v0, Index v1, const Window& w, const WindowSource& source) {
  if (!(w.b1 > w.b0)) return;
  if (w.source_y == 0 || !(length > 0)) {
    // Paths along the edge's line: they matter only at its end points.
    if (w.b0 <= kEndpointTolerance * length) relax(v0, w.distance_at(0, source.sigma), source.site);
    if (w.b1 >= length * (1 - kEndpointTolerance)) relax(v1, w.distance_at(length, source.sigma), source.site);
    return;
  }
  // Xin & Wang's filter: if the path through an end vertex along the edge is
  // no longer at the window's far end, it is no longer anywhere on the window
  // (the difference is monotone along the edge), and neither beyond it.
  if (distance(v0) + w.b1 < w.distance_at(w.b1, source.sigma)) return;
  if (distance(v1) + (length - w.b0) < w.distance_at(w.b0, source.sigma)) return;

  created_.clear();
  store_.insert(e, w, source, length, created_);
  stats_.windows_created += static_cast<std::int64_t>(created_.size());
  if (store_.bytes() > window_bytes_limit_) {
    throw Error("geodesic propagation needs more than the window memory limit of " +
                std::to_string(options_.window_memory_limit_bytes >> 20) +
                " MiB; raise the limit, use fewer sites, or keep redundant window removal on");
  }
  peak_window_bytes_ = std::max(peak_window_bytes_, store_.bytes());
  for (const WindowStore::Piece& created : created_) {
    Window piece = w;
    piece.b0 = created.b0;
    piece.b1 = created.b1;
    if (piece.b0 <= kEndpointTolerance * length) relax(v0, piece.distance_at(0, source.sigma), source.site);
    if (piece.b1 >= length * (1 - kEndpointTolerance)) relax(v1, piece.distance_at(length, source.sigma), source.site);
    schedule(e, v0, v1, piece, source.sigma, created.position);
  }
}

void WindowVtp::schedule(Index e, Index v0, Index v1, const Window& w, double sigma, Index position) {
  const Index face = pm_.edge_faces[e][w.entering_side()];
  if (face < 0) return;
  if (face_flags_[face] & kTraversed) {
    store_.on_edge(e)[position].queued = 1;
    enqueue_edge(e);
    return;
  }
  // A wavefront window: its edge's end points wait in the vertex queue.
  const double key = w.min_distance(sigma);
  push_expand(v0, key);
  push_expand(v1, key);
}

void WindowVtp::enqueue_edge(Index e) {
  if (store_.marked(e)) return;  // already waiting
  store_.set_marked(e, true);
  fifo_.push_back(e);
}

void WindowVtp::propagate(Index e, const Window& w) {
  store_.prefetch_source(w);  // a cache miss, overlapped with the face's
  const int side = w.entering_side();
  const Index g = pm_.edge_faces[e][side];
  if (g < 0) return;
  const FaceRecord& face = pm_.face_records[g];
  // The windows of an edge go through in turn (drain_fifo), most into the
  // same face: its layout is made once for them.
  EnteredFace& entered = entered_face_;
  if (entered.edge != e || entered.side != side) {
    entered.edge = e;
    entered.side = side;
    entered.k = PropagationMesh::local_edge(face, e);
    entered.lengths = pm_.face_lengths(face);
    entered.layout = layout_on_edge(entered.lengths, entered.k);
  }
  const int k = entered.k;
  const std::array<double, 3>& lengths = entered.lengths;
  const EdgeLayout& l = entered.layout;
  const double length = l.length;

  // The window in g's frame for edge k: A = (0,0), B = (length,0), C = apex
  // above the axis, the source below it.
  const bool flip = face.flipped(k);
  const Eigen::Vector2d s(flip ? length - w.source_x : w.source_x, side == 0 ? w.source_y : -w.source_y);
  const double b0 = flip ? length - w.b1 : w.b0;
  const double b1 = flip ? length - w.b0 : w.b1;
  if (!(s.y() < 0)) return;
  const WindowSource source = store_.source_of(w);
  const Eigen::Vector2d a(0, 0), b(length, 0), c = l.apex;

  // Where the ray from the source through C crosses the edge.
  const double t = -s.y() / (c.y() - s.y());
  const double x_c = s.x() + (c.x() - s.x()) * t;
  const double tolerance = kEndpointTolerance * length;
  if (x_c >= b0 - tolerance && x_c <= b1 + tolerance) {
    relax(face.vertex[(k + 2) % 3], source.sigma + (c - s).norm(), source.site);
  }

  // Child windows: the part of the cone left of C lands on edge C -> A
  // (local edge k + 2), the part right of C on edge B -> C (local edge k + 1).
  auto emit_child = [&](int j, const Eigen::Vector2d& p, const Eigen::Vector2d& q, double x_lo, double x_hi) {
    const double len = lengths[j];
    const Eigen::Vector2d pq = q - p;
    const double pq_norm = pq.norm();
    if (!(len > 0) || !(pq_norm > 0)) return;
    auto hit = [&](double x) {
      // The ray from s through (x, 0) meets line p + lambda (q - p) at lambda.
      const Eigen::Vector2d d(x - s.x(), -s.y());
      const double den = cross(pq, d);
      return den != 0 ? std::clamp(cross(s - p, d) / den, 0.0, 1.0) : std::numeric_limits<double>::quiet_NaN();
    };
    const double l0 = hit(x_lo), l1 = hit(x_hi);
    if (std::isnan(l0) || std::isnan(l1)) return;
    const double lo = std::min(l0, l1) * len, hi = std::max(l0, l1) * len;
    if (hi - lo <= 1e-12 * len) return;
    const Eigen::Vector2d u = pq / pq_norm;
    const Eigen::Vector2d r = s - p;
    const Eigen::Vector2d source_local(r.dot(u), u.x() * r.y() - u.y() * r.x());
    // In the frame of edge j (see face_frame_to_edge_frame).
    const bool flip_j = face.flipped(j);
    const double src_x = flip_j ? len - source_local.x() : source_local.x();
    const double src_y = face.side(j) == 0 ? source_local.y() : -source_local.y();
    submit(face.edge(j), len, face.edge_start(j), face.edge_end(j),
           {flip_j ? len - hi : lo, flip_j ? len - lo : hi, src_x, src_y, w.source, 0}, source);
  };
  if (b0 < x_c) emit_child((k + 2) % 3, c, a, b0, std::min(b1, x_c));
  if (x_c < b1) emit_child((k + 1) % 3, b, c, std::max(b0, x_c), b1);
}

void WindowVtp::drain_fifo() {
  // Edges with windows waiting to be propagated; each pass takes all of an
  // edge's waiting windows. Propagation only adds windows to other edges
  // (the entered face's two others), so the edge's array stays as it is.
  while (fifo_head_ < fifo_.size()) {
    const Index e = fifo_[fifo_head_++];
    store_.set_marked(e, false);
    const std::size_t count = store_.on_edge(e).size();
    for (std::size_t i = 0; i < count; ++i) {
      Window& w = store_.on_edge(e)[i];
      if (!w.queued) continue;
      w.queued = 0;
      propagate(e, Window(w));
    }
  }
  fifo_.clear();
  fifo_head_ = 0;
}

void WindowVtp::expand(Index v) {
  vertex_flags_[v] |= kPopped;
  ++stats_.vertices_popped;
  new_faces_.clear();
  pm_.faces_around(v, fan_);
  for (const Index f : fan_) {
    if (face_flags_[f] & kTraversed) continue;
    face_flags_[f] |= kTraversed;
    ++faces_traversed_;
    new_faces_.push_back(f);
  }
  // Step 3: the windows waiting on the new faces' edges go in.
  for (const Index f : new_faces_) {
    const FaceRecord& face = pm_.face_records[f];
    for (int k = 0; k < 3; ++k) {
      const Index e = face.edge(k);
      const int side = face.side(k);
      bool any = false;
      for (Window& w : store_.on_edge(e)) {
        if (w.entering_side() == side && !w.queued) {
          w.queued = 1;
          any = true;
        }
      }
      if (any) enqueue_edge(e);
    }
  }
  drain_fifo();
  // Step 6: the new faces join the inactive-region queue.
  if (options_.remove_redundant_windows) {
    for (const Index f : new_faces_) push_face_key(f);
  }
}

void WindowVtp::relax(Index v, double d, Index site) {
  const double current = distance(v);
  if (!(d < current)) return;
  const bool first_time = current == kInfinity;
  if (limits_ != nullptr && label_plus_one_[v] == 0) reached_.push_back(v);
  distance_[v] = d;
  label_plus_one_[v] = site + 1;
  vertex_flags_[v] &= static_cast<std::uint8_t>(~kEmitted);
  if (pm_.is_pseudo_source[v]) events_.push_or_decrease({d, v, EventKind::emit});
  if (first_time && (vertex_flags_[v] & kFaceWaits) && options_.remove_redundant_windows) {
    pm_.faces_around(v, fan_);
    for (const Index f : fan_) {
      if (face_flags_[f] & kTraversed) push_face_key(f);
    }
  }
}

void WindowVtp::push_expand(Index v, double key) {
  // The queue keeps the smallest key pushed while the vertex waits.
  if ((vertex_flags_[v] & kPopped) || !(key < kInfinity)) return;
  events_.push_or_decrease({key, v, EventKind::expand});
}

bool WindowVtp::pop_event(Event& event) {
  while (!events_.empty()) {
    event = events_.top();
    events_.pop();
    // A vertex site emits at once, not from the queue.
    if (event.kind == EventKind::expand || !(vertex_flags_[event.vertex] & kEmitted)) return true;
  }
  return false;
}

double WindowVtp::next_event_key() const { return events_.empty() ? kInfinity : events_.top().key; }

// --------------------------------------------------------------------- RWR --

void WindowVtp::push_face_key(Index face) {
  if (face_flags_[face] & kKeyPushed) return;
  double d_min = kInfinity;
  for (int c = 0; c < 3; ++c) d_min = std::min(d_min, distance(pm_.vertex(face, c)));
  if (d_min == kInfinity) {
    // Pushed when a corner is first reached (relax looks round the corners
    // marked here, and only those).
    for (int c = 0; c < 3; ++c) vertex_flags_[pm_.vertex(face, c)] |= kFaceWaits;
    return;
  }
  face_flags_[face] |= kKeyPushed;
  const std::array<double, 3> lengths = pm_.face_lengths(pm_.face_records[face]);
  const double key = d_min + std::max({lengths[0], lengths[1], lengths[2]});
  float rounded_up = static_cast<float>(key);
  if (static_cast<double>(rounded_up) < key)
    rounded_up = std::nextafter(rounded_up, std::numeric_limits<float>::infinity());
  face_events_.push({rounded_up, face});
}

// Definition 3.1 (redundant triangle): all windows on the face's three edges
// come from one source. Its three vertices must carry that source's label too,
// so that the face holds no piece of a cell boundary through a vertex.
bool WindowVtp::face_is_redundant(Index face) const {
  const Index site = label(pm_.vertex(face, 0));
  if (site < 0) return false;
  for (int c = 1; c < 3; ++c) {
    if (label(pm_.vertex(face, c)) != site) return false;
  }
  for (int k = 0; k < 3; ++k) {
    const Index e = pm_.face_edges(face)[k];
    const Index summary = store_.edge_site(e);
    if (summary == site || summary == WindowStore::kNoSite) continue;
    if (summary != WindowStore::kMixedSites) return false;
    for (const Window& w : store_.on_edge(e)) {
      if (store_.source_of(w).site != site) return false;
    }
  }
  return true;
}

// For a point x of the face, d(x) <= d_min + |e_max| through its nearest
// corner, and every site of another group is at least |x - c0| - |e_max| away
// from x in space (c0 = corner 0), so at least that far on the surface:
// where no such site lies within d_min + 2 |e_max| of c0, this group's site
// is strictly nearest all over the face, and its windows there are final.
bool WindowVtp::away_from_other_groups(Index face) const {
  if (limits_ == nullptr || limits_->sites == nullptr) return true;
  double d_min = kInfinity;
  for (int c = 0; c < 3; ++c) d_min = std::min(d_min, distance(pm_.vertex(face, c)));
  const std::array<double, 3> lengths = pm_.face_lengths(pm_.face_records[face]);
  const double radius = (d_min + 2 * std::max({lengths[0], lengths[1], lengths[2]})) * (1 + 1e-9);
  const Index corner = limits_->old_vertex[static_cast<std::size_t>(pm_.vertex(face, 0))];
  return !limits_->sites->other_group_within(limits_->mesh->vertices.row(corner).transpose(), radius, limits_->group);
}

// RWR, the paper's Procedure 1: Step 1 (Proposition 3.1, below) finds the faces
// now inactive, Step 2 (Definition 3.1) frees the windows of the redundant
// edges among them: edges whose two faces are both inactive and redundant.
void WindowVtp::remove_redundant_windows(double lower_bound) {
  // Proposition 3.1: with d_min(f) taken from f's vertices (an upper bound of
  // the true minimum over f), no window yet to come, all of which are at least
  // `lower_bound` away, can lower any distance on f's edges once
  // d_min(f) + |e_max(f)| <= lower_bound.
  while (!face_events_.empty() && static_cast<double>(face_events_.top().key) <= lower_bound) {
    const Index f = face_events_.top().face;
    face_events_.pop();
    if (face_flags_[f] & kInactive) continue;
    face_flags_[f] |= kInactive;
    ++stats_.faces_inactive;
    if (!face_is_redundant(f) || !away_from_other_groups(f)) continue;
    face_flags_[f] |= kRedundant;
    for (int k = 0; k < 3; ++k) {
      const Index e = pm_.face_edges(f)[k];
      const Index other = pm_.edge_faces[e][1 - pm_.side_of(e, f)];
      if (other < 0 || ((face_flags_[other] & kInactive) && (face_flags_[other] & kRedundant))) {
        store_.clear_edge(e);
        if (limits_ != nullptr) freed_edges_.push_back(e);
      }
    }
  }
}

// -------------------------------------------------------------- main loop --

void WindowVtp::report_progress() {
  if (!options_.progress || (++steps_ & 1023) != 0) return;
  const double fraction =
      pm_.num_included_faces > 0 ? static_cast<double>(faces_traversed_) / pm_.num_included_faces : 1.0;
  if (!options_.progress(fraction)) throw Cancelled("geodesic computation cancelled");
}

// Algorithm 2. Step 0 (one window per edge opposite each source, its
// neighbours into Q) ran in the constructor and add_sites(); each pass of the
// loop is Steps 1-6: pop the nearest vertex (Step 1), add its faces to the
// traversed area and propagate their waiting windows through a FIFO (Steps
// 2-3, expand), free what the inactive region makes redundant (Step 4),
// and queue the new faces for it (Step 6, in expand); vertex keys are
// updated as windows reach them (Step 5, relax).
void WindowVtp::run() {
  drain_fifo();
  Event event{};
  while (pop_event(event)) {
    if (event.kind == EventKind::emit) {
      vertex_flags_[event.vertex] |= kEmitted;
      ++stats_.pseudo_sources;
      emit_from_vertex(event.vertex, event.key, label(event.vertex));
      drain_fifo();
    } else {
      expand(event.vertex);
    }
    if (options_.remove_redundant_windows) remove_redundant_windows(next_event_key());  // Step 4
    report_progress();
  }
  if (options_.remove_redundant_windows) remove_redundant_windows(kInfinity);
  if (options_.progress && !options_.progress(1.0)) throw Cancelled("geodesic computation cancelled");
  // The queues are empty now: their memory goes back before the caller
  // builds its results next to what is kept (distances, labels, windows).
  events_ = EventQueue(0);
  face_events_ = decltype(face_events_)();
  fifo_ = std::vector<Index>();
  created_ = std::vector<WindowStore::Piece>();
  new_faces_ = std::vector<Index>();
  fan_ = std::vector<Index>();
  emit_faces_ = std::vector<Index>();
  stats_.windows_stored = store_.live();
  stats_.peak_windows = store_.peak();
  stats_.peak_window_bytes = peak_window_bytes_;
}

// A valid face is one Definition 3.1 does not call redundant: windows from
// different sites meet on it, so a cell boundary crosses it.
std::vector<bool> WindowVtp::valid_faces() const {
  std::vector<bool> valid(static_cast<std::size_t>(pm_.num_faces()), false);
  for (Index f = 0; f < pm_.num_faces(); ++f) {
    if (!pm_.included(f) || label(pm_.vertex(f, 0)) < 0) continue;
    valid[f] = (face_flags_[f] & kInactive) ? !(face_flags_[f] & kRedundant) : !face_is_redundant(f);
  }
  return valid;
}

}  // namespace geodual::voronoi::detail
