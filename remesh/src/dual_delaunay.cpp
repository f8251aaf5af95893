#include "geodual/remesh/dual_delaunay.hpp"
#include "geodual/remesh/manifold_cut.hpp"

#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/mesh_topology.hpp"
#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
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
    for (std::size_t e = 0; e < field.edge_vertices.size(); ++e) {
      const auto [u, v] = field.edge_vertices[e];
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
std::vector<std::uint8_t> faces_to_reverse(const TriangleMesh& mesh, const voronoi::GeodesicField& field) {
  const Index num_faces = static_cast<Index>(mesh.faces.rows());
  std::vector<std::uint8_t> reverse(static_cast<std::size_t>(num_faces), 0);
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(num_faces), 0);
  auto forward = [&](Index face, int side) {
    return mesh.faces(face, side) == field.edge_vertices[field.face_edges[face][side]][0];
  };
  std::vector<Index> piece;  // breadth-first: the faces of one piece
  for (Index start = 0; start < num_faces; ++start) {
    if (seen[start] || has_repeated_corner(mesh, start)) continue;
    piece.assign(1, start);
    seen[start] = 1;
    std::size_t reversed = 0;
    for (std::size_t i = 0; i < piece.size(); ++i) {
      const Index face = piece[i];
      for (int side = 0; side < 3; ++side) {
        const Index edge = field.face_edges[face][side];
        if (edge < 0) continue;
        const auto [f0, f1] = field.edge_faces[edge];
        const Index other = f0 == face ? f1 : f0;
        if (other < 0 || other == face || seen[other]) continue;
        int other_side = 0;
        while (other_side < 2 && field.face_edges[other][other_side] != edge) ++other_side;
        // Consistent when the two run along the edge in opposite directions.
        const bool same_direction = (forward(face, side) != (reverse[face] != 0)) == forward(other, other_side);
        reverse[other] = same_direction ? 1 : 0;
        reversed += reverse[other];
        seen[other] = 1;
        piece.push_back(other);
      }
    }
    if (2 * reversed > piece.size()) {
      for (const Index face : piece) reverse[face] ^= 1;
    }
  }
  return reverse;
}

Index vertex_of(const TriangleMesh& mesh, const SurfacePoint& p) {
  return p.kind == SurfacePoint::Kind::vertex ? p.element : mesh.faces(p.element, 0);
}

}  // namespace

DualMesh dual_delaunay(const TriangleMesh& input, const voronoi::VoronoiDiagram& diagram) {
  const voronoi::GeodesicField& field = diagram.field;
  const Index num_sites = static_cast<Index>(field.sites.size());
  DualMesh dual;
  DualCheck& check = dual.check;

  // Vertices and triangles.
  dual.mesh.vertices.resize(num_sites, 3);
  for (Index s = 0; s < num_sites; ++s) dual.mesh.vertices.row(s) = field.sites[s].position(input).transpose();
  std::vector<std::array<Index, 3>> triangles;
  triangles.reserve(diagram.vertices.size());
  // Each Voronoi vertex orders its sites as its face is oriented; faces at
  // odds with their neighbours (an input not oriented consistently) would
  // give triangles at odds with theirs.
  const std::vector<std::uint8_t> reverse = faces_to_reverse(input, field);
  std::vector<Index> corners;
  for (const voronoi::VoronoiVertex& vertex : diagram.vertices) {
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
    }
  }
  dual.mesh.faces.resize(static_cast<Index>(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) dual.mesh.faces(static_cast<Index>(t), c) = triangles[t][c];
  }

  // Where to add sites: far from a site, at the vertex of its cell farthest
  // from it, or in a cell that holds no mesh vertex (sites denser than the
  // mesh's vertices), at its farthest Voronoi vertex; between two cells,
  // halfway along an arc.
  std::vector<Index> farthest_vertex(num_sites, -1);
  for (Index v = 0; v < static_cast<Index>(field.distance.size()); ++v) {
    const Index s = field.nearest_site[v];
    if (s < 0) continue;
    if (farthest_vertex[s] < 0 || field.distance[v] > field.distance[farthest_vertex[s]]) farthest_vertex[s] = v;
  }
  std::vector<Index> farthest_voronoi_vertex(num_sites, -1);
  for (std::size_t v = 0; v < diagram.vertices.size(); ++v) {
    const double distance = diagram.vertices[v].distance;
    for (const Index s : diagram.sites_of(diagram.vertices[v])) {
      Index& farthest = farthest_voronoi_vertex[s];
      if (farthest < 0 || distance > diagram.vertices[farthest].distance) farthest = static_cast<Index>(v);
    }
  }
  constexpr double infinity = std::numeric_limits<double>::infinity();
  // Each repair site keeps others at most this far away (see the filter
  // below); infinity: the default spacing.
  std::vector<double> repair_apart;
  auto repair_at = [&](const SurfacePoint& p, double apart_at_most) {
    check.repair_sites.push_back(p);
    repair_apart.push_back(apart_at_most);
  };
  auto repair_far_from = [&](Index site) {
    if (site < 0) return;
    if (farthest_vertex[site] >= 0) {
      if (field.distance[farthest_vertex[site]] > 0) {
        repair_at(SurfacePoint::at_vertex(farthest_vertex[site]), infinity);
      }
    } else if (farthest_voronoi_vertex[site] >= 0) {
      repair_at(diagram.vertices[farthest_voronoi_vertex[site]].location, infinity);
    }
  };
  auto repair_on_arc = [&](const voronoi::VoronoiArc& arc) {
    repair_at(diagram.point_locations[(arc.point_begin + arc.point_end) / 2], infinity);
  };
  // A closed boundary (a cell enclosed by another) girdles a protrusion or a
  // tube thinner than the sites' spacing: one site on it would only stack
  // another band of cells there, so three go around it, a third of its length
  // apart, and cells meet at Voronoi vertices across it.
  auto repair_around_loop = [&](const voronoi::VoronoiArc& arc) {
    const auto line = diagram.polyline(arc);
    if (line.empty()) return;
    double length = 0;
    for (std::size_t i = 0; i < line.size(); ++i) length += (line[(i + 1) % line.size()] - line[i]).norm();
    double walked = 0;
    int placed = 0;
    for (std::size_t i = 0; i < line.size() && placed < 3; ++i) {
      if (walked >= placed * length / 3) {
        repair_at(diagram.point_locations[arc.point_begin + static_cast<Index>(i)], length / 6);
        ++placed;
      }
      walked += (line[(i + 1) % line.size()] - line[i]).norm();
    }
  };

  // Triangles: degenerate, duplicated; edges: at most two triangles, opposite.
  const double diagonal = input.vertices.rows() > 0
                              ? (input.vertices.colwise().maxCoeff() - input.vertices.colwise().minCoeff()).norm()
                              : 0.0;
  std::vector<std::array<Index, 3>> sorted = triangles;
  for (auto& t : sorted) std::sort(t.begin(), t.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i] == sorted[i - 1]) {
      ++check.duplicate_triangles;
      repair_far_from(sorted[i][0]);
    }
  }
  // Each undirected edge with its uses along (u < v) and against.
  std::vector<std::array<Index, 3>> edges;  // {min, max, 1 if used min -> max}
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = dual.mesh.vertices.row(t[0]), b = dual.mesh.vertices.row(t[1]),
                          c = dual.mesh.vertices.row(t[2]);
    if (!((b - a).cross(c - a).norm() > 1e-14 * diagonal * diagonal)) {
      ++check.degenerate_triangles;
      repair_far_from(t[0]);
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
      repair_far_from(edges[i][0]);
      repair_far_from(edges[i][1]);
    }
    i = j;
  }

  // Vertices: each site a corner, its triangles one fan. The manifold cut
  // gives every fan (triangles joined through two-triangle edges) its own
  // copy of the vertex: a site with copies is not a disk's centre.
  std::vector<std::uint8_t> used(static_cast<std::size_t>(num_sites), 0);
  for (const auto& t : triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  for (Index s = 0; s < num_sites; ++s) {
    if (!used[s]) {
      ++check.unused_sites;
      repair_far_from(s);
    }
  }
  const ManifoldCut fans = cut_to_manifold(dual.mesh, {.disable_duplicate_faces = false, .min_component_faces = 0});
  std::vector<std::uint8_t> several_fans(static_cast<std::size_t>(num_sites), 0);
  for (std::size_t copy = static_cast<std::size_t>(num_sites); copy < fans.original_vertex.size(); ++copy) {
    several_fans[fans.original_vertex[copy]] = 1;
  }
  for (Index s = 0; s < num_sites; ++s) {
    if (!several_fans[s]) continue;
    ++check.nonmanifold_vertices;
    repair_far_from(s);
  }

  // Arcs: two cells along one arc, every boundary ending at vertices.
  for (const voronoi::CellAdjacency& pair : diagram.adjacency) {
    if (pair.arc_count <= 1) continue;
    ++check.split_arcs;
    for (const voronoi::VoronoiArc& arc : diagram.arcs) {
      const Index a = std::min(arc.left_site, arc.right_site), b = std::max(arc.left_site, arc.right_site);
      if (a == pair.site_a && b == pair.site_b) repair_on_arc(arc);
    }
  }
  for (const voronoi::VoronoiArc& arc : diagram.arcs) {
    if (arc.closed) {
      ++check.closed_arcs;
      repair_around_loop(arc);
    }
  }

  // Topology per component: the input's (faces with a repeated index aside)
  // against the dual's, matched through the sites.
  UnionFind input_components(static_cast<std::size_t>(input.num_vertices()));
  const auto input_topology = field_topology(input, field, input_components);
  const MeshTopology dual_topology = build_mesh_topology(dual.mesh);
  std::map<Index, std::vector<Index>> sites_by_component;
  std::string first_mismatch;
  for (Index s = 0; s < num_sites; ++s) {
    sites_by_component[input_components.find(vertex_of(input, field.sites[s]))].push_back(s);
  }
  for (const auto& [component, sites] : sites_by_component) {
    const Index dual_component = dual_topology.vertex_component[sites[0]];
    bool same = dual_component >= 0 && std::all_of(sites.begin(), sites.end(), [&](Index s) {
                  return dual_topology.vertex_component[s] == dual_component;
                });
    const ComponentCounts& expected = input_topology.at(component);
    same = same && dual_topology.components[dual_component].euler_characteristic() == expected.euler_characteristic() &&
           dual_topology.components[dual_component].boundary_loops == expected.boundary_loops;
    if (same) continue;
    if (check.topology_mismatches++ == 0) {
      // Named in the message: where to look (a scrap far below the sites'
      // spacing may need to go; a large piece needs more sites), what the
      // piece is and what the remesh made of it.
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
      first_mismatch = " (the first: the piece with input vertex " + std::to_string(component) + ", " +
                       std::to_string(expected.faces) + " faces, " + std::to_string(sites.size()) +
                       " sites, Euler characteristic " + std::to_string(expected.euler_characteristic()) + ", " +
                       loops(expected.boundary_loops) + "; in the remesh: " + remeshed + ")";
    }
    // Local problems explain most mismatches; without any, refine where
    // cells are largest (a handle or hole inside one): their farthest vertices.
    if (!check.repair_sites.empty()) continue;
    std::vector<std::pair<double, Index>> by_area;
    for (const Index s : sites) by_area.emplace_back(-diagram.cell_area[s], s);
    std::sort(by_area.begin(), by_area.end());
    const std::size_t count = std::max<std::size_t>(1, sites.size() / 20);
    for (std::size_t i = 0; i < count && i < by_area.size(); ++i) repair_far_from(by_area[i].second);
  }

  // Repair sites: apart from the sites (the engine rejects two sites at one
  // point; points 1e-9 of the diagonal apart are one point here), and from
  // each other by a quarter of the sites' mean spacing (two arcs of one
  // problem often end side by side, and two sites there would make a sliver).
  double cells_area = 0;
  for (const double area : diagram.cell_area) cells_area += area;
  const double apart =
      0.25 * std::sqrt(cells_area / static_cast<double>(std::max<std::size_t>(diagram.cell_area.size(), 1)));
  const double spacing = std::max(1e-9 * diagonal, 1e-300);
  std::map<std::array<std::int64_t, 3>, std::vector<Eigen::Vector3d>> grid;
  auto cell_of = [&](const Eigen::Vector3d& x) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(x.x() / spacing)),
                                       static_cast<std::int64_t>(std::floor(x.y() / spacing)),
                                       static_cast<std::int64_t>(std::floor(x.z() / spacing))};
  };
  auto taken = [&](const Eigen::Vector3d& x) {
    const auto cell = cell_of(x);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (const Eigen::Vector3d& y : it->second) {
            if ((x - y).norm() <= spacing) return true;
          }
        }
      }
    }
    return false;
  };
  for (const SurfacePoint& site : field.sites) {
    const Eigen::Vector3d x = site.position(input);
    grid[cell_of(x)].push_back(x);
  }
  // Repair sites are few (a round adds tens to hundreds): each is compared
  // with those kept before it.
  // Two are kept apart by the smaller of their own separations.
  std::vector<SurfacePoint> repairs;
  std::vector<std::pair<Eigen::Vector3d, double>> kept;
  for (std::size_t i = 0; i < check.repair_sites.size(); ++i) {
    const SurfacePoint& p = check.repair_sites[i];
    const Eigen::Vector3d x = p.position(input);
    const double own = std::min(apart, repair_apart[i]);
    auto near_kept = [&](const std::pair<Eigen::Vector3d, double>& y) {
      return (x - y.first).norm() <= std::min(own, y.second);
    };
    if (taken(x) || std::any_of(kept.begin(), kept.end(), near_kept)) continue;
    grid[cell_of(x)].push_back(x);
    kept.emplace_back(x, own);
    repairs.push_back(p);
  }
  check.repair_sites = std::move(repairs);

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
  return dual;
}

}  // namespace geodual::remesh
