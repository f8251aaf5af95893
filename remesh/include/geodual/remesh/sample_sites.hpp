#pragma once
// Initial sites for the remesher: points on the surface drawn at random by
// area, as blue noise (Poisson disk), or by farthest point sampling, with
// sites placed along the boundary loops so that the dual keeps them.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/remesh_surface.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual::remesh {

/// How interior sites are placed (docs/algorithms.md#sampling-the-sites).
enum class SamplingStrategy {
  random,   ///< uniform by area: the fastest, with the clusters and gaps of any independent sample
  poisson,  ///< blue noise: weighted sample elimination [Yuk15] of 5 n random candidates down to n
  fps,      ///< farthest point sampling under an approximate geodesic metric: the best covering
};

struct SamplingOptions {
  SamplingStrategy strategy = SamplingStrategy::poisson;
  /// The same mesh, count and options give the same sites, bit for bit, on every platform.
  std::uint64_t seed = 1;
  /// Sites along every boundary loop (at least 3 each), so that the dual keeps holes and borders.
  bool sites_on_boundary = true;
};

/// Exactly `count` sites: SurfacePoint::in_face with barycentric coordinates
/// that are multiples of 2^-32 summing to 1, on faces with positive area,
/// never at a vertex, no two at one position; boundary sites first (on a
/// boundary edge), then interior ones, each group by connected component.
/// Components share `count` in proportion to their area, each at least
/// max(4, 3 x its boundary loops) where `count` allows.
/// \throw geodual::UsageError when count < 4, count > 2^31 - 1 or count is
/// below 3 per boundary loop (saying how many are needed); geodual::Error
/// when no face has positive area, or for a bad index or coordinate.
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
SampledSites sample_sites_for_topology(const RemeshSurface& surface, std::int64_t count,
                                       const SamplingOptions& options = {});

/// How sample_sites_around shares its sites among the components that hold given ones.
enum class GivenSiteShare {
  /// Each given site stands for half a site of its component's area (a site
  /// on a crease has half a cell on either side): a component ringed by
  /// creases gets sites for the rest of its area, as dense as elsewhere.
  half_cell,
  /// The given sites stand for no area: the components share the sites by
  /// area alone, denser where creases ring a small component.
  none,
};

/// sample_sites_for_topology around sites the caller placed on boundary
/// loops (feature_sites: along sharp chains cut open): they come first, as
/// given (never moved, twins at one position allowed), the loops they lie on
/// get no other boundary sites, and a component holding one needs no minimum
/// of its own; `count` (>= 0) more sites are placed, shared as `given_share` says.
SampledSites sample_sites_around(const TriangleMesh& mesh, std::int64_t count,
                                 std::span<const SurfacePoint> boundary_sites, const SamplingOptions& options = {},
                                 GivenSiteShare given_share = GivenSiteShare::half_cell);
SampledSites sample_sites_around(const RemeshSurface& surface, std::int64_t count,
                                 std::span<const SurfacePoint> boundary_sites, const SamplingOptions& options = {},
                                 GivenSiteShare given_share = GivenSiteShare::half_cell);

/// Checks that every connected piece of `surface` (faces with three distinct
/// corners, joined through shared vertices) holds one of `sites` at least: a
/// piece without one would be left out of the remesh without a trace. For
/// sites not sampled here (a site file). \throw Error naming how many pieces
/// have none and the first of them.
void require_a_site_on_every_piece(const TriangleMesh& surface, std::span<const SurfacePoint> sites);
void require_a_site_on_every_piece(const RemeshSurface& surface, std::span<const SurfacePoint> sites);

/// "random", "poisson", "fps" -> the strategy; anything else throws
/// geodual::UsageError naming the accepted values.
SamplingStrategy parse_sampling_strategy(std::string_view name);

/// The strategy's name, as parse_sampling_strategy accepts it.
std::string sampling_strategy_name(SamplingStrategy strategy);

}  // namespace geodual::remesh
