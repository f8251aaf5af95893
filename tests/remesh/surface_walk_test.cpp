// Walking on the surface (Lloyd's and the warm start's steps): a walk never
// ends inside a zero-area face, where a site would have no barycentric
// coordinates.

#include "../../remesh/src/common/surface_walk.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace geodual {
namespace {

double face_area(const TriangleMesh& mesh, Index f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                        c = mesh.vertices.row(mesh.faces(f, 2));
  return (b - a).cross(c - a).norm() / 2;
}

TEST(SurfaceWalk, NeverEndsInAZeroAreaFace) {
  // ogre has zero-area faces joined to their neighbours. Walks from each
  // neighbour's centre towards the flat face's corners and points along it,
  // of lengths that end short of, inside and past the flat face.
  const TriangleMesh mesh = remesh::cut_to_manifold(io::read_mesh("tests/data/ogre.ply").mesh).mesh;
  const voronoi::GeodesicField field = voronoi::compute_geodesic_field(
      mesh, std::vector<SurfacePoint>{SurfacePoint::in_face(0, 1.0 / 3, 1.0 / 3, 1.0 / 3)});
  int flat_faces = 0, walks = 0, through_flat = 0;
  for (Index flat = 0; flat < mesh.num_faces(); ++flat) {
    if (face_area(mesh, flat) > 0 || field.face_edges[flat][0] < 0) continue;
    ++flat_faces;
    for (int k = 0; k < 3; ++k) {
      const Index edge = field.face_edges[flat][k];
      const Index from = field.edge_faces[edge][0] == flat ? field.edge_faces[edge][1] : field.edge_faces[edge][0];
      if (from < 0 || !(face_area(mesh, from) > 0)) continue;
      const SurfacePoint start = SurfacePoint::in_face(from, 1.0 / 3, 1.0 / 3, 1.0 / 3);
      const Eigen::Vector3d origin = start.position(mesh);
      for (int c = 0; c < 3; ++c) {
        for (const double along : {0.25, 0.5, 0.75}) {
          const Eigen::Vector3d target = (1 - along) * Eigen::Vector3d(mesh.vertices.row(mesh.faces(flat, c))) +
                                         along * Eigen::Vector3d(mesh.vertices.row(mesh.faces(flat, (c + 1) % 3)));
          const double distance = (target - origin).norm();
          for (const double scale : {0.9, 1.0, 1.0001, 1.1, 2.0}) {
            const SurfacePoint end =
                remesh::detail::walk_on_surface(mesh, *field.topology, start, target - origin, scale * distance);
            ++walks;
            through_flat += end.element == from ? 0 : 1;
            ASSERT_TRUE(end.barycentric.allFinite()) << "from face " << from << " towards flat face " << flat;
            EXPECT_GT(face_area(mesh, end.element), 0) << "from face " << from << " towards flat face " << flat;
            EXPECT_NEAR(end.barycentric.sum(), 1.0, 1e-12);
            EXPECT_GE(end.barycentric.minCoeff(), 0.0);
          }
        }
      }
    }
  }
  EXPECT_GE(flat_faces, 1);
  EXPECT_GT(walks, 100);
  EXPECT_GT(through_flat, 0);
}

}  // namespace
}  // namespace geodual
