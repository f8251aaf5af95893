#pragma once
// Per-vertex data besides positions -- colours, normals, named scalars -- as
// readers find them in a scan and writers put them out again, and their
// transfer to points of the surface by barycentric interpolation.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace geodual {

/// Per-vertex colours, one row per vertex: 3 columns (RGB) or 4 (RGBA), each in [0, 1].
using ColorMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The type a file stores a value in, kept so that a writer can store it the same way.
enum class ValueType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

/// PLY's name of the type: char, uchar, short, ushort, int, uint, float, double.
std::string_view ply_type_name(ValueType type);

/// One named value per vertex, e.g. a scanner's "intensity" or "confidence".
struct VertexScalar {
  std::string name;
  ValueType type = ValueType::float64;
  std::vector<double> values;  ///< one per vertex, finite
};

/// What a mesh carries per vertex besides its position. Each member is empty
/// or has one row (value) per vertex; every member has a default, so
/// designated initializers may leave any of them out.
struct VertexAttributes {
  /// Colours as files store them for display: sRGB-encoded, not linear (PLY's
  /// and OBJ's convention; glTF's linear COLOR_0 is converted on reading and
  /// writing). color_type is how the file stored them: uint8 (0-255), uint16
  /// (0-65535) or float32/float64 (0-1).
  ColorMatrix colors{};
  ValueType color_type = ValueType::uint8;
  /// Unit normals (not necessarily unit in the file: interpolation renormalises).
  VertexMatrix normals{};
  ValueType normal_type = ValueType::float32;
  std::vector<VertexScalar> scalars{};

  bool empty() const { return colors.rows() == 0 && normals.rows() == 0 && scalars.empty(); }
};

/// The attributes at `points` of `mesh` (one row per point, in order): the
/// barycentric interpolation of the face's corner values (exact for fields
/// linear on each face), a vertex's own values at a vertex. Normals are
/// renormalised (left as interpolated where they cancel out); scalars of an
/// integer type are rounded to the nearest value the type holds.
/// \pre attributes has one row per vertex of mesh; every point is on mesh.
VertexAttributes interpolate_attributes(const TriangleMesh& mesh, const VertexAttributes& attributes,
                                        std::span<const SurfacePoint> points);

/// The first attribute whose row count is not mesh's vertex count, e.g.
/// "colors: 10 rows for 12 vertices", or an empty string when all agree.
std::string attribute_size_problem(const VertexAttributes& attributes, Index vertex_count);

/// sRGB encoding and decoding of one channel in [0, 1] (IEC 61966-2-1).
float srgb_from_linear(float linear);
float linear_from_srgb(float encoded);

}  // namespace geodual
