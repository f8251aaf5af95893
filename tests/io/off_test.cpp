// OFF reading: comments, where the counts may stand, polygons of any size,
// per-face colours, and the COFF / NOFF variants.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geodual::test {
namespace {

TEST(OffReader, TrianglesAndPolygonsWithCommentsAndFaceColours) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "mesh.off",
                                          "OFF\n"
                                          "# a pentagon, a quad and a triangle\n"
                                          "\n"
                                          "6 3 0\n"
                                          "0 0 0\n"
                                          "1 0 0   # comment after a vertex\n"
                                          "2 1 0\n"
                                          "1 2 0\n"
                                          "0 1 0\n"
                                          "7 7 7\n"
                                          "5 0 1 2 3 4\n"
                                          "4 4 3 2 1 255 0 0\n"
                                          "3 0 1 4 0.5 0.5 0.5 1.0\n");
  EXPECT_EQ(loaded.mesh.num_vertices(), 6);  // vertex 5 is unused and stays
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 2, 4, 2, 1, 0, 1, 4}));
  EXPECT_EQ(loaded.info.polygons_split, 2);
  EXPECT_EQ(loaded.info.format, io::MeshFormat::off);
  EXPECT_EQ(loaded.mesh.vertices(5, 2), 7.0);
}

TEST(OffReader, CountsOnTheHeaderLineAndCrlf) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "inline.off", "OFF 3 1 3\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(loaded.mesh.vertices(1, 0), 1.0);
}

TEST(OffReader, CountsWithoutEdgesAndHeaderAfterComments) {
  TempDir dir;
  const io::LoadedMesh loaded =
      read_text(dir, "noedges.off", "# written by hand\nOFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0");
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{2, 1, 0}));
}

TEST(OffReader, ColourAndNormalVariantsIgnoreTheExtraValues) {
  TempDir dir;
  const io::LoadedMesh coff = read_text(dir, "c.off",
                                        "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n"
                                        "3 0 1 2\n");
  EXPECT_EQ(vertex_list(coff.mesh), (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const io::LoadedMesh noff = read_text(dir, "n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
  EXPECT_EQ(vertex_list(noff.mesh), (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(face_list(noff.mesh), (std::vector<Index>{0, 1, 2}));
}

TEST(OffReader, DoubleCoordinatesAreExact) {
  TempDir dir;
  const io::LoadedMesh loaded =
      read_text(dir, "exact.off", "OFF\n3 1 0\n0.1 0.2 0.30000000000000004\n1e-310 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(loaded.mesh.vertices(0, 0), 0.1);
  EXPECT_EQ(loaded.mesh.vertices(0, 2), 0.1 + 0.2);
  EXPECT_EQ(loaded.mesh.vertices(1, 0), 1e-310);
}

}  // namespace
}  // namespace geodual::test
