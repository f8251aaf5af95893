// make_textured_scan IN OUT.glb [--texture-size 1024] [--padding 3]
//
// Makes a small textured scan for the texture benchmark (texture_bench) and
// the repository's tests: the mesh IN (any format io::read_mesh reads; a
// manifold without degenerate faces, e.g. tests/data/spot.ply) parameterised
// once with geodual::remesh::make_texture_atlas, and given the procedural
// texture of procedural_texture.hpp: every texel whose centre lies in a
// chart's triangle takes the colour f(p) of its point p on the surface, and
// the texels up to --padding texels outside the charts take the colour of
// the nearest point of the chart, so that bilinear filtering at a chart's
// border does not mix in the background. Written as glTF (.glb) with one PNG
// base colour texture: the mesh's vertices copied per atlas vertex (glTF
// splits vertices along the seams, as a textured scan from any tool does),
// TEXCOORD_0 the atlas's, NORMAL the mesh's angle-weighted vertex normals
// (the same at every copy of a vertex, so that shading has no seams), e.g.
//
//   build/bench/make_textured_scan tests/data/spot.ply tests/data/textured/spot_procedural.glb

#include "bench_support.hpp"
#include "procedural_texture.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/io/image_file.hpp"
#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/texture_image.hpp"
#include "geodual/remesh/texture_atlas.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace geodual::bench {
namespace {

constexpr const char* usage =
    "usage: make_textured_scan IN OUT.glb [--texture-size 1024] [--padding 3]\n"
    "  IN: a manifold mesh without degenerate faces (e.g. tests/data/spot.ply)\n";

/// The point of segment [a, b] nearest to p, as the parameter t in [0, 1].
double nearest_on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  if (!(length2 > 0)) return 0;
  return std::clamp((p - a).dot(ab) / length2, 0.0, 1.0);
}

/// The texture image: f at each texel's point, the gutter padded.
TextureImage paint(const TriangleMesh& mesh, const remesh::TextureAtlas& atlas, const ProceduralTexture& texture,
                   int size, int padding) {
  TextureImage image{.width = size, .height = size, .channels = 3, .texels = {}};
  image.texels.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 3, 0);
  // Per texel, the distance (in texels) from its centre to the triangle that painted it.
  std::vector<double> painted_at(static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                                 std::numeric_limits<double>::infinity());
  for (Index f = 0; f < atlas.faces.rows(); ++f) {
    Eigen::Vector2d uv[3];
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      const Index v = atlas.faces(f, k);
      uv[k] = Eigen::Vector2d(atlas.uvs(v, 0), atlas.uvs(v, 1)) * size;  // in texels
      p[k] = mesh.vertices.row(atlas.source_vertex[static_cast<std::size_t>(v)]).transpose();
    }
    const double area2 = (uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() - (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x();
    if (!(std::abs(area2) > 0)) continue;
    const Eigen::Vector2d lower = uv[0].cwiseMin(uv[1]).cwiseMin(uv[2]).array() - padding;
    const Eigen::Vector2d upper = uv[0].cwiseMax(uv[1]).cwiseMax(uv[2]).array() + padding;
    const int x0 = std::max(0, static_cast<int>(std::floor(lower.x())));
    const int y0 = std::max(0, static_cast<int>(std::floor(lower.y())));
    const int x1 = std::min(size - 1, static_cast<int>(std::ceil(upper.x())));
    const int y1 = std::min(size - 1, static_cast<int>(std::ceil(upper.y())));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d c(x + 0.5, y + 0.5);
        // Barycentric coordinates of the texel's centre.
        auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
        Eigen::Vector3d w(cross(uv[1] - c, uv[2] - c), cross(uv[2] - c, uv[0] - c), cross(uv[0] - c, uv[1] - c));
        w /= area2;
        double distance = 0;
        if (w.minCoeff() < 0) {
          // Outside: the nearest point of the triangle's edges.
          distance = std::numeric_limits<double>::infinity();
          for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d& a = uv[k];
            const Eigen::Vector2d& b = uv[(k + 1) % 3];
            const double t = nearest_on_segment(c, a, b);
            const double d = (a + t * (b - a) - c).norm();
            if (d < distance) {
              distance = d;
              w = Eigen::Vector3d::Zero();
              w[k] = 1 - t;
              w[(k + 1) % 3] = t;
            }
          }
          if (distance > padding) continue;
        }
        const std::size_t texel =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
        if (!(distance < painted_at[texel])) continue;
        painted_at[texel] = distance;
        const Eigen::Vector3d rgb = texture.color(w[0] * p[0] + w[1] * p[1] + w[2] * p[2]);
        for (int k = 0; k < 3; ++k) {
          image.texels[3 * texel + static_cast<std::size_t>(k)] =
              static_cast<std::uint8_t>(std::lround(std::clamp(rgb[k], 0.0, 1.0) * 255));
        }
      }
    }
  }
  return image;
}

int run(int argc, char** argv) {
  int size = 1024;
  int padding = 3;
  const std::vector<std::filesystem::path> paths =
      parse_command_line(argc, argv, usage, [&](const std::string& word, const NextValue& value) {
        if (word == "--texture-size") {
          size = static_cast<int>(parse_integer(word, value(), 64, 16384));
        } else if (word == "--padding") {
          padding = static_cast<int>(parse_integer(word, value(), 0, 16));
        } else {
          return false;
        }
        return true;
      });
  if (paths.size() != 2) throw UsageError(usage);
  const std::filesystem::path& input = paths[0];
  const std::filesystem::path& output = paths[1];
  if (output.extension() != ".glb") throw UsageError("OUT must be a .glb file, not " + output.string());

  const auto start = Clock::now();
  const io::LoadedMesh loaded = io::read_mesh(input);
  const TriangleMesh& mesh = loaded.mesh;
  const remesh::TextureAtlas atlas = remesh::make_texture_atlas(mesh, {.texture_size = size});
  const ProceduralTexture texture = ProceduralTexture::of(mesh);
  const TextureImage image = paint(mesh, atlas, texture, size, padding);

  io::GltfTriangleMesh entry;
  entry.name = input.stem().string() + "_procedural";
  const auto copies = static_cast<Index>(atlas.source_vertex.size());
  entry.mesh.vertices.resize(copies, 3);
  entry.normals.resize(copies, 3);
  entry.texcoords.resize(copies, 2);
  const VertexMatrix normals = angle_weighted_normals(mesh);
  for (Index v = 0; v < copies; ++v) {
    const Index source = atlas.source_vertex[static_cast<std::size_t>(v)];
    entry.mesh.vertices.row(v) = mesh.vertices.row(source);
    entry.normals.row(v) = normals.row(source);
    entry.texcoords.row(v) = atlas.uvs.row(v).cast<float>();
  }
  entry.mesh.faces = atlas.faces;
  const std::vector<std::byte> png = io::encode_image(image, io::ImageFormat::png);
  entry.base_color_texture = {.bytes = png, .mime_type = std::string(io::image_mime_type(io::ImageFormat::png))};

  io::GltfScene scene;
  scene.triangle_meshes.push_back(std::move(entry));
  scene.generator = "geodual bench/make_textured_scan";
  scene.extras_json = "{\"procedural_texture\": {\"definition\": \"bench/procedural_texture.hpp\", \"source\": \"" +
                      input.filename().string() + "\", \"period\": " + std::to_string(texture.period) +
                      ", \"texture_size\": " + std::to_string(size) + "}}";
  io::write_gltf(output, scene);
  double area = 0;
  for (Index f = 0; f < mesh.num_faces(); ++f) area += face_area(mesh, f);

  std::printf(
      "%s -> %s: %d vertices (%d copies in the atlas), %d faces, %lld charts, %.1f%% of %dx%d texels used, "
      "area distortion mean %.3f, angle distortion mean %.2f deg; checker period %.4g (%.1f texels); "
      "PNG %zu bytes, file %ju bytes, %.2f s\n",
      input.string().c_str(), output.string().c_str(), mesh.num_vertices(), copies, mesh.num_faces(),
      static_cast<long long>(atlas.charts), 100 * atlas.texture_used, size, size, atlas.mean_area_distortion,
      atlas.mean_angle_distortion, texture.period, texture.period * std::sqrt(atlas.texture_used * size * size / area),
      png.size(), static_cast<std::uintmax_t>(std::filesystem::file_size(output)), seconds_since(start));
  return 0;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main("make_textured_scan", [&] { return geodual::bench::run(argc, argv); });
}
