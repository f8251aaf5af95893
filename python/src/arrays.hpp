#pragma once
// Conversions between numpy arrays and geodual's plain data, with the checks
// that give a Python caller a clear error (TypeError for what is not a
// numeric array, ValueError for wrong shapes, non-finite values and indices
// out of range) instead of a crash. Call with the GIL held.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/texture_image.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/mesh/vertex_attributes.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <vector>

namespace geodual::python {

namespace py = pybind11;

/// V (n x 3, any real or integer dtype, finite) and F (m x 3, integers or
/// integral floats in [0, n), m >= 1) as a TriangleMesh.
TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces);

/// n x 3 or n x 4 colours: floats in [0, 1], or uint8 (0-255, divided by 255).
/// `vertex_count`: the rows required.
ColorMatrix colors_from_array(const py::handle& colors, Index vertex_count);

/// Sites: a sequence whose items are vertex indices or (face, u, v, w) tuples
/// (a 1-D integer array, a k x 4 array, or a list mixing both). Indices are
/// checked against the mesh; barycentric coordinates are checked by the
/// geodesic engine.
std::vector<SurfacePoint> sites_from_object(const py::handle& sites, const TriangleMesh& mesh);

/// A Python or numpy integer (not an array, although one-element arrays have __index__ too).
bool is_integer(const py::handle& value);

/// New numpy arrays (copies) of geodual's data.
py::array_t<double> vertices_to_array(const VertexMatrix& vertices);
py::array_t<Index> faces_to_array(const FaceMatrix& faces);
py::array_t<float> colors_to_array(const ColorMatrix& colors);
py::array_t<double> points_to_array(std::span<const Eigen::Vector3d> points);
/// A row-major matrix of doubles as an n x k array (e.g. texture coordinates, tangents).
py::array_t<double> matrix_to_array(
    const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>& matrix);
/// An image as a height x width x channels uint8 array (rows top first), or None where it is empty.
py::object image_to_array(const TextureImage& image);
template <class T>
py::array_t<T> vector_to_array(std::span<const T> values) {
  py::array_t<T> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

}  // namespace geodual::python
