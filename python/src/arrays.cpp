#include "arrays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace geodual::python {
namespace {

/// `object` as a numpy array of a real or integer dtype; TypeError otherwise.
py::array numeric_array(const py::handle& object, const char* name) {
  py::array array = py::array::ensure(object);
  if (!array) {
    throw py::type_error(std::string(name) + " must be a numeric array, got " +
                         std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(std::string(name) + " must have a real or integer dtype, got " +
                         std::string(py::str(array.dtype())));
  }
  return array;
}

/// The shape as "(3, 4)", for messages.
std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

void require_rows_of(const py::array& array, const char* name, std::initializer_list<py::ssize_t> columns) {
  const bool ok = array.ndim() == 2 && std::find(columns.begin(), columns.end(), array.shape(1)) != columns.end();
  if (!ok) {
    std::string wanted;
    for (const py::ssize_t c : columns) wanted += (wanted.empty() ? "n x " : " or n x ") + std::to_string(c);
    throw py::value_error(std::string(name) + " must be an " + wanted + " array, got shape " + shape_text(array));
  }
}

/// A C-contiguous copy (or view) of `array` as `T`, casting from any numeric dtype.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> as_type(const py::array& array) {
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
}

/// `value` as an index into `count` elements: an integer (Python or numpy) in [0, count).
Index index_from(const py::handle& value, Index count, const char* what, const char* what_plural) {
  if (!is_integer(value)) {
    throw py::type_error(std::string(what) + " index must be an integer, got " +
                         std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  const auto index = py::cast<long long>(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
  if (index < 0 || index >= count) {
    throw py::value_error(std::string(what) + " index " + std::to_string(index) + " out of range: the mesh has " +
                          std::to_string(count) + " " + (count == 1 ? what : what_plural));
  }
  return static_cast<Index>(index);
}

}  // namespace

bool is_integer(const py::handle& value) {
  // numpy arrays have __index__ too (for one element); an array is not an integer here.
  return PyIndex_Check(value.ptr()) &&
         !(py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() > 0);
}

TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces) {
  TriangleMesh mesh;
  const py::array v = numeric_array(vertices, "V");
  require_rows_of(v, "V", {3});
  if (v.shape(0) > std::numeric_limits<Index>::max()) throw py::value_error("V: more than 2^31 - 1 vertices");
  const auto positions = as_type<double>(v);
  const py::ssize_t n = v.shape(0);
  mesh.vertices.resize(n, 3);
  std::memcpy(mesh.vertices.data(), positions.data(), static_cast<std::size_t>(n) * 3 * sizeof(double));
  for (py::ssize_t i = 0; i < n * 3; ++i) {
    if (!std::isfinite(mesh.vertices.data()[i])) {
      throw py::value_error("V[" + std::to_string(i / 3) + "] is not finite (NaN or infinite coordinates)");
    }
  }

  const py::array f = numeric_array(faces, "F");
  require_rows_of(f, "F", {3});
  if (f.shape(0) == 0) throw py::value_error("F has no faces: a mesh needs at least one triangle");
  const py::ssize_t m = f.shape(0);
  mesh.faces.resize(m, 3);
  const auto check = [&](auto corner, py::ssize_t i) {
    if (!(corner >= 0 && corner < static_cast<decltype(corner)>(n))) {
      throw py::value_error("F[" + std::to_string(i / 3) + "] refers to vertex " +
                            py::str(py::cast(corner)).cast<std::string>() + ", out of range: V has " +
                            std::to_string(n) + " rows");
    }
    mesh.faces.data()[i] = static_cast<Index>(corner);
  };
  if (f.dtype().kind() == 'f') {
    const auto corners = as_type<double>(f);
    for (py::ssize_t i = 0; i < m * 3; ++i) {
      const double corner = corners.data()[i];
      if (corner != std::floor(corner)) {
        throw py::value_error("F[" + std::to_string(i / 3) + "] has a vertex index that is not an integer");
      }
      check(corner, i);
    }
  } else {
    // int64 holds every index an unsigned dtype can hold that is in range; larger ones wrap to negative.
    const auto corners = as_type<std::int64_t>(f);
    for (py::ssize_t i = 0; i < m * 3; ++i) check(corners.data()[i], i);
  }
  return mesh;
}

ColorMatrix colors_from_array(const py::handle& colors, Index vertex_count) {
  const py::array c = numeric_array(colors, "colors");
  require_rows_of(c, "colors", {3, 4});
  if (c.shape(0) != vertex_count) {
    throw py::value_error("colors has " + std::to_string(c.shape(0)) + " rows for " + std::to_string(vertex_count) +
                          " vertices");
  }
  const bool bytes = c.dtype().kind() == 'u' && c.dtype().itemsize() == 1;
  const auto values = as_type<float>(c);
  ColorMatrix matrix(c.shape(0), c.shape(1));
  for (py::ssize_t i = 0; i < matrix.size(); ++i) {
    const float value = bytes ? values.data()[i] / 255.0f : values.data()[i];
    if (!(value >= 0.0f && value <= 1.0f)) {
      throw py::value_error("colors[" + std::to_string(i / matrix.cols()) +
                            "] is not in [0, 1] (floats in [0, 1] or uint8 0-255)");
    }
    matrix.data()[i] = value;
  }
  return matrix;
}

std::vector<SurfacePoint> sites_from_object(const py::handle& sites, const TriangleMesh& mesh) {
  if (is_integer(sites) || (!py::isinstance<py::sequence>(sites) && !py::isinstance<py::array>(sites))) {
    throw py::type_error("sites must be a sequence of vertex indices or (face, u, v, w) tuples");
  }
  std::vector<SurfacePoint> points;
  for (const py::handle item : sites) {
    if (is_integer(item)) {
      points.push_back(SurfacePoint::at_vertex(index_from(item, mesh.num_vertices(), "vertex", "vertices")));
      continue;
    }
    if ((!py::isinstance<py::sequence>(item) && !py::isinstance<py::array>(item)) || py::len(item) != 4) {
      throw py::type_error("each site must be a vertex index or a (face, u, v, w) tuple, got " +
                           std::string(py::repr(item)));
    }
    const py::sequence tuple = py::reinterpret_borrow<py::sequence>(item);
    py::object face = tuple[0];
    // A row of a float k x 4 array: the face index is a float holding an integer.
    if (!is_integer(face) && PyFloat_Check(face.ptr())) {  // numpy float64 is a float too
      const double value = face.cast<double>();
      if (value == std::floor(value) && std::abs(value) < 1e15) face = py::int_(static_cast<long long>(value));
    }
    const Index f = index_from(face, mesh.num_faces(), "face", "faces");
    points.push_back(
        SurfacePoint::in_face(f, tuple[1].cast<double>(), tuple[2].cast<double>(), tuple[3].cast<double>()));
  }
  if (points.empty()) throw py::value_error("sites is empty: give at least one site");
  return points;
}

py::array_t<double> vertices_to_array(const VertexMatrix& vertices) {
  py::array_t<double> array({static_cast<py::ssize_t>(vertices.rows()), py::ssize_t{3}});
  std::copy_n(vertices.data(), vertices.size(), array.mutable_data());
  return array;
}

py::array_t<double> matrix_to_array(
    const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>& matrix) {
  py::array_t<double> array({static_cast<py::ssize_t>(matrix.rows()), static_cast<py::ssize_t>(matrix.cols())});
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) array.mutable_data()[r * matrix.cols() + c] = matrix(r, c);
  }
  return array;
}

py::object image_to_array(const TextureImage& image) {
  if (image.empty()) return py::none();
  py::array_t<std::uint8_t> array({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width),
                                   static_cast<py::ssize_t>(image.channels)});
  std::copy(image.texels.begin(), image.texels.end(), array.mutable_data());
  return array;
}

py::array_t<Index> faces_to_array(const FaceMatrix& faces) {
  py::array_t<Index> array({static_cast<py::ssize_t>(faces.rows()), py::ssize_t{3}});
  std::copy_n(faces.data(), faces.size(), array.mutable_data());
  return array;
}

py::array_t<float> colors_to_array(const ColorMatrix& colors) {
  py::array_t<float> array({static_cast<py::ssize_t>(colors.rows()), static_cast<py::ssize_t>(colors.cols())});
  std::copy_n(colors.data(), colors.size(), array.mutable_data());
  return array;
}

py::array_t<double> points_to_array(std::span<const Eigen::Vector3d> points) {
  py::array_t<double> array({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  double* out = array.mutable_data();
  for (const Eigen::Vector3d& p : points) {
    *out++ = p.x();
    *out++ = p.y();
    *out++ = p.z();
  }
  return array;
}

}  // namespace geodual::python
