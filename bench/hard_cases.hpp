#pragma once
// Generated hard cases for the remesher: meshes built in code (deterministic,
// no files) with the features real inputs break on: boundary loops, thin
// walls, many small components, pinch vertices, slits and duplicated faces.
// Each is between 1K and 50K faces. Header-only, so that bench/ programs and
// tests can both use it.
//
//   for (const auto& hard_case : geodual::bench::hard_cases()) remesh(hard_case.build());

#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace geodual::bench {

namespace hard_case_detail {

/// Collects vertices and triangles; meshes are appended with their indices shifted.
class MeshBuilder {
 public:
  Index add_vertex(const Eigen::Vector3d& p) {
    vertices_.push_back(p);
    return static_cast<Index>(vertices_.size() - 1);
  }
  void add_face(Index a, Index b, Index c) { faces_.push_back({a, b, c}); }
  /// Two triangles a b c, a c d of the counter-clockwise quad a b c d.
  void add_quad(Index a, Index b, Index c, Index d) {
    add_face(a, b, c);
    add_face(a, c, d);
  }
  void append(const TriangleMesh& mesh) {
    const Index offset = static_cast<Index>(vertices_.size());
    for (Index v = 0; v < mesh.num_vertices(); ++v) vertices_.push_back(mesh.vertices.row(v).transpose());
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      add_face(mesh.faces(f, 0) + offset, mesh.faces(f, 1) + offset, mesh.faces(f, 2) + offset);
    }
  }
  TriangleMesh build() const {
    TriangleMesh mesh;
    mesh.vertices.resize(static_cast<Eigen::Index>(vertices_.size()), 3);
    for (std::size_t v = 0; v < vertices_.size(); ++v) mesh.vertices.row(static_cast<Eigen::Index>(v)) = vertices_[v];
    mesh.faces.resize(static_cast<Eigen::Index>(faces_.size()), 3);
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Eigen::Index>(f), c) = faces_[f][static_cast<std::size_t>(c)];
    }
    return mesh;
  }

 private:
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<Index, 3>> faces_;
};

/// `count` coordinates from `from` to `to` evenly spaced (count >= 2).
inline std::vector<double> even_steps(double from, double to, int count) {
  std::vector<double> values(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) values[static_cast<std::size_t>(i)] = from + (to - from) * i / (count - 1);
  return values;
}

/// The boundary of a union of boxes of a rectilinear lattice: cell (i, j, k)
/// spans [x[i], x[i+1]] x [y[j], y[j+1]] x [z[k], z[k+1]] and is solid where
/// `solid(i, j, k)`. Every cell face between a solid and an empty cell becomes
/// two triangles, oriented outwards; lattice points are shared, so the result
/// is closed. Solid cells must never touch along an edge or a corner only
/// (that would make non-manifold edges or vertices).
inline TriangleMesh voxel_surface(const std::array<std::vector<double>, 3>& lattice,
                                  const std::function<bool(int, int, int)>& solid) {
  const std::array<int, 3> cells = {static_cast<int>(lattice[0].size()) - 1, static_cast<int>(lattice[1].size()) - 1,
                                    static_cast<int>(lattice[2].size()) - 1};
  auto inside = [&](const std::array<int, 3>& c) {
    for (int d = 0; d < 3; ++d) {
      if (c[static_cast<std::size_t>(d)] < 0 || c[static_cast<std::size_t>(d)] >= cells[static_cast<std::size_t>(d)])
        return false;
    }
    return solid(c[0], c[1], c[2]);
  };
  MeshBuilder builder;
  std::map<std::array<int, 3>, Index> point_index;  // ordered: the vertex order depends on the input only
  auto point = [&](const std::array<int, 3>& p) {
    const auto [it, inserted] = point_index.try_emplace(p, 0);
    if (inserted) {
      it->second =
          builder.add_vertex({lattice[0][static_cast<std::size_t>(p[0])], lattice[1][static_cast<std::size_t>(p[1])],
                              lattice[2][static_cast<std::size_t>(p[2])]});
    }
    return it->second;
  };
  for (int i = 0; i < cells[0]; ++i) {
    for (int j = 0; j < cells[1]; ++j) {
      for (int k = 0; k < cells[2]; ++k) {
        const std::array<int, 3> cell = {i, j, k};
        if (!inside(cell)) continue;
        for (std::size_t d = 0; d < 3; ++d) {
          const std::size_t u = (d + 1) % 3, v = (d + 2) % 3;  // e_u x e_v = e_d
          for (const int side : {0, 1}) {
            std::array<int, 3> neighbour = cell;
            neighbour[d] += side == 1 ? 1 : -1;
            if (inside(neighbour)) continue;
            std::array<int, 3> p = cell;
            p[d] += side;
            std::array<int, 3> pu = p, puv = p, pv = p;
            pu[u] += 1;
            puv[u] += 1;
            puv[v] += 1;
            pv[v] += 1;
            if (side == 1) {
              builder.add_quad(point(p), point(pu), point(puv), point(pv));
            } else {
              builder.add_quad(point(p), point(pv), point(puv), point(pu));
            }
          }
        }
      }
    }
  }
  return builder.build();
}

/// A flat (z = 0) square [0, size]^2 of n x n cells, each cut into two
/// triangles along alternating diagonals; vertex (i, j) is i + (n + 1) j.
inline void add_grid(MeshBuilder& builder, int n, double size, const std::function<bool(int, int)>& keep_cell,
                     const std::function<Index(int, int, int, int)>& corner) {
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) builder.add_vertex({size * i / n, size * j / n, 0.0});
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (!keep_cell(i, j)) continue;
      // corner(i, j, ci, cj): the index of the cell's corner (ci, cj) as this cell sees it.
      const Index a = corner(i, j, i, j), b = corner(i, j, i + 1, j), c = corner(i, j, i + 1, j + 1),
                  d = corner(i, j, i, j + 1);
      if ((i + j) % 2 == 0) {
        builder.add_quad(a, b, c, d);
      } else {
        builder.add_quad(b, c, d, a);
      }
    }
  }
}

/// A closed sphere of `segments` meridians and `rings` latitude bands around `centre`.
inline TriangleMesh uv_sphere(const Eigen::Vector3d& centre, double radius, int segments, int rings) {
  MeshBuilder builder;
  const Index south = builder.add_vertex(centre - Eigen::Vector3d(0, 0, radius));
  for (int r = 1; r < rings; ++r) {
    const double polar = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2 * std::numbers::pi * s / segments;
      builder.add_vertex(centre + radius * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth),
                                                           std::sin(polar) * std::sin(azimuth), -std::cos(polar)));
    }
  }
  const Index north = builder.add_vertex(centre + Eigen::Vector3d(0, 0, radius));
  auto ring_vertex = [&](int r, int s) { return static_cast<Index>(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    builder.add_face(south, ring_vertex(1, s + 1), ring_vertex(1, s));
    for (int r = 1; r + 1 < rings; ++r) {
      builder.add_quad(ring_vertex(r, s), ring_vertex(r, s + 1), ring_vertex(r + 1, s + 1), ring_vertex(r + 1, s));
    }
    builder.add_face(north, ring_vertex(rings - 1, s), ring_vertex(rings - 1, s + 1));
  }
  return builder.build();
}

/// A closed torus around the z axis (major radius R, tube radius r).
inline TriangleMesh torus(double major_radius, double minor_radius, int segments, int tube_segments) {
  MeshBuilder builder;
  for (int s = 0; s < segments; ++s) {
    const double u = 2 * std::numbers::pi * s / segments;
    for (int t = 0; t < tube_segments; ++t) {
      const double v = 2 * std::numbers::pi * t / tube_segments;
      const double radius = major_radius + minor_radius * std::cos(v);
      builder.add_vertex({radius * std::cos(u), radius * std::sin(u), minor_radius * std::sin(v)});
    }
  }
  auto at = [&](int s, int t) { return static_cast<Index>((s % segments) * tube_segments + (t % tube_segments)); };
  for (int s = 0; s < segments; ++s) {
    for (int t = 0; t < tube_segments; ++t) builder.add_quad(at(s, t), at(s + 1, t), at(s + 1, t + 1), at(s, t + 1));
  }
  return builder.build();
}

/// A closed cone: apex at `apex`, axis `axis` (unit) pointing from the apex
/// to the base disc of `radius` at distance `height`; the side has `rings`
/// bands, the base `rings / 2` rings around its centre. The apex is vertex 0.
inline TriangleMesh closed_cone(const Eigen::Vector3d& apex, const Eigen::Vector3d& axis, double radius, double height,
                                int segments, int rings) {
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d helper = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = a.cross(helper).normalized(), e2 = a.cross(e1);
  MeshBuilder builder;
  builder.add_vertex(apex);
  auto direction = [&](int s) {
    const double angle = 2 * std::numbers::pi * s / segments;
    return Eigen::Vector3d(std::cos(angle) * e1 + std::sin(angle) * e2);
  };
  // Side rings 1..rings (ring `rings` is the rim), then base rings rings/2 - 1 .. 1, then the base centre.
  for (int r = 1; r <= rings; ++r) {
    const double t = static_cast<double>(r) / rings;
    for (int s = 0; s < segments; ++s) builder.add_vertex(apex + t * height * a + t * radius * direction(s));
  }
  const int base_rings = std::max(1, rings / 2);
  for (int r = base_rings - 1; r >= 1; --r) {
    const double t = static_cast<double>(r) / base_rings;
    for (int s = 0; s < segments; ++s) builder.add_vertex(apex + height * a + t * radius * direction(s));
  }
  const Index centre = builder.add_vertex(apex + height * a);
  // Ring q (1-based over side and base rings together) starts at 1 + (q - 1) * segments.
  auto at = [&](int q, int s) { return static_cast<Index>(1 + (q - 1) * segments + (s % segments)); };
  const int last_ring = rings + base_rings - 1;
  for (int s = 0; s < segments; ++s) {
    builder.add_face(0, at(1, s + 1), at(1, s));
    for (int q = 1; q < last_ring; ++q) builder.add_quad(at(q, s), at(q, s + 1), at(q + 1, s + 1), at(q + 1, s));
    builder.add_face(centre, at(last_ring, s), at(last_ring, s + 1));
  }
  return builder.build();
}

/// Whether cell (i, j) of an n x n grid on the unit square has its centre in
/// one of the plates' five round holes. Cutting such cells out never leaves
/// two cells meeting at a corner only (a disc never holds two opposite cells
/// of a 2 x 2 block without a third).
inline bool in_plate_hole(int i, int j, int n) {
  constexpr std::array<std::array<double, 3>, 5> holes = {
      {{0.25, 0.25, 0.15}, {0.72, 0.3, 0.1}, {0.3, 0.72, 0.06}, {0.7, 0.72, 0.03}, {0.5, 0.5, 0.015}}};  // x, y, radius
  const double x = (i + 0.5) / n, y = (j + 0.5) / n;
  return std::any_of(holes.begin(), holes.end(),
                     [&](const std::array<double, 3>& h) { return std::hypot(x - h[0], y - h[1]) < h[2]; });
}

}  // namespace hard_case_detail

/// A flat unit square of 100 x 100 cells with five round holes of different
/// sizes (six boundary loops), about 18K faces.
inline TriangleMesh plate_with_holes() {
  using namespace hard_case_detail;
  constexpr int n = 100;
  MeshBuilder builder;
  add_grid(
      builder, n, 1.0, [&](int i, int j) { return !in_plate_hole(i, j, n); },
      [&](int, int, int ci, int cj) { return static_cast<Index>(ci + (n + 1) * cj); });
  TriangleMesh mesh = builder.build();
  // Drop the vertices of removed cells that no kept cell uses: keep the mesh
  // free of unreferenced vertices.
  std::vector<Index> new_index(static_cast<std::size_t>(mesh.num_vertices()), -1);
  Index used = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      Index& target = new_index[static_cast<std::size_t>(mesh.faces(f, c))];
      if (target < 0) target = used++;
    }
  }
  TriangleMesh compact;
  compact.vertices.resize(used, 3);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (new_index[static_cast<std::size_t>(v)] >= 0)
      compact.vertices.row(new_index[static_cast<std::size_t>(v)]) = mesh.vertices.row(v);
  }
  compact.faces = mesh.faces;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) compact.faces(f, c) = new_index[static_cast<std::size_t>(mesh.faces(f, c))];
  }
  return compact;
}

/// The same five holes through a plate 2 % as thick as it is wide, made of
/// 60 x 60 boxes: one closed surface of genus 5 with staircase rims whose
/// walls are 0.02 high. About 13K faces.
inline TriangleMesh thick_plate_with_holes() {
  using namespace hard_case_detail;
  constexpr int n = 60;
  const std::vector<double> across = even_steps(0.0, 1.0, n + 1);
  return voxel_surface({across, across, {0.0, 0.02}}, [&](int i, int j, int) { return !in_plate_hole(i, j, n); });
}

/// A closed unit box with an open top whose walls are solid and 0.01 thick:
/// one closed surface (genus 0) whose outer and inner sheets lie 1 % of the
/// box's size apart, joined along the rim. About 9K faces.
inline TriangleMesh thin_walled_box() {
  using namespace hard_case_detail;
  constexpr double wall = 0.01;
  constexpr int n = 20;  // cells across the inside
  std::vector<double> across = {0.0};
  for (const double x : even_steps(wall, 1 - wall, n + 1)) across.push_back(x);
  across.push_back(1.0);
  const int last = n + 1;  // index of the last cell (the far wall)
  return voxel_surface({across, across, across}, [&](int i, int j, int k) {
    return i == 0 || i == last || j == 0 || j == last || k == 0;  // walls and floor, no lid
  });
}

/// 47 closed pieces on a 7 x 7 grid: spheres and boxes of radii 0.02 to 0.4
/// and resolutions from 8 to 32 segments (a tiny piece next to a large one).
/// About 18K faces.
inline TriangleMesh assembly_47() {
  using namespace hard_case_detail;
  MeshBuilder builder;
  for (int piece = 0; piece < 47; ++piece) {
    const Eigen::Vector3d centre(piece % 7, piece / 7, 0.1 * (piece % 3));
    // Sizes and resolutions cycle with different periods, so that every
    // combination of small and large, coarse and fine occurs.
    const double radius = 0.02 + 0.38 * ((piece * 7) % 11) / 10.0;
    const int segments = 8 + 4 * ((piece * 5) % 7);
    if (piece % 4 == 3) {
      const std::vector<double> steps = even_steps(-radius, radius, std::max(2, segments / 4));
      std::array<std::vector<double>, 3> lattice = {steps, steps, steps};
      for (int d = 0; d < 3; ++d) {
        for (double& x : lattice[static_cast<std::size_t>(d)]) x += centre[d];
      }
      builder.append(voxel_surface(lattice, [](int, int, int) { return true; }));
    } else {
      builder.append(uv_sphere(centre, radius, segments, std::max(3, segments / 2)));
    }
  }
  return builder.build();
}

/// Closed cones joined at their apexes: four double cones (two cones sharing
/// one apex vertex, a pinch vertex with two fans) and one star of three cones
/// sharing one apex (three fans). About 12K faces.
inline TriangleMesh pinched_cones() {
  using namespace hard_case_detail;
  MeshBuilder builder;
  auto add_sharing_apex = [&](const std::vector<TriangleMesh>& cones) {
    // Every cone's vertex 0 is its apex: map them all to the first cone's.
    Index apex = -1;
    for (const TriangleMesh& cone : cones) {
      std::vector<Index> index(static_cast<std::size_t>(cone.num_vertices()));
      for (Index v = 0; v < cone.num_vertices(); ++v) {
        index[static_cast<std::size_t>(v)] =
            (v == 0 && apex >= 0) ? apex : builder.add_vertex(cone.vertices.row(v).transpose());
      }
      if (apex < 0) apex = index[0];
      for (Index f = 0; f < cone.num_faces(); ++f) {
        builder.add_face(index[static_cast<std::size_t>(cone.faces(f, 0))],
                         index[static_cast<std::size_t>(cone.faces(f, 1))],
                         index[static_cast<std::size_t>(cone.faces(f, 2))]);
      }
    }
  };
  for (int pair = 0; pair < 4; ++pair) {
    const Eigen::Vector3d apex(2.5 * pair, 0, 0);
    const Eigen::Vector3d axis(std::sin(0.3 * pair), 0, std::cos(0.3 * pair));  // tilted differently
    const double radius = 0.4 + 0.15 * pair;
    add_sharing_apex(
        {closed_cone(apex, axis, radius, 1.0, 32, 12), closed_cone(apex, -axis, 0.5, 0.8 + 0.2 * pair, 32, 12)});
  }
  const Eigen::Vector3d star(4.0, 3.0, 0);
  std::vector<TriangleMesh> arms;
  for (int arm = 0; arm < 3; ++arm) {
    const double angle = 2 * std::numbers::pi * arm / 3;
    arms.push_back(closed_cone(star, {std::cos(angle), std::sin(angle), 0.2}, 0.45, 1.2, 32, 12));
  }
  add_sharing_apex(arms);
  return builder.build();
}

/// A flat unit square of 100 x 100 cells with three straight slits (cuts of
/// zero width: each side has its own vertices, the tips are shared): one
/// from the left edge to x = 0.4, one inside from x = 0.3 to 0.7 (a boundary
/// loop that runs out and back), one from the right edge to x = 0.55. Two
/// boundary loops, 20K faces.
inline TriangleMesh slit_square() {
  using namespace hard_case_detail;
  constexpr int n = 100;
  struct Slit {
    int row, first, last;  ///< on grid line y = row / n, vertices first..last are split
  };
  const std::array<Slit, 3> slits = {Slit{30, 0, 39}, Slit{70, 31, 69}, Slit{50, 56, 100}};
  MeshBuilder builder;
  const Index grid_vertices = (n + 1) * (n + 1);
  // Copies of the split vertices, used by the cells above each slit; added
  // after the grid, so the grid's vertex (i, j) stays i + (n + 1) j.
  std::map<std::pair<int, int>, Index> copy;
  Index next = grid_vertices;
  for (const Slit& slit : slits) {
    for (int i = slit.first; i <= slit.last; ++i) copy[{i, slit.row}] = next++;
  }
  add_grid(
      builder, n, 1.0, [](int, int) { return true; },
      [&](int, int cell_row, int ci, int cj) {
        if (cj == cell_row) {  // the cell's lower edge: use the copy if a slit runs there
          const auto it = copy.find({ci, cj});
          if (it != copy.end()) return it->second;
        }
        return static_cast<Index>(ci + (n + 1) * cj);
      });
  // The copies were numbered slit by slit: add their positions in that order.
  for (const Slit& slit : slits) {
    for (int i = slit.first; i <= slit.last; ++i)
      builder.add_vertex({static_cast<double>(i) / n, static_cast<double>(slit.row) / n, 0.0});
  }
  return builder.build();
}

/// A closed torus (genus 1, 9,600 faces) followed by a copy of every tenth
/// face, every other copy flipped: the duplicate triangles of a CAD soup.
/// The copies lie along eight rings around the tube, so that a cut along
/// their edges leaves eight annuli.
inline TriangleMesh duplicate_soup() {
  using namespace hard_case_detail;
  const TriangleMesh ring = torus(1.0, 0.35, 120, 40);
  MeshBuilder builder;
  builder.append(ring);
  for (Index f = 0, copies = 0; f < ring.num_faces(); f += 10, ++copies) {
    const Index a = ring.faces(f, 0), b = ring.faces(f, 1), c = ring.faces(f, 2);
    if (copies % 2 == 0) {
      builder.add_face(a, b, c);
    } else {
      builder.add_face(a, c, b);
    }
  }
  return builder.build();
}

/// A closed solid of revolution about the z axis, `segments` quads round per
/// side of its profile: the profile's corners (r, z) counter-clockwise with r
/// across and z up, either a closed polygon with r > 0 throughout (a part
/// with a hole, genus 1) or a path from a point on the axis (r = 0) to
/// another (a solid part, whose two axis points are fan apexes). Each corner
/// of the profile turns into a circular crease of the surface, as on a
/// turned part.
inline TriangleMesh revolved_profile(const std::vector<std::array<double, 2>>& profile, int segments) {
  using namespace hard_case_detail;
  MeshBuilder builder;
  std::vector<std::vector<Index>> rings;
  for (const auto& [r, z] : profile) {
    std::vector<Index>& ring = rings.emplace_back();
    if (r == 0) {
      ring.push_back(builder.add_vertex({0, 0, z}));
      continue;
    }
    for (int k = 0; k < segments; ++k) {
      const double angle = 2 * std::numbers::pi * k / segments;
      ring.push_back(builder.add_vertex({r * std::cos(angle), r * std::sin(angle), z}));
    }
  }
  const bool closed = profile.front()[0] > 0;
  const std::size_t bands = closed ? rings.size() : rings.size() - 1;
  for (std::size_t i = 0; i < bands; ++i) {
    const std::vector<Index>& a = rings[i];
    const std::vector<Index>& b = rings[(i + 1) % rings.size()];
    for (int k = 0; k < segments; ++k) {
      const auto at = [&](const std::vector<Index>& ring, int j) {
        return ring.size() == 1 ? ring[0] : ring[static_cast<std::size_t>(j % segments)];
      };
      // Outward normals: the profile's direction crossed into the turning direction.
      if (b.size() > 1) builder.add_face(at(a, k), at(b, k + 1), at(b, k));
      if (a.size() > 1) builder.add_face(at(a, k), at(a, k + 1), at(b, k + 1));
    }
  }
  return builder.build();
}

/// A stepped shaft: three diameters, a chamfered end (six circular creases,
/// steps a fifth to a third of the largest radius wide), 72 quads round.
inline TriangleMesh stepped_shaft() {
  return revolved_profile(
      {{0, 0}, {1.0, 0}, {1.0, 2.0}, {0.7, 2.0}, {0.7, 3.5}, {0.5, 3.5}, {0.5, 4.8}, {0.4, 5.0}, {0, 5.0}}, 72);
}

/// A V-belt pulley with a bore (genus 1): its groove and rims give seven
/// circular creases, five of them sharper than 60 degrees, 120 quads round.
inline TriangleMesh pulley() {
  return revolved_profile({{0.3, 0}, {1.2, 0}, {1.2, 0.2}, {1.0, 0.35}, {1.2, 0.5}, {1.2, 0.7}, {0.3, 0.7}}, 120);
}

/// A spur gear: 24 teeth 0.12 deep on a disc of radius 1, 0.5 thick, in 4
/// bands; each cap is a fan of needles from its centre, as CAD exports
/// triangulate them. The teeth are about one remesh spacing wide at 3,000
/// sites: 192 corners, creases between them one to two spacings long.
inline TriangleMesh spur_gear() {
  constexpr int kTeeth = 24, kPerTooth = 8, kBands = 4;
  constexpr int n = kTeeth * kPerTooth;
  constexpr double kDepth = 0.12, kHeight = 0.5;
  using namespace hard_case_detail;
  MeshBuilder builder;
  const Index bottom = builder.add_vertex({0, 0, 0}), top = builder.add_vertex({0, 0, kHeight});
  for (int band = 0; band <= kBands; ++band) {
    for (int k = 0; k < n; ++k) {
      const double angle = 2 * std::numbers::pi * k / n;
      const double radius = 1 + (std::cos(kTeeth * angle) > 0 ? kDepth : 0.0);
      builder.add_vertex({radius * std::cos(angle), radius * std::sin(angle), kHeight * band / kBands});
    }
  }
  const auto at = [&](int band, int k) { return static_cast<Index>(2 + band * n + k % n); };
  for (int k = 0; k < n; ++k) {
    builder.add_face(bottom, at(0, k + 1), at(0, k));
    builder.add_face(top, at(kBands, k), at(kBands, k + 1));
    for (int band = 0; band < kBands; ++band)
      builder.add_quad(at(band, k), at(band, k + 1), at(band + 1, k + 1), at(band + 1, k));
  }
  return builder.build();
}

/// The wall of a letter's hole as CAD text is extruded: a half-ellipse of
/// semi-axes 0.113 and 0.111 closed by its chord, 60 arc segments, 1 high,
/// one band of quads (122 faces; open, 2 boundary loops). The chord's panel
/// is a single quad between two creases: at 23 sites its sites all go
/// in the weld's repair, and with them the panel (as on the "e" of
/// OpenFOAM's opencfd_text.stl).
inline TriangleMesh letter_wall() {
  constexpr int kArc = 60;
  using namespace hard_case_detail;
  MeshBuilder builder;
  for (const double z : {0.0, 1.0}) {
    for (int k = 0; k <= kArc; ++k) {
      const double angle = std::numbers::pi * k / kArc;
      builder.add_vertex({-0.113 * std::cos(angle), 0.111 * std::sin(angle), z});
    }
  }
  constexpr Index n = kArc + 1;
  for (Index k = 0; k < n; ++k) builder.add_quad(k, (k + 1) % n, n + (k + 1) % n, n + k);
  return builder.build();
}

struct HardCase {
  std::string name;
  std::string description;
  std::function<TriangleMesh()> build;
};

/// Every generated hard case, in a fixed order.
inline std::vector<HardCase> hard_cases() {
  return {
      {"plate_holes", "flat square, 5 round holes (6 boundary loops)", plate_with_holes},
      {"thick_plate_holes", "closed plate 2 % thick with the same 5 holes (genus 5)", thick_plate_with_holes},
      {"thin_box", "open box with solid walls 1 % thick (closed, two sheets close together)", thin_walled_box},
      {"assembly_47", "47 closed spheres and boxes of varied size", assembly_47},
      {"pinch_cones", "closed cones sharing apexes: 4 pinches of 2 fans, 1 of 3", pinched_cones},
      {"slits", "flat square with 3 slits (2 boundary loops)", slit_square},
      {"dup_soup", "torus plus every 10th face again, half of them flipped", duplicate_soup},
      {"shaft", "turned shaft: 3 diameters, a chamfer (6 circular creases)", stepped_shaft},
      {"pulley", "V-belt pulley with a bore (genus 1, 5 circular creases)", pulley},
      {"gear", "24-tooth spur gear with fanned caps (192 corners)", spur_gear},
      {"letter_wall", "wall of a letter's hole: an arc and its chord, one quad high (2 creases)", letter_wall},
  };
}

}  // namespace geodual::bench
