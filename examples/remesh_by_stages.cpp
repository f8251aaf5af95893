// Remeshes a mesh with geodual's stages called one by one: the same remesh,
// byte for byte, as `geodual remesh MESH --sites SITES -o OUT.ply` with its
// default options (sharp features, deviation fitting and angle smoothing
// included), where the CLI's first try keeps the features. Where it does
// not, this program stops and says so; the CLI then tries again with the
// creases near the failure left out (docs/library.md).
//
//   remesh_by_stages MESH SITES OUT.ply

#include <geodual/io/read_mesh.hpp>
#include <geodual/io/write_mesh.hpp>
#include <geodual/mesh/coordinate_range.hpp>
#include <geodual/remesh/chain_slider.hpp>
#include <geodual/remesh/remesh.hpp>
#include <geodual/remesh/remesh_smoothing.hpp>
#include <geodual/remesh/welded_dual.hpp>

#include <cstdint>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <utility>

namespace remesh = geodual::remesh;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: remesh_by_stages MESH SITES OUT.ply\n";
    return 2;
  }
  try {
    const geodual::io::LoadedMesh input = geodual::io::read_mesh(argv[1]);
    const std::int64_t sites = std::stoll(argv[2]);
    // The CLI's defaults, stage by stage.
    const remesh::SamplingOptions sampling;          // blue noise, seed 1
    const remesh::FeatureRemeshOptions features;     // creases at 60 degrees, continued at 30
    const remesh::RemeshOptions options;             // Lloyd-Newton, up to 10 repair rounds
    const remesh::RemeshSmoothingOptions smoothing;  // deviation fitting, angle smoothing at 30 degrees

    // The surface: the input cut apart at non-manifold edges and vertices.
    // Its topology, built once (by the cut) for the features and the sampling
    // (remesh/remesh_surface.hpp).
    geodual::MeshTopology topology;
    const remesh::ManifoldCut surface = remesh::cut_to_manifold(input.mesh, {}, topology);
    std::optional<remesh::RemeshSurface> prepared(std::in_place, surface.mesh, std::move(topology));

    // Features: creases at the remesh's scale, cut open and lined with sites.
    remesh::FeatureSamplingOptions feature_options = remesh::feature_sampling_options(features, input.mesh, surface);
    feature_options.max_chord_error = 5e-4 * geodual::referenced_bounding_box(input.mesh).diagonal();
    const remesh::FeatureSampling creases = remesh::sample_features(*prepared, sites, feature_options);

    // Sites: blue noise around the chains' sites, on the surface cut along them.
    const remesh::RemeshSites initial = remesh::sample_remesh_sites(*prepared, sites, creases, {}, sampling);
    const geodual::TriangleMesh& cut = creases.sites_surface(surface.mesh);

    // Relaxation (Lloyd-Newton), the sites on chains sliding along them; the
    // surface is prepared once for every diagram of this stage and the next.
    remesh::LloydOptions lloyd = remesh::relaxation_options(cut, initial, creases.density, options);
    std::optional<remesh::ChainSlider> slider;
    if (!creases.empty()) {
      slider.emplace(*prepared, creases.features, creases.cut);
      lloyd.slide_boundary_sites = std::cref(*slider);
    }
    prepared.reset();  // not needed by the relaxation, whose memory peaks
    const geodual::voronoi::GeodesicSurface geodesic(cut);
    remesh::LloydResult relaxed = remesh::lloyd_relax(geodesic, initial.sites, lloyd);

    // The dual with repair, welded along the chains.
    const remesh::RepairOptions repair =
        creases.empty() ? remesh::repair_options(options)
                        : remesh::repair_options(options, features, static_cast<std::int64_t>(initial.sites.size()));
    remesh::RepairedDual remeshed =
        creases.empty() ? remesh::dual_with_repair(geodesic, relaxed.sites, std::move(relaxed.diagram), repair)
                        : remesh::welded_dual_with_repair(geodesic, surface.mesh, creases.features, creases.cut,
                                                          relaxed.sites, std::move(relaxed.diagram), repair);

    // Deviation fitting and angle smoothing; the input's attributes carried over.
    remesh::smooth_remesh(remeshed, cut, *geodesic.topology(), smoothing);
    const geodual::VertexAttributes attributes = geodual::interpolate_attributes(
        input.mesh, input.attributes, remesh::remesh_points_on_input(remeshed, surface, creases.cut));
    geodual::io::write_mesh(argv[3], remeshed.mesh, attributes);

    std::cout << "vertices " << remeshed.mesh.num_vertices() << ", faces " << remeshed.mesh.num_faces() << ", chains "
              << creases.features.sharp_chains << ", sites added by repair " << remeshed.sites_added << '\n';
  } catch (const remesh::DualRepairError& error) {
    std::cerr << "remesh_by_stages: " << error.what()
              << " (geodual remesh tries again with the creases near there left out)\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "remesh_by_stages: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
