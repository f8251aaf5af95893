#include "geodual/pipeline/sites.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/random.hpp"
#include "parse_token.hpp"

#include <array>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_set>

namespace geodual {
using detail::parse_token;

std::vector<SurfacePoint> random_vertex_sites(const TriangleMesh& mesh, std::int64_t count, std::uint64_t seed) {
  // Candidates: vertices of faces with three distinct corners (the others
  // take no part in any surface computation).
  std::vector<std::uint8_t> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_corner(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) used[mesh.faces(f, k)] = 1;
  }
  std::vector<Index> candidates;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    if (used[v]) candidates.push_back(v);
  }
  if (count < 1 || count > static_cast<std::int64_t>(candidates.size())) {
    throw UsageError("--sites " + std::to_string(count) + ": must be between 1 and the mesh's " +
                     std::to_string(candidates.size()) + " vertices used by a face");
  }
  // A partial Fisher-Yates shuffle; a vertex at the position of one already
  // drawn is skipped (two sites at one point have no cell between them).
  struct PositionHash {
    std::size_t operator()(const std::array<double, 3>& p) const {
      std::size_t h = 0;
      for (const double x : p) h = h * 1000003u ^ std::hash<double>{}(x);
      return h;
    }
  };
  std::unordered_set<std::array<double, 3>, PositionHash> taken;
  SplitMix64 rng(seed);
  std::vector<SurfacePoint> sites;
  sites.reserve(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < candidates.size() && sites.size() < static_cast<std::size_t>(count); ++i) {
    const std::size_t j = i + rng.below(candidates.size() - i);
    std::swap(candidates[i], candidates[j]);
    const Index v = candidates[i];
    if (taken.insert({mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)}).second) {
      sites.push_back(SurfacePoint::at_vertex(v));
    }
  }
  if (sites.size() < static_cast<std::size_t>(count)) {
    throw UsageError("--sites " + std::to_string(count) + ": the mesh has only " + std::to_string(sites.size()) +
                     " vertices at distinct positions used by a face");
  }
  return sites;
}

std::vector<SurfacePoint> read_site_file(const std::filesystem::path& path, const TriangleMesh& mesh) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the site file");
  std::vector<SurfacePoint> sites;
  std::string line;
  for (std::int64_t number = 1; std::getline(in, line); ++number) {
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string w; tokens >> w;) words.push_back(w);
    if (words.empty() || words[0][0] == '#') continue;
    if (words.size() == 1) {
      Index v = 0;
      if (!parse_token(words[0], v))
        throw Error(where + "expected a vertex index or 'f FACE U V W', got '" + line + "'");
      if (v < 0 || v >= mesh.num_vertices()) {
        throw Error(where + "vertex " + words[0] + " is out of range [0, " + std::to_string(mesh.num_vertices()) + ")");
      }
      sites.push_back(SurfacePoint::at_vertex(v));
      continue;
    }
    Index f = 0;
    double u = 0, v = 0, w = 0;
    if (words.size() != 5 || words[0] != "f" || !parse_token(words[1], f) || !parse_token(words[2], u) ||
        !parse_token(words[3], v) || !parse_token(words[4], w)) {
      throw Error(where + "expected a vertex index or 'f FACE U V W', got '" + line + "'");
    }
    if (f < 0 || f >= mesh.num_faces()) {
      throw Error(where + "face " + words[1] + " is out of range [0, " + std::to_string(mesh.num_faces()) + ")");
    }
    sites.push_back(SurfacePoint::in_face(f, u, v, w));
  }
  if (in.bad()) throw Error(path.string() + ": read error");
  if (sites.empty()) throw Error(path.string() + ": the site file holds no sites");
  return sites;
}

}  // namespace geodual
