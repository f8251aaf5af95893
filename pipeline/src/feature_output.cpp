#include "geodual/pipeline/feature_output.hpp"

#include "geodual/mesh/sorted_edges.hpp"

#include <algorithm>
#include <array>

namespace geodual::pipeline {

ColorMatrix feature_colors(const RemeshPipelineResult& result) {
  const TriangleMesh& remeshed = result.remesh.mesh;
  ColorMatrix colors(remeshed.vertices.rows(), 3);
  colors.rowwise() = Eigen::RowVector3f(0.8f, 0.8f, 0.8f);
  const Eigen::RowVector3f red(0.85f, 0.1f, 0.05f);
  const auto vertex_of = [&](std::size_t site) {
    return result.remesh.vertex_of_site.empty() ? static_cast<Index>(site) : result.remesh.vertex_of_site[site];
  };
  for (const Index vertex : crease_pin_vertices(result)) {  // on the short creases
    if (vertex >= 0) colors.row(vertex) = red;
  }
  if (result.features.empty()) return colors;
  // The chains' vertices and edges, on the surface the features were found on.
  std::vector<char> on_chain(static_cast<std::size_t>(result.surface.mesh.num_vertices()), 0);
  std::vector<std::array<Index, 2>> chain_edges;
  for (const remesh::FeatureChain& chain : result.features.chains) {
    for (std::size_t k = 0; k < chain.vertices.size(); ++k) {
      on_chain[static_cast<std::size_t>(chain.vertices[k])] = 1;
      if (k == 0) continue;
      const Index a = chain.vertices[k - 1], b = chain.vertices[k];
      chain_edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(chain_edges.begin(), chain_edges.end());
  // The sites lie on the features' cut: a site is on a chain where it is a
  // copy of a chain vertex or a point on a chain edge (a zero barycentric).
  const remesh::FeatureCut& cut = result.feature_cut;
  auto original = [&](Index cut_vertex) { return cut.original_vertex[static_cast<std::size_t>(cut_vertex)]; };
  for (std::size_t s = 0; s < result.remesh.sites.size(); ++s) {
    const SurfacePoint& site = result.remesh.sites[s];
    bool on = false;
    if (site.kind == SurfacePoint::Kind::vertex) {
      on = on_chain[static_cast<std::size_t>(original(site.element))] != 0;
    } else {
      for (int zero = 0; zero < 3 && !on; ++zero) {
        if (site.barycentric[zero] != 0) continue;
        const Index a = original(cut.mesh.faces(site.element, (zero + 1) % 3));
        const Index b = original(cut.mesh.faces(site.element, (zero + 2) % 3));
        on = find_sorted_edge(chain_edges, a, b) >= 0;
      }
    }
    const Index vertex = vertex_of(s);
    if (on && vertex >= 0) colors.row(vertex) = red;
  }
  return colors;
}

std::vector<std::vector<Eigen::Vector3d>> feature_polylines(const RemeshPipelineResult& result) {
  std::vector<std::vector<Eigen::Vector3d>> lines;
  for (const remesh::FeatureChain& chain : result.features.chains) {
    std::vector<Eigen::Vector3d>& line = lines.emplace_back();
    for (const Index v : chain.vertices) line.push_back(result.surface.mesh.vertices.row(v).transpose());
  }
  if (result.crease_pins > 0) {
    for (const remesh::FeatureChain& crease : result.features.short_creases) {
      std::vector<Eigen::Vector3d>& line = lines.emplace_back();
      for (const Index v : crease.vertices) line.push_back(result.surface.mesh.vertices.row(v).transpose());
    }
  }
  return lines;
}

}  // namespace geodual::pipeline
