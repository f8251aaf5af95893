#pragma once
// What every sampling strategy needs to know about the mesh: which faces may
// carry a site, their areas grouped by connected component (for drawing
// faces by area), and the boundary loops. Plus the portable random number
// generator and the exact barycentric lattice all sites live on.

#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/random.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace geodual::remesh::detail {

/// Site barycentrics are multiples of 2^-32: integers that sum to 2^32 give
/// coordinates that are exact in double and sum to exactly 1 in any order.
inline constexpr std::uint64_t kLattice = std::uint64_t{1} << 32;
inline constexpr double kLatticeUnit = 0x1p-32;

/// geodual's seeded generator (xoshiro256**), with lattice draws.
class Rng : public Xoshiro256 {
 public:
  using Xoshiro256::Xoshiro256;
  /// Uniform integer in [1, 2^32 - 1].
  std::uint64_t lattice_interior();
};

/// The point of the face for lattice coordinates (a, b) in [1, 2^32 - 1]^2
/// of the unit square, folded onto the triangle; all barycentrics positive.
SurfacePoint point_in_face_from_square(Index face, std::uint64_t a, std::uint64_t b);

/// A uniform random point strictly inside the face (all three barycentrics
/// positive multiples of 2^-32, summing to 1), by the parallelogram fold.
SurfacePoint random_point_in_face(Index face, Rng& rng);

/// The point at parameter t in [0, 1] along the face's edge from corner
/// `corner` to corner + 1, t rounded to the lattice and kept at least 2^-20
/// away from both ends; the opposite corner's barycentric is exactly 0.
SurfacePoint point_on_face_edge(Index face, int corner, double t);

/// Splits `total` into integer parts proportional to `weights` (all > 0),
/// part i at least minimum[i] (total >= sum of the minimums): parts whose
/// share falls below their minimum are fixed there and the rest is shared
/// again; then largest remainders, ties to the lower index. Where part i
/// already holds held[i] (empty: nothing), the split is of the total with
/// what the parts hold, each part less what it holds: part i is about
/// lambda * weights[i] - held[i].
std::vector<std::int64_t> proportional_split(const std::vector<double>& weights,
                                             const std::vector<std::int64_t>& minimum, std::int64_t total,
                                             const std::vector<double>& held = {});

/// A boundary edge as the face that carries it: from corner `corner` to
/// corner + 1 of `face`.
struct BoundaryEdge {
  Index face = -1;
  int corner = 0;
  double length = 0;
  /// The walk runs it the other way, from corner + 1 to `corner` (faces
  /// oriented against their neighbours, a non-orientable surface, the second
  /// half of a figure eight).
  bool reversed = false;
};

struct BoundaryLoop {
  Index component = -1;
  /// The edges in walking order whose face has positive area (the others
  /// cannot carry a site); never empty.
  std::vector<BoundaryEdge> edges;
  double length = 0;  ///< sum of `edges`' lengths
  /// false for an open chain (a walk between two vertices with an odd number
  /// of boundary edges, on a broken mesh).
  bool closed = true;
};

struct SamplingSurface {
  const TriangleMesh* mesh = nullptr;
  /// Per face: its area; 0 for faces with a repeated corner and for faces
  /// the geodesic engine sees as flat (has_positive_area), which
  /// must carry no site.
  std::vector<double> face_area;
  /// Per face: its component, -1 for faces with a repeated corner (which
  /// take no part in any surface computation).
  std::vector<Index> face_component;
  Index num_components = 0;
  /// Faces with three distinct corners, by component (CSR, increasing face
  /// index within a component).
  std::vector<Index> component_face_begin;
  std::vector<Index> component_faces;
  /// Faces with positive area, by component (CSR), with the running sum of
  /// their areas within the component: the table random_face searches.
  std::vector<Index> component_area_face_begin;
  std::vector<Index> component_area_faces;
  std::vector<double> component_cumulative_area;
  /// Per component: total area of its faces.
  std::vector<double> component_area;
  /// Empty unless asked for; loops of components with positive area only.
  std::vector<BoundaryLoop> boundary_loops;

  std::span<const Index> faces_of(Index component) const {
    return {component_faces.data() + component_face_begin[component],
            component_faces.data() + component_face_begin[component + 1]};
  }
  /// A face of the component drawn with probability proportional to area.
  Index random_face(Index component, Rng& rng) const;
  /// `count` points spread evenly by area over the component: the i-th at
  /// running area (i + u) A / count (systematic sampling, u random), so that
  /// every face gets its expected share up to one point; inside a face, the
  /// R2 low-discrepancy sequence from a random start. Fewer gaps and clumps
  /// than independent points, still uniform on average.
  void stratified_points(Index component, std::int64_t count, Rng& rng, std::vector<SurfacePoint>& out) const;
};

SamplingSurface build_sampling_surface(const TriangleMesh& mesh, bool with_boundary_loops);
/// The same with the mesh's topology built already (RemeshSurface); the faces must be valid.
SamplingSurface build_sampling_surface(const TriangleMesh& mesh, const MeshTopology& topology,
                                       bool with_boundary_loops);

/// A site's position exactly as SurfacePoint::position computes it.
inline Eigen::Vector3d site_position(const TriangleMesh& mesh, const SurfacePoint& site) { return site.position(mesh); }

}  // namespace geodual::remesh::detail
