// OBJ reading: every face-corner form, relative indices, polygons, the
// keywords that are ignored, comments and CRLF line ends.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geodual::test {
namespace {

TEST(ObjReader, AllFaceCornerForms) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "forms.obj",
                                          "v 0 0 0\n"
                                          "v 1 0 0\n"
                                          "v 1 1 0\n"
                                          "v 0 1 0\n"
                                          "vt 0 0\nvt 1 0\nvt 1 1\n"
                                          "vn 0 0 1\n"
                                          "f 1 2 3\n"
                                          "f 1/1 3/2 4/3\n"
                                          "f 2//1 3//1 4//1\n"
                                          "f 4/3/1 1/1/1 2/2/1\n");
  EXPECT_EQ(loaded.mesh.num_vertices(), 4);
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 2, 3, 1, 2, 3, 3, 0, 1}));
  EXPECT_EQ(loaded.info.format, io::MeshFormat::obj);
  EXPECT_EQ(loaded.info.polygons_split, 0);
}

TEST(ObjReader, NegativeIndicesCountBackFromTheLatestVertex) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "relative.obj",
                                          "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                          "f -3 -2 -1\n"
                                          "v 5 5 5\n"
                                          "f -1/-1 -3 -2//-1\n");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 3, 1, 2}));
}

TEST(ObjReader, PolygonsAreFanTriangulated) {
  TempDir dir;
  const io::LoadedMesh loaded =
      read_text(dir, "poly.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\nf 5 4 3 2\n");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 2, 4, 2, 1}));
  EXPECT_EQ(loaded.info.polygons_split, 2);
}

TEST(ObjReader, GroupsMaterialsCommentsAndOtherKeywordsAreIgnored) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "keywords.obj",
                                          "# exported by a scanner\n"
                                          "mtllib scan.mtl\n"
                                          "o scan\n"
                                          "g body head\n"
                                          "usemtl skin\n"
                                          "s 1\n"
                                          "v 0 0 0 1.0   # a w coordinate\n"
                                          "v 1 0 0 0.5 0.5 0.5\n"
                                          "\n"
                                          "   \t\n"
                                          "v 0 1 0\n"
                                          "vp 0.5\n"
                                          "l 1 2\n"
                                          "p 3\n"
                                          "s off\n"
                                          "f 1 2 3 # trailing comment\n"
                                          "#f 3 2 1\n");
  EXPECT_EQ(loaded.mesh.num_vertices(), 3);
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(loaded.mesh.vertices(1, 0), 1.0);
}

TEST(ObjReader, CrlfLineEnds) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(loaded.mesh.vertices(2, 1), 1.0);
}

TEST(ObjReader, VertexOrderAndUnusedVerticesAreKept) {
  TempDir dir;
  const io::LoadedMesh loaded =
      read_text(dir, "unused.obj", "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\nf 2 3 4\nf 2 2 3\n");
  EXPECT_EQ(loaded.mesh.num_vertices(), 5);
  EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{9, 9, 9, 0, 0, 0, 1, 0, 0, 0, 1, 0, 9, 9, 9}));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{1, 2, 3, 1, 1, 2}));  // the degenerate face stays
}

TEST(ObjReader, FacesMayPrecedeTheirVertices) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2}));
}

TEST(ObjReader, CoordinatesAreReadExactly) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "exact.obj",
                                          "v 0.1 -1e-300 +3.25\n"
                                          "v 1.7976931348623157e308 4.9406564584124654e-324 -0\n"
                                          "v 0.30000000000000004 2 3\n"
                                          "f 1 2 3\n");
  EXPECT_EQ(loaded.mesh.vertices(0, 0), 0.1);
  EXPECT_EQ(loaded.mesh.vertices(0, 1), -1e-300);
  EXPECT_EQ(loaded.mesh.vertices(0, 2), 3.25);
  EXPECT_EQ(loaded.mesh.vertices(1, 0), 1.7976931348623157e308);
  EXPECT_EQ(loaded.mesh.vertices(1, 1), 4.9406564584124654e-324);
  EXPECT_EQ(loaded.mesh.vertices(2, 0), 0.1 + 0.2);
}

}  // namespace
}  // namespace geodual::test
