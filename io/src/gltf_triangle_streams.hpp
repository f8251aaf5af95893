#pragma once
// Internal: a triangle mesh entry's vertex data once checked, as the glTF
// writer stores it (float32, one row per vertex), for the compressed forms
// (gltf_meshopt.hpp, gltf_draco.hpp) to encode.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

/// One float per vertex under an attribute name as written (e.g. "_DISTANCE").
struct NamedScalars {
  std::string name{};
  std::vector<float> values{};
};

struct TriangleStreams {
  std::size_t vertex_count = 0;
  std::vector<float> positions{};  ///< 3 per vertex, finite
  std::vector<float> normals{};    ///< 3 per vertex, unit length
  int color_channels = 0;          ///< 0 (no COLOR_0), 3 or 4
  std::vector<float> colors{};     ///< color_channels per vertex, linear, in [0, 1]
  std::vector<NamedScalars> scalars{};
  std::vector<float> texcoords{};        ///< TEXCOORD_0: empty, or 2 per vertex, finite
  std::vector<float> tangents{};         ///< TANGENT: empty, or 4 per vertex, xyz unit, w +-1
  std::vector<std::uint32_t> indices{};  ///< 3 per triangle, each < vertex_count
};

}  // namespace geodual::io::detail::gltf
