// Writes one .glb and one .gltf for each kind of scene geodual's glTF writer
// produces (triangles, colours, scalar attributes, LINES, POINTS, extras, both
// index widths, degenerate and unreferenced vertices, awkward names), and of
// some of them compressed with meshopt and with Draco, so that validate.mjs
// can check them with the Khronos glTF-Validator.
//
//   geodual_gltf_samples OUTPUT_FOLDER
//
// Prints the path of every file it wrote, one a line. Exit status 0, or 1 with
// a message when the writer refuses a scene (which is itself a failure: every
// scene here is valid input).

#include "geodual/io/gltf.hpp"
#include "geodual/io/image_file.hpp"
#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;
using namespace geodual;
using namespace geodual::io;

// A UV sphere of radius r: `rings` x `segments` quads split in two, with one
// pole vertex each end. Coordinates are not float32 values (the writer rounds).
TriangleMesh uv_sphere(double radius, int rings, int segments) {
  TriangleMesh mesh;
  const int ring_vertices = (rings - 1) * segments;
  mesh.vertices.resize(ring_vertices + 2, 3);
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      mesh.vertices.row((i - 1) * segments + j) << radius * std::sin(theta) * std::cos(phi),
          radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta);
    }
  }
  const Index north = ring_vertices;
  const Index south = ring_vertices + 1;
  mesh.vertices.row(north) << 0.0, 0.0, radius;
  mesh.vertices.row(south) << 0.0, 0.0, -radius;
  std::vector<Index> faces;
  auto ring_vertex = [segments](int ring, int j) { return static_cast<Index>((ring - 1) * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j) {
    faces.insert(faces.end(), {north, ring_vertex(1, j), ring_vertex(1, j + 1)});
    faces.insert(faces.end(), {south, ring_vertex(rings - 1, j + 1), ring_vertex(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      const Index a = ring_vertex(i, j), b = ring_vertex(i + 1, j);
      const Index c = ring_vertex(i + 1, j + 1), d = ring_vertex(i, j + 1);
      faces.insert(faces.end(), {a, b, c, a, c, d});
    }
  }
  mesh.faces = Eigen::Map<const FaceMatrix>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  return mesh;
}

// An n x n vertex grid in the plane z = 0.1 x y, offset to negative coordinates.
TriangleMesh grid(int n) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(n) * n, 3);
  mesh.faces.resize(2 * static_cast<Eigen::Index>(n - 1) * (n - 1), 3);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const double u = x / 7.0 - 3.0, v = y / 3.0 - 100.0;
      mesh.vertices.row(static_cast<Eigen::Index>(y) * n + x) << u, v, 0.1 * u * v;
    }
  }
  Eigen::Index f = 0;
  for (int y = 0; y + 1 < n; ++y) {
    for (int x = 0; x + 1 < n; ++x) {
      const Index a = y * n + x, b = a + 1, c = a + n, d = c + 1;
      mesh.faces.row(f++) << a, b, d;
      mesh.faces.row(f++) << a, d, c;
    }
  }
  return mesh;
}

// Per-vertex colours from the positions (3 or 4 channels, all in [0, 1]).
ColorMatrix colors_for(const VertexMatrix& points, int channels) {
  ColorMatrix colors(points.rows(), channels);
  const Eigen::RowVector3d lo = points.colwise().minCoeff();
  const Eigen::RowVector3d extent = (points.colwise().maxCoeff() - lo).cwiseMax(1e-30);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < channels; ++c) {
      colors(i, c) = static_cast<float>(c < 3 ? (points(i, c) - lo(c)) / extent(c) : (i % 2 == 0 ? 0.25 : 0.75));
    }
  }
  return colors;
}

std::vector<float> height_field(const VertexMatrix& points) {
  std::vector<float> values(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    values[static_cast<std::size_t>(i)] = static_cast<float>(points(i, 2));
  }
  return values;
}

// A closed polyline around the sphere's equator and a few spokes.
GltfLineSet equator_lines(double radius, int n, bool with_colors) {
  GltfLineSet lines{.name = with_colors ? "boundaries" : ""};
  lines.points.resize(n + 1, 3);
  lines.segments.resize(n + 3, 2);
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / n;
    lines.points.row(i) << radius * std::cos(phi), radius * std::sin(phi), 0.0;
    lines.segments.row(i) << i, (i + 1) % n;
  }
  lines.points.row(n) << 0.0, 0.0, 0.0;
  lines.segments.row(n) << n, 0;
  lines.segments.row(n + 1) << n, n / 3;
  lines.segments.row(n + 2) << n, (2 * n) / 3;
  if (with_colors) lines.colors = colors_for(lines.points, 3);
  return lines;
}

GltfPointSet some_points(const TriangleMesh& mesh, int stride, bool with_colors) {
  GltfPointSet points{.name = with_colors ? "sites" : ""};
  const Eigen::Index count = (mesh.vertices.rows() + stride - 1) / stride;
  points.points.resize(count, 3);
  for (Eigen::Index i = 0; i < count; ++i) points.points.row(i) = mesh.vertices.row(i * stride);
  if (with_colors) points.colors = colors_for(points.points, 4);
  return points;
}

// A tetrahedron, an unreferenced vertex, a zero-area (collinear) triangle,
// vertices used only by degenerate triangles (their normal is the (0, 0, 1)
// fallback) and a triangle with a repeated index, as scans have them.
TriangleMesh awkward_mesh() {
  TriangleMesh mesh;
  mesh.vertices =
      VertexMatrix{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {5, 5, 5}, {2, 0, 0}, {3, 0, 0}, {-1, -1, -1}};
  mesh.faces = FaceMatrix{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {1, 5, 6}, {7, 7, 2}};
  return mesh;
}

// A 16 x 16 image of `channels` channels: a gradient, or flat normals tilted
// by a wave (`normals`), as a baker writes them.
TextureImage small_image(int channels, bool normals) {
  TextureImage image{.width = 16, .height = 16, .channels = channels};
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      if (normals) {
        const double nx = 0.3 * std::sin(x * 0.7), ny = 0.3 * std::cos(y * 0.5);
        const double nz = std::sqrt(1 - nx * nx - ny * ny);
        for (const double c : {nx, ny, nz})
          image.texels.push_back(static_cast<std::uint8_t>(std::lround((c + 1) * 127.5)));
      } else {
        image.texels.insert(image.texels.end(),
                            {static_cast<std::uint8_t>(16 * x), static_cast<std::uint8_t>(16 * y), 200});
        if (channels == 4) image.texels.push_back(255);
      }
    }
  }
  return image;
}

// The grid as a baker's textured remesh: TEXCOORD_0 over [0, 1]^2, TANGENT
// along +u, a base colour texture (`format`) and a PNG normal map.
GltfTriangleMesh textured_grid(ImageFormat format) {
  GltfTriangleMesh entry{.name = "textured", .mesh = grid(9)};
  const auto n = entry.mesh.num_vertices();
  entry.texcoords.resize(n, 2);
  entry.tangents.resize(n, 4);
  for (Index v = 0; v < n; ++v) {
    entry.texcoords.row(v) << static_cast<float>((v % 9) / 8.0), static_cast<float>(1 - (v / 9) / 8.0);
    const Eigen::Vector3d along_x(1, 0, 0.1 * entry.mesh.vertices(v, 1));  // d(position)/dx on the grid's surface
    const Eigen::Vector3f t = along_x.normalized().cast<float>();
    entry.tangents.row(v) << t.x(), t.y(), t.z(), 1.0F;
  }
  entry.base_color_texture = {.bytes = encode_image(small_image(4, false), format),
                              .mime_type = std::string(image_mime_type(format))};
  entry.normal_texture = {.bytes = encode_image(small_image(3, true), ImageFormat::png), .mime_type = "image/png"};
  return entry;
}

struct Sample {
  std::string name;
  GltfScene scene;
};

std::vector<Sample> samples() {
  std::vector<Sample> out;
  const TriangleMesh sphere = uv_sphere(1.3, 12, 24);

  out.push_back({"triangles", {}});
  out.back().scene.triangle_meshes.push_back({.name = "sphere", .mesh = sphere});

  out.push_back({"triangles_rgb_scalars", {}});
  out.back().scene.triangle_meshes.push_back(
      {.name = "sphere",
       .mesh = sphere,
       .colors = colors_for(sphere.vertices, 3),
       .scalars = {
           {.name = "_DISTANCE", .values = height_field(sphere.vertices)},
           {.name = "_CELL", .values = std::vector<float>(static_cast<std::size_t>(sphere.num_vertices()), 3.0F)}}});

  out.push_back({"triangles_rgba", {}});
  out.back().scene.triangle_meshes.push_back({.mesh = sphere, .colors = colors_for(sphere.vertices, 4)});

  // A remesh with the attributes of a scan: sRGB colours with alpha, given
  // normals (one zero: the area-weighted one replaces it), a scalar.
  out.push_back({"triangles_scan_attributes", {}});
  {
    VertexAttributes attributes{.colors = colors_for(sphere.vertices, 4), .normals = sphere.vertices};
    attributes.normals.row(0).setZero();
    const std::vector<float> heights = height_field(sphere.vertices);
    attributes.scalars.push_back({"intensity", ValueType::uint16, std::vector<double>(heights.begin(), heights.end())});
    out.back().scene.triangle_meshes.push_back(gltf_triangle_mesh("scan", sphere, attributes));
  }

  out.push_back({"awkward_mesh", {}});
  out.back().scene.triangle_meshes.push_back({.name = "tetrahedron and degenerate", .mesh = awkward_mesh()});

  // More than 65535 vertices: uint32 indices.
  out.push_back({"uint32_indices", {}});
  {
    TriangleMesh big = grid(260);
    out.back().scene.triangle_meshes.push_back(
        {.name = "grid", .mesh = big, .scalars = {{.name = "_HEIGHT", .values = height_field(big.vertices)}}});
  }

  out.push_back({"textured_png", {}});
  out.back().scene.triangle_meshes.push_back(textured_grid(ImageFormat::png));
  out.push_back({"textured_jpeg", {}});
  out.back().scene.triangle_meshes.push_back(textured_grid(ImageFormat::jpeg));

  out.push_back({"lines", {}});
  out.back().scene.line_sets.push_back(equator_lines(1.0, 30, false));

  out.push_back({"lines_colored", {}});
  out.back().scene.line_sets.push_back(equator_lines(2.0, 17, true));

  out.push_back({"points", {}});
  out.back().scene.point_sets.push_back(some_points(sphere, 1, false));

  out.push_back({"points_colored_single", {}});
  {
    GltfPointSet one{
        .name = "one", .points = VertexMatrix{{0.1, -0.2, 0.3}}, .colors = ColorMatrix::Constant(1, 3, 1.0F)};
    out.back().scene.point_sets.push_back(std::move(one));
  }

  // Everything at once, as `geodual voronoi` writes it, plus extras and names
  // with non-ASCII and invalid UTF-8 bytes (the writer replaces the latter).
  out.push_back({"everything_extras", {}});
  {
    GltfScene& scene = out.back().scene;
    scene.triangle_meshes.push_back({.name = "cells \xC3\xA9t\xC3\xA9",
                                     .mesh = sphere,
                                     .colors = colors_for(sphere.vertices, 3),
                                     .scalars = {{.name = "_DISTANCE", .values = height_field(sphere.vertices)}}});
    scene.triangle_meshes.push_back({.name = "bad \xFF\xFE utf8", .mesh = awkward_mesh()});
    scene.line_sets.push_back(equator_lines(1.3, 40, true));
    scene.line_sets.push_back(equator_lines(0.5, 5, false));
    scene.point_sets.push_back(some_points(sphere, 7, true));
    scene.point_sets.push_back(some_points(sphere, 11, false));
    scene.extras_json = R"({"generator": "geodual_gltf_samples", "sites": 42, "energy": [1.5, 0.25e-7],
      "nested": {"ok": true, "none": null, "text": "\u00e9\u4e2d"}})";
  }

  // Compressed for the web: the scan's attributes, uint32 indices, and
  // everything at once (degenerate and unreferenced vertices, lines and points
  // left uncompressed beside the meshes).
  for (const GltfCompression compression : {GltfCompression::meshopt, GltfCompression::draco}) {
    for (const char* name : {"triangles_scan_attributes", "uint32_indices", "everything_extras", "textured_png"}) {
      const auto base = std::find_if(out.begin(), out.end(), [&](const Sample& sample) { return sample.name == name; });
      Sample compressed = *base;
      compressed.name = std::string(name) + "_" + std::string(gltf_compression_name(compression));
      compressed.scene.compression = compression;
      out.push_back(std::move(compressed));
    }
  }
  return out;
}

void write_bytes(const fs::path& path, const std::vector<std::byte>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw Error("cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: geodual_gltf_samples OUTPUT_FOLDER\n";
    return 2;
  }
  try {
    const fs::path folder = argv[1];
    fs::create_directories(folder);
    for (const Sample& sample : samples()) {
      // encode_gltf for both containers, written here ...
      const fs::path glb = folder / (sample.name + ".glb");
      const fs::path gltf = folder / (sample.name + ".gltf");
      write_bytes(glb, encode_gltf(sample.scene, GltfContainer::glb));
      write_bytes(gltf, encode_gltf(sample.scene, GltfContainer::gltf_embedded));
      std::cout << glb.string() << '\n' << gltf.string() << '\n';
    }
    // ... and write_gltf choosing the container by the (case-insensitive)
    // extension, for a scene and for a bare TriangleMesh.
    const TriangleMesh sphere = uv_sphere(0.75, 6, 9);
    GltfScene scene;
    scene.triangle_meshes.push_back({.name = "written", .mesh = sphere, .colors = colors_for(sphere.vertices, 3)});
    scene.point_sets.push_back(some_points(sphere, 2, true));
    scene.extras_json = R"({"via": "write_gltf"})";
    const std::vector<fs::path> written = {folder / "write_gltf_scene.GLB", folder / "write_gltf_scene.gltf",
                                           folder / "write_gltf_mesh.glb", folder / "write_gltf_mesh.Gltf"};
    write_gltf(written[0], scene);
    write_gltf(written[1], scene);
    write_gltf(written[2], sphere);
    write_gltf(written[3], awkward_mesh());
    for (const fs::path& path : written) std::cout << path.string() << '\n';
  } catch (const std::exception& error) {
    std::cerr << "geodual_gltf_samples: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
