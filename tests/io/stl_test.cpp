// STL reading: ASCII and binary (also a binary file that begins with
// "solid"), welding by exact position in first-occurrence order.

#include "io_test_files.hpp"

#include "geodual/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace geodual::test {
namespace {

using Triangle = std::array<std::array<float, 3>, 3>;

/// Two triangles sharing the edge (1,0,0)-(0,1,0), then a third that only
/// touches (0,0,0); 9 corners at 5 distinct positions.
const std::vector<Triangle> two_plus_one = {
    Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
    Triangle{{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
    Triangle{{{0, 0, 0}, {0, 1, 0}, {-1, 0, 0}}},
};

std::string binary_stl(const std::vector<Triangle>& triangles, std::string_view header_text) {
  ByteWriter file;
  std::string header(header_text);
  header.resize(80, ' ');
  file.text(header).put(static_cast<std::uint32_t>(triangles.size()));
  for (const Triangle& triangle : triangles) {
    file.put(0.f).put(0.f).put(1.f);  // normal
    for (const auto& corner : triangle) {
      file.put(corner[0]).put(corner[1]).put(corner[2]);
    }
    file.put<std::uint16_t>(0);
  }
  return file.str();
}

std::string ascii_stl(const std::vector<Triangle>& triangles) {
  std::string text = "solid scan\n";
  for (const Triangle& triangle : triangles) {
    text += "  facet normal 0 0 1\n    outer loop\n";
    for (const auto& corner : triangle) {
      text += "      vertex " + std::to_string(corner[0]) + " " + std::to_string(corner[1]) + " " +
              std::to_string(corner[2]) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid scan\n";
}

void expect_two_plus_one(const io::LoadedMesh& loaded) {
  EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, -1, 0, 0}));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 1, 3, 2, 0, 2, 4}));
  EXPECT_EQ(loaded.info.welded_corners, 4);
  EXPECT_EQ(loaded.info.format, io::MeshFormat::stl);
  ASSERT_FALSE(loaded.info.notes.empty());
  EXPECT_NE(loaded.info.notes.back().find("9 corners were welded into 5 vertices"), std::string::npos)
      << loaded.info.notes.back();
}

TEST(StlReader, BinaryIsWeldedInFirstOccurrenceOrder) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "b.stl", binary_stl(two_plus_one, "exported by a scanner"));
  expect_two_plus_one(loaded);
  EXPECT_EQ(loaded.info.encoding, "binary");
}

TEST(StlReader, BinaryThatBeginsWithSolidIsStillBinary) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "solid.stl", binary_stl(two_plus_one, "solid part exported by CAD"));
  expect_two_plus_one(loaded);
  EXPECT_EQ(loaded.info.encoding, "binary");
}

TEST(StlReader, Ascii) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "a.stl", ascii_stl(two_plus_one));
  expect_two_plus_one(loaded);
  EXPECT_EQ(loaded.info.encoding, "ascii");
}

TEST(StlReader, AsciiWithCrlfSeveralSolidsAndNoFinalNewline) {
  TempDir dir;
  const io::LoadedMesh loaded = read_text(dir, "multi.stl",
                                          "solid a\r\nfacet normal 0 0 1\r\nouter loop\r\n"
                                          "vertex 0 0 0\r\nvertex 1 0 0\r\nvertex 0 1 0\r\n"
                                          "endloop\r\nendfacet\r\nendsolid a\r\n"
                                          "solid b\r\nfacet normal 0 0 1\r\nouter loop\r\n"
                                          "vertex 1 0 0\r\nvertex 0 1 0\r\nvertex 0 0 2.5e-1\r\n"
                                          "endloop\r\nendfacet\r\nendsolid b");
  EXPECT_EQ(vertex_list(loaded.mesh), (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.25}));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 1, 2, 3}));
}

TEST(StlReader, OnlyExactlyEqualPositionsAreWelded) {
  TempDir dir;
  const float next_after_one = 1.0000001f;
  const std::vector<Triangle> triangles = {
      Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
      Triangle{{{-0.f, 0, -0.f}, {next_after_one, 0, 0}, {0, 1, 0}}},  // -0 equals 0; 1+ulp does not equal 1
  };
  const io::LoadedMesh loaded = read_text(dir, "exact.stl", binary_stl(triangles, "exact"));
  EXPECT_EQ(loaded.mesh.num_vertices(), 4);
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 3, 2}));
  EXPECT_EQ(loaded.mesh.vertices(3, 0), static_cast<double>(next_after_one));
  EXPECT_EQ(loaded.info.welded_corners, 2);
}

TEST(StlReader, WeldNoteCountsEveryCorner) {
  // A tetrahedron: 4 triangles, 12 corners at 4 positions, 8 of them repeats.
  const std::array<std::array<float, 3>, 4> p = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const std::vector<Triangle> tetrahedron = {Triangle{{p[0], p[2], p[1]}}, Triangle{{p[0], p[1], p[3]}},
                                             Triangle{{p[1], p[2], p[3]}}, Triangle{{p[2], p[0], p[3]}}};
  TempDir dir;
  for (const auto& [name, bytes] :
       {std::pair{"binary.stl", binary_stl(tetrahedron, "t")}, std::pair{"ascii.stl", ascii_stl(tetrahedron)}}) {
    const io::LoadedMesh loaded = read_text(dir, name, bytes);
    EXPECT_EQ(loaded.mesh.num_vertices(), 4);
    EXPECT_EQ(loaded.info.welded_corners, 8);
    ASSERT_EQ(loaded.info.notes.size(), 1u);
    EXPECT_EQ(loaded.info.notes[0],
              "STL stores every triangle corner separately: 12 corners were welded into 4 vertices by exact "
              "position (first occurrence order; 8 corners repeated an earlier position)");
  }
}

TEST(StlReader, DegenerateTrianglesStay) {
  TempDir dir;
  const std::vector<Triangle> triangles = {
      Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
      Triangle{{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}}},
  };
  const io::LoadedMesh loaded = read_text(dir, "degenerate.stl", binary_stl(triangles, "d"));
  EXPECT_EQ(face_list(loaded.mesh), (std::vector<Index>{0, 1, 2, 0, 0, 1}));
}

}  // namespace
}  // namespace geodual::test
