#include "geodual/pipeline/field_output.hpp"

#include "geodual/io/gltf.hpp"
#include "geodual/io/mesh_format.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/version.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace geodual {

std::array<float, 3> site_color(Index site) {
  if (site < 0) return {0.5f, 0.5f, 0.5f};
  // Hues stepped by the golden ratio never repeat and stay well apart.
  const double hue = std::fmod(0.1 + static_cast<double>(site) * 0.618033988749895, 1.0) * 6.0;
  const double saturation = site % 2 == 0 ? 0.65 : 0.45, value = site % 3 == 0 ? 0.95 : 0.8;
  const double c = value * saturation;
  const double x = c * (1 - std::abs(std::fmod(hue, 2.0) - 1));
  const double m = value - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(hue)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  return {static_cast<float>(r + m), static_cast<float>(g + m), static_cast<float>(b + m)};
}

void write_geodesic_field(const std::filesystem::path& path, const TriangleMesh& mesh,
                          const voronoi::GeodesicField& field) {
  const io::MeshFormat format = io::format_from_extension(path);
  const auto n = static_cast<std::size_t>(mesh.num_vertices());
  if (format == io::MeshFormat::ply) {
    VertexAttributes attributes;
    attributes.scalars.push_back({"distance", ValueType::float64, field.distance});
    attributes.scalars.push_back(
        {"site", ValueType::int32, std::vector<double>(field.nearest_site.begin(), field.nearest_site.end())});
    io::write_ply(path, mesh, attributes);
    return;
  }
  if (format == io::MeshFormat::glb || format == io::MeshFormat::gltf) {
    io::GltfTriangleMesh entry;
    entry.name = "geodesic_distance";
    entry.mesh = mesh;
    entry.colors.resize(static_cast<Eigen::Index>(n), 3);
    io::GltfVertexScalar distance{"_DISTANCE", std::vector<float>(n)};
    for (std::size_t v = 0; v < n; ++v) {
      const std::array<float, 3> color = site_color(field.nearest_site[v]);
      for (int c = 0; c < 3; ++c) entry.colors(static_cast<Eigen::Index>(v), c) = color[c];
      distance.values[v] = std::isfinite(field.distance[v]) ? static_cast<float>(field.distance[v]) : -1.0f;
    }
    entry.scalars.push_back(std::move(distance));
    io::GltfScene scene;
    scene.generator = "geodual " + std::string(build_version());
    scene.triangle_meshes.push_back(std::move(entry));
    io::write_gltf(path, scene);
    return;
  }
  throw Error(path.string() + ": a distance field is written as .ply, .glb or .gltf");
}

}  // namespace geodual
