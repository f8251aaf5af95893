#pragma once
// window-VTP (Qin, Yu & Zhang 2017, Algorithm 2): multi-source exact geodesics
// by vertex-sorted triangle propagation, with Redundant Window Removal.
//
// One priority queue holds vertices keyed by the smallest distance of the
// waiting windows on their edges (§4.2), plus pseudo-source events keyed by a
// saddle/boundary vertex's distance (emitted once that distance is final).
// Popping a vertex adds its untraversed faces to the traversed area R and
// propagates the windows waiting on their edges through R with a FIFO until
// they reach the wavefront or die (Step 3). A second queue holds faces keyed
// by d_min(f) + |e_max(f)|; a face whose key is <= the smallest key left in
// the first queue is inactive (Proposition 3.1) and, if redundant, its edges'
// windows are freed (Procedure 1, Step 4).

#include "event_queue.hpp"
#include "geodual/voronoi/geodesic_field.hpp"
#include "propagation_mesh.hpp"
#include "site_groups.hpp"
#include "window_store.hpp"
#include "zeroed_array.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <queue>
#include <span>
#include <utility>
#include <vector>

namespace geodual::voronoi::detail {

/// One group's share of a propagation split into groups of sites (see
/// site_groups.hpp): paths longer than `distance_bound` are dropped, and a
/// redundant face's windows are freed only where no site of another group
/// can be nearer anywhere on the face.
struct GroupLimits {
  /// Per vertex: an upper bound of the distance to the nearest site of any
  /// group (surface_path_upper_bound).
  std::span<const double> distance_bound;
  const SiteTree* sites = nullptr;
  int group = 0;
  /// Per vertex of the propagation mesh, its position (for the SiteTree).
  const TriangleMesh* mesh = nullptr;
  std::span<const Index> old_vertex;
};

class WindowVtp {
 public:
  /// With `limits`, propagates one group of sites (add_sites gets only that
  /// group's sites, with their global indices as labels): distances start at
  /// the bound, so a vertex keeps label -1 where the group cannot be nearest.
  WindowVtp(const PropagationMesh& mesh, const GeodesicOptions& options, const GroupLimits* limits = nullptr);

  /// Seeds the propagation from the sites (already validated; index = label,
  /// or labels[index] where given).
  void add_sites(const std::vector<SurfacePoint>& sites, std::span<const Index> labels = {});
  /// Runs the propagation to the end.
  void run();

  /// A vertex's distance: where not reached, where it started (the group's
  /// bound with limits, +inf without).
  double distance(Index v) const {
    if (label_plus_one_[v] != 0) return distance_[v];
    return limits_ != nullptr ? limits_->distance_bound[v] : kUnreached;
  }
  /// A vertex's nearest site, -1 where not reached.
  Index label(Index v) const { return label_plus_one_[v] - 1; }
  /// With limits, the vertices reached, in the order first reached: the
  /// others keep their start. (Empty without.)
  std::span<const Index> reached() const { return reached_; }
  /// Every vertex's distance and label, for the caller to keep.
  std::vector<double> distances() const;
  std::vector<Index> labels() const;
  const WindowStore& windows() const { return store_; }
  /// Moves the windows out, for the caller to keep when the rest goes.
  WindowStore take_windows() { return std::move(store_); }
  /// Per face: windows of different sites meet on its edges or vertices.
  std::vector<bool> valid_faces() const;
  const GeodesicStats& stats() const { return stats_; }
  /// Point sources (sites, and pseudo-sources on zero-area faces) lying in a
  /// face or on its edges, which queries inside that face must consider.
  const std::vector<FacePointSource>& point_sources() const { return point_sources_; }
  /// With limits: the edges whose windows RWR freed (with repeats).
  const std::vector<Index>& freed_edges() const { return freed_edges_; }

 private:
  /// kFaceWaits: a traversed face at the vertex waits for its key until one
  /// of its corners is reached (see push_face_key).
  enum VertexFlags : std::uint8_t { kPopped = 1, kEmitted = 2, kFaceWaits = 4 };
  static constexpr double kUnreached = std::numeric_limits<double>::infinity();
  enum FaceFlags : std::uint8_t { kTraversed = 1, kInactive = 2, kRedundant = 4, kKeyPushed = 8 };
  /// A face's inactivity key d_min(f) + |e_max(f)| (Proposition 3.1),
  /// rounded up to a float: a key no smaller only makes the face inactive
  /// no earlier, which is safe, and halves the queue (8 bytes an event).
  struct FaceEvent {
    float key;
    Index face;
    bool operator>(const FaceEvent& o) const { return key != o.key ? key > o.key : face > o.face; }
  };

  void add_vertex_site(Index vertex, Index site);
  void add_face_site(Index face, const Eigen::Vector3d& barycentric, Index site);
  /// Windows from a point source at `source` (in the face's planar layout
  /// `plane`) onto the face's edges other than local edge `skip_local_edge`.
  void emit_from_point_in_face(Index face, const FaceInPlane& plane, const Eigen::Vector2d& source, int skip_local_edge,
                               double sigma, Index site, int depth);
  /// A point source on local edge k of `face`, at abscissa x_face of the
  /// face's frame for that edge: windows into the face on the other side.
  void emit_across_edge(Index face, int k, double x_face, double sigma, Index site, int depth);
  /// Pseudo-source (or vertex site) v: windows on the edges opposite v.
  void emit_from_vertex(Index v, double sigma, Index site);

  /// Inserts a window on edge e (of the given length, from v0 to v1); its
  /// surviving pieces relax the edge's end points and are scheduled.
  /// `source` is the window's (the store's table has it too; passing it on
  /// saves looking it up in the hot path).
  void submit(Index e, double length, Index v0, Index v1, const Window& window, const WindowSource& source);
  void submit(Index e, const Window& window, const WindowSource& source);
  /// A window on e goes into the FIFO if the face it enters is traversed;
  /// otherwise it is on the wavefront and its edge's end points wait in the
  /// vertex queue.
  void schedule(Index e, Index v0, Index v1, const Window& window, double sigma, Index position);
  void enqueue_edge(Index e);
  void propagate(Index e, const Window& window);
  void drain_fifo();
  void expand(Index v);
  void relax(Index v, double d, Index site);
  void push_expand(Index v, double key);
  void push_face_key(Index face);
  bool pop_event(Event& event);
  double next_event_key() const;
  void remove_redundant_windows(double lower_bound);
  bool face_is_redundant(Index face) const;
  /// True unless limits are set and a site of another group may be nearer
  /// somewhere on the face.
  bool away_from_other_groups(Index face) const;
  void report_progress();

  const PropagationMesh& pm_;
  const GeodesicOptions& options_;
  const GroupLimits* limits_ = nullptr;
  GeodesicStats stats_;

  /// Per vertex, in zeroed pages: a group of sites makes only its part of
  /// the mesh resident, not the whole of both arrays. A vertex is reached
  /// once it has a label; until then distance_ holds nothing (distance()).
  ZeroedArray<double> distance_;
  ZeroedArray<Index> label_plus_one_;
  std::vector<Index> reached_;
  /// Per vertex: expanded; emitted windows as a pseudo-source (or vertex
  /// site) at its current distance.
  ZeroedArray<std::uint8_t> vertex_flags_;
  ZeroedArray<std::uint8_t> face_flags_;
  Index faces_traversed_ = 0;

  WindowStore store_;
  EventQueue events_;
  std::priority_queue<FaceEvent, std::vector<FaceEvent>, std::greater<>> face_events_;
  std::vector<Index> fifo_;  // edges with queued windows (marked in the store while they wait)
  std::size_t fifo_head_ = 0;
  std::vector<WindowStore::Piece> created_;  // scratch for WindowStore::insert
  /// The face the last propagated window entered, laid out (see propagate).
  struct EnteredFace {
    Index edge = -1;
    int side = 0, k = 0;
    std::array<double, 3> lengths{};
    EdgeLayout layout;
  };
  EnteredFace entered_face_;
  std::vector<Index> new_faces_;   // scratch for expand
  std::vector<Index> fan_;         // scratch: faces around a vertex (expand, relax)
  std::vector<Index> emit_faces_;  // scratch: faces around a pseudo-source (emit_from_vertex)
  std::int64_t window_bytes_limit_ = 0;
  std::int64_t peak_window_bytes_ = 0;
  std::int64_t steps_ = 0;
  std::vector<FacePointSource> point_sources_;
  std::vector<Index> freed_edges_;
};

}  // namespace geodual::voronoi::detail
