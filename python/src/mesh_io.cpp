// read_mesh and write_mesh: geodual's readers and writers on numpy arrays.

#include "arrays.hpp"
#include "bindings.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/gltf.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>
#include <utility>

namespace geodual::python {
namespace {

py::object read_mesh(const std::filesystem::path& path, bool colors) {
  io::LoadedMesh loaded;
  {
    py::gil_scoped_release release;
    loaded = io::read_mesh(path);
  }
  py::array_t<double> vertices = vertices_to_array(loaded.mesh.vertices);
  py::array_t<Index> faces = faces_to_array(loaded.mesh.faces);
  if (!colors) return py::make_tuple(std::move(vertices), std::move(faces));
  const ColorMatrix& c = loaded.attributes.colors;
  return py::make_tuple(std::move(vertices), std::move(faces),
                        c.rows() > 0 ? py::object(colors_to_array(c)) : py::object(py::none()));
}

io::GltfCompression compression_from_name(const std::string& name, const std::filesystem::path& path) {
  io::GltfCompression compression = io::GltfCompression::none;
  if (name == "meshopt") {
    compression = io::GltfCompression::meshopt;
  } else if (name == "draco") {
    compression = io::GltfCompression::draco;
  } else if (name != "none") {
    throw UsageError("write_mesh: compress='" + name + "' is not one of 'none', 'meshopt', 'draco'");
  }
  const std::string extension = io::lowercase_extension(path);
  if (compression != io::GltfCompression::none && extension != ".glb" && extension != ".gltf") {
    throw UsageError("write_mesh: compress='" + name + "' compresses glTF; " + path.string() + " is not .glb or .gltf");
  }
  return compression;
}

void write_mesh(const std::filesystem::path& path, const py::handle& vertices, const py::handle& faces,
                const py::handle& colors, const std::string& compress) {
  const io::GltfCompression compression = compression_from_name(compress, path);
  const TriangleMesh mesh = mesh_from_arrays(vertices, faces);
  VertexAttributes attributes;
  if (!colors.is_none()) {
    attributes.colors = colors_from_array(colors, mesh.num_vertices());
    attributes.color_type = ValueType::uint8;
  }
  py::gil_scoped_release release;
  if (compression != io::GltfCompression::none) {
    io::write_gltf(path, mesh, attributes, compression);
  } else {
    io::write_mesh(path, mesh, attributes);
  }
}

}  // namespace

void add_mesh_io(py::module_& module) {
  module.def("read_mesh", &read_mesh, py::arg("path"), py::arg("colors") = false,
             R"(Read a triangle mesh: OBJ, PLY, OFF, STL, glTF or GLB, chosen by the extension.

Returns (V, F): V the vertex positions, float64 n x 3; F the triangles, int32
m x 3 (indices into V, counter-clockwise seen from outside). Vertices are kept
exactly as the file stores them (order and count, unreferenced ones too);
polygons are split into triangles.

With colors=True returns (V, F, C): C the per-vertex colours as the file
stores them (sRGB, not linear), float32 n x 3 (RGB) or n x 4 (RGBA) in [0, 1],
or None when the file has none.

Raises geodual.Error, whose message names the file and what is wrong (a
missing file, a bad header, an index out of range...).

Example:
    V, F = geodual.read_mesh("scan.ply")
)");
  module.def("write_mesh", &write_mesh, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("colors") = py::none(),
             py::arg("compress") = "none",
             R"(Write a triangle mesh by extension: .ply (binary), .obj, .glb or .gltf.

V: n x 3 vertex positions (any real or integer dtype, finite); F: m x 3 vertex
indices (integers in [0, n)); colors: None or n x 3 / n x 4 per-vertex colours,
floats in [0, 1] or uint8, stored as 8-bit colours where the format has room.
The file is written to a temporary name and renamed: a failure leaves no
partial file.

compress: "none", or for .glb/.gltf "meshopt" (EXT_meshopt_compression with
KHR_mesh_quantization) or "draco" (KHR_draco_mesh_compression), as
`geodual remesh --compress` writes them; only viewers with the extension read
such files, and geodual.read_mesh refuses them.

Raises ValueError for bad shapes, non-finite coordinates or indices out of
range, TypeError for non-numeric arrays, geodual.UsageError (a ValueError)
for an unknown compress or one with a non-glTF path, geodual.Error for what
the writer refuses (an unknown extension, a folder that does not exist).
)");
}

}  // namespace geodual::python
