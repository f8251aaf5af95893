// Feature files: polylines of vertex indices read as edges, every error
// naming the file and line; the pipeline's check of given feature edges.

#include "geodual/pipeline/feature_file.hpp"
#include "geodual/mesh/error.hpp"
#include "small_grid.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace geodual {
namespace {

namespace fs = std::filesystem;

TriangleMesh grid() { return test::small_grid(false); }

using test::write_temp;

TEST(ReadFeatureFile, PolylinesBecomeTheirEdges) {
  const fs::path path = write_temp("ok.txt", "# the middle row, then a diagonal\n3 4 5\n\n  0 4 8  \n");
  const std::vector<std::array<Index, 2>> edges = read_feature_file(path, grid());
  const std::vector<std::array<Index, 2>> expected = {{3, 4}, {4, 5}, {0, 4}, {4, 8}};
  EXPECT_EQ(edges, expected);
  fs::remove(path);
}

TEST(ReadFeatureFile, ErrorsNameFileAndLine) {
  struct Case {
    std::string text, expected;
  };
  for (const Case& c : {Case{"0 1\nbanana 3\n", ":2: expected vertex indices"},
                        Case{"0 1 99\n", ":1: vertex 99 is out of range [0, 9)"},
                        Case{"0 2\n", ":1: vertices 0 and 2 are not an edge"},  // same row, two apart
                        Case{"\n\n4\n", ":3: a polyline needs two vertices"}, Case{"-1 0\n", ":1: vertex -1"},
                        Case{"# nothing\n", "holds no edges"}}) {
    const fs::path path = write_temp("bad.txt", c.text);
    try {
      read_feature_file(path, grid());
      ADD_FAILURE() << "no error for: " << c.text;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
    fs::remove(path);
  }
  EXPECT_THROW(read_feature_file("/nonexistent/features.txt", grid()), Error);
}

TEST(RequireEdgesOf, NamesThePairThatIsNoEdge) {
  EXPECT_NO_THROW(require_edges_of(grid(), {{4, 0}, {1, 2}}, "feature edge"));
  EXPECT_NO_THROW(require_edges_of(grid(), {}, "feature edge"));
  try {
    require_edges_of(grid(), {{0, 1}, {2, 6}}, "feature edge");
    ADD_FAILURE() << "no error for the pair 2 6";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("feature edge 2 6: not an edge"), std::string::npos) << e.what();
  }
  EXPECT_THROW(require_edges_of(grid(), {{0, 9}}, "feature edge"), UsageError);
}

}  // namespace
}  // namespace geodual
