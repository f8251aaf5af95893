#pragma once
// Test support for the geodesic-engine suites: a private reader for the shared
// binary PLY files (independent of geodual_io), deterministic random numbers,
// site sampling, mesh topology helpers, and generators of meshes whose
// geodesic distances are known in closed form (flat square, L-shaped plate,
// prism "cylinder", cube, cone with a convex or saddle apex).

#include "geodual/mesh/random.hpp"
#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace geodual::test {

// ---------------------------------------------------------------------------
// Test meshes

/// tests/data relative to the repository root (tests run there).
std::filesystem::path test_mesh_dir();
/// test_mesh_dir() / file.
std::filesystem::path test_mesh_path(const std::string& file);
/// The *.ply files of test_mesh_dir(), sorted by name.
std::vector<std::string> test_mesh_files();

/// Reads the test meshes' fixed PLY layout (binary little endian, x y z as
/// float or double, faces as `list uchar int`) without geodual_io, so that the
/// oracle tests do not depend on the reader under test. Throws
/// std::runtime_error on anything else.
TriangleMesh read_test_ply(const std::filesystem::path& path);

// ---------------------------------------------------------------------------
// Deterministic random numbers (the same sequence on every standard library)

/// The library's SplitMix64 with the draws these tests use.
class Rng : public SplitMix64 {
 public:
  using SplitMix64::SplitMix64;
  using SplitMix64::uniform;  ///< [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// [0, n)
  std::int64_t below(std::int64_t n) {
    return static_cast<std::int64_t>(SplitMix64::below(static_cast<std::uint64_t>(n)));
  }
};

// ---------------------------------------------------------------------------
// Mesh facts

double bbox_diagonal(const TriangleMesh& mesh);
/// True for a face whose three vertex indices are distinct.
bool face_takes_part(const TriangleMesh& mesh, Index face);
/// Per vertex: referenced by at least one face with three distinct indices.
std::vector<bool> referenced_vertices(const TriangleMesh& mesh);
/// Per vertex: component id (union of the corners of faces that take part);
/// vertices referenced by no such face get a component of their own.
std::vector<Index> vertex_components(const TriangleMesh& mesh);
/// Unique undirected edges {a < b} of the faces that take part.
std::vector<std::array<Index, 2>> unique_edges(const TriangleMesh& mesh);

/// `count` distinct referenced vertices, no two at the same position.
std::vector<SurfacePoint> random_vertex_sites(const TriangleMesh& mesh, int count, std::uint64_t seed);
/// `count` points strictly inside random faces of positive area (barycentric
/// coordinates at least 0.05 each), in distinct faces.
std::vector<SurfacePoint> random_face_sites(const TriangleMesh& mesh, int count, std::uint64_t seed);

// ---------------------------------------------------------------------------
// Analytic meshes. Each carries a function giving the exact geodesic distance
// between two surface points of the *polyhedral* surface.

/// Unit square z = 0 on an n x n grid, interior vertices jittered by up to
/// `jitter` cells, diagonals alternating. Geodesic = Euclidean distance.
TriangleMesh flat_square(int n, double jitter, std::uint64_t seed);

/// A flat square on an n x n grid (n a power of two, so that coordinates and
/// midpoints are exact in binary) where `count` cells get a vertex m at the
/// exact midpoint of their diagonal a-c and the triangles (a, b, m), (m, b, c),
/// (a, m, c), (a, c, d): the third one has distinct vertices and exactly zero
/// area, and the mesh stays an oriented manifold. Vertices not on such a
/// diagonal are jittered. The new vertices m are listed in `midpoints`.
struct ZeroAreaSquare {
  TriangleMesh mesh;
  std::vector<Index> midpoints;
  std::vector<Index> zero_area_faces;
};
ZeroAreaSquare flat_square_with_zero_area_faces(int n, int count, double jitter, std::uint64_t seed);

/// Non-manifold surfaces with exact distances.
///
/// Book: `pages` flat rectangles [0,1] x [0,height] (n x m cells, interior
/// vertices jittered) sharing the spine from (0,0,0) to (1,0,0), page k turned
/// by 2 pi k / pages about the x axis. Spine edges have `pages` faces, so
/// (engine contract) their interiors cannot be crossed and paths change page
/// only through spine vertices: between pages the distance is the minimum of
/// |s e| + |e p| over spine vertices e; within a page it is straight (every
/// page is convex).
///
/// Bowtie (pages == 0 is not used): two unit squares z = 0, [0,1]^2 and
/// [-1,0]^2, sharing only the vertex at the origin (a pinch vertex): between
/// the squares the distance is |s o| + |o p|.
struct NonManifold {
  TriangleMesh mesh;
  std::vector<Index> vertex_page;  ///< -1 for the shared vertices (spine or pinch)
  std::vector<Index> face_page;
  std::vector<Index> shared;  ///< the spine or pinch vertices
  bool spine = false;         ///< book: every point of the x axis is shared
  double distance(const SurfacePoint& a, const SurfacePoint& b) const;
};
NonManifold book(int pages, int n, int m, double height, double jitter, std::uint64_t seed);
NonManifold bowtie(int n, double jitter, std::uint64_t seed);

/// The plate [0,2]^2 minus the open square (1,2)^2: a flat L with one reflex
/// boundary corner at (1,1); cells of size 1/n, interior vertices jittered.
TriangleMesh l_shape(int n, double jitter, std::uint64_t seed);
/// Exact geodesic distance inside that L: straight when the segment stays in
/// the plate, else through the reflex corner (1, 1).
double l_shape_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Open prism with `sides` vertical rectangles of a regular polygon of
/// circumradius `radius`, height `height`, `rings` + 1 rows of vertices (the
/// two boundary rows at z = 0 and z = height exactly, interior rows jittered
/// per vertex in z). Every side is exactly planar, so the surface unrolls
/// isometrically onto a periodic strip.
struct Prism {
  TriangleMesh mesh;
  std::vector<Index> face_side;      ///< side (rectangle) of each face
  std::vector<Index> vertex_column;  ///< polygon corner of each vertex
  std::vector<double> column_s;      ///< unrolled abscissa of each corner (column_s[0] = 0)
  double perimeter = 0;              ///< unrolled period
  /// Unrolled (s, z) of a point.
  Eigen::Vector2d unroll(const SurfacePoint& p) const;
  double distance(const SurfacePoint& a, const SurfacePoint& b) const;
};
Prism prism(int sides, int rings, double radius, double height, double jitter, std::uint64_t seed);

/// The cube [0,1]^3, each square face on an n x n grid with interior vertices
/// jittered within the face plane. distance() enumerates the unfoldings of
/// simple sequences of cube faces (shortest paths on a convex polyhedron avoid
/// vertices and enter each face at most once).
struct Cube {
  TriangleMesh mesh;
  std::vector<int> face_square;  ///< cube face (0..5) of each mesh face
  double distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
};
Cube cube(int n, double jitter, std::uint64_t seed);

/// A polyhedral cone: apex vertex 0 at the origin, `rulings` straight rulings
/// (even count), `rings` rings of vertices along them (interior rings jittered
/// along the rulings, the outer ring at `radius` exactly). Each sector between
/// two rulings is planar, so the surface is flat except at the apex, whose
/// angle sum is `apex_angle` (rulings alternate up and down to get more than
/// 2 pi: a saddle apex). Exact distance: in intrinsic polar coordinates
/// (r, phi), with delta the angular separation, the straight segment when
/// delta < pi, else r1 + r2 through the apex.
struct Cone {
  TriangleMesh mesh;
  std::vector<Index> face_sector;    ///< sector k lies between rulings k and k + 1 (mod count)
  std::vector<Index> vertex_ruling;  ///< -1 for the apex
  std::vector<double> ruling_phi;    ///< intrinsic angle of each ruling
  std::vector<Eigen::Vector3d> ruling_dir;
  double total_angle = 0;                              ///< the apex angle sum, from the built coordinates
  Eigen::Vector2d polar(const SurfacePoint& p) const;  ///< (r, phi)
  double distance(const SurfacePoint& a, const SurfacePoint& b) const;
};
Cone cone(int rulings, int rings, double radius, double apex_angle, double jitter, std::uint64_t seed);

}  // namespace geodual::test
