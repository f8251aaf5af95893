#include "geodual/remesh/dual_delaunay.hpp"

#include "dual/boundary_triangles.hpp"
#include "geodual/remesh/manifold_cut.hpp"

#include "geodual/mesh/detail/point_hash.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace geodual::remesh {
namespace {

/// Euler characteristic and boundary loops of each vertex-connected component
/// of a triangle soup, keyed by the component's smallest vertex. Faces with a
/// repeated index are skipped. Boundary loops are the connected pieces of the
/// graph of edges with one face (loops that touch at a vertex count once, as
/// in MeshReport and MeshTopology). `for_each_edge(visit)` calls
/// visit(u, v, boundary) once for every edge of the mesh.
template <class ForEachEdge>
std::map<Index, ComponentCounts> topology_by_component(const TriangleMesh& mesh, UnionFind& components,
                                                       ForEachEdge for_each_edge) {
  const Index n = mesh.num_vertices();
  std::vector<std::uint8_t> used(n, 0);
  for (Index f = 0; f < mesh.faces.rows(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    components.unite(a, b);
    components.unite(b, c);
    used[a] = used[b] = used[c] = 1;
  }
  std::map<Index, ComponentCounts> result;
  for (Index f = 0; f < mesh.faces.rows(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    ++result[components.find(mesh.faces(f, 0))].faces;
  }
  for (Index v = 0; v < n; ++v) {
    if (used[v]) ++result[components.find(v)].vertices;
  }
  UnionFind boundary(static_cast<std::size_t>(n));
  std::vector<std::uint8_t> on_boundary(n, 0);
  for_each_edge([&](Index u, Index v, bool is_boundary) {
    ++result[components.find(u)].edges;
    if (!is_boundary) return;
    boundary.unite(u, v);
    on_boundary[u] = on_boundary[v] = 1;
  });
  for (Index v = 0; v < n; ++v) {
    if (on_boundary[v] && boundary.find(v) == v) ++result[components.find(v)].boundary_loops;
  }
  return result;
}

/// Calls visit(u, v, boundary) for each run of equal vertex pairs in
/// `pairs` (sorted here): one edge, on the boundary if the pair is alone.
template <class Visit>
void visit_pair_runs(std::vector<std::array<Index, 2>>& pairs, Visit&& visit) {
  std::sort(pairs.begin(), pairs.end());
  for (std::size_t i = 0; i < pairs.size();) {
    std::size_t j = i;
    while (j < pairs.size() && pairs[j] == pairs[i]) ++j;
    visit(pairs[i][0], pairs[i][1], j - i == 1);
    i = j;
  }
}

/// The edges of the surface the diagram lies on, from the field's edge table
/// (a large input's half-edges need not be sorted again): an edge with two
/// faces is one edge there; an edge with one face, or three or more, is one
/// boundary edge per face, told apart here by how many share its ends.
std::map<Index, ComponentCounts> field_topology(const TriangleMesh& mesh, const voronoi::GeodesicField& field,
                                                UnionFind& components) {
  return topology_by_component(mesh, components, [&](auto&& visit) {
    std::vector<std::array<Index, 2>> split;
    for (std::size_t e = 0; e < field.edge_faces.size(); ++e) {
      const auto [u, v] = field.edge_vertices(mesh, static_cast<Index>(e));
      if (field.edge_faces[e][1] >= 0) {
        visit(u, v, false);
      } else {
        split.push_back({std::min(u, v), std::max(u, v)});
      }
    }
    visit_pair_runs(split, visit);
  });
}

/// Per face of the surface the field lies on: whether to reverse it so that
/// faces joined by an edge use it once each way (a consistent orientation),
/// taking in each connected piece the orientation most of its faces have.
/// In a piece that cannot be oriented (a Moebius band) some pairs stay at odds.
/// Each piece is walked breadth-first, and walked again to flip it where
/// most of it was reversed: the queue holds only the walk's front, never a
/// whole piece (a scan's millions of faces).
std::vector<std::uint8_t> faces_to_reverse(const TriangleMesh& mesh, const voronoi::GeodesicField& field) {
  constexpr std::uint8_t kReverse = 1, kSeen = 2, kFlipped = 4;
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  std::vector<std::uint8_t> state(static_cast<std::size_t>(num_faces), 0);
  auto forward = [&](Index face, int side) {
    return mesh.faces(face, side) == field.edge_vertices(mesh, field.face_edges[face][side])[0];
  };
  // Calls visit(face, side, other, other_side) for each neighbour across an
  // edge that `mark` is not yet set on, setting it.
  std::deque<Index> front;
  auto walk = [&](Index start, std::uint8_t mark, auto&& visit) {
    state[static_cast<std::size_t>(start)] |= mark;
    front.assign(1, start);
    while (!front.empty()) {
      const Index face = front.front();
      front.pop_front();
      for (int side = 0; side < 3; ++side) {
        const Index edge = field.face_edges[face][side];
        if (edge < 0) continue;
        const auto [f0, f1] = field.edge_faces[edge];
        const Index other = f0 == face ? f1 : f0;
        if (other < 0 || other == face || (state[static_cast<std::size_t>(other)] & mark) != 0) continue;
        const int other_side = field.topology->side_of(other, edge);
        state[static_cast<std::size_t>(other)] |= mark;
        visit(face, side, other, other_side);
        front.push_back(other);
      }
    }
  };
  for (Index start = 0; start < num_faces; ++start) {
    if ((state[static_cast<std::size_t>(start)] & kSeen) != 0 || has_repeated_corner(mesh, start)) continue;
    std::size_t faces = 1, reversed = 0;
    walk(start, kSeen, [&](Index face, int side, Index other, int other_side) {
      // Consistent when the two run along the edge in opposite directions.
      const bool reverse_face = (state[static_cast<std::size_t>(face)] & kReverse) != 0;
      if ((forward(face, side) != reverse_face) == forward(other, other_side)) {
        state[static_cast<std::size_t>(other)] |= kReverse;
        ++reversed;
      }
      ++faces;
    });
    if (2 * reversed > faces) {
      state[static_cast<std::size_t>(start)] ^= kReverse;
      walk(start, kFlipped, [&](Index, int, Index other, int) { state[static_cast<std::size_t>(other)] ^= kReverse; });
    }
  }
  for (std::uint8_t& face : state) face &= kReverse;
  return state;
}

Index vertex_of(const TriangleMesh& mesh, const SurfacePoint& p) {
  return p.kind == SurfacePoint::Kind::vertex ? p.element : mesh.faces(p.element, 0);
}

/// Per vertex: whether it lies on the boundary (an edge with one face, or
/// three or more) with its faces' angles there summing to less than a right
/// angle.
std::vector<std::uint8_t> sharp_boundary_corners(const TriangleMesh& mesh, const voronoi::GeodesicField& field) {
  std::vector<std::uint8_t> on_boundary(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (std::size_t e = 0; e < field.edge_faces.size(); ++e) {
    if (field.edge_faces[e][1] >= 0) continue;
    const auto [u, v] = field.edge_vertices(mesh, static_cast<Index>(e));
    on_boundary[u] = on_boundary[v] = 1;
  }
  std::vector<double> angle(static_cast<std::size_t>(mesh.num_vertices()), 0.0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.faces(f, c);
      if (!on_boundary[v]) continue;
      const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, (c + 1) % 3)) - mesh.vertices.row(v);
      const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, (c + 2) % 3)) - mesh.vertices.row(v);
      angle[v] += std::atan2(a.cross(b).norm(), a.dot(b));
    }
  }
  std::vector<std::uint8_t> sharp(on_boundary.size(), 0);
  for (std::size_t v = 0; v < sharp.size(); ++v) sharp[v] = on_boundary[v] && angle[v] < 0.5 * std::numbers::pi;
  return sharp;
}

/// How a site whose cell fails a check is repaired (the strongest one found
/// for it counts).
enum class SiteRepair : std::uint8_t {
  none,
  farthest_point,    ///< a non-manifold, duplicate or zero-area triangle at it
  each_fan,          ///< its triangles form several fans
  boundary_corners,  ///< no Voronoi vertex: its cell meets others only along arcs to the mesh boundary
};

/// Where the checks of a dual failed.
struct Faults {
  std::vector<SiteRepair> site;                ///< per site
  std::vector<std::array<Index, 2>> fan_tips;  ///< {site, Voronoi vertex}: each fan's farthest, for each_fan
  std::vector<Index> split_pairs;              ///< into diagram.adjacency: pairs meeting along several arcs
  std::vector<Index> closed_arcs;              ///< into diagram.arcs
  std::vector<Index> mismatched;               ///< input components (smallest vertex) whose topology differs
  std::vector<std::uint8_t> left_out;          ///< per site, 1 if dropped (redundant_sites)
  std::vector<Index> component_of_site;        ///< per site, its input component
  std::map<Index, std::vector<Index>> sites_of_component;

  /// `repair` for site `s` (-1: none), where it is stronger than the one it has.
  void mark(Index s, SiteRepair repair) {
    if (s >= 0) site[s] = std::max(site[s], repair);
  }
};

/// Candidate points for new sites, in the order found.
struct RepairPoints {
  std::vector<SurfacePoint> points;
  /// Per point, how far it keeps other repair points at most
  /// (points_kept_apart); infinity: a quarter of the sites' mean spacing.
  std::vector<double> apart_at_most;

  void add(const SurfacePoint& p, double apart) {
    points.push_back(p);
    apart_at_most.push_back(apart);
  }
};

/// The distance of the diagram's point `point` from its nearest site.
double point_distance(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram, Index point) {
  return voronoi::query(diagram.field, input, diagram.point_locations[point]).distance;
}

/// The diagonal of the box round all of `input`'s vertices (0 without any).
double vertex_box_diagonal(const TriangleMesh& input) {
  return input.vertices.rows() > 0 ? (input.vertices.colwise().maxCoeff() - input.vertices.colwise().minCoeff()).norm()
                                   : 0.0;
}

/// Points this close are one point here (the engine rejects two sites at one point).
double same_point_distance(const TriangleMesh& input) { return std::max(1e-9 * vertex_box_diagonal(input), 1e-300); }

/// Repair points between cells (split pairs and closed arcs of `faults`)
/// into `out`; returns per site whether it was repaired so.
std::vector<std::uint8_t> repair_between_cells(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                                               const Faults& faults, double same_point, RepairPoints& out) {
  const voronoi::GeodesicField& field = diagram.field;
  const auto num_sites = static_cast<Index>(field.sites.size());
  // Between cells. Two cells meeting along several arcs wrap a tube or a
  // spire thinner than the spacing: a site halfway along each arc. A closed
  // boundary (a cell enclosed by another) girdles one: one site on it would
  // only stack another band of cells there, so three go round it, a third
  // of its length apart, and cells meet at Voronoi vertices across it. There
  // the new sites must come closer than the spacing: they keep apart by half
  // their distance to the sites (a sixth of the loop). A loop too short for
  // three distinct points is a cell of no size at a point (a corner's site on
  // a piece that only touches it there), which a site beside it would only
  // make a sliver with: none.
  std::vector<std::uint8_t> repaired_between(static_cast<std::size_t>(num_sites), 0);
  for (const Index p : faults.split_pairs) {
    const voronoi::CellAdjacency& pair = diagram.adjacency[p];
    for (const voronoi::VoronoiArc& arc : diagram.arcs) {
      if (std::min(arc.left_site, arc.right_site) != pair.site_a ||
          std::max(arc.left_site, arc.right_site) != pair.site_b) {
        continue;
      }
      const SurfacePoint& halfway = diagram.point_locations[(arc.point_begin + arc.point_end) / 2];
      out.add(halfway, 0.5 * (halfway.position(input) - field.sites[arc.left_site].position(input)).norm());
    }
    repaired_between[pair.site_a] = repaired_between[pair.site_b] = 1;
  }
  for (const Index a : faults.closed_arcs) {
    const voronoi::VoronoiArc& arc = diagram.arcs[a];
    repaired_between[arc.left_site] = repaired_between[arc.right_site] = 1;
    const auto line = diagram.polyline(arc);
    double length = 0;
    for (std::size_t i = 0; i < line.size(); ++i) length += (line[(i + 1) % line.size()] - line[i]).norm();
    if (length <= 3 * same_point) continue;
    double walked = 0;
    int placed = 0;
    for (std::size_t i = 0; i < line.size() && placed < 3; ++i) {
      if (walked >= placed * length / 3) {
        out.add(diagram.point_locations[arc.point_begin + static_cast<Index>(i)], length / 6);
        ++placed;
      }
      walked += (line[(i + 1) % line.size()] - line[i]).norm();
    }
  }
  return repaired_between;
}

/// Where a piece's topology differs without a local fault to explain it.
struct TopologyRepairs {
  std::vector<std::pair<SurfacePoint, double>> crossings;  ///< points across strips, each with how far apart it keeps
  std::vector<Index> largest_cells;                        ///< sites to refine at their farthest points
};

/// The repairs of the pieces whose topology differs (faults.mismatched);
/// `holds_sharp_corner` and `repaired_between` per site.
TopologyRepairs topology_repairs(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                                 const Faults& faults, std::span<const std::uint8_t> holds_sharp_corner,
                                 std::span<const std::uint8_t> repaired_between) {
  const voronoi::GeodesicField& field = diagram.field;
  auto distance_at = [&](Index point) { return point_distance(input, diagram, point); };
  // Pieces whose topology differs. Local faults explain most (a faulty
  // site, cells meeting along several arcs or enclosed, a site left out):
  // they are repaired where they are. Besides them,
  // an arc from the mesh boundary to the mesh boundary crosses a strip
  // narrower than the spacing (between two holes, a hole and the border,
  // the sides of a slot), which the dual leaves out, merging holes or
  // cutting the piece: a site at its end farther from its sites, where no
  // site holds that stretch of boundary; not across a sharp corner of one
  // loop, where it would only make the next cell cut off there (see
  // redundant_sites). Where there is neither, refine where cells are
  // largest (a handle or hole inside one), at their farthest points.
  std::vector<std::pair<SurfacePoint, double>> crossings;
  std::vector<std::uint8_t> crossed(faults.mismatched.size(), 0);
  UnionFind loops(faults.mismatched.empty() ? 0 : static_cast<std::size_t>(input.num_vertices()));
  std::vector<std::uint8_t> on_boundary(faults.mismatched.empty() ? 0 : static_cast<std::size_t>(input.num_vertices()),
                                        0);
  for (std::size_t e = 0; e < field.edge_faces.size() && !faults.mismatched.empty(); ++e) {
    if (field.edge_faces[e][1] >= 0) continue;
    const auto [u, v] = field.edge_vertices(input, static_cast<Index>(e));
    loops.unite(u, v);
    on_boundary[u] = on_boundary[v] = 1;
  }
  // The boundary loop (its smallest vertex) through a point on the mesh boundary.
  auto loop_of = [&](const SurfacePoint& p) {
    if (p.kind == SurfacePoint::Kind::vertex) return on_boundary[p.element] ? loops.find(p.element) : Index{-1};
    Index best = -1;
    for (int c = 0; c < 3; ++c) {
      const Index v = input.faces(p.element, c);
      if (on_boundary[v] && (best < 0 || p.barycentric[c] > p.barycentric[best])) best = c;
    }
    return best < 0 ? Index{-1} : loops.find(input.faces(p.element, best));
  };
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    if (faults.mismatched.empty() || arc.closed || arc.start_vertex >= 0 || arc.end_vertex >= 0 ||
        arc.point_end <= arc.point_begin) {
      continue;
    }
    const Index component = faults.component_of_site[arc.left_site];
    const auto it = std::lower_bound(faults.mismatched.begin(), faults.mismatched.end(), component);
    if (it == faults.mismatched.end() || *it != component) continue;
    if ((holds_sharp_corner[arc.left_site] || holds_sharp_corner[arc.right_site]) &&
        loop_of(diagram.point_locations[arc.point_begin]) == loop_of(diagram.point_locations[arc.point_end - 1])) {
      continue;
    }
    const double first = distance_at(arc.point_begin), last = distance_at(arc.point_end - 1);
    crossings.emplace_back(diagram.point_locations[last > first ? arc.point_end - 1 : arc.point_begin],
                           0.5 * std::max(first, last));
    crossed[static_cast<std::size_t>(it - faults.mismatched.begin())] = 1;
  }
  std::vector<Index> largest_cells;
  for (std::size_t i = 0; i < faults.mismatched.size(); ++i) {
    const std::vector<Index>& sites = faults.sites_of_component.at(faults.mismatched[i]);
    if (crossed[i] || std::any_of(sites.begin(), sites.end(), [&](Index s) {
          return faults.site[s] != SiteRepair::none || repaired_between[s] || faults.left_out[s];
        })) {
      continue;
    }
    std::vector<std::pair<double, Index>> by_area;
    for (const Index s : sites) by_area.emplace_back(-diagram.cell_area[s], s);
    std::sort(by_area.begin(), by_area.end());
    const std::size_t count = std::max<std::size_t>(1, sites.size() / 20);
    for (std::size_t k = 0; k < count && k < by_area.size(); ++k) largest_cells.push_back(by_area[k].second);
  }
  return {std::move(crossings), std::move(largest_cells)};
}

/// Per site, where farthest-point refinement may put a new site.
struct FarthestPoints {
  std::vector<Index> vertex;          ///< its cell's farthest mesh vertex (-1: none)
  std::vector<Index> voronoi_vertex;  ///< its cell's farthest Voronoi vertex (-1: none)
  /// Per refined site, the ends of its arcs on the mesh boundary (indices
  /// into the diagram's points), with their distances.
  std::vector<std::vector<std::pair<double, Index>>> boundary_ends;
};

// At sites, but for those repaired between cells (their split or enclosed
// cell is the cause, and a point beside those repairs would crowd them):
// farthest-point refinement, each new site at the point of the cell
// farthest from its site, so at least that far from every site. That
// point is the cell's farthest mesh vertex, or where the cell holds none
// beyond the site (sites denser than the mesh's vertices) the farthest of
// its Voronoi vertices and of the ends of its arcs on the mesh boundary.
// A boundary corner sharper than a right angle is no place for a site:
// its cell is cut off by a single arc (no Voronoi vertex) unless the
// sites on either side are almost equally far, and each repair there would
// only put the next site closer to the tip.
FarthestPoints farthest_points(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                               std::span<const std::uint8_t> refined, std::span<const std::uint8_t> sharp) {
  const voronoi::GeodesicField& field = diagram.field;
  const auto num_sites = static_cast<Index>(field.sites.size());
  FarthestPoints result;
  std::vector<Index>& farthest_vertex = result.vertex;
  std::vector<Index>& farthest_voronoi_vertex = result.voronoi_vertex;
  std::vector<std::vector<std::pair<double, Index>>>& boundary_ends = result.boundary_ends;
  auto distance_at = [&](Index point) { return point_distance(input, diagram, point); };
  farthest_vertex.assign(static_cast<std::size_t>(num_sites), -1);
  for (Index v = 0; v < static_cast<Index>(field.distance.size()); ++v) {
    const Index s = field.nearest_site[v];
    if (s < 0 || sharp[v] || !refined[s]) continue;
    if (farthest_vertex[s] < 0 || field.distance[v] > field.distance[farthest_vertex[s]]) farthest_vertex[s] = v;
  }
  farthest_voronoi_vertex.assign(static_cast<std::size_t>(num_sites), -1);
  for (std::size_t v = 0; v < diagram.vertices.size(); ++v) {
    const double distance = diagram.vertices[v].distance;
    for (const Index s : diagram.sites_of(diagram.vertices[v])) {
      Index& farthest = farthest_voronoi_vertex[s];
      if (farthest < 0 || distance > diagram.vertices[farthest].distance) farthest = static_cast<Index>(v);
    }
  }
  boundary_ends.resize(static_cast<std::size_t>(num_sites));
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    if (arc.closed || arc.point_end <= arc.point_begin) continue;
    const bool left = refined[arc.left_site] != 0;
    const bool right = refined[arc.right_site] != 0;
    if (!left && !right) continue;
    for (const auto& [open, point] :
         {std::pair{arc.start_vertex < 0, arc.point_begin}, std::pair{arc.end_vertex < 0, arc.point_end - 1}}) {
      if (!open) continue;
      const double distance = distance_at(point);
      if (left) boundary_ends[arc.left_site].emplace_back(distance, point);
      if (right) boundary_ends[arc.right_site].emplace_back(distance, point);
    }
  }
  return result;
}

/// The point of `site`'s cell farthest from it, into `out`: its farthest
/// mesh vertex, else the farther of its farthest Voronoi vertex and of the
/// ends of its arcs on the mesh boundary.
void add_farthest_point(const voronoi::VoronoiDiagram& diagram, const FarthestPoints& farthest, Index site,
                        RepairPoints& out) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  if (farthest.vertex[site] >= 0 && diagram.field.distance[farthest.vertex[site]] > 0) {
    out.add(SurfacePoint::at_vertex(farthest.vertex[site]), infinity);
    return;
  }
  const Index voronoi_vertex = farthest.voronoi_vertex[site];
  const auto& ends = farthest.boundary_ends[site];
  const auto end = std::max_element(ends.begin(), ends.end());
  if (end != ends.end() && (voronoi_vertex < 0 || end->first > diagram.vertices[voronoi_vertex].distance)) {
    out.add(diagram.point_locations[end->second], infinity);
  } else if (voronoi_vertex >= 0) {
    out.add(diagram.vertices[voronoi_vertex].location, infinity);
  }
}

// The points kept: apart from the sites (the engine rejects two sites at
// one point; points 1e-9 of the diagonal apart are one point here), and
// from each other by a quarter of the sites' mean spacing (two arcs of one
// problem often end side by side, and two sites there would make a
// sliver) or the smaller of their own separations. Only points on one
// piece keep apart; a point where a site already is on another sheet
// (vertices cut apart, the two sides of a cut, pieces that touch) moves a
// step into its face instead. "Where a site is" reaches 1e-4 of that
// quarter spacing: a boundary site sits 2^-20 of its edge off a mesh
// vertex, and a point at the vertex would make an edge of that length.
std::vector<SurfacePoint> points_kept_apart(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                                            const RepairPoints& candidates, UnionFind& components, double same_point) {
  const voronoi::GeodesicField& field = diagram.field;
  const double apart = 0.25 * diagram.mean_spacing();
  const double crowded = std::max(same_point, 1e-4 * apart);
  PointHash<char> grid(crowded);  // the sites and the points kept
  auto taken = [&](const Eigen::Vector3d& x) { return grid.any_within(x, crowded, [](char) { return true; }); };
  for (const SurfacePoint& site : field.sites) grid.insert(site.position(input), 0);
  std::vector<Index> face_at_vertex;  // a face with area at each vertex, found when first needed
  auto into_face = [&](const SurfacePoint& p) {
    Index face = p.element;
    Eigen::Vector3d barycentric = p.barycentric;
    if (p.kind == SurfacePoint::Kind::vertex) {
      if (face_at_vertex.empty()) {
        face_at_vertex.assign(static_cast<std::size_t>(input.num_vertices()), -1);
        for (Index f = input.num_faces() - 1; f >= 0; --f) {
          if (!has_positive_area(input, f)) continue;
          for (int c = 0; c < 3; ++c) face_at_vertex[input.faces(f, c)] = f;
        }
      }
      face = face_at_vertex[p.element];
      if (face < 0) return p;
      for (int c = 0; c < 3; ++c) barycentric[c] = input.faces(face, c) == p.element ? 1.0 : 0.0;
    }
    barycentric = 0.98 * barycentric + Eigen::Vector3d::Constant(0.02 / 3);
    return SurfacePoint::in_face(face, barycentric[0], barycentric[1], barycentric[2]);
  };
  // Repair points are few (a round adds tens to hundreds): each is compared
  // with those kept before it.
  struct Kept {
    Eigen::Vector3d position;
    double apart;
    Index component;
  };
  std::vector<Kept> kept;
  std::vector<SurfacePoint> result;
  for (std::size_t i = 0; i < candidates.points.size(); ++i) {
    SurfacePoint p = candidates.points[i];
    if (p.kind == SurfacePoint::Kind::face && !has_positive_area(input, p.element)) {
      // Arcs cross faces without area, which take no site: their nearest corner.
      int corner = 0;
      for (int c = 1; c < 3; ++c) corner = p.barycentric[c] > p.barycentric[corner] ? c : corner;
      p = SurfacePoint::at_vertex(input.faces(p.element, corner));
    }
    Eigen::Vector3d x = p.position(input);
    if (taken(x) && voronoi::query(field, input, p).distance > crowded) {
      p = into_face(p);
      x = p.position(input);
    }
    const Index component = components.find(vertex_of(input, p));
    const double own = std::min(apart, candidates.apart_at_most[i]);
    auto near = [&](const Kept& y) {
      return y.component == component && (x - y.position).norm() <= std::min(own, y.apart);
    };
    if (taken(x) || std::any_of(kept.begin(), kept.end(), near)) continue;
    grid.insert(x, 0);
    kept.push_back({x, own, component});
    result.push_back(p);
  }
  return result;
}

/// Points where new sites restore the closed-ball property, for the faults
/// of the dual of `diagram` on `input` (`components`: the input's, by smallest vertex).
std::vector<SurfacePoint> repair_sites(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                                       const Faults& faults, UnionFind& components) {
  const voronoi::GeodesicField& field = diagram.field;
  const Index num_sites = static_cast<Index>(field.sites.size());
  const double same_point = same_point_distance(input);
  RepairPoints candidates;
  const std::vector<std::uint8_t> repaired_between =
      repair_between_cells(input, diagram, faults, same_point, candidates);
  const std::vector<std::uint8_t> sharp = sharp_boundary_corners(input, field);
  std::vector<std::uint8_t> holds_sharp_corner(static_cast<std::size_t>(num_sites), 0);
  for (Index v = 0; v < static_cast<Index>(field.nearest_site.size()); ++v) {
    if (sharp[v] && field.nearest_site[v] >= 0) holds_sharp_corner[field.nearest_site[v]] = 1;
  }
  const TopologyRepairs topology = topology_repairs(input, diagram, faults, holds_sharp_corner, repaired_between);
  std::vector<std::uint8_t> refined(static_cast<std::size_t>(num_sites), 0);
  for (Index s = 0; s < num_sites; ++s) refined[s] = faults.site[s] != SiteRepair::none;
  for (const Index s : topology.largest_cells) refined[s] = 1;
  const FarthestPoints farthest = farthest_points(input, diagram, refined, sharp);
  // Several fans: the cell has several boundary cycles (a band round a tube
  // or a spire) or reaches the mesh boundary in several places; like a
  // closed boundary, each fan gets a site, at its farthest Voronoi vertex. A
  // cell with no Voronoi vertex meets its neighbours only along arcs from
  // the mesh boundary to the mesh boundary (across a strip or a flap
  // narrower than the spacing, or cutting off a corner): a site at every end
  // of them, so that the strip gets sites on both sides. Both keep apart by
  // half their distance to the sites.
  for (Index s = 0; s < num_sites; ++s) {
    if (faults.site[s] == SiteRepair::none || repaired_between[s]) continue;
    if (faults.site[s] == SiteRepair::each_fan) {
      auto tip = std::lower_bound(faults.fan_tips.begin(), faults.fan_tips.end(), s,
                                  [](const std::array<Index, 2>& t, Index site) { return t[0] < site; });
      for (; tip != faults.fan_tips.end() && (*tip)[0] == s; ++tip) {
        const voronoi::VoronoiVertex& vertex = diagram.vertices[(*tip)[1]];
        candidates.add(vertex.location, 0.5 * vertex.distance);
      }
    } else if (faults.site[s] == SiteRepair::boundary_corners && !farthest.boundary_ends[s].empty()) {
      for (const auto& [distance, point] : farthest.boundary_ends[s])
        candidates.add(diagram.point_locations[point], 0.5 * distance);
    } else {
      add_farthest_point(diagram, farthest, s, candidates);
    }
  }
  for (const auto& [point, apart] : topology.crossings) candidates.add(point, apart);
  for (const Index s : topology.largest_cells) add_farthest_point(diagram, farthest, s, candidates);
  return points_kept_apart(input, diagram, candidates, components, same_point);
}

/// The dual's triangles: per Voronoi vertex, a fan over its sites, and
/// with options.close_boundary_stretches those along the boundary; each with
/// its Voronoi vertex (-1: along the boundary).
struct DualTriangles {
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Index> voronoi_vertex_of;
};

DualTriangles dual_triangles(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                             const DualOptions& options, const VertexMatrix& vertices) {
  DualTriangles dual;
  std::vector<std::array<Index, 3>>& triangles = dual.triangles;
  std::vector<Index>& voronoi_vertex_of = dual.voronoi_vertex_of;
  triangles.reserve(diagram.vertices.size());
  voronoi_vertex_of.reserve(diagram.vertices.size());
  // Each Voronoi vertex orders its sites as its face is oriented; faces at
  // odds with their neighbours (an input not oriented consistently) would
  // give triangles at odds with theirs.
  const std::vector<std::uint8_t> reverse = faces_to_reverse(input, diagram.field);
  std::vector<Index> corners;
  for (std::size_t v = 0; v < diagram.vertices.size(); ++v) {
    const voronoi::VoronoiVertex& vertex = diagram.vertices[v];
    const auto ordered = diagram.sites_of(vertex);
    corners.assign(ordered.begin(), ordered.end());
    if (vertex.location.kind == SurfacePoint::Kind::face && reverse[vertex.location.element]) {
      std::reverse(corners.begin(), corners.end());
    }
    const std::size_t k = corners.size();
    const std::size_t apex =
        static_cast<std::size_t>(std::min_element(corners.begin(), corners.end()) - corners.begin());
    for (std::size_t i = 1; i + 1 < k; ++i) {
      triangles.push_back({corners[apex], corners[(apex + i) % k], corners[(apex + i + 1) % k]});
      voronoi_vertex_of.push_back(static_cast<Index>(v));
    }
  }
  if (options.close_boundary_stretches) {
    for (const auto& t : detail::boundary_triangles(input, diagram, triangles, vertices)) {
      triangles.push_back(t);
      voronoi_vertex_of.push_back(-1);
    }
  }
  return dual;
}

/// Triangles degenerate or duplicated, and edges of more than two triangles
/// or used twice the same way, into `check` and `faults`.
void check_triangles_and_edges(std::span<const std::array<Index, 3>> triangles, const VertexMatrix& vertices,
                               double diagonal, DualCheck& check, Faults& faults) {
  std::vector<std::array<Index, 3>> sorted(triangles.begin(), triangles.end());
  for (auto& t : sorted) std::sort(t.begin(), t.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i] == sorted[i - 1]) {
      ++check.duplicate_triangles;
      faults.mark(sorted[i][0], SiteRepair::farthest_point);
    }
  }
  // Each undirected edge with its uses along (u < v) and against.
  std::vector<std::array<Index, 3>> edges;  // {min, max, 1 if used min -> max}
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = vertices.row(t[0]), b = vertices.row(t[1]), c = vertices.row(t[2]);
    if (!((b - a).cross(c - a).norm() > 1e-14 * diagonal * diagonal)) {
      ++check.degenerate_triangles;
      faults.mark(t[0], SiteRepair::farthest_point);
    }
    for (int k = 0; k < 3; ++k) {
      const Index u = t[k], v = t[(k + 1) % 3];
      edges.push_back({std::min(u, v), std::max(u, v), u < v ? 1 : 0});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int along = 0;
    for (; j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]; ++j) along += edges[j][2];
    const int uses = static_cast<int>(j - i);
    if (uses > 2 || along > 1 || uses - along > 1) {
      ++check.nonmanifold_edges;
      faults.mark(edges[i][0], SiteRepair::farthest_point);
      faults.mark(edges[i][1], SiteRepair::farthest_point);
    }
    i = j;
  }
}

/// Sites in no triangle (`used` per site: in some), into `check` and
/// `faults`; those that cut a sharp boundary corner off their one
/// neighbour's cell are check.redundant_sites.
void check_unused_sites(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram,
                        std::span<const std::uint8_t> used, DualCheck& check, Faults& faults) {
  const voronoi::GeodesicField& field = diagram.field;
  const auto num_sites = static_cast<Index>(field.sites.size());
  for (Index s = 0; s < num_sites; ++s) {
    if (!used[s]) {
      ++check.unused_sites;
      faults.mark(s, SiteRepair::boundary_corners);
    }
  }
  if (check.unused_sites == 0) return;
  // A cell whose whole boundary is one arc from the mesh boundary to the
  // mesh boundary, holding a boundary corner sharper than a right angle,
  // cuts the corner off its one neighbour's cell. No site added near it
  // gives it a Voronoi vertex (its neighbours would have to be almost
  // equally far on both sides of the corner), and each try puts the next
  // site closer to the tip; without its site, the neighbour's cell takes
  // the corner in.
  std::vector<int> arcs_of(static_cast<std::size_t>(num_sites), 0);
  std::vector<std::uint8_t> cut_off(static_cast<std::size_t>(num_sites), 0);
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    for (const Index s : {arc.left_site, arc.right_site}) {
      if (used[s]) continue;
      ++arcs_of[s];
      cut_off[s] = !arc.closed && arc.start_vertex < 0 && arc.end_vertex < 0;
    }
  }
  const std::vector<std::uint8_t> sharp = sharp_boundary_corners(input, field);
  std::vector<std::uint8_t> at_sharp_corner(static_cast<std::size_t>(num_sites), 0);
  for (Index v = 0; v < static_cast<Index>(field.nearest_site.size()); ++v) {
    if (sharp[v] && field.nearest_site[v] >= 0) at_sharp_corner[field.nearest_site[v]] = 1;
  }
  for (Index s = 0; s < num_sites; ++s) {
    if (!used[s] && arcs_of[s] == 1 && cut_off[s] && at_sharp_corner[s]) check.redundant_sites.push_back(s);
  }
}

/// Sites whose triangles form several fans (the manifold cut gives every
/// fan its own copy of the vertex: a site with copies is not a disk's
/// centre), into `check` and `faults`, with each fan's farthest Voronoi
/// vertex (faults.fan_tips).
void check_fans(const voronoi::VoronoiDiagram& diagram, const TriangleMesh& dual,
                std::span<const Index> voronoi_vertex_of, DualCheck& check, Faults& faults) {
  const auto num_sites = static_cast<Index>(diagram.field.sites.size());
  const ManifoldCut fans = cut_to_manifold(dual, {.disable_duplicate_faces = false, .min_component_faces = 0});
  std::vector<std::uint8_t> several_fans(static_cast<std::size_t>(num_sites), 0);
  for (std::size_t copy = static_cast<std::size_t>(num_sites); copy < fans.original_vertex.size(); ++copy) {
    several_fans[fans.original_vertex[copy]] = 1;
  }
  for (Index s = 0; s < num_sites; ++s) {
    if (!several_fans[s]) continue;
    ++check.nonmanifold_vertices;
    faults.mark(s, SiteRepair::each_fan);
  }
  if (check.nonmanifold_vertices == 0) return;
  // Per fan (a vertex of the cut dual) of such a site: its farthest Voronoi vertex.
  std::vector<Index> farthest(fans.original_vertex.size(), -1);
  for (Index t = 0; t < fans.mesh.num_faces(); ++t) {
    const Index v = voronoi_vertex_of[t];
    if (v < 0) continue;  // a triangle along the boundary
    for (int c = 0; c < 3; ++c) {
      Index& tip = farthest[fans.mesh.faces(t, c)];
      if (several_fans[fans.original_vertex[fans.mesh.faces(t, c)]] &&
          (tip < 0 || diagram.vertices[v].distance > diagram.vertices[tip].distance)) {
        tip = v;
      }
    }
  }
  for (std::size_t copy = 0; copy < farthest.size(); ++copy) {
    if (farthest[copy] >= 0) faults.fan_tips.push_back({fans.original_vertex[copy], farthest[copy]});
  }
  std::stable_sort(faults.fan_tips.begin(), faults.fan_tips.end(),
                   [](const auto& a, const auto& b) { return a[0] < b[0]; });
}

/// What a piece of the input (`component`: its smallest vertex; `expected`
/// its counts) holding `sites` became in the dual, for the message: where to
/// look (a scrap far below the sites' spacing may need to go; a large piece
/// needs more sites), what the piece is and what the remesh made of it.
std::string mismatch_text(Index component, const ComponentCounts& expected, std::span<const Index> sites,
                          const MeshTopology& dual_topology) {
  auto loops = [](std::int64_t n) { return std::to_string(n) + (n == 1 ? " boundary loop" : " boundary loops"); };
  std::vector<Index> pieces;  // of the remesh, holding the piece's sites
  for (const Index s : sites) {
    if (dual_topology.vertex_component[s] >= 0) pieces.push_back(dual_topology.vertex_component[s]);
  }
  std::sort(pieces.begin(), pieces.end());
  pieces.erase(std::unique(pieces.begin(), pieces.end()), pieces.end());
  ComponentCounts made;
  for (const Index p : pieces) {
    made.vertices += dual_topology.components[p].vertices;
    made.edges += dual_topology.components[p].edges;
    made.faces += dual_topology.components[p].faces;
    made.boundary_loops += dual_topology.components[p].boundary_loops;
  }
  const std::string remeshed =
      pieces.empty() ? "no triangle"
                     : (pieces.size() > 1 ? std::to_string(pieces.size()) + " pieces, together " : std::string()) +
                           "Euler characteristic " + std::to_string(made.euler_characteristic()) + ", " +
                           loops(made.boundary_loops);
  return " (the first: the piece with input vertex " + std::to_string(component) + ", " +
         std::to_string(expected.faces) + " faces, " + std::to_string(sites.size()) + " sites, Euler characteristic " +
         std::to_string(expected.euler_characteristic()) + ", " + loops(expected.boundary_loops) +
         "; in the remesh: " + remeshed + ")";
}

/// Topology per component: the input's (faces with a repeated index aside,
/// its components into `input_components`) against the dual's, matched
/// through the sites, into `check` and `faults`. Returns the first
/// mismatch's mismatch_text ("" where none).
std::string check_topology(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram, const TriangleMesh& dual,
                           UnionFind& input_components, DualCheck& check, Faults& faults) {
  const voronoi::GeodesicField& field = diagram.field;
  const auto num_sites = static_cast<Index>(field.sites.size());
  const auto input_topology = field_topology(input, field, input_components);
  const MeshTopology dual_topology = build_mesh_topology(dual);
  std::string first_mismatch;
  faults.component_of_site.resize(static_cast<std::size_t>(num_sites));
  for (Index s = 0; s < num_sites; ++s) {
    faults.component_of_site[s] = input_components.find(vertex_of(input, field.sites[s]));
    faults.sites_of_component[faults.component_of_site[s]].push_back(s);
  }
  for (const auto& [component, sites] : faults.sites_of_component) {
    const Index dual_component = dual_topology.vertex_component[sites[0]];
    bool same = dual_component >= 0 && std::all_of(sites.begin(), sites.end(), [&](Index s) {
                  return dual_topology.vertex_component[s] == dual_component;
                });
    const ComponentCounts& expected = input_topology.at(component);
    same = same && dual_topology.components[dual_component].euler_characteristic() == expected.euler_characteristic() &&
           dual_topology.components[dual_component].boundary_loops == expected.boundary_loops;
    if (same) continue;
    if (check.topology_mismatches++ == 0) first_mismatch = mismatch_text(component, expected, sites, dual_topology);
    faults.mismatched.push_back(component);
  }
  return first_mismatch;
}

}  // namespace

DualMesh dual_delaunay(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram, const DualOptions& options) {
  const voronoi::GeodesicField& field = diagram.field;
  const Index num_sites = static_cast<Index>(field.sites.size());
  DualMesh dual;
  DualCheck& check = dual.check;

  // Vertices and triangles.
  dual.mesh.vertices.resize(num_sites, 3);
  for (Index s = 0; s < num_sites; ++s) dual.mesh.vertices.row(s) = field.sites[s].position(input).transpose();
  const DualTriangles triangles = dual_triangles(input, diagram, options, dual.mesh.vertices);
  dual.mesh.faces.resize(static_cast<Index>(triangles.triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) dual.mesh.faces(static_cast<Index>(t), c) = triangles.triangles[t][c];
  }

  Faults faults;
  faults.site.assign(static_cast<std::size_t>(num_sites), SiteRepair::none);
  // Triangles: degenerate, duplicated; edges: at most two triangles, opposite.
  const double diagonal = vertex_box_diagonal(input);
  check_triangles_and_edges(triangles.triangles, dual.mesh.vertices, diagonal, check, faults);
  // Vertices: each site a corner, its triangles one fan.
  std::vector<std::uint8_t> used(static_cast<std::size_t>(num_sites), 0);
  for (const auto& t : triangles.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  check_unused_sites(input, diagram, used, check, faults);
  check_fans(diagram, dual.mesh, triangles.voronoi_vertex_of, check, faults);
  // Arcs: two cells along one arc, every boundary ending at vertices.
  for (std::size_t p = 0; p < diagram.adjacency.size(); ++p) {
    if (diagram.adjacency[p].arc_count <= 1) continue;
    ++check.split_arcs;
    faults.split_pairs.push_back(static_cast<Index>(p));
  }
  for (std::size_t a = 0; a < diagram.arcs.size(); ++a) {
    if (!diagram.arcs[a].closed) continue;
    ++check.closed_arcs;
    faults.closed_arcs.push_back(static_cast<Index>(a));
  }
  UnionFind input_components(static_cast<std::size_t>(input.num_vertices()));
  const std::string first_mismatch = check_topology(input, diagram, dual.mesh, input_components, check, faults);

  auto note = [&](std::int64_t count, const std::string& what) {
    if (count > 0) check.problems.push_back(std::to_string(count) + " " + what);
  };
  note(check.nonmanifold_edges, "non-manifold or misoriented dual edges");
  note(check.nonmanifold_vertices, "sites whose triangles form several fans");
  note(check.unused_sites, "sites with no Voronoi vertex");
  note(check.duplicate_triangles, "duplicate triangles");
  note(check.degenerate_triangles, "zero-area triangles");
  note(check.split_arcs, "cell pairs meeting along several arcs");
  note(check.closed_arcs, "cells enclosed by another");
  note(check.topology_mismatches,
       "components whose Euler characteristic or boundary loops differ from the input's" + first_mismatch);
  check.valid = check.problems.empty();
  faults.left_out.assign(static_cast<std::size_t>(num_sites), 0);
  for (const Index s : check.redundant_sites) {
    faults.site[s] = SiteRepair::none;
    faults.left_out[s] = 1;
  }
  if (!check.valid) check.repair_sites = repair_sites(input, diagram, faults, input_components);
  return dual;
}

std::string problems_line(const std::vector<std::string>& problems) {
  std::string line;
  for (const std::string& problem : problems) line += (line.empty() ? "" : "; ") + problem;
  return line;
}

}  // namespace geodual::remesh
