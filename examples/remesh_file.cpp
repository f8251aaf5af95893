// Remeshes a scan with the whole geodual pipeline and writes the result.
//
//   remesh_file INPUT OUTPUT [SITES]     e.g. remesh_file scan.ply remeshed.glb 2000
//
// INPUT: .ply .obj .off .stl .gltf .glb; OUTPUT: .ply .obj .glb .gltf.
// Default options (4000 blue-noise sites, 10 Newton-accelerated Lloyd iterations,
// quality and Hausdorff distance measured against the input), but the
// distance measured on fewer points.

#include <geodual/io/write_mesh.hpp>
#include <geodual/pipeline/remesh_pipeline.hpp>

#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::cerr << "usage: remesh_file INPUT OUTPUT [SITES]\n";
    return 2;
  }
  try {
    geodual::pipeline::RemeshPipelineOptions options;
    if (argc == 4) options.sites = std::stoll(argv[3]);
    options.quality.samples_per_side = 100'000;  // for the Hausdorff figure; 10x fewer than the default
    const auto result = geodual::pipeline::run_remesh_pipeline(argv[1], options);
    geodual::io::write_mesh(argv[2], result.remesh.mesh, result.attributes);  // with the scan's colours

    const auto& stats = *result.statistics;  // set: options.statistics is true by default
    std::cout << "vertices  " << result.remesh.mesh.num_vertices() << '\n'
              << "faces     " << result.remesh.mesh.num_faces() << '\n'
              << "Qavg      " << stats.candidate.q_avg << '\n'
              << "Hausdorff " << stats.hausdorff_pct << " % of the bounding-box diagonal\n";
  } catch (const std::exception& error) {  // geodual::Error: bad file, bad site count, ...
    std::cerr << "remesh_file: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
