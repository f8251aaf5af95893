#pragma once
// Exact distance to each nearby site at any point of one face, or of one edge,
// rebuilt from the windows a GeodesicField keeps: the building block of the
// Voronoi diagram extraction.
//
// In the face's plane the windows on its edges are cones sigma + |p - s| seen
// through an interval of the edge (Surazhsky et al. 2005, §3). Outside its
// wedge, a window still bounds the distance from above by the path that bends
// at the nearer end of its interval; adding those two bends as unrestricted
// cones makes the per-site lower envelope continuous, and it stays exact: the
// shortest path to p enters the face through some window's interval, a corner
// or a site in the face.

#include "geodual/mesh/detail/index_hash_map.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <span>
#include <vector>

namespace geodual::voronoi::detail {

/// A face laid out in its plane from its intrinsic edge lengths: corner 0 at
/// the origin, corner 1 on the +x axis, corner 2 in the upper half plane, so
/// counter-clockwise is the face's orientation.
struct FaceLayout {
  std::array<Eigen::Vector2d, 3> corner;
  double area = 0;

  static FaceLayout of(const GeodesicField& field, Index face);
  /// Barycentric coordinates of a point of the plane (clamped to the face).
  Eigen::Vector3d barycentric(const Eigen::Vector2d& p) const;
  Eigen::Vector2d point(const Eigen::Vector3d& barycentric) const {
    return barycentric[0] * corner[0] + barycentric[1] * corner[1] + barycentric[2] * corner[2];
  }
};

/// sigma + |p - apex|, either everywhere or only for p inside the wedge that
/// opens from `apex` counter-clockwise from `ray0` to `ray1`.
struct DistanceCone {
  Eigen::Vector2d apex = Eigen::Vector2d::Zero();
  double sigma = 0;
  bool in_wedge_only = false;
  /// cross(ray0, ray1) > 0, kept with the rays; otherwise the apex lies on
  /// the line of the interval and the cone sees only the interval itself.
  bool wedge_opens = false;
  Eigen::Vector2d ray0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d ray1 = Eigen::Vector2d::Zero();

  void set_rays(const Eigen::Vector2d& from, const Eigen::Vector2d& to);
  bool sees(const Eigen::Vector2d& p) const;
  /// The value at p, whether or not the cone sees p.
  double value(const Eigen::Vector2d& p) const { return sigma + (p - apex).norm(); }
  /// An opening wedge's two half-planes, for q = p - apex: it sees p where both hold.
  bool after_ray0(const Eigen::Vector2d& q) const { return ray0.x() * q.y() - ray0.y() * q.x() >= 0; }
  bool before_ray1(const Eigen::Vector2d& q) const { return q.x() * ray1.y() - q.y() * ray1.x() >= 0; }
};

/// A cone with its site, as the nearest-site indexes keep them.
struct SiteCone {
  DistanceCone cone;
  Index site = -1;
};

/// The nearest site at one point among cones read one by one, by
/// ConeEnvelope::nearest_site's rule: the smallest value, ties to the
/// smaller site, among the cones that see the point. The order of reading is free.
struct NearestCone {
  Eigen::Vector2d at;
  double value = std::numeric_limits<double>::infinity();
  Index site = -1;
  void consider(const DistanceCone& cone, Index cone_site) {
    const double d = cone.value(at);
    if ((d < value || (d == value && cone_site < site)) && cone.sees(at)) value = d, site = cone_site;
  }
  void consider(const SiteCone& c) { consider(c.cone, c.site); }
};

/// The lower envelopes, one per site, of a set of cones in one plane. The
/// cones are kept grouped by site (a slot each, numbered in order of first
/// appearance), so a query about one or two sites reads only their cones.
class ConeEnvelope {
 public:
  void clear();
  void add(const Eigen::Vector2d& apex, double sigma, Index site);
  void add_wedge(const Eigen::Vector2d& apex, double sigma, Index site, const Eigen::Vector2d& end0,
                 const Eigen::Vector2d& end1);

  /// Adds the cones of `other`, moved by p -> ((p - origin) . x_axis, (p - origin) . y_axis)
  /// for orthonormal axes (a reflection when they are left-handed).
  void add_moved(const ConeEnvelope& other, const Eigen::Vector2d& origin, const Eigen::Vector2d& x_axis,
                 const Eigen::Vector2d& y_axis);

  int slot_count() const { return static_cast<int>(slot_site_.size()); }
  /// The cones of all slots.
  std::size_t cone_count() const;
  Index site(int slot) const { return slot_site_[slot]; }
  /// The slot of a site, or -1 if no cone of it reaches here.
  int slot_of(Index site) const;
  bool has_site(Index site) const { return slot_of(site) >= 0; }
  /// The cones of one slot, in the order they were added.
  std::span<const DistanceCone> cones(int slot) const { return slot_cones_[slot]; }

  /// Distance to one site at p (+inf if none of its cones sees p) and its
  /// gradient there.
  double distance(int slot, const Eigen::Vector2d& p, Eigen::Vector2d* gradient = nullptr) const;
  /// The nearest site at p; ties go to the smaller site index. -1 if none.
  Index nearest_site(const Eigen::Vector2d& p) const;
  /// distance(site a) - distance(site b) at p, 0 where both are unreachable.
  double difference(Index site_a, Index site_b, const Eigen::Vector2d& p) const;

 private:
  int slot_for(Index site);

  /// The cones of each slot in the order they were added (distance() gives
  /// a tie to the earlier cone). Buckets past slot_count() are spares kept
  /// empty with their capacity, so rebuilding an envelope does not allocate.
  std::vector<std::vector<DistanceCone>> slot_cones_;
  std::vector<Index> slot_site_;
  /// Beyond this many slots, a site's slot is looked up in slot_index_
  /// rather than by a scan (a face holding many sites has hundreds).
  static constexpr int kScannedSlots = 16;
  IndexHashMap<int> slot_index_;
};

/// Builds the envelopes valid inside `face` (laid out as `layout`): its
/// corners, the sites in it, and the windows entering it through its edges.
void build_face_envelope(const GeodesicField& field, const TriangleMesh& mesh, Index face, const FaceLayout& layout,
                         ConeEnvelope& envelope);

/// Builds the envelopes valid on edge `edge`, laid out along the x axis from
/// its end v0 at 0 to v1 at edge_length[edge] (SurfaceTopology::edge_vertices): the
/// windows on the edge and its end vertices; on a boundary edge, where the
/// engine keeps only some windows, also its face's envelope. `scratch` is
/// working space.
void build_edge_envelope(const GeodesicField& field, const TriangleMesh& mesh, Index edge, ConeEnvelope& envelope,
                         ConeEnvelope& scratch);

}  // namespace geodual::voronoi::detail
