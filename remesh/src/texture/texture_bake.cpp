// Baking the input's appearance onto a remesh's atlas (texture_bake.hpp).
//
// Three passes over the texture: the faces are rasterised in order (a texel
// belongs to the last face whose triangle holds its centre), then every
// covered texel is baked on its own -- in parallel by rows, each row in
// order, so that the nearest-triangle search of a texel starts from its left
// neighbour's result without making the bytes depend on the threads -- and
// finally the charts are spread into the free texels round them.

#include "geodual/remesh/texture_bake.hpp"

#include "geodual/mesh/detail/nearest_primitive.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/triangle_distance.hpp"
#include "texture/texel_raster.hpp"

#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace geodual::remesh {
namespace {

using aabb::Kernel;
using aabb::Point;
using aabb::Triangle;
using aabb::TrianglePrimitive;
using aabb::TriangleTree;

Eigen::Vector3d to_eigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

double squared_distance_to(const Point& p, const Triangle& t) {
  return squared_distance_to_triangle(to_eigen(p), to_eigen(t[0]), to_eigen(t[1]), to_eigen(t[2]));
}

using NearestTriangle = NearestPrimitive<Kernel, TrianglePrimitive, squared_distance_to>;

/// The input's faces of non-zero area in an AABB tree, to find the input's
/// point nearest to a point of the remesh.
class NearestPointFinder {
 public:
  explicit NearestPointFinder(const TriangleMesh& mesh) : mesh_(mesh) {
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      if (!has_positive_area(mesh, f)) continue;
      std::array<Point, 3> corners;
      for (int c = 0; c < 3; ++c) {
        const auto p = mesh.vertices.row(mesh.faces(f, c));
        corners[c] = Point(p.x(), p.y(), p.z());
      }
      triangles_.emplace_back(corners[0], corners[1], corners[2]);
      face_.push_back(f);
    }
    if (triangles_.empty()) throw Error("bake_textures: every face of the input has zero area");
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
  }

  /// The input's point nearest to p: a face and barycentric coordinates.
  /// `near` (an index into the tree's triangles) starts the search and is
  /// set to the nearest triangle.
  SurfacePoint nearest(const Eigen::Vector3d& p, std::size_t& near) const {
    const Point query(p.x(), p.y(), p.z());
    NearestTriangle search(triangles_.cbegin(), squared_distance_to(query, triangles_[near]), near);
    tree_.traversal_with_priority(query, search);
    near = search.nearest_primitive();
    const Index f = face_[near];
    const Eigen::Vector3d weights = nearest_point_on_triangle(p, mesh_.vertices.row(mesh_.faces(f, 0)).transpose(),
                                                              mesh_.vertices.row(mesh_.faces(f, 1)).transpose(),
                                                              mesh_.vertices.row(mesh_.faces(f, 2)).transpose());
    return SurfacePoint::in_face(f, weights[0], weights[1], weights[2]);
  }

 private:
  const TriangleMesh& mesh_;
  std::vector<Triangle> triangles_;
  std::vector<Index> face_;  ///< per triangle, the input's face
  TriangleTree tree_;
};

/// Unit vertex normals, each face's normal weighted by its angle at the
/// vertex (Thürmer and Wüthrich); (0, 0, 1) where no face of area touches.
VertexMatrix angle_weighted_normals(const TriangleMesh& mesh) {
  VertexMatrix normals = VertexMatrix::Zero(mesh.num_vertices(), 3);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    std::array<Eigen::Vector3d, 3> p;
    for (int c = 0; c < 3; ++c) p[c] = mesh.vertices.row(mesh.faces(f, c)).transpose();
    const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(normal.norm() > 0)) continue;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d e1 = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d e2 = p[(c + 2) % 3] - p[c];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      normals.row(mesh.faces(f, c)) += angle * normal.normalized().transpose();
    }
  }
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    const double length = normals.row(v).norm();
    if (length > 0) {
      normals.row(v) /= length;
    } else {
      normals.row(v) = Eigen::RowVector3d(0, 0, 1);
    }
  }
  return normals;
}

/// Any unit vector perpendicular to the unit vector n.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d axis = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

/// Per atlas vertex, its tangent frame as glTF's TANGENT: the surface's
/// direction of increasing u, averaged over its faces by their angles at the
/// vertex and made perpendicular to its normal, and the sign w that makes
/// cross(normal, tangent) w point along decreasing v (the image's up). This
/// is MikkTSpace's construction for an atlas whose charts have no inner seams.
Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> atlas_tangents(const TriangleMesh& remesh,
                                                                         const TextureAtlas& atlas,
                                                                         const VertexMatrix& normals) {
  const auto count = static_cast<Eigen::Index>(atlas.source_vertex.size());
  VertexMatrix along_u = VertexMatrix::Zero(count, 3);
  VertexMatrix along_v = VertexMatrix::Zero(count, 3);
  for (Eigen::Index f = 0; f < atlas.faces.rows(); ++f) {
    std::array<Eigen::Vector3d, 3> p;
    std::array<Eigen::Vector2d, 3> uv;
    for (int c = 0; c < 3; ++c) {
      p[c] = remesh.vertices.row(atlas.source_vertex[atlas.faces(f, c)]).transpose();
      uv[c] = atlas.uvs.row(atlas.faces(f, c)).transpose();
    }
    // dP = Pu du + Pv dv along both edges from corner 0, solved for Pu and Pv.
    const Eigen::Vector3d e1 = p[1] - p[0], e2 = p[2] - p[0];
    const Eigen::Vector2d t1 = uv[1] - uv[0], t2 = uv[2] - uv[0];
    const double det = t1.x() * t2.y() - t2.x() * t1.y();
    if (!(std::abs(det) > 0)) continue;
    const Eigen::Vector3d pu = (e1 * t2.y() - e2 * t1.y()) / det;
    const Eigen::Vector3d pv = (e2 * t1.x() - e1 * t2.x()) / det;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d a = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d b = p[(c + 2) % 3] - p[c];
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      along_u.row(atlas.faces(f, c)) += angle * pu.normalized().transpose();
      along_v.row(atlas.faces(f, c)) += angle * pv.normalized().transpose();
    }
  }
  Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> tangents(count, 4);
  for (Eigen::Index v = 0; v < count; ++v) {
    const Eigen::Vector3d n = normals.row(v).transpose();
    Eigen::Vector3d t = along_u.row(v).transpose();
    t -= n.dot(t) * n;
    t = t.norm() > 1e-12 ? t.normalized() : perpendicular(n);
    const double w = n.cross(t).dot(-along_v.row(v).transpose()) >= 0 ? 1.0 : -1.0;
    tangents.row(v) << t.x(), t.y(), t.z(), w;
  }
  return tangents;
}

/// A face's corners in texel coordinates (texel (i, j) has its centre at (i + 0.5, j + 0.5)).
std::array<Eigen::Vector2d, 3> texel_corners(const TextureAtlas& atlas, Eigen::Index f, int size) {
  std::array<Eigen::Vector2d, 3> corners;
  for (int c = 0; c < 3; ++c) corners[c] = atlas.uvs.row(atlas.faces(f, c)).transpose() * size;
  return corners;
}

/// Barycentric coordinates of q in the triangle (its signed area `area2` times two, non-zero).
Eigen::Vector3d barycentric(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& q, double area2) {
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const double w0 = cross(t[2] - t[1], q - t[1]) / area2;
  const double w1 = cross(t[0] - t[2], q - t[2]) / area2;
  return {w0, w1, 1.0 - w0 - w1};
}

double signed_area2(const std::array<Eigen::Vector2d, 3>& t) {
  const Eigen::Vector2d a = t[1] - t[0], b = t[2] - t[0];
  return a.x() * b.y() - a.y() * b.x();
}

/// Per texel (row-major), the face whose triangle holds its centre (the last
/// in face order where several do), or -1.
std::vector<Index> rasterise_faces(const TextureAtlas& atlas, int size) {
  std::vector<Index> owner(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), -1);
  for (Eigen::Index f = 0; f < atlas.faces.rows(); ++f) {
    detail::for_each_texel_in(texel_corners(atlas, f, size), size, [&](int x, int y, const Eigen::Vector3d&) {
      owner[static_cast<std::size_t>(y) * size + x] = static_cast<Index>(f);
    });
  }
  return owner;
}

/// Linear light of each 8-bit sRGB-encoded value.
using SrgbTable = std::array<float, 256>;
SrgbTable srgb_table() {
  SrgbTable table{};
  for (int i = 0; i < 256; ++i) table[static_cast<std::size_t>(i)] = linear_from_srgb(static_cast<float>(i) / 255.0F);
  return table;
}

/// The image's colour at texture coordinates (u, v), in linear light: the
/// four nearest texels mixed bilinearly, coordinates wrapped (REPEAT).
std::array<float, 4> sample_linear(const TextureImage& image, const SrgbTable& linear, double u, double v) {
  // REPEAT: only the fraction counts (a coordinate that is not finite reads as 0).
  const auto fraction = [](double t) { return std::isfinite(t) ? t - std::floor(t) : 0.0; };
  const double x = fraction(u) * image.width - 0.5;
  const double y = fraction(v) * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  const auto wrap = [](double i, int n) { return static_cast<int>(((static_cast<long long>(i) % n) + n) % n); };
  std::array<float, 4> out{0, 0, 0, image.channels == 4 ? 0.0F : 1.0F};
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const auto weight = static_cast<float>((dx ? ax : 1 - ax) * (dy ? ay : 1 - ay));
      const std::size_t at = image.offset(wrap(fx + dx, image.width), wrap(fy + dy, image.height));
      for (int k = 0; k < 3; ++k) out[k] += weight * linear[image.texels[at + k]];
      if (image.channels == 4) out[3] += weight * (image.texels[at + 3] / 255.0F);
    }
  }
  return out;
}

std::uint8_t to_byte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255)); }

/// Spreads the filled texels of `image` into the empty ones round them,
/// `passes` texels far: each pass gives every empty texel beside a filled one
/// (of 8) the mean of those neighbours.
void spread_charts(TextureImage& image, std::vector<std::uint8_t>& filled, int passes) {
  const int w = image.width, h = image.height, channels = image.channels;
  std::vector<std::size_t> fresh;
  std::vector<std::uint8_t> values;
  for (int pass = 0; pass < passes; ++pass) {
    fresh.clear();
    values.clear();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t at = static_cast<std::size_t>(y) * w + x;
        if (filled[at]) continue;
        std::array<int, 4> sum{};
        int neighbours = 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            if (!filled[static_cast<std::size_t>(ny) * w + nx]) continue;
            const std::size_t texel = image.offset(nx, ny);
            for (int k = 0; k < channels; ++k) sum[k] += image.texels[texel + k];
            ++neighbours;
          }
        }
        if (neighbours == 0) continue;
        fresh.push_back(at);
        for (int k = 0; k < channels; ++k) {
          values.push_back(static_cast<std::uint8_t>((sum[k] + neighbours / 2) / neighbours));
        }
      }
    }
    if (fresh.empty()) return;
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      filled[fresh[i]] = 1;
      for (int k = 0; k < channels; ++k) {
        image.texels[fresh[i] * channels + k] = values[i * channels + k];
      }
    }
  }
}

TextureImage blank_image(int size, int channels) {
  TextureImage image{.width = size, .height = size, .channels = channels};
  image.texels.assign(static_cast<std::size_t>(size) * size * channels, 0);
  return image;
}

void check_sizes(const TriangleMesh& input, const BakeSource& source, const TriangleMesh& remesh,
                 const TextureAtlas& atlas) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("bake_textures: " + what);
  };
  const auto input_vertices = static_cast<Eigen::Index>(input.num_vertices());
  require(source.colors.rows() == 0 ||
              (source.colors.rows() == input_vertices && (source.colors.cols() == 3 || source.colors.cols() == 4)),
          "the colours must be one RGB or RGBA row per input vertex");
  require(source.normals.rows() == 0 || source.normals.rows() == input_vertices,
          "the normals must be one row per input vertex");
  require(
      source.texture.empty() || source.texture.corner_uvs.rows() == 3 * static_cast<Eigen::Index>(input.num_faces()),
      "the texture's coordinates must be three rows per input face");
  for (const TextureImage& image : source.texture.images) {
    require((image.channels == 3 || image.channels == 4) && image.width > 0 && image.height > 0 &&
                image.texels.size() == image.offset(0, image.height),
            "the texture's images must be RGB or RGBA with width x height texels");
  }
  require(source.texture.face_image.empty() ||
              source.texture.face_image.size() == static_cast<std::size_t>(input.num_faces()),
          "the texture's images must be given one per input face, or not at all");
  for (const std::int32_t image : source.texture.face_image) {
    require(image >= 0 && static_cast<std::size_t>(image) < source.texture.images.size(),
            "a face of the input names texture image " + std::to_string(image));
  }
  require(atlas.faces.rows() == remesh.faces.rows(), "the atlas has " + std::to_string(atlas.faces.rows()) +
                                                         " faces for a remesh of " +
                                                         std::to_string(remesh.faces.rows()));
  require(atlas.uvs.rows() == static_cast<Eigen::Index>(atlas.source_vertex.size()) && atlas.uvs.allFinite(),
          "the atlas needs one finite texture coordinate per atlas vertex");
  for (const Index v : atlas.source_vertex) {
    require(v >= 0 && v < remesh.num_vertices(), "an atlas vertex copies vertex " + std::to_string(v) +
                                                     " of a remesh of " + std::to_string(remesh.num_vertices()));
  }
  for (Eigen::Index i = 0; i < atlas.faces.size(); ++i) {
    const Index v = atlas.faces.data()[i];
    require(v >= 0 && v < static_cast<Index>(atlas.source_vertex.size()),
            "an atlas face refers to atlas vertex " + std::to_string(v));
  }
}

}  // namespace

void check_options(const BakeOptions& options) {
  auto require = [](bool holds, const std::string& what) {
    if (!holds) throw UsageError("bake_textures: " + what);
  };
  require(options.texture_size >= 1 && options.texture_size <= 16384,
          "texture_size must be in [1, 16384], got " + std::to_string(options.texture_size));
  require(options.padding >= 0, "padding must be >= 0, got " + std::to_string(options.padding));
}

BakedTextures bake_textures(const TriangleMesh& input, const BakeSource& source, const TriangleMesh& remesh,
                            const TextureAtlas& atlas, const BakeOptions& options) {
  check_options(options);
  check_sizes(input, source, remesh, atlas);
  const int size = options.texture_size;
  BakedTextures baked;

  const VertexMatrix remesh_normals = angle_weighted_normals(remesh);
  const auto atlas_vertices = static_cast<Eigen::Index>(atlas.source_vertex.size());
  baked.normals.resize(atlas_vertices, 3);
  for (Eigen::Index v = 0; v < atlas_vertices; ++v) baked.normals.row(v) = remesh_normals.row(atlas.source_vertex[v]);

  const bool bake_color = options.base_color && (!source.texture.empty() || source.colors.rows() > 0);
  const bool bake_normal = options.normal_map;
  if (bake_normal) baked.tangents = atlas_tangents(remesh, atlas, baked.normals);
  if (!bake_color && !bake_normal) return baked;

  int color_channels = static_cast<int>(source.colors.cols());
  if (!source.texture.empty()) {
    color_channels = 3;
    for (const TextureImage& image : source.texture.images) color_channels = std::max(color_channels, image.channels);
  }
  if (bake_color) baked.base_color = blank_image(size, color_channels);
  if (bake_normal) baked.normal_map = blank_image(size, 3);
  const VertexMatrix input_normals =
      bake_normal ? (source.normals.rows() > 0 ? source.normals : angle_weighted_normals(input)) : VertexMatrix{};

  const std::vector<Index> owner = rasterise_faces(atlas, size);
  const NearestPointFinder finder(input);
  const SrgbTable linear_of_byte = srgb_table();
  // The vertex colours in linear light, once (alpha is linear already).
  ColorMatrix linear_colors = source.colors;
  for (Eigen::Index v = 0; v < linear_colors.rows(); ++v) {
    for (Eigen::Index k = 0; k < std::min<Eigen::Index>(3, linear_colors.cols()); ++k) {
      linear_colors(v, k) = linear_from_srgb(linear_colors(v, k));
    }
  }

  tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& rows) {
    std::size_t near = 0;
    for (int j = rows.begin(); j < rows.end(); ++j) {
      near = 0;  // every row starts alike, so that its bytes do not depend on how rows are split
      for (int i = 0; i < size; ++i) {
        const Index f = owner[static_cast<std::size_t>(j) * size + i];
        if (f < 0) continue;
        const auto t = texel_corners(atlas, f, size);
        const Eigen::Vector3d w = barycentric(t, {i + 0.5, j + 0.5}, signed_area2(t));
        std::array<Index, 3> corner;
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        for (int c = 0; c < 3; ++c) {
          corner[c] = atlas.faces(f, c);
          point += w[c] * remesh.vertices.row(atlas.source_vertex[corner[c]]).transpose();
        }
        const SurfacePoint on_input = finder.nearest(point, near);
        const auto input_corner = [&](int c) { return input.faces(on_input.element, c); };
        const Eigen::Vector3d& b = on_input.barycentric;

        if (bake_color) {
          std::array<float, 4> linear{0, 0, 0, 1};
          if (!source.texture.empty()) {
            Eigen::Vector2d uv = Eigen::Vector2d::Zero();
            for (int c = 0; c < 3; ++c) {
              uv +=
                  b[c] * source.texture.corner_uvs.row(3 * static_cast<Eigen::Index>(on_input.element) + c).transpose();
            }
            linear = sample_linear(source.texture.image_of(on_input.element), linear_of_byte, uv.x(), uv.y());
          } else {
            for (int k = 0; k < color_channels; ++k) {
              double mixed = 0;
              for (int c = 0; c < 3; ++c) mixed += b[c] * linear_colors(input_corner(c), k);
              linear[k] = static_cast<float>(mixed);
            }
          }
          const std::size_t at = baked.base_color.offset(i, j);
          for (int k = 0; k < color_channels; ++k) {
            baked.base_color.texels[at + k] = to_byte(k < 3 ? srgb_from_linear(linear[k]) : linear[k]);
          }
        }

        if (bake_normal) {
          Eigen::Vector3d target = Eigen::Vector3d::Zero();
          for (int c = 0; c < 3; ++c) target += b[c] * input_normals.row(input_corner(c)).transpose();
          // The frame a glTF viewer interpolates from the vertices' NORMAL and
          // TANGENT and normalises per fragment; the texel holds the
          // coordinates of the input's normal in it.
          Eigen::Vector3d n = Eigen::Vector3d::Zero(), tangent = Eigen::Vector3d::Zero(),
                          bitangent = Eigen::Vector3d::Zero();
          for (int c = 0; c < 3; ++c) {
            const Eigen::Vector3d nc = baked.normals.row(corner[c]).transpose();
            const Eigen::Vector3d tc = baked.tangents.row(corner[c]).head<3>().transpose();
            n += w[c] * nc;
            tangent += w[c] * tc;
            bitangent += w[c] * nc.cross(tc) * baked.tangents(corner[c], 3);
          }
          Eigen::Matrix3d frame;
          frame << tangent.normalized(), bitangent.normalized(), n.normalized();
          Eigen::Vector3d local = frame.transpose() * target;
          if (std::abs(frame.determinant()) > 1e-6) local = frame.inverse() * target;
          local = local.norm() > 0 ? local.normalized() : Eigen::Vector3d::UnitZ();
          const std::size_t at = baked.normal_map.offset(i, j);
          for (int k = 0; k < 3; ++k) baked.normal_map.texels[at + k] = to_byte((local[k] + 1) / 2);
        }
      }
    }
  });

  std::vector<std::uint8_t> covered(owner.size());
  for (std::size_t t = 0; t < owner.size(); ++t) covered[t] = owner[t] >= 0 ? 1 : 0;
  baked.texels_baked = std::count(covered.begin(), covered.end(), std::uint8_t{1});
  if (bake_color) {
    std::vector<std::uint8_t> filled = covered;
    spread_charts(baked.base_color, filled, options.padding);
  }
  if (bake_normal) {
    std::vector<std::uint8_t> filled = covered;
    spread_charts(baked.normal_map, filled, options.padding);
  }
  return baked;
}

}  // namespace geodual::remesh
