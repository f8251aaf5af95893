#include "remesh/analytic_surfaces.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace geodual::test {
TriangleMesh mesh_from_lists(const std::vector<Eigen::Vector3d>& vertices,
                             const std::vector<std::array<Index, 3>>& faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) mesh.vertices.row(static_cast<Index>(i)) = vertices[i].transpose();
  mesh.faces.resize(static_cast<Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Index>(i), c) = faces[i][c];
  }
  return mesh;
}

namespace {

/// Vertices and faces of a torus grid, skipping the quads for which `cut` is true.
template <class Cut>
void add_torus(double R, double r, int n, int m, double centre_x, Cut cut, std::vector<Eigen::Vector3d>& vertices,
               std::vector<std::array<Index, 3>>& faces) {
  const Index base = static_cast<Index>(vertices.size());
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      vertices.emplace_back(centre_x + (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                            r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return base + static_cast<Index>(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      if (cut(i, j)) continue;
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
}

}  // namespace

TriangleMesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (auto& v : vertices) v.normalize();
  std::vector<std::array<Index, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<Index, Index>, Index> midpoint;
    auto middle = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      vertices.push_back((vertices[a] + vertices[b]).normalized());
      return midpoint[key] = static_cast<Index>(vertices.size()) - 1;
    };
    std::vector<std::array<Index, 3>> finer;
    for (const auto& f : faces) {
      const Index ab = middle(f[0], f[1]), bc = middle(f[1], f[2]), ca = middle(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  return mesh_from_lists(vertices, faces);
}

TriangleMesh torus(double R, double r, int n, int m, double centre_x) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  add_torus(
      R, r, n, m, centre_x, [](int, int) { return false; }, vertices, faces);
  return mesh_from_lists(vertices, faces);
}

TriangleMesh double_torus(double R, double r, int n, int m, int k) {
  // Torus A around x = 0 with a hole at u = 0 (its outer side, +x); torus B
  // around x = c, its mirror image, with the hole at u = pi facing A.
  const double c = 2 * (R + r) + 0.5 * r;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  const int i0 = n - k / 2, j0 = m - k / 2;  // the hole's first quad, around (0, 0)
  auto in_hole = [&](int i, int j) { return (i - i0 + n) % n < k && (j - j0 + m) % m < k; };
  add_torus(R, r, n, m, 0, in_hole, vertices, faces);
  const Index base_b = static_cast<Index>(vertices.size());
  // B: vertex (i, j) is A's vertex (i, j) mirrored in the plane x = c / 2, so
  // its faces are A's with the winding reversed.
  for (Index v = 0; v < base_b; ++v) vertices.emplace_back(c - vertices[v].x(), vertices[v].y(), vertices[v].z());
  const std::size_t faces_a = faces.size();
  for (std::size_t f = 0; f < faces_a; ++f) {
    faces.push_back({faces[f][0] + base_b, faces[f][2] + base_b, faces[f][1] + base_b});
  }
  // The tube: the hole's boundary loop walked the way A's faces use it, each
  // of its edges joined to the mirrored edge.
  auto id = [&](int i, int j) { return static_cast<Index>(((i + n) % n) * m + (j + m) % m); };
  std::vector<Index> loop;
  for (int s = 0; s < k; ++s) loop.push_back(id(i0 + s, j0));          // along u at the bottom
  for (int s = 0; s < k; ++s) loop.push_back(id(i0 + k, j0 + s));      // up at the far side
  for (int s = 0; s < k; ++s) loop.push_back(id(i0 + k - s, j0 + k));  // back along the top
  for (int s = 0; s < k; ++s) loop.push_back(id(i0, j0 + k - s));      // down the near side
  // A's faces around the hole use these edges in the opposite direction of
  // this walk (the walk goes counter-clockwise around the missing quads).
  for (std::size_t s = 0; s < loop.size(); ++s) {
    const Index a0 = loop[s], a1 = loop[(s + 1) % loop.size()];
    const Index b0 = a0 + base_b, b1 = a1 + base_b;
    faces.push_back({a0, a1, b1});
    faces.push_back({a0, b1, b0});
  }
  return mesh_from_lists(vertices, faces);
}

TriangleMesh disk(int rings, int segments) {
  std::vector<Eigen::Vector3d> vertices = {Eigen::Vector3d::Zero()};
  for (int ring = 1; ring <= rings; ++ring) {
    for (int s = 0; s < segments; ++s) {
      const double a = 2 * std::numbers::pi * s / segments, radius = static_cast<double>(ring) / rings;
      vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), 0);
    }
  }
  auto id = [&](int ring, int s) {
    return ring == 0 ? Index{0} : static_cast<Index>(1 + (ring - 1) * segments + (s + segments) % segments);
  };
  std::vector<std::array<Index, 3>> faces;
  for (int s = 0; s < segments; ++s) faces.push_back({0, id(1, s), id(1, s + 1)});
  for (int ring = 1; ring < rings; ++ring) {
    for (int s = 0; s < segments; ++s) {
      faces.push_back({id(ring, s), id(ring + 1, s), id(ring + 1, s + 1)});
      faces.push_back({id(ring, s), id(ring + 1, s + 1), id(ring, s + 1)});
    }
  }
  return mesh_from_lists(vertices, faces);
}

TriangleMesh unit_square(int n) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<Index, 3>> faces;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) vertices.emplace_back(double(i) / n, double(j) / n, 0.0);
  }
  const auto at = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh_from_lists(vertices, faces);
}

TriangleMesh slit_square(int n) {
  if (n < 2 || n % 2 != 0) throw std::invalid_argument("slit_square: n must be even and >= 2");
  std::vector<Eigen::Vector3d> vertices;
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) vertices.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n, 0);
  }
  // Copies of the slit's vertices (i < n / 2 on row n / 2), for the faces above it.
  std::vector<Index> above(static_cast<std::size_t>(n / 2));
  for (int i = 0; i < n / 2; ++i) {
    above[static_cast<std::size_t>(i)] = static_cast<Index>(vertices.size());
    vertices.push_back(vertices[static_cast<std::size_t>(id(i, n / 2))]);
  }
  std::vector<std::array<Index, 3>> faces;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      // Row n / 2 left of the centre, seen from the cells above it: the copies.
      auto v = [&](int a, int b) {
        return b == n / 2 && j == n / 2 && a < n / 2 ? above[static_cast<std::size_t>(a)] : id(a, b);
      };
      faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      faces.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  }
  return mesh_from_lists(vertices, faces);
}

}  // namespace geodual::test
