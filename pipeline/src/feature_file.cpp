#include "geodual/pipeline/feature_file.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/sorted_edges.hpp"
#include "parse_token.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace geodual {
namespace {

/// The mesh's edges as vertex pairs (smaller first), sorted, once each.
std::vector<std::array<Index, 2>> mesh_edges(const TriangleMesh& mesh) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

bool is_edge(const std::vector<std::array<Index, 2>>& edges, Index a, Index b) {
  return find_sorted_edge(edges, a, b) >= 0;
}

}  // namespace

std::vector<std::array<Index, 2>> read_feature_file(const std::filesystem::path& path, const TriangleMesh& mesh) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the feature file");
  const std::vector<std::array<Index, 2>> edges_of_mesh = mesh_edges(mesh);
  std::vector<std::array<Index, 2>> edges;
  std::string line;
  for (std::int64_t number = 1; std::getline(in, line); ++number) {
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    std::istringstream tokens(line);
    std::vector<Index> polyline;
    for (std::string word; tokens >> word;) {
      if (polyline.empty() && word[0] == '#') break;
      Index v = 0;
      if (!detail::parse_token(word, v)) {
        throw Error(where + "expected vertex indices 'A B ...' (a polyline of the mesh's edges), got '" + word + "'");
      }
      if (v < 0 || v >= mesh.num_vertices()) {
        throw Error(where + "vertex " + word + " is out of range [0, " + std::to_string(mesh.num_vertices()) + ")");
      }
      if (!polyline.empty() && !is_edge(edges_of_mesh, polyline.back(), v)) {
        throw Error(where + "vertices " + std::to_string(polyline.back()) + " and " + word +
                    " are not an edge of the mesh (no face has both)");
      }
      polyline.push_back(v);
    }
    if (polyline.size() == 1) throw Error(where + "a polyline needs two vertices or more, got one");
    for (std::size_t i = 1; i < polyline.size(); ++i) edges.push_back({polyline[i - 1], polyline[i]});
  }
  if (in.bad()) throw Error(path.string() + ": read error");
  if (edges.empty()) throw Error(path.string() + ": the feature file holds no edges");
  return edges;
}

void require_edges_of(const TriangleMesh& mesh, const std::vector<std::array<Index, 2>>& edges,
                      const std::string& what) {
  if (edges.empty()) return;
  const std::vector<std::array<Index, 2>> edges_of_mesh = mesh_edges(mesh);
  for (const auto& [a, b] : edges) {
    const std::string pair = what + " " + std::to_string(a) + " " + std::to_string(b) + ": ";
    if (a < 0 || b < 0 || a >= mesh.num_vertices() || b >= mesh.num_vertices()) {
      throw UsageError(pair + "a vertex out of range [0, " + std::to_string(mesh.num_vertices()) + ")");
    }
    if (!is_edge(edges_of_mesh, a, b)) throw UsageError(pair + "not an edge of the mesh (no face has both vertices)");
  }
}

}  // namespace geodual
