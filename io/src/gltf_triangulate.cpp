#include "gltf_triangulate.hpp"

#include <utility>

namespace geodual::io::detail::gltf {
namespace {

void add_unless_degenerate(Triangulation& out, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a == b || b == c || a == c) {
    ++out.degenerate_dropped;
    return;
  }
  out.corners.insert(out.corners.end(), {a, b, c});
}

}  // namespace

Triangulation triangulate(PrimitiveMode mode, std::vector<std::uint32_t> vertices) {
  Triangulation out;
  const std::size_t n = vertices.size();
  switch (mode) {
    case PrimitiveMode::triangles:
      out.trailing_ignored = n % 3;
      vertices.resize(n - n % 3);
      out.corners = std::move(vertices);
      break;
    case PrimitiveMode::triangle_strip:
      if (n < 3) break;
      out.corners.reserve(3 * (n - 2));
      for (std::size_t i = 0; i + 2 < n; ++i) {
        const std::size_t odd = i % 2;
        add_unless_degenerate(out, vertices[i], vertices[i + 1 + odd], vertices[i + 2 - odd]);
      }
      break;
    case PrimitiveMode::triangle_fan:
      if (n < 3) break;
      out.corners.reserve(3 * (n - 2));
      for (std::size_t i = 0; i + 2 < n; ++i) {
        add_unless_degenerate(out, vertices[i + 1], vertices[i + 2], vertices[0]);
      }
      break;
    case PrimitiveMode::points:
    case PrimitiveMode::lines:
    case PrimitiveMode::line_loop:
    case PrimitiveMode::line_strip: break;
  }
  return out;
}

}  // namespace geodual::io::detail::gltf
