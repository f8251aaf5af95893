#include "geodual/mesh_report.hpp"

namespace geodual {

// Placeholder until the analysis lands (issue 2): counts only.
MeshReport analyze_mesh(const TriangleMesh& mesh) {
  MeshReport report;
  report.vertices = mesh.num_vertices();
  report.faces = mesh.num_faces();
  return report;
}

}  // namespace geodual
