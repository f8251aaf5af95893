// A remesh from sites of our own choosing: farthest point sampling on the
// mesh's vertices, with distances measured along mesh edges (Dijkstra), in
// place of remesh::sample_sites. The pipeline takes the sites through
// RemeshPipelineOptions::given_sites and runs the rest: Lloyd relaxation,
// the dual, repair, statistics.
//
//   custom_sampling INPUT OUTPUT [SITES]     e.g. custom_sampling scan.ply remeshed.ply 1000

#include <geodual/io/read_mesh.hpp>
#include <geodual/io/write_mesh.hpp>
#include <geodual/pipeline/remesh_pipeline.hpp>
#include <geodual/remesh/manifold_cut.hpp>
#include <geodual/remesh/sample_sites.hpp>

#include <cstdint>
#include <exception>
#include <functional>
#include <iostream>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

namespace {

using geodual::Index;
using geodual::SurfacePoint;
using geodual::TriangleMesh;

/// Farthest point sampling on the vertices, by edge-graph distance.
class FarthestPointSampler {
 public:
  explicit FarthestPointSampler(const TriangleMesh& mesh) : mesh_(mesh) {
    // Vertex adjacency in compressed rows: each face side once in each direction.
    const auto vertex_count = static_cast<std::size_t>(mesh.num_vertices());
    first_.assign(vertex_count + 1, 0);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      for (int c = 0; c < 3; ++c) first_[static_cast<std::size_t>(mesh.faces(f, c)) + 1] += 2;
    }
    for (std::size_t v = 0; v < vertex_count; ++v) first_[v + 1] += first_[v];
    neighbour_.resize(first_.back());
    std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const Index a = mesh.faces(f, c), b = mesh.faces(f, (c + 1) % 3);
        neighbour_[next[static_cast<std::size_t>(a)]++] = b;
        neighbour_[next[static_cast<std::size_t>(b)]++] = a;
      }
    }
    distance_.assign(vertex_count, infinity);
    // One face of three distinct corners per vertex, to give sites as face points.
    corner_face_.assign(vertex_count, -1);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
      const auto corners = mesh.faces.row(f);
      if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) continue;
      for (const Index v : {corners[0], corners[1], corners[2]}) {
        if (corner_face_[static_cast<std::size_t>(v)] < 0) corner_face_[static_cast<std::size_t>(v)] = f;
      }
    }
  }

  /// A site that is already there (for example on a boundary loop): the
  /// distance of its face's corners is the straight line to it.
  void add_fixed_site(const SurfacePoint& site) {
    const Eigen::Vector3d p = site.position(mesh_);
    if (site.kind == SurfacePoint::Kind::vertex) {
      relax_from(site.element, 0.0);
      return;
    }
    for (int c = 0; c < 3; ++c) {
      const Index corner = mesh_.faces(site.element, c);
      relax_from(corner, (mesh_.vertices.row(corner).transpose() - p).norm());
    }
  }

  /// The vertex farthest from every site so far (an unreached one, of a
  /// component without sites, first), made a site. It is returned as the
  /// corner of a face, not as SurfacePoint::at_vertex: Lloyd relaxation
  /// moves face points only.
  SurfacePoint add_farthest_vertex() {
    Index farthest = -1;
    for (Index v = 0; v < mesh_.num_vertices(); ++v) {
      const std::size_t i = static_cast<std::size_t>(v);
      if (corner_face_[i] >= 0 && (farthest < 0 || distance_[i] > distance_[static_cast<std::size_t>(farthest)])) {
        farthest = v;
      }
    }
    relax_from(farthest, 0.0);
    const Index face = corner_face_[static_cast<std::size_t>(farthest)];
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) barycentric[c] = mesh_.faces(face, c) == farthest ? 1.0 : 0.0;
    return SurfacePoint::in_face(face, barycentric[0], barycentric[1], barycentric[2]);
  }

 private:
  static constexpr double infinity = std::numeric_limits<double>::infinity();

  // Dijkstra from one vertex, visiting only vertices it brings closer: each
  // new site touches its own (shrinking) cell, not the whole mesh.
  void relax_from(Index start, double start_distance) {
    if (start_distance >= distance_[static_cast<std::size_t>(start)]) return;
    distance_[static_cast<std::size_t>(start)] = start_distance;
    queue_.push({start_distance, start});
    while (!queue_.empty()) {
      const auto [d, v] = queue_.top();
      queue_.pop();
      if (d > distance_[static_cast<std::size_t>(v)]) continue;  // a stale entry
      for (std::size_t k = first_[static_cast<std::size_t>(v)]; k < first_[static_cast<std::size_t>(v) + 1]; ++k) {
        const Index w = neighbour_[k];
        const double through_v = d + (mesh_.vertices.row(w) - mesh_.vertices.row(v)).norm();
        if (through_v < distance_[static_cast<std::size_t>(w)]) {
          distance_[static_cast<std::size_t>(w)] = through_v;
          queue_.push({through_v, w});
        }
      }
    }
  }

  const TriangleMesh& mesh_;
  std::vector<std::size_t> first_;  // neighbours of v: neighbour_[first_[v] .. first_[v + 1])
  std::vector<Index> neighbour_;
  std::vector<double> distance_;    // to the nearest site so far
  std::vector<Index> corner_face_;  // per vertex: a face it is a corner of (-1: none)
  std::priority_queue<std::pair<double, Index>, std::vector<std::pair<double, Index>>, std::greater<>> queue_;
};

/// `count` sites: the library's sites on the boundary loops (without them the
/// dual would close the mesh's holes), then farthest vertices. `mesh` is the
/// surface the pipeline remeshes (see main).
std::vector<SurfacePoint> farthest_vertex_sites(const TriangleMesh& mesh, std::int64_t count) {
  FarthestPointSampler sampler(mesh);
  std::vector<SurfacePoint> sites;
  // sample_sites puts its boundary sites on boundary edges: one barycentric
  // coordinate exactly 0 (its interior sites have all three > 0).
  for (const SurfacePoint& site : geodual::remesh::sample_sites(mesh, count)) {
    if (site.barycentric.minCoeff() == 0.0) {
      sites.push_back(site);
      sampler.add_fixed_site(site);
    }
  }
  while (static_cast<std::int64_t>(sites.size()) < count) sites.push_back(sampler.add_farthest_vertex());
  return sites;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::cerr << "usage: custom_sampling INPUT OUTPUT [SITES]\n";
    return 2;
  }
  try {
    geodual::io::LoadedMesh input = geodual::io::read_mesh(argv[1]);
    const std::int64_t count = argc == 4 ? std::stoll(argv[3]) : 1000;

    geodual::pipeline::RemeshPipelineOptions options;
    // The pipeline remeshes the input cut apart at non-manifold edges and
    // vertices (they become boundaries, which need sites); the cut keeps the
    // faces, so face points on it are face points on the input.
    const geodual::TriangleMesh surface = geodual::remesh::cut_to_manifold(input.mesh).mesh;
    options.given_sites = farthest_vertex_sites(surface, count);
    options.quality.samples_per_side = 100'000;  // a quick Hausdorff estimate
    // Progress: one line per stage as it starts. Returning false would cancel
    // the run (geodual::Cancelled is thrown).
    options.progress = [last = -1](geodual::pipeline::Stage stage, double) mutable {
      if (static_cast<int>(stage) != last) std::cout << "stage " << geodual::pipeline::stage_name(stage) << '\n';
      last = static_cast<int>(stage);
      return true;
    };

    const auto result = geodual::pipeline::run_remesh_pipeline(std::move(input), options);
    geodual::io::write_mesh(argv[2], result.remesh.mesh);

    const auto& stats = *result.statistics;
    std::cout << "sites     " << result.initial_sites.size() << " farthest-point, " << result.remesh.sites_added
              << " added by repair, " << result.relaxation.iterations << " Lloyd iterations\n"
              << "output    " << argv[2] << " (" << result.remesh.mesh.num_vertices() << " vertices, "
              << result.remesh.mesh.num_faces() << " faces)\n"
              << "quality   Qmin " << stats.candidate.q_min << ", Qavg " << stats.candidate.q_avg << ", "
              << stats.candidate.pct_angles_lt30 << " % of angles < 30 deg\n"
              << "distance  Hausdorff " << stats.hausdorff_pct << " %, RMS " << stats.rms_pct
              << " % of the bounding-box diagonal\n"
              << "topology  Euler characteristic " << stats.candidate.euler_characteristic << " (input "
              << stats.reference.euler_characteristic << "), " << stats.candidate.boundary_loops
              << " boundary loops (input " << stats.reference.boundary_loops << ")\n";
  } catch (const std::exception& error) {  // geodual::Error: bad file, too few sites, ...
    std::cerr << "custom_sampling: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
