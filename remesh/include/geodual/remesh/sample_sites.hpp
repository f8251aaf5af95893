#pragma once
// Initial sites for the remesher: points on the surface drawn at random by
// area, as blue noise (Poisson disk), or by farthest point sampling, with
// sites placed along the boundary loops so that the dual keeps them.

#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/surface_point.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::remesh {

/// How interior sites are placed. s below is the hexagonal spacing of the
/// component's sites, s = sqrt(2 A / (sqrt(3) n)): the distance between
/// neighbours if n sites tiled area A in a perfect triangular lattice.
enum class SamplingStrategy {
  /// Uniform by area: each face with probability proportional to its area
  /// (running sums, binary search), then a uniform point inside it. The
  /// fastest (10^6 sites on 259K faces: about 0.5 s); clusters and gaps like
  /// any independent sample (for 2000 sites: nearest pair about 0.005 s,
  /// largest empty ball 1.6-1.7 s).
  random,
  /// Blue noise: weighted sample elimination (Yuksel 2015) of 5 n random
  /// candidates down to n, with 3D distance as the metric and the boundary
  /// sites as fixed neighbours. No hard guarantee, but on six meshes and a
  /// sphere the nearest pair of sites measures 0.62-0.65 s (the tests
  /// require >= 0.5 s); the largest empty ball 0.91-1.0 s.
  poisson,
  /// Farthest point sampling under an approximate geodesic metric: distance
  /// fields grown from the sites through a graph of mesh vertices, edges and
  /// 6 n + 32 evenly spread candidate points, the distance of a node to its
  /// site estimated by the straight line (or half the graph path, where that
  /// is longer, so that thin gaps are not jumped). Each new site is the
  /// candidate farthest from all sites so far. 99% of the sites have their
  /// nearest neighbour at >= 0.65 s, the single nearest pair 0.42-0.67 s (the
  /// tests require >= 0.45 s on a sphere); the largest empty ball
  /// 0.83-1.01 s, the best covering of the three.
  fps,
};

struct SamplingOptions {
  SamplingStrategy strategy = SamplingStrategy::random;
  /// Same mesh, count and options give the same sites, bit for bit: the
  /// random generator and every step are ours (no std:: distributions, no
  /// threads), so neither the standard library nor the machine changes them.
  std::uint64_t seed = 1;
  /// Put sites along every boundary loop (evenly by arc length, at least 3
  /// per loop) so that the dual mesh keeps the input's holes and borders.
  bool sites_on_boundary = true;
};

/// Exactly `count` sites, each SurfacePoint::in_face(face, u, v, w) with
/// u, v, w >= 0 multiples of 2^-32 summing to exactly 1, on a face with three
/// distinct corners and positive area, never at a vertex, no two at the same
/// position (as SurfacePoint::position computes it). Interior sites have
/// u, v, w > 0; boundary sites lie on a boundary edge, the opposite corner's
/// coordinate exactly 0. Boundary sites come first, then interior sites, each
/// group by connected component.
///
/// Connected components (faces with three distinct corners, connected through
/// shared vertices) with positive area share `count` in proportion to their
/// area, each getting at least max(4, 3 x its boundary loops). When `count`
/// is too small for that, every boundary loop still gets its 3 sites and the
/// rest tops components up to their minimum, largest area first (smaller
/// components may then get fewer than 4 sites, or none).
///
/// Boundary edges are the edges of exactly one face with three distinct
/// corners (edges of 3+ faces are not). With n sites on a component of area
/// A, the target spacing is the hexagonal s = sqrt(2 A / (sqrt(3) n)); a loop
/// of length L gets max(3, round(L / s)) sites, but all the loops of a
/// component together take at most n - 1 sites (never fewer than 3 each).
/// Sites go evenly by arc length along the parts of the loop whose face has
/// positive area, k of them at (j + 1/2) L / k; a loop with no such part
/// gets none. The exception is a slit, where the loop runs out and back
/// along itself for at least s / 2 (at most L / 6): its end gets a site
/// (just off the vertex) and the others go evenly between such ends, in
/// proportion to the stretches' lengths. Evenly spaced sites would land in
/// mirrored pairs at one point on its two sides, and the pair next to the
/// end would share a triangle of zero area. Loops are walks along the boundary edges: two loops touching at
/// a pinch vertex may be walked as one figure eight, and on broken meshes (a
/// vertex with an odd number of boundary edges) a walk may be an open chain.
///
/// The spacing figures of SamplingStrategy are without boundary sites: a
/// loop shorter than 3 s still gets 3 sites, closer together than s.
///
/// Cost, one thread, measured on igea.ply (268K faces) on a shared machine:
/// random 10^6 sites 0.5 s; poisson 10^5 1.5 s, 10^6 26 s (0.7 GB);
/// fps 10^5 2.4 s, 10^6 25 s (2.1 GB).
///
/// Throws geodual::UsageError when count < 4, count > 2^31 - 1, or count is
/// below 3 x the number of boundary loops (the message says how many are
/// needed); geodual::Error when the mesh has no face of positive area, a face
/// refers to a vertex that does not exist, or a face's corner is not finite.
std::vector<SurfacePoint> sample_sites(const TriangleMesh& mesh, std::int64_t count,
                                       const SamplingOptions& options = {});

/// Sites for a remesh, and how many were added to the count asked.
struct SampledSites {
  std::vector<SurfacePoint> sites;
  /// Sites beyond the count asked that the surface's topology needs, and
  /// why (empty when none were added).
  std::int64_t sites_added_for_topology = 0;
  std::string topology_reason;
  /// Boundary loops that got sites (0 without sites on the boundary).
  std::int64_t boundary_loops = 0;
};

/// sample_sites for a remesh, which must keep every piece and every hole:
/// where `count` is below what every component with area needs
/// (max(4, 3 x its boundary loops) each), the count is raised to exactly that
/// sum instead of throwing or leaving small components without sites; the
/// sites are then shared as sample_sites shares them. Throws as sample_sites
/// does otherwise.
SampledSites sample_sites_for_topology(const TriangleMesh& mesh, std::int64_t count,
                                       const SamplingOptions& options = {});

/// "random", "poisson", "fps" -> the strategy; anything else throws
/// geodual::UsageError naming the accepted values.
SamplingStrategy parse_sampling_strategy(std::string_view name);

/// The strategy's name, as parse_sampling_strategy accepts it.
std::string sampling_strategy_name(SamplingStrategy strategy);

}  // namespace geodual::remesh
