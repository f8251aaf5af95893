#include "voronoi/test_meshes.hpp"

#include "geodual/mesh/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace geodual::test {

namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Vector3d vertex(const TriangleMesh& mesh, Index v) { return mesh.vertices.row(v).transpose(); }

TriangleMesh to_mesh(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<Index, 3>>& tris) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  mesh.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) {
    for (int c = 0; c < 3; ++c) mesh.faces(static_cast<Eigen::Index>(i), c) = tris[i][static_cast<std::size_t>(c)];
  }
  return mesh;
}

/// Splits the quad a b c d (counter-clockwise seen from outside) into two
/// triangles along a-c or b-d.
void add_quad(std::vector<std::array<Index, 3>>& tris, Index a, Index b, Index c, Index d, bool diagonal_ac) {
  if (diagonal_ac) {
    tris.push_back({a, b, c});
    tris.push_back({a, c, d});
  } else {
    tris.push_back({a, b, d});
    tris.push_back({b, c, d});
  }
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// The faces of one page: an n x m grid of quads over the vertex ids `id`
/// (row-major, (n + 1) per row), two triangles each, both tagged with page k.
void add_page_faces(const std::vector<Index>& id, int n, int m, Index k, std::vector<std::array<Index, 3>>& tris,
                    std::vector<Index>& face_page) {
  const auto at = [&](int a, int b) { return id[static_cast<std::size_t>(b * (n + 1) + a)]; };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      add_quad(tris, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), (i + j) % 2 == 0);
      face_page.push_back(k);
      face_page.push_back(k);
    }
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// Test meshes

std::filesystem::path test_mesh_dir() { return std::filesystem::path("tests") / "data"; }

std::filesystem::path test_mesh_path(const std::string& file) { return test_mesh_dir() / file; }

std::vector<std::string> test_mesh_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(test_mesh_dir())) {
    if (entry.is_regular_file() && entry.path().extension() == ".ply")
      files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TriangleMesh read_test_ply(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  auto fail = [&](const std::string& what) { throw std::runtime_error(path.string() + ": " + what); };

  std::string line;
  std::getline(in, line);
  if (line != "ply") fail("not a PLY file");
  std::int64_t num_vertices = -1, num_faces = -1;
  int coord_bytes = 0;
  int vertex_properties = 0;
  std::string current;
  bool little_endian = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string format;
      words >> format;
      little_endian = format == "binary_little_endian";
    } else if (keyword == "element") {
      std::int64_t count = 0;
      words >> current >> count;
      if (current == "vertex")
        num_vertices = count;
      else if (current == "face")
        num_faces = count;
      else
        fail("unexpected element " + current);
    } else if (keyword == "property") {
      std::string type, name;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> name;
        if (current != "face" || count_type != "uchar" || item_type != "int") fail("unexpected list property");
      } else {
        words >> name;
        if (current != "vertex") fail("unexpected face property");
        const int bytes = (type == "float" || type == "float32") ? 4 : (type == "double" || type == "float64") ? 8 : 0;
        if (bytes == 0 || (coord_bytes != 0 && bytes != coord_bytes)) fail("unexpected vertex property type " + type);
        coord_bytes = bytes;
        static const char* const expected[] = {"x", "y", "z"};
        if (vertex_properties >= 3 || name != expected[vertex_properties]) fail("unexpected vertex property " + name);
        ++vertex_properties;
      }
    }
  }
  if (!little_endian || num_vertices < 0 || num_faces < 0 || vertex_properties != 3) fail("unsupported header");

  TriangleMesh mesh;
  mesh.vertices.resize(num_vertices, 3);
  std::vector<char> buffer(static_cast<std::size_t>(num_vertices) * 3 * static_cast<std::size_t>(coord_bytes));
  in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  if (!in) fail("truncated vertex data");
  for (std::int64_t v = 0; v < num_vertices; ++v) {
    for (int c = 0; c < 3; ++c) {
      const char* at = buffer.data() + (static_cast<std::size_t>(v) * 3 + static_cast<std::size_t>(c)) *
                                           static_cast<std::size_t>(coord_bytes);
      double value = 0;
      if (coord_bytes == 4) {
        float f = 0;
        std::memcpy(&f, at, 4);
        value = f;
      } else {
        std::memcpy(&value, at, 8);
      }
      mesh.vertices(v, c) = value;
    }
  }
  mesh.faces.resize(num_faces, 3);
  for (std::int64_t f = 0; f < num_faces; ++f) {
    unsigned char count = 0;
    in.read(reinterpret_cast<char*>(&count), 1);
    if (!in || count != 3) fail("face " + std::to_string(f) + " is not a triangle");
    std::int32_t idx[3];
    in.read(reinterpret_cast<char*>(idx), sizeof idx);
    if (!in) fail("truncated face data");
    for (int c = 0; c < 3; ++c) {
      if (idx[c] < 0 || idx[c] >= num_vertices) fail("face " + std::to_string(f) + " index out of range");
      mesh.faces(f, c) = idx[c];
    }
  }
  return mesh;
}

// ---------------------------------------------------------------------------
// Mesh facts

double bbox_diagonal(const TriangleMesh& mesh) {
  const auto referenced = referenced_vertices(mesh);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (!referenced[v]) continue;
    lo = lo.cwiseMin(vertex(mesh, v));
    hi = hi.cwiseMax(vertex(mesh, v));
  }
  return (hi - lo).norm();
}

bool face_takes_part(const TriangleMesh& mesh, Index f) {
  const Index a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  return a != b && b != c && a != c;
}

std::vector<bool> referenced_vertices(const TriangleMesh& mesh) {
  std::vector<bool> referenced(static_cast<std::size_t>(mesh.num_vertices()), false);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!face_takes_part(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) referenced[mesh.faces(f, c)] = true;
  }
  return referenced;
}

std::vector<Index> vertex_components(const TriangleMesh& mesh) {
  UnionFind uf(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!face_takes_part(mesh, f)) continue;
    uf.unite(mesh.faces(f, 0), mesh.faces(f, 1));
    uf.unite(mesh.faces(f, 0), mesh.faces(f, 2));
  }
  std::vector<Index> component(static_cast<std::size_t>(mesh.num_vertices()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) component[v] = uf.find(v);
  return component;
}

std::vector<std::array<Index, 2>> unique_edges(const TriangleMesh& mesh) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(static_cast<std::size_t>(mesh.num_faces()) * 3);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!face_takes_part(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index a = mesh.faces(f, c), b = mesh.faces(f, (c + 1) % 3);
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<SurfacePoint> random_vertex_sites(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  const auto referenced = referenced_vertices(mesh);
  std::vector<Index> candidates;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (referenced[v]) candidates.push_back(v);
  }
  if (static_cast<std::size_t>(count) > candidates.size()) throw std::runtime_error("too many sites asked for");
  Rng rng(seed);
  std::set<Index> chosen;
  std::set<std::tuple<double, double, double>> positions;
  std::vector<SurfacePoint> sites;
  int attempts = 0;
  while (static_cast<int>(sites.size()) < count) {
    if (++attempts > 100 * count + 1000) throw std::runtime_error("cannot find distinct vertex sites");
    const Index v = candidates[static_cast<std::size_t>(rng.below(static_cast<std::int64_t>(candidates.size())))];
    const auto key = std::make_tuple(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
    if (chosen.count(v) || positions.count(key)) continue;
    chosen.insert(v);
    positions.insert(key);
    sites.push_back(SurfacePoint::at_vertex(v));
  }
  return sites;
}

std::vector<SurfacePoint> random_face_sites(const TriangleMesh& mesh, int count, std::uint64_t seed) {
  Rng rng(seed);
  std::set<Index> chosen;
  std::vector<SurfacePoint> sites;
  int attempts = 0;
  while (static_cast<int>(sites.size()) < count) {
    if (++attempts > 100 * count + 1000) throw std::runtime_error("cannot find face sites");
    const Index f = static_cast<Index>(rng.below(mesh.num_faces()));
    if (chosen.count(f) || !face_takes_part(mesh, f)) continue;
    const Eigen::Vector3d a = vertex(mesh, mesh.faces(f, 0)), b = vertex(mesh, mesh.faces(f, 1)),
                          c = vertex(mesh, mesh.faces(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!(area > 1e-3 * longest * longest)) continue;  // skip needle and zero-area faces
    double u = 0, v = 0, w = 0;
    do {
      u = rng.uniform(0.05, 0.9);
      v = rng.uniform(0.05, 0.9);
      w = 1.0 - u - v;
    } while (w < 0.05);
    chosen.insert(f);
    sites.push_back(SurfacePoint::in_face(f, u, v, w));
  }
  return sites;
}

// ---------------------------------------------------------------------------
// Flat square and L

TriangleMesh flat_square(int n, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Vector3d> points;
  auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      if (i > 0 && i < n && j > 0 && j < n) {
        x += jitter / n * rng.uniform(-1, 1);
        y += jitter / n * rng.uniform(-1, 1);
      }
      points.emplace_back(x, y, 0.0);
    }
  }
  std::vector<std::array<Index, 3>> tris;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i)
      add_quad(tris, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
  }
  return to_mesh(points, tris);
}

ZeroAreaSquare flat_square_with_zero_area_faces(int n, int count, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  std::vector<Eigen::Vector3d> points;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) points.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n, 0.0);
  }
  // Interior cells with the diagonal a-c, no two sharing a corner.
  std::vector<bool> used(points.size(), false), chosen(static_cast<std::size_t>(n * n), false);
  int made = 0, attempts = 0;
  while (made < count && attempts++ < 100 * count) {
    const int i = 1 + static_cast<int>(rng.below(n - 2)), j = 1 + static_cast<int>(rng.below(n - 2));
    if ((i + j) % 2 != 0) continue;
    const Index corners[4] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
    bool free = true;
    for (Index c : corners) free = free && !used[static_cast<std::size_t>(c)];
    if (!free) continue;
    for (Index c : corners) used[static_cast<std::size_t>(c)] = true;
    chosen[static_cast<std::size_t>(j * n + i)] = true;
    ++made;
  }
  // Jitter every interior vertex that is not the end of a split diagonal.
  std::vector<bool> fixed(points.size(), false);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (!chosen[static_cast<std::size_t>(j * n + i)]) continue;
      fixed[static_cast<std::size_t>(id(i, j))] = fixed[static_cast<std::size_t>(id(i + 1, j + 1))] = true;
    }
  }
  for (int j = 1; j < n; ++j) {
    for (int i = 1; i < n; ++i) {
      const auto v = static_cast<std::size_t>(id(i, j));
      if (fixed[v]) continue;
      points[v].x() += jitter / n * rng.uniform(-1, 1);
      points[v].y() += jitter / n * rng.uniform(-1, 1);
    }
  }
  ZeroAreaSquare out;
  std::vector<std::array<Index, 3>> tris;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (!chosen[static_cast<std::size_t>(j * n + i)]) {
        add_quad(tris, a, b, c, d, (i + j) % 2 == 0);
        continue;
      }
      const Index m = static_cast<Index>(points.size());
      points.push_back(0.5 * (points[static_cast<std::size_t>(a)] + points[static_cast<std::size_t>(c)]));
      out.midpoints.push_back(m);
      tris.push_back({a, b, m});
      tris.push_back({m, b, c});
      out.zero_area_faces.push_back(static_cast<Index>(tris.size()));
      tris.push_back({a, m, c});
      tris.push_back({a, c, d});
    }
  }
  out.mesh = to_mesh(points, tris);
  return out;
}

TriangleMesh l_shape(int n, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  const int m = 2 * n;
  std::vector<Index> id(static_cast<std::size_t>((m + 1) * (m + 1)), -1);
  std::vector<Eigen::Vector3d> points;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= m; ++i) {
      if (i > n && j > n) continue;
      const bool boundary = i == 0 || j == 0 || i == m || j == m || (i == n && j >= n) || (j == n && i >= n);
      double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      if (!boundary) {
        x += jitter / n * rng.uniform(-1, 1);
        y += jitter / n * rng.uniform(-1, 1);
      }
      id[static_cast<std::size_t>(j * (m + 1) + i)] = static_cast<Index>(points.size());
      points.emplace_back(x, y, 0.0);
    }
  }
  auto at = [&](int i, int j) { return id[static_cast<std::size_t>(j * (m + 1) + i)]; };
  std::vector<std::array<Index, 3>> tris;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      if (i >= n && j >= n) continue;
      add_quad(tris, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), (i + j) % 2 == 0);
    }
  }
  return to_mesh(points, tris);
}

double l_shape_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // Does the segment a-b meet the open square (1,2) x (1,2)?
  double t0 = 0, t1 = 1;
  bool blocked = true;
  for (int axis = 0; axis < 2 && blocked; ++axis) {
    const double p = a[axis], d = b[axis] - a[axis];
    if (d == 0) {
      if (!(p > 1 && p < 2)) blocked = false;
      continue;
    }
    double lo = (1 - p) / d, hi = (2 - p) / d;
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
  }
  blocked = blocked && t1 > t0;
  if (!blocked) return (a - b).head<2>().norm();
  const Eigen::Vector2d corner(1, 1);
  return (a.head<2>() - corner).norm() + (b.head<2>() - corner).norm();
}

// ---------------------------------------------------------------------------
// Non-manifold surfaces

NonManifold book(int pages, int n, int m, double height, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  NonManifold out;
  out.spine = true;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= n; ++i) {
    out.shared.push_back(static_cast<Index>(points.size()));
    out.vertex_page.push_back(-1);
    points.emplace_back(static_cast<double>(i) / n, 0.0, 0.0);
  }
  std::vector<std::array<Index, 3>> tris;
  for (int k = 0; k < pages; ++k) {
    const double theta = 2 * kPi * k / pages;
    std::vector<Index> id(static_cast<std::size_t>((n + 1) * (m + 1)));
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= n; ++i) {
        if (j == 0) {
          id[static_cast<std::size_t>(i)] = static_cast<Index>(i);
          continue;
        }
        double x = static_cast<double>(i) / n, r = height * j / m;
        if (i > 0 && i < n && j < m) {
          x += jitter / n * rng.uniform(-1, 1);
          r += jitter * height / m * rng.uniform(-1, 1);
        }
        id[static_cast<std::size_t>(j * (n + 1) + i)] = static_cast<Index>(points.size());
        out.vertex_page.push_back(k);
        points.emplace_back(x, r * std::cos(theta), r * std::sin(theta));
      }
    }
    add_page_faces(id, n, m, k, tris, out.face_page);
  }
  out.mesh = to_mesh(points, tris);
  return out;
}

NonManifold bowtie(int n, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  NonManifold out;
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero()};
  out.vertex_page.push_back(-1);
  out.shared.push_back(0);
  std::vector<std::array<Index, 3>> tris;
  for (int k = 0; k < 2; ++k) {
    const double sign = k == 0 ? 1.0 : -1.0;
    std::vector<Index> id(static_cast<std::size_t>((n + 1) * (n + 1)));
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        if (i == 0 && j == 0) {
          id[0] = 0;
          continue;
        }
        double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
        if (i > 0 && i < n && j > 0 && j < n) {
          x += jitter / n * rng.uniform(-1, 1);
          y += jitter / n * rng.uniform(-1, 1);
        }
        id[static_cast<std::size_t>(j * (n + 1) + i)] = static_cast<Index>(points.size());
        out.vertex_page.push_back(k);
        points.emplace_back(sign * x, sign * y, 0.0);
      }
    }
    add_page_faces(id, n, n, k, tris, out.face_page);
  }
  out.mesh = to_mesh(points, tris);
  return out;
}

double NonManifold::distance(const SurfacePoint& a, const SurfacePoint& b) const {
  // Shared points (on the spine, or the pinch vertex) belong to every page.
  auto page = [&](const SurfacePoint& p, const Eigen::Vector3d& x) {
    if (p.kind == SurfacePoint::Kind::vertex) return vertex_page[static_cast<std::size_t>(p.element)];
    if (spine ? (x.y() == 0 && x.z() == 0) : x.isZero()) return Index{-1};
    return face_page[static_cast<std::size_t>(p.element)];
  };
  const Eigen::Vector3d pa = a.position(mesh), pb = b.position(mesh);
  const Index ka = page(a, pa), kb = page(b, pb);
  if (ka < 0 || kb < 0 || ka == kb) return (pa - pb).norm();
  double best = std::numeric_limits<double>::infinity();
  for (Index e : shared) {
    const Eigen::Vector3d pe = mesh.vertices.row(e).transpose();
    best = std::min(best, (pa - pe).norm() + (pe - pb).norm());
  }
  return best;
}

// ---------------------------------------------------------------------------
// Prism

Prism prism(int sides, int rings, double radius, double height, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  Prism out;
  std::vector<Eigen::Vector2d> corner(static_cast<std::size_t>(sides));
  for (int k = 0; k < sides; ++k) {
    const double t = 2 * kPi * k / sides;
    corner[static_cast<std::size_t>(k)] = Eigen::Vector2d(radius * std::cos(t), radius * std::sin(t));
  }
  std::vector<Eigen::Vector3d> points;
  auto id = [sides](int j, int k) { return static_cast<Index>(j * sides + (k % sides)); };
  for (int j = 0; j <= rings; ++j) {
    for (int k = 0; k < sides; ++k) {
      double z = height * j / rings;
      if (j > 0 && j < rings) z += jitter * height / rings * rng.uniform(-1, 1);
      const auto& c = corner[static_cast<std::size_t>(k)];
      points.emplace_back(c.x(), c.y(), z);
      out.vertex_column.push_back(k);
    }
  }
  std::vector<std::array<Index, 3>> tris;
  for (int j = 0; j < rings; ++j) {
    for (int k = 0; k < sides; ++k) {
      add_quad(tris, id(j, k), id(j, k + 1), id(j + 1, k + 1), id(j + 1, k), (j + k) % 2 == 0);
      out.face_side.push_back(k);
      out.face_side.push_back(k);
    }
  }
  out.mesh = to_mesh(points, tris);
  out.column_s.assign(static_cast<std::size_t>(sides) + 1, 0.0);
  for (int k = 0; k < sides; ++k) {
    out.column_s[static_cast<std::size_t>(k) + 1] =
        out.column_s[static_cast<std::size_t>(k)] +
        (corner[static_cast<std::size_t>((k + 1) % sides)] - corner[static_cast<std::size_t>(k)]).norm();
  }
  out.perimeter = out.column_s.back();
  out.column_s.pop_back();
  return out;
}

Eigen::Vector2d Prism::unroll(const SurfacePoint& p) const {
  const Eigen::Vector3d x = p.position(mesh);
  if (p.kind == SurfacePoint::Kind::vertex)
    return {column_s[static_cast<std::size_t>(vertex_column[p.element])], x.z()};
  const Index k = face_side[p.element];
  const Index sides = static_cast<Index>(column_s.size());
  const Eigen::Vector2d a = mesh.vertices.row(k).head<2>().transpose();
  const Eigen::Vector2d b = mesh.vertices.row((k + 1) % sides).head<2>().transpose();
  const double s = column_s[static_cast<std::size_t>(k)] + (x.head<2>() - a).dot((b - a).normalized());
  return {s, x.z()};
}

double Prism::distance(const SurfacePoint& a, const SurfacePoint& b) const {
  const Eigen::Vector2d pa = unroll(a), pb = unroll(b);
  const double ds = pa.x() - pb.x(), dz = pa.y() - pb.y();
  double best = std::numeric_limits<double>::infinity();
  for (int m = -1; m <= 1; ++m) best = std::min(best, std::hypot(ds + m * perimeter, dz));
  return best;
}

// ---------------------------------------------------------------------------
// Cube

namespace {

struct Square {
  std::array<Eigen::Vector3d, 4> corners;  // cyclic
  int axis = 0;
  double value = 0;
  bool contains(const Eigen::Vector3d& p) const {
    constexpr double tol = 1e-12;
    if (std::abs(p[axis] - value) > tol) return false;
    for (int a = 0; a < 3; ++a) {
      if (a != axis && (p[a] < -tol || p[a] > 1 + tol)) return false;
    }
    return true;
  }
};

std::array<Square, 6> cube_squares() {
  std::array<Square, 6> squares;
  for (int id = 0; id < 6; ++id) {
    Square& s = squares[static_cast<std::size_t>(id)];
    s.axis = id / 2;
    s.value = id % 2;
    const int u = (s.axis + 1) % 3, v = (s.axis + 2) % 3;
    const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int c = 0; c < 4; ++c) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      p[s.axis] = s.value;
      p[u] = uv[c][0];
      p[v] = uv[c][1];
      s.corners[static_cast<std::size_t>(c)] = p;
    }
  }
  return squares;
}

/// An isometry from a square's plane to the unfolding plane.
struct Unfold {
  Eigen::Vector3d origin3, d3, m3;  // origin, unit in-plane axes
  Eigen::Vector2d origin2, d2, m2;
  Eigen::Vector2d operator()(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d r = x - origin3;
    return origin2 + d2 * r.dot(d3) + m2 * r.dot(m3);
  }
};

Eigen::Vector3d centroid(const Square& s) { return 0.25 * (s.corners[0] + s.corners[1] + s.corners[2] + s.corners[3]); }

Unfold unfold_across(const Square& g, const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Unfold& current,
                     const Eigen::Vector2d& current_centroid2) {
  Unfold next;
  next.origin3 = p;
  next.d3 = (q - p).normalized();
  Eigen::Vector3d m = centroid(g) - p;
  m -= m.dot(next.d3) * next.d3;
  next.m3 = m.normalized();
  next.origin2 = current(p);
  next.d2 = (current(q) - next.origin2).normalized();
  Eigen::Vector2d perp(-next.d2.y(), next.d2.x());
  if (perp.dot(current_centroid2 - next.origin2) > 0) perp = -perp;
  next.m2 = perp;
  return next;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

double Cube::distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  static const std::array<Square, 6> squares = cube_squares();
  double best = std::numeric_limits<double>::infinity();
  struct Edge2 {
    Eigen::Vector2d p, q;
  };
  std::vector<Edge2> crossed;
  std::array<bool, 6> used{};

  // The segment s -> t must cross every entry edge, in order.
  auto valid = [&](const Eigen::Vector2d& s, const Eigen::Vector2d& t) {
    constexpr double tol = 1e-12;
    double last = 0;
    const Eigen::Vector2d d = t - s;
    for (const Edge2& e : crossed) {
      const Eigen::Vector2d f = e.q - e.p;
      const double den = cross2(d, f);
      if (std::abs(den) < 1e-300) return false;
      const double tt = cross2(e.p - s, f) / den;  // along s -> t
      const double uu = cross2(e.p - s, d) / den;  // along the edge
      if (uu < -tol || uu > 1 + tol || tt < last - tol || tt > 1 + tol) return false;
      last = tt;
    }
    return true;
  };

  std::function<void(int, const Unfold&, const Eigen::Vector2d&)> visit = [&](int f, const Unfold& map,
                                                                              const Eigen::Vector2d& s2) {
    const Square& sq = squares[static_cast<std::size_t>(f)];
    if (sq.contains(b)) {
      const Eigen::Vector2d t2 = map(b);
      if ((t2 - s2).norm() < best && valid(s2, t2)) best = (t2 - s2).norm();
    }
    const Eigen::Vector2d c2 = map(centroid(sq));
    for (int e = 0; e < 4; ++e) {
      const Eigen::Vector3d& p = sq.corners[static_cast<std::size_t>(e)];
      const Eigen::Vector3d& q = sq.corners[static_cast<std::size_t>((e + 1) % 4)];
      for (int g = 0; g < 6; ++g) {
        if (used[static_cast<std::size_t>(g)]) continue;
        const Square& other = squares[static_cast<std::size_t>(g)];
        if (!other.contains(p) || !other.contains(q)) continue;
        const Unfold next = unfold_across(other, p, q, map, c2);
        // A longer path through more faces cannot beat `best` if the edge is
        // already farther away than best.
        used[static_cast<std::size_t>(g)] = true;
        crossed.push_back({map(p), map(q)});
        visit(g, next, s2);
        crossed.pop_back();
        used[static_cast<std::size_t>(g)] = false;
      }
    }
  };

  for (int f = 0; f < 6; ++f) {
    const Square& sq = squares[static_cast<std::size_t>(f)];
    if (!sq.contains(a)) continue;
    Unfold map;
    map.origin3 = sq.corners[0];
    map.d3 = (sq.corners[1] - sq.corners[0]).normalized();
    map.m3 = (sq.corners[3] - sq.corners[0]).normalized();
    map.origin2 = Eigen::Vector2d::Zero();
    map.d2 = Eigen::Vector2d(1, 0);
    map.m2 = Eigen::Vector2d(0, 1);
    used.fill(false);
    used[static_cast<std::size_t>(f)] = true;
    visit(f, map, map(a));
  }
  return best;
}

Cube cube(int n, double jitter, std::uint64_t seed) {
  Rng rng(seed);
  Cube out;
  const auto squares = cube_squares();
  std::vector<Eigen::Vector3d> points;
  std::vector<Index> grid_id(static_cast<std::size_t>((n + 1) * (n + 1) * (n + 1)), -1);
  auto grid_index = [n](int i, int j, int k) { return static_cast<std::size_t>((k * (n + 1) + j) * (n + 1) + i); };
  std::vector<std::array<Index, 3>> tris;
  for (int s = 0; s < 6; ++s) {
    const Square& sq = squares[static_cast<std::size_t>(s)];
    const int u = (sq.axis + 1) % 3, v = (sq.axis + 2) % 3;
    // The face's u x v orientation is outward for value 1, inward for value 0.
    const bool outward = sq.value == 1;
    auto id = [&](int i, int j) {
      int g[3];
      g[sq.axis] = sq.value == 1 ? n : 0;
      g[u] = i;
      g[v] = j;
      Index& slot = grid_id[grid_index(g[0], g[1], g[2])];
      if (slot < 0) {
        Eigen::Vector3d p(static_cast<double>(g[0]) / n, static_cast<double>(g[1]) / n, static_cast<double>(g[2]) / n);
        if (i > 0 && i < n && j > 0 && j < n) {
          p[u] += jitter / n * rng.uniform(-1, 1);
          p[v] += jitter / n * rng.uniform(-1, 1);
        }
        slot = static_cast<Index>(points.size());
        points.push_back(p);
      }
      return slot;
    };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const Index a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
        if (outward)
          add_quad(tris, a, b, c, d, (i + j + s) % 2 == 0);
        else
          add_quad(tris, a, d, c, b, (i + j + s) % 2 == 0);
        out.face_square.push_back(s);
        out.face_square.push_back(s);
      }
    }
  }
  out.mesh = to_mesh(points, tris);
  return out;
}

// ---------------------------------------------------------------------------
// Cone

Cone cone(int rulings, int rings, double radius, double apex_angle, double jitter, std::uint64_t seed) {
  if (rulings % 2 != 0) throw std::runtime_error("cone: even ruling count expected");
  Rng rng(seed);
  Cone out;
  const double dt = 2 * kPi / rulings, gamma = apex_angle / rulings;
  double beta = 0;
  bool alternate = false;
  if (apex_angle > 2 * kPi) {
    beta = std::acos(std::sqrt((std::cos(gamma) + 1) / (std::cos(dt) + 1)));
    alternate = true;
  } else if (apex_angle < 2 * kPi) {
    beta = std::acos(std::sqrt((1 - std::cos(gamma)) / (1 - std::cos(dt))));
  }
  for (int k = 0; k < rulings; ++k) {
    const double b = alternate && k % 2 == 1 ? -beta : beta;
    out.ruling_dir.emplace_back(std::cos(k * dt) * std::cos(b), std::sin(k * dt) * std::cos(b), std::sin(b));
  }
  out.ruling_phi.assign(static_cast<std::size_t>(rulings), 0.0);
  for (int k = 0; k < rulings; ++k) {
    const double step = angle_between(out.ruling_dir[static_cast<std::size_t>(k)],
                                      out.ruling_dir[static_cast<std::size_t>((k + 1) % rulings)]);
    if (k + 1 < rulings)
      out.ruling_phi[static_cast<std::size_t>(k) + 1] = out.ruling_phi[static_cast<std::size_t>(k)] + step;
    else
      out.total_angle = out.ruling_phi[static_cast<std::size_t>(k)] + step;
  }

  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero()};
  out.vertex_ruling.push_back(-1);
  auto id = [rulings](int j, int k) { return static_cast<Index>(1 + (j - 1) * rulings + (k % rulings)); };
  for (int j = 1; j <= rings; ++j) {
    for (int k = 0; k < rulings; ++k) {
      double r = radius * j / rings;
      if (j < rings) r += jitter * radius / rings * rng.uniform(-1, 1);
      points.push_back(r * out.ruling_dir[static_cast<std::size_t>(k)]);
      out.vertex_ruling.push_back(k);
    }
  }
  std::vector<std::array<Index, 3>> tris;
  for (int k = 0; k < rulings; ++k) {
    tris.push_back({0, id(1, k), id(1, k + 1)});
    out.face_sector.push_back(k);
  }
  for (int j = 1; j < rings; ++j) {
    for (int k = 0; k < rulings; ++k) {
      add_quad(tris, id(j, k), id(j + 1, k), id(j + 1, k + 1), id(j, k + 1), (j + k) % 2 == 0);
      out.face_sector.push_back(k);
      out.face_sector.push_back(k);
    }
  }
  out.mesh = to_mesh(points, tris);
  return out;
}

Eigen::Vector2d Cone::polar(const SurfacePoint& p) const {
  const Eigen::Vector3d x = p.position(mesh);
  const double r = x.norm();
  if (p.kind == SurfacePoint::Kind::vertex) {
    const Index k = vertex_ruling[p.element];
    return {r, k < 0 ? 0.0 : ruling_phi[static_cast<std::size_t>(k)]};
  }
  if (r == 0) return {0, 0};
  const Index k = face_sector[p.element];
  return {r, ruling_phi[static_cast<std::size_t>(k)] + angle_between(ruling_dir[static_cast<std::size_t>(k)], x)};
}

double Cone::distance(const SurfacePoint& a, const SurfacePoint& b) const {
  const Eigen::Vector2d pa = polar(a), pb = polar(b);
  double delta = std::fmod(std::abs(pa.y() - pb.y()), total_angle);
  delta = std::min(delta, total_angle - delta);
  if (delta >= kPi) return pa.x() + pb.x();
  const double s = std::sin(0.5 * delta);
  const double dr = pa.x() - pb.x();
  return std::sqrt(dr * dr + 4 * pa.x() * pb.x() * s * s);
}

}  // namespace geodual::test
