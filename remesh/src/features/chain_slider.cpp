#include "geodual/remesh/chain_slider.hpp"

#include "features/chain_points.hpp"
#include "geodual/mesh/mesh_topology.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace geodual::remesh {
namespace {

/// The copy in cut.mesh of surface vertex v at face f.
Index copy_at(const FeatureCut& cut, const TriangleMesh& surface, Index f, Index v) {
  for (int k = 0; k < 3; ++k) {
    if (surface.faces(f, k) == v) return cut.mesh.faces(f, k);
  }
  return -1;
}

/// A point on a chain held by one or more sites (twins, one per side).
struct ChainPoint {
  detail::SiteKey key;
  Index chain = 0;
  double at = 0;         ///< arc length along the chain
  double pull = 0;       ///< sum over its sites of the moment along the chain's tangent
  double mass = 0;       ///< sum over its sites of their cells' mass
  std::size_t site = 0;  ///< of its first site in `members`
  std::size_t count = 0;
};

}  // namespace

ChainSlider::ChainSlider(const TriangleMesh& surface, const FeatureSet& features, const FeatureCut& cut)
    : ChainSlider(RemeshSurface(surface), features, cut) {}

ChainSlider::ChainSlider(const RemeshSurface& prepared, const FeatureSet& features, const FeatureCut& cut)
    : surface_(&prepared.mesh()), features_(&features), cut_(&cut) {
  const TriangleMesh& surface = prepared.mesh();
  const MeshTopology& topology = prepared.topology();
  side_faces_.resize(features.chains.size());
  for (std::size_t c = 0; c < features.chains.size(); ++c) {
    const std::vector<Index>& vertices = features.chains[c].vertices;
    std::vector<std::array<Index, 2>>& sides = side_faces_[c];
    for (std::size_t i = 0; i + 1 < vertices.size(); ++i) {
      const Index a = vertices[i], b = vertices[i + 1];
      const Index e = topology.find_edge(a, b);
      std::array<Index, 2> faces = {-1, -1};
      if (e >= 0) {
        const auto around = topology.edge_faces(e);
        for (std::size_t k = 0; k < around.size() && k < 2; ++k) faces[k] = around[k];
        // Side 0 goes on through the copy of a that side 0 of the last edge has.
        if (i > 0 && faces[1] >= 0 && sides.back()[0] >= 0 &&
            copy_at(cut, surface, faces[1], a) == copy_at(cut, surface, sides.back()[0], a)) {
          std::swap(faces[0], faces[1]);
        }
      }
      sides.push_back(faces);
      edges_.push_back({{std::min(a, b), std::max(a, b)}, static_cast<Index>(c), static_cast<Index>(i)});
    }
  }
  std::sort(edges_.begin(), edges_.end(), [](const EdgeOnChain& x, const EdgeOnChain& y) { return x.edge < y.edge; });
}

std::vector<SurfacePoint> ChainSlider::operator()(std::span<const SurfacePoint> sites, std::span<const double> mass,
                                                  std::span<const Eigen::Vector3d> moment) const {
  std::vector<SurfacePoint> moved(sites.begin(), sites.end());
  const TriangleMesh& surface = *surface_;
  std::vector<detail::ChainWalk> walks;
  walks.reserve(features_->chains.size());
  for (const FeatureChain& chain : features_->chains) walks.emplace_back(surface, chain);

  // The sites on chain edges, with their side, grouped into points by key.
  struct Member {
    detail::SiteKey key;
    std::size_t site;
    Index chain, segment;
    int side;
  };
  std::vector<Member> members;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    const detail::SiteKey key = detail::site_key(surface, *cut_, sites[s]);
    if (key.lo < 0 || key.lo == key.hi) continue;  // inside a face, or at a vertex (corners stay)
    const std::array<Index, 2> edge = {key.lo, key.hi};
    const auto it = std::lower_bound(edges_.begin(), edges_.end(), edge,
                                     [](const EdgeOnChain& x, const std::array<Index, 2>& e) { return x.edge < e; });
    if (it == edges_.end() || it->edge != edge) continue;
    const std::array<Index, 2>& faces = side_faces_[it->chain][it->segment];
    const int side = sites[s].element == faces[0] ? 0 : sites[s].element == faces[1] ? 1 : -1;
    if (side < 0) continue;
    members.push_back({key, s, it->chain, it->segment, side});
  }
  std::sort(members.begin(), members.end(),
            [](const Member& x, const Member& y) { return x.key < y.key || (x.key == y.key && x.site < y.site); });
  std::vector<ChainPoint> points;
  for (std::size_t m = 0; m < members.size(); ++m) {
    const Member& member = members[m];
    if (points.empty() || !(points.back().key == member.key)) {
      const detail::ChainWalk& walk = walks[member.chain];
      const std::size_t i = static_cast<std::size_t>(member.segment);
      const Index first = walk.chain.vertices[i];
      const double along = first == member.key.lo ? member.key.t : 1 - member.key.t;
      points.push_back({member.key, member.chain, walk.at[i] + along * (walk.at[i + 1] - walk.at[i]), 0, 0, m, 0});
    }
    ChainPoint& point = points.back();
    const detail::ChainWalk& walk = walks[member.chain];
    const std::size_t i = static_cast<std::size_t>(member.segment);
    const Eigen::Vector3d tangent =
        (surface.vertices.row(walk.chain.vertices[i + 1]) - surface.vertices.row(walk.chain.vertices[i]))
            .transpose()
            .normalized();
    point.pull += tangent.dot(moment[member.site]);
    point.mass += mass[member.site];
    ++point.count;
  }

  // Along each chain in order: the step to the cells' centroid along the
  // tangent, kept within a third of the way to either neighbour (the
  // corners at an open chain's ends, the last point round a closed one).
  std::stable_sort(points.begin(), points.end(), [](const ChainPoint& x, const ChainPoint& y) {
    return x.chain < y.chain || (x.chain == y.chain && x.at < y.at);
  });
  for (std::size_t begin = 0; begin < points.size();) {
    std::size_t end = begin;
    while (end < points.size() && points[end].chain == points[begin].chain) ++end;
    const detail::ChainWalk& walk = walks[points[begin].chain];
    const bool closed = walk.chain.closed;
    const double length = walk.length();
    if (closed && end - begin < 3) {
      begin = end;
      continue;
    }
    std::vector<double> target(end - begin);
    for (std::size_t p = begin; p < end; ++p) {
      const ChainPoint& point = points[p];
      const double before = p > begin ? points[p - 1].at : closed ? points[end - 1].at - length : 0.0;
      const double after = p + 1 < end ? points[p + 1].at : closed ? points[begin].at + length : length;
      const double step = point.mass > 0 ? point.pull / point.mass : 0.0;
      double at = std::clamp(point.at + step, point.at - (point.at - before) / 3, point.at + (after - point.at) / 3);
      if (closed) at -= length * std::floor(at / length);
      target[p - begin] = at;
    }
    for (std::size_t p = begin; p < end; ++p) {
      const ChainPoint& point = points[p];
      const detail::SiteKey key = walk.key_at(target[p - begin]);
      if (key == point.key) continue;
      double t = 0;
      const std::size_t segment = walk.locate(target[p - begin], t);
      for (std::size_t m = point.site; m < point.site + point.count; ++m) {
        const Index face = side_faces_[point.chain][segment][members[m].side];
        if (face >= 0) moved[members[m].site] = detail::point_on_edge(surface, face, key.lo, key.hi, key.t);
      }
    }
    begin = end;
  }
  return moved;
}

}  // namespace geodual::remesh
