#pragma once
// The large-mesh tier of the benchmarks: no >= 1M-face scan is stored, so it
// is made at run time by Loop subdivision of a given mesh (igea.ply, 268,686
// faces: one step gives 1,074,744 faces, two give 4,298,976). Files are cached by name, so a
// benchmark calls ensure_subdivided() and pays for the subdivision once.
//
// The files are written with geodual::io::write_ply, which stores float64
// coordinates: a 1.07M-face file is about 27 MB where a float32 scan of the
// same size would be about 21 MB.
//
// Header-only: every bench/*.cpp is its own executable (bench/CMakeLists.txt).

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <cstdint>
#include <filesystem>
#include <string>

namespace geodual::bench {

/// OpenMesh triangle mesh with double positions (the default is float).
struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OpenMeshTriangles = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

/// `mesh` subdivided `levels` times with Loop's scheme (OpenMesh LoopT): each
/// step splits every triangle into four and smooths the positions. Needs a
/// 2-manifold that OpenMesh accepts face by face; throws geodual::Error if not.
inline TriangleMesh loop_subdivide(const TriangleMesh& mesh, int levels) {
  if (levels < 0) throw Error("loop_subdivide: negative number of levels " + std::to_string(levels));
  OpenMeshTriangles om;
  om.reserve(static_cast<std::size_t>(mesh.num_vertices()), 3 * static_cast<std::size_t>(mesh.num_faces()),
             static_cast<std::size_t>(mesh.num_faces()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    om.add_vertex(OpenMeshTriangles::Point(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const auto face = om.add_face(OpenMesh::VertexHandle(mesh.faces(f, 0)), OpenMesh::VertexHandle(mesh.faces(f, 1)),
                                  OpenMesh::VertexHandle(mesh.faces(f, 2)));
    if (!face.is_valid()) {
      throw Error("loop_subdivide: face " + std::to_string(f) +
                  " makes the mesh non-manifold; Loop subdivision needs a clean 2-manifold");
    }
  }

  OpenMesh::Subdivider::Uniform::LoopT<OpenMeshTriangles> loop;
  loop.attach(om);
  loop(static_cast<std::size_t>(levels));
  loop.detach();

  TriangleMesh result;
  result.vertices.resize(static_cast<Eigen::Index>(om.n_vertices()), 3);
  for (const auto v : om.vertices()) {
    const auto& p = om.point(v);
    result.vertices.row(v.idx()) << p[0], p[1], p[2];
  }
  result.faces.resize(static_cast<Eigen::Index>(om.n_faces()), 3);
  for (const auto f : om.faces()) {
    int corner = 0;
    for (const auto v : om.fv_range(f)) result.faces(f.idx(), corner++) = v.idx();
  }
  return result;
}

/// Where ensure_subdivided() keeps `input` subdivided `levels` times:
/// <cache_folder>/<input stem>_loop<levels>.ply.
inline std::filesystem::path subdivided_path(const std::filesystem::path& input, int levels,
                                             const std::filesystem::path& cache_folder) {
  return cache_folder / (input.stem().string() + "_loop" + std::to_string(levels) + ".ply");
}

/// Reads `input`, subdivides it and writes the binary PLY to `output`
/// (atomically; never over the input). Returns the subdivided mesh.
inline TriangleMesh write_subdivided(const std::filesystem::path& input, int levels,
                                     const std::filesystem::path& output) {
  io::refuse_to_overwrite_inputs(output, {input});
  const io::LoadedMesh loaded = io::read_mesh(input);
  TriangleMesh subdivided = loop_subdivide(loaded.mesh, levels);
  const std::int64_t expected_faces = static_cast<std::int64_t>(loaded.mesh.num_faces()) << (2 * levels);
  if (subdivided.num_faces() != expected_faces) {
    throw Error(input.string() + ": Loop subdivision gave " + std::to_string(subdivided.num_faces()) +
                " faces instead of " + std::to_string(expected_faces));
  }
  io::write_ply(output, subdivided);
  return subdivided;
}

/// The path of `input` subdivided `levels` times, generated into
/// `cache_folder` (created if needed) only when it is not there yet.
inline std::filesystem::path ensure_subdivided(const std::filesystem::path& input, int levels,
                                               const std::filesystem::path& cache_folder) {
  const std::filesystem::path output = subdivided_path(input, levels, cache_folder);
  if (!std::filesystem::exists(output)) {
    std::filesystem::create_directories(cache_folder);
    write_subdivided(input, levels, output);
  }
  return output;
}

}  // namespace geodual::bench
