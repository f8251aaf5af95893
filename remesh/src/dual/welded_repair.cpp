#include "geodual/remesh/welded_dual.hpp"

#include "dual/crack_fill.hpp"
#include "dual/fault_places.hpp"
#include "features/chain_points.hpp"

#include "geodual/mesh/detail/point_hash.hpp"
#include "geodual/mesh/detail/point_text.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace geodual::remesh {

using detail::site_key;
using detail::SiteKey;

namespace {

/// Chain points closer than this many spacings are one point (doubled_chain_points).
constexpr double kDoubledPoint = 0.2;

/// Per site, whether it doubles a point on a chain: it lies on a sharp edge
/// or a vertex of one, within `tolerance` of a corner or of a site there with
/// another key and a lower index (a twin shares its key and is no double).
/// The dual's repair keeps its points apart only on one piece, and the two
/// sheets of a cut are two: each may get a point a hair from the other's, or
/// from a chain site, which welded makes a triangle with a side of almost
/// nothing. Corners are never doubles.
std::vector<std::uint8_t> doubled_chain_points(const TriangleMesh& surface, const FeatureSet& features,
                                               const FeatureCut& cut, std::span<const SurfacePoint> sites,
                                               double tolerance) {
  std::vector<std::uint8_t> on_chain(static_cast<std::size_t>(surface.vertices.rows()), 0);
  for (const auto& [a, b] : features.sharp_edges) on_chain[a] = on_chain[b] = 1;
  std::vector<std::uint8_t> doubled(sites.size(), 0);
  PointHash<SiteKey> grid(tolerance);  // the chain points held, by key
  std::vector<SiteKey> keys(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) keys[i] = site_key(surface, cut, sites[i]);
  for (const bool corners : {true, false}) {
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const SiteKey& key = keys[i];
      if (key.lo < 0) continue;
      const bool corner =
          key.lo == key.hi && std::binary_search(features.corners.begin(), features.corners.end(), key.lo);
      const bool chain_point = key.lo == key.hi ? on_chain[key.lo] != 0 : features.is_sharp(key.lo, key.hi);
      if (corner != corners || !chain_point) continue;
      const Eigen::Vector3d x = sites[i].position(cut.mesh);
      if (!corner && grid.any_within(x, tolerance, [&](const SiteKey& other) { return !(other == key); })) {
        doubled[i] = 1;
        continue;
      }
      grid.insert(x, key);
    }
  }
  return doubled;
}

/// `sites` less those `marked`.
std::vector<SurfacePoint> sites_not_marked(std::span<const SurfacePoint> sites,
                                           const std::vector<std::uint8_t>& marked) {
  std::vector<SurfacePoint> kept;
  kept.reserve(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (!marked[i]) kept.push_back(sites[i]);
  }
  return kept;
}

/// The first piece of `surface` (cut along the features) that the welded
/// remesh does not keep: `what` describes it for an error message ("" when it
/// keeps them all), `sites` are where it went wrong. A piece is kept when its
/// sites are the vertices of one piece of the remesh, which holds no other
/// piece's sites and has the same Euler characteristic and boundary loops.
/// (Each piece of the cut is checked on its own before the weld, but only
/// those holding sites: a piece of the cut whose sites were all left out
/// would go missing unseen.)
struct PieceNotKept {
  std::string what;
  /// Indices of the sites that went astray: those of the piece away from the
  /// remesh piece most of them are on, or another piece's on that one (none
  /// where only the counts differ).
  std::vector<std::size_t> sites;
};
PieceNotKept first_piece_not_kept(const FeatureCut& cut, std::span<const SurfacePoint> sites,
                                  const WeldedDual& welded) {
  const TriangleMesh& surface = cut.mesh;  // the surface's faces, in order
  const SurfaceOutline& pieces = cut.surface;
  const MeshTopology remeshed = build_mesh_topology(welded.mesh);
  std::vector<std::uint8_t> has_area(pieces.components.size(), 0);
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Index piece = pieces.face_component[f];
    if (piece >= 0 && has_positive_area(surface, f)) has_area[piece] = 1;
  }
  // Per site, its piece of the surface and of the remesh (-1: none).
  std::vector<Index> piece_of(sites.size(), -1), made_of(sites.size(), -1);
  // Per piece of the surface, the piece of the remesh its sites are on (-1:
  // none, -2: several, or a site on none); per piece of the remesh, the
  // surface's piece whose sites it holds (-2: several).
  std::vector<Index> remeshed_of(pieces.components.size(), -1);
  std::vector<Index> surface_of(remeshed.components.size(), -1);
  std::vector<Index> first_vertex(pieces.components.size(), -1);
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const SurfacePoint& site = sites[s];
    const Index piece = site.kind == SurfacePoint::Kind::vertex
                            ? pieces.vertex_component[cut.original_vertex[static_cast<std::size_t>(site.element)]]
                            : pieces.face_component[site.element];
    const Index vertex = welded.vertex_of_site[s];
    const Index made = vertex >= 0 ? remeshed.vertex_component[vertex] : -1;
    piece_of[s] = piece;
    made_of[s] = made;
    if (piece < 0) continue;
    Index& mine = remeshed_of[piece];
    if (made < 0 || (mine >= 0 && mine != made)) {
      mine = -2;
    } else if (mine == -1) {
      mine = made;
    }
    if (made >= 0) surface_of[made] = surface_of[made] == -1 || surface_of[made] == piece ? piece : -2;
  }
  for (Index f = 0; f < surface.num_faces(); ++f) {
    const Index piece = pieces.face_component[f];
    if (piece >= 0 && first_vertex[piece] < 0) first_vertex[piece] = cut.original_vertex[surface.faces(f, 0)];
  }
  auto counts = [](const ComponentCounts& c) {
    return "Euler characteristic " + std::to_string(c.euler_characteristic()) + ", " +
           std::to_string(c.boundary_loops) + (c.boundary_loops == 1 ? " boundary loop" : " boundary loops");
  };
  for (std::size_t piece = 0; piece < pieces.components.size(); ++piece) {
    if (!has_area[piece]) continue;
    const ComponentCounts& expected = pieces.components[piece];
    const Index made = remeshed_of[piece];
    PieceNotKept lost;
    const auto piece_index = static_cast<Index>(piece);
    if (made == -1) {
      lost.what = "no vertex";
    } else if (made == -2) {
      lost.what = "its sites on several pieces, or on none";
      std::vector<std::int64_t> on(remeshed.components.size(), 0);
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (piece_of[s] == piece_index && made_of[s] >= 0) ++on[made_of[s]];
      }
      const auto most = static_cast<Index>(std::max_element(on.begin(), on.end()) - on.begin());
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (piece_of[s] == piece_index && made_of[s] != most) lost.sites.push_back(s);
      }
    } else if (surface_of[made] != piece_index) {
      lost.what = "a piece shared with another";
      for (std::size_t s = 0; s < sites.size(); ++s) {
        if (made_of[s] == made && piece_of[s] != piece_index) lost.sites.push_back(s);
      }
    } else if (remeshed.components[made].euler_characteristic() != expected.euler_characteristic() ||
               remeshed.components[made].boundary_loops != expected.boundary_loops) {
      lost.what = counts(remeshed.components[made]);
    } else {
      continue;
    }
    lost.what = "the piece with input vertex " + std::to_string(first_vertex[piece]) + " (" +
                std::to_string(expected.faces) + " faces, " + counts(expected) + "; in the remesh: " + lost.what + ")";
    return lost;
  }
  return {};
}

/// The positions of `sites` (on `mesh`) whose index is in `which`: for
/// DualRepairError's places.
template <typename Indices>
std::vector<Eigen::Vector3d> positions(const TriangleMesh& mesh, std::span<const SurfacePoint> sites,
                                       const Indices& which) {
  std::vector<Eigen::Vector3d> points;
  for (const auto i : which) points.push_back(sites[static_cast<std::size_t>(i)].position(mesh));
  return points;
}

/// The weld's failure: `what`, where (fault_places of `points` a `spacing`
/// apart) and the remedy.
DualRepairError weld_error(const std::string& what, std::span<const Eigen::Vector3d> points, double spacing,
                           const std::string& remedy = "") {
  std::vector<Eigen::Vector3d> places = fault_places(points, spacing);
  const std::string message = "the remesh " + what + fault_places_text(places) + remedy;
  return DualRepairError(message, std::move(places));
}

/// The figures welded_dual_with_repair adds up over its rounds.
struct WeldRounds {
  std::int64_t sites_added = 0, sites_left_out = 0;
  int repair_rounds = 0;  ///< of the rounds before the last
  int leave_out_rounds = 0;
  std::vector<std::string> repair_problems;
  double geodesic_seconds = 0, diagram_seconds = 0, dual_seconds = 0;

  /// A round's dual with repair.
  void add(const RepairedDual& round) {
    sites_added += round.sites_added;
    sites_left_out += round.sites_left_out;
    repair_problems.insert(repair_problems.end(), round.repair_problems.begin(), round.repair_problems.end());
    geodesic_seconds += round.geodesic_seconds;
    diagram_seconds += round.diagram_seconds;
    dual_seconds += round.dual_seconds;
  }

  /// The sums into the last round's result.
  void finish(RepairedDual& result) {
    result.sites_added = sites_added;
    result.sites_left_out = sites_left_out;
    result.repair_rounds += repair_rounds;
    result.repair_problems = std::move(repair_problems);
    result.geodesic_seconds = geodesic_seconds;
    result.diagram_seconds = diagram_seconds;
    result.dual_seconds = dual_seconds;
  }
};

constexpr const char* kRemedy = "; try more sites, or a larger sharp angle";

/// Where the repair doubled points on a chain (doubled_chain_points): the
/// sites of round `round`'s `result` without the doubles, and with the twins
/// of the points they doubled, which serve both sheets; none where nothing
/// is doubled. \throw DualRepairError where it is after options' max_rounds.
std::optional<std::vector<SurfacePoint>> sites_without_doubles(const TriangleMesh& surface, const FeatureSet& features,
                                                               const FeatureCut& cut, const RepairedDual& result,
                                                               double spacing, int round, int max_rounds,
                                                               WeldRounds& rounds) {
  const std::vector<std::uint8_t> doubled =
      doubled_chain_points(surface, features, cut, result.sites, kDoubledPoint * spacing);
  const auto count = std::count(doubled.begin(), doubled.end(), 1);
  if (count == 0) return std::nullopt;
  if (round >= max_rounds) {
    std::vector<std::size_t> doubles;
    for (std::size_t i = 0; i < doubled.size(); ++i) {
      if (doubled[i]) doubles.push_back(i);
    }
    throw weld_error("welded along the sharp features doubles " + std::to_string(count) +
                         " points on its creases after " + std::to_string(round) + " rounds",
                     positions(cut.mesh, result.sites, doubles), spacing);
  }
  std::vector<SurfacePoint> sites = sites_not_marked(result.sites, doubled);
  const std::vector<SurfacePoint> twins = missing_twins(surface, features, cut, sites);
  sites.insert(sites.end(), twins.begin(), twins.end());
  rounds.sites_added += static_cast<std::int64_t>(twins.size());
  rounds.sites_left_out += count;
  rounds.repair_rounds += result.repair_rounds + 1;
  rounds.repair_problems.push_back(std::to_string(count) +
                                   " repair sites doubling points on the sharp features (left out)");
  return sites;
}

/// \throw DualRepairError where the weld has edges of three or more triangles.
void require_manifold_weld(const WeldedDual& welded, double spacing) {
  if (welded.nonmanifold_edges == 0) return;
  const MeshTopology topology = build_mesh_topology(welded.mesh);
  std::vector<Eigen::Vector3d> ends;
  for (Index e = 0; e < topology.num_edges(); ++e) {
    if (!topology.is_manifold_edge(e)) ends.push_back(welded.mesh.vertices.row(topology.edge_vertices[e][0]));
  }
  throw weld_error("welded along the sharp features has " + std::to_string(welded.nonmanifold_edges) +
                       " edges with three or more triangles",
                   ends, spacing);
}

/// The sites of round `round`'s `result` without those whose triangles all
/// folded away in `welded`, or that would close a crack all but on another
/// site; none where there are none. Twice at most: where folds keep coming,
/// the weld will not close. \throw DualRepairError after that, or after
/// options' max_rounds.
std::optional<std::vector<SurfacePoint>> sites_without_unusable(const TriangleMesh& cut_mesh,
                                                                const RepairedDual& result, const WeldedDual& welded,
                                                                double spacing, int round, int max_rounds,
                                                                WeldRounds& rounds) {
  if (welded.unused_sites.empty() && welded.doubling_sites.empty()) return std::nullopt;
  const std::size_t left_out = welded.unused_sites.size() + welded.doubling_sites.size();
  if (round >= max_rounds || ++rounds.leave_out_rounds > 2) {
    std::vector<Eigen::Vector3d> points = positions(cut_mesh, result.sites, welded.unused_sites);
    const std::vector<Eigen::Vector3d> doubling = positions(cut_mesh, result.sites, welded.doubling_sites);
    points.insert(points.end(), doubling.begin(), doubling.end());
    throw weld_error("welded along the sharp features leaves " + std::to_string(left_out) +
                         " sites in no triangle or on another after " + std::to_string(round) + " rounds",
                     points, spacing);
  }
  std::vector<std::uint8_t> unused(result.sites.size(), 0);
  for (const std::size_t site : welded.unused_sites) unused[site] = 1;
  for (const std::size_t site : welded.doubling_sites) unused[site] = 1;
  rounds.sites_left_out += static_cast<std::int64_t>(left_out);
  rounds.repair_rounds += result.repair_rounds + 1;
  if (!welded.unused_sites.empty()) {
    rounds.repair_problems.push_back(std::to_string(welded.unused_sites.size()) +
                                     " sites in no triangle once welded (left out)");
  }
  if (!welded.doubling_sites.empty()) {
    rounds.repair_problems.push_back(std::to_string(welded.doubling_sites.size()) +
                                     " sites that would close a crack all but on another site (left out)");
  }
  return sites_not_marked(result.sites, unused);
}

/// The weld as the remesh, in `result`: every triangle of positive area
/// (each piece's dual has only such; welded, three sites on one straight
/// stretch of a chain could still make one flat) and every piece of the
/// surface kept. \throw DualRepairError where either fails.
void take_weld(RepairedDual& result, WeldedDual& welded, const FeatureCut& cut, double spacing) {
  for (Index f = 0; f < welded.mesh.num_faces(); ++f) {
    if (has_positive_area(welded.mesh, f)) continue;
    const Eigen::Vector3d corner = welded.mesh.vertices.row(welded.mesh.faces(f, 0));
    throw DualRepairError(
        "the remesh welded along the sharp features has a triangle of zero area, at " + point_text(corner), {corner});
  }
  if (const PieceNotKept lost = first_piece_not_kept(cut, result.sites, welded); !lost.what.empty()) {
    throw weld_error("welded along the sharp features does not keep " + lost.what,
                     positions(cut.mesh, std::span<const SurfacePoint>(result.sites), lost.sites), spacing, kRemedy);
  }
  result.mesh = std::move(welded.mesh);
  result.vertex_of_site = std::move(welded.vertex_of_site);
}

/// The last resort, after round `round`: the weld's cracks are holes of a
/// few edges on the sites as they are; closed with triangles on their
/// vertices, the weld is a remesh of the surface, the connectivity there not
/// the dual's. \throw DualRepairError where they do not close.
void close_cracks_or_fail(RepairedDual& result, WeldedDual& welded, const FeatureCut& cut, double spacing, int round,
                          WeldRounds& rounds) {
  if (const std::optional<CrackFill> fill = close_cracks(welded.mesh, welded.crack_vertices)) {
    take_weld(result, welded, cut, spacing);
    result.cracks_closed = fill->holes;
    result.crack_triangles = fill->triangles;
    rounds.repair_problems.push_back(std::to_string(welded.cracked_edges) +
                                     " edges of the welded remesh leaving the sharp features after " +
                                     std::to_string(round) + " rounds, closed with " + std::to_string(fill->triangles) +
                                     " triangles on their vertices");
    return;
  }
  std::vector<Eigen::Vector3d> ends;
  for (const Index v : welded.crack_vertices) ends.push_back(welded.mesh.vertices.row(v));
  throw weld_error("does not close along the sharp features after " + std::to_string(round) +
                       " rounds: " + std::to_string(welded.cracked_edges) +
                       " edges of its boundary leave the surface's creases and boundary",
                   ends, spacing, kRemedy);
}

}  // namespace

RepairedDual welded_dual_with_repair(const voronoi::GeodesicSurface& cut_surface, const TriangleMesh& surface,
                                     const FeatureSet& features, const FeatureCut& cut, std::vector<SurfacePoint> sites,
                                     voronoi::VoronoiDiagram diagram, const RepairOptions& options) {
  RepairedDual result;
  WeldRounds rounds;
  // The next round's diagram, of `sites`.
  const auto recompute = [&] {
    diagram = voronoi::compute_voronoi(cut_surface, sites, options.voronoi);
    rounds.geodesic_seconds += diagram.stats.geodesic_seconds;
    rounds.diagram_seconds += diagram.stats.extraction_seconds;
  };
  for (int round = 0;; ++round) {
    RepairOptions within = options;  // with the sites still allowed
    if (options.max_sites_added > 0) {
      within.max_sites_added = std::max<std::int64_t>(1, options.max_sites_added - rounds.sites_added);
    }
    result = dual_with_repair(cut_surface, std::move(sites), std::move(diagram), within);
    rounds.add(result);
    // Points the repair doubled on a chain go, the points they doubled get
    // their twins, and the diagram is computed again.
    const double spacing = result.diagram.mean_spacing();
    if (std::optional<std::vector<SurfacePoint>> next =
            sites_without_doubles(surface, features, cut, result, spacing, round, options.max_rounds, rounds)) {
      sites = std::move(*next);
      recompute();
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    WeldedDual welded = weld_along_features(surface, features, cut, result.mesh, result.sites);
    require_manifold_weld(welded, spacing);
    if (std::optional<std::vector<SurfacePoint>> next =
            sites_without_unusable(cut.mesh, result, welded, spacing, round, options.max_rounds, rounds)) {
      sites = std::move(*next);
      rounds.dual_seconds += seconds();
      recompute();
      continue;
    }
    std::vector<std::pair<std::size_t, SurfacePoint>> moved_from;  // to undo the moves
    for (const auto& [site, point] : welded.site_moves) {
      moved_from.emplace_back(site, result.sites[site]);
      result.sites[site] = point;
    }
    const std::vector<SurfacePoint> more = missing_twins(surface, features, cut, result.sites);
    if (welded.cracked_edges == 0 && more.empty()) {
      take_weld(result, welded, cut, spacing);
      break;
    }
    rounds.dual_seconds += seconds();
    if (round >= options.max_rounds || (more.empty() && welded.site_moves.empty())) {
      for (const auto& [site, point] : moved_from) result.sites[site] = point;
      close_cracks_or_fail(result, welded, cut, spacing, round, rounds);
      break;
    }
    // The sites inside that reached a boundary moved onto it, the twins of
    // the sites on chains added, and the diagram computed again.
    sites = std::move(result.sites);
    rounds.sites_added += static_cast<std::int64_t>(more.size());
    rounds.repair_rounds += result.repair_rounds + 1;
    if (options.max_sites_added > 0 && rounds.sites_added > options.max_sites_added) {
      std::vector<Eigen::Vector3d> twins;
      for (const SurfacePoint& twin : more) twins.push_back(twin.position(cut.mesh));
      throw weld_error("welded along the sharp features would add " + std::to_string(rounds.sites_added) +
                           " sites in " + std::to_string(round + 1) + " rounds, more than the " +
                           std::to_string(options.max_sites_added) + " allowed: its creases are finer than the spacing",
                       twins, spacing, kRemedy);
    }
    if (!more.empty()) {
      rounds.repair_problems.push_back(std::to_string(more.size()) +
                                       " points of the sharp features without their twin sites");
    }
    if (welded.cracked_edges > 0) {
      rounds.repair_problems.push_back(std::to_string(welded.cracked_edges) +
                                       " edges of the welded remesh leaving the sharp features");
    }
    sites.insert(sites.end(), more.begin(), more.end());
    recompute();
  }
  rounds.finish(result);
  return result;
}

}  // namespace geodual::remesh
