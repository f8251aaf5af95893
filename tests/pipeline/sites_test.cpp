// Random and file sites for the command line.

#include "geodual/pipeline/sites.hpp"
#include "geodual/mesh/error.hpp"
#include "small_grid.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace geodual {
namespace {

namespace fs = std::filesystem;

TriangleMesh grid_with_unreferenced_vertex() { return test::small_grid(true); }

using test::write_temp;

TEST(RandomVertexSites, DistinctReferencedAndDeterministic) {
  const TriangleMesh mesh = grid_with_unreferenced_vertex();
  const auto a = random_vertex_sites(mesh, 9, 42);
  const auto b = random_vertex_sites(mesh, 9, 42);
  std::set<Index> seen;
  ASSERT_EQ(a.size(), 9u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].kind, SurfacePoint::Kind::vertex);
    EXPECT_EQ(a[i].element, b[i].element);
    EXPECT_NE(a[i].element, 9) << "the unreferenced vertex must never be drawn";
    seen.insert(a[i].element);
  }
  EXPECT_EQ(seen.size(), 9u);
  const auto c = random_vertex_sites(mesh, 3, 43);
  const auto d = random_vertex_sites(mesh, 3, 42);
  EXPECT_FALSE(c[0].element == d[0].element && c[1].element == d[1].element && c[2].element == d[2].element);
}

TEST(RandomVertexSites, RejectsImpossibleCounts) {
  const TriangleMesh mesh = grid_with_unreferenced_vertex();
  EXPECT_THROW(random_vertex_sites(mesh, 10, 1), UsageError);
  EXPECT_THROW(random_vertex_sites(mesh, 0, 1), UsageError);
}

TEST(ReadSiteFile, VertexAndFaceLines) {
  const TriangleMesh mesh = grid_with_unreferenced_vertex();
  const fs::path path = write_temp("ok.txt", "# comment\n4\n\nf 2 0.25 0.25 0.5\n  7  \n");
  const auto sites = read_site_file(path, mesh);
  ASSERT_EQ(sites.size(), 3u);
  EXPECT_EQ(sites[0].kind, SurfacePoint::Kind::vertex);
  EXPECT_EQ(sites[0].element, 4);
  EXPECT_EQ(sites[1].kind, SurfacePoint::Kind::face);
  EXPECT_EQ(sites[1].element, 2);
  EXPECT_DOUBLE_EQ(sites[1].barycentric[2], 0.5);
  EXPECT_EQ(sites[2].element, 7);
  fs::remove(path);
}

TEST(ReadSiteFile, ErrorsNameFileAndLine) {
  const TriangleMesh mesh = grid_with_unreferenced_vertex();
  struct Case {
    std::string text, expected;
  };
  for (const Case& c : {Case{"1\nbanana\n", ":2: expected"}, Case{"99\n", ":1: vertex 99 is out of range"},
                        Case{"f 8 0.3 0.3 0.4\n", ":1: face 8 is out of range"}, Case{"f 1 0.3 0.3\n", ":1: expected"},
                        Case{"# nothing\n", "holds no sites"}}) {
    const fs::path path = write_temp("bad.txt", c.text);
    try {
      read_site_file(path, mesh);
      ADD_FAILURE() << "no error for: " << c.text;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
    fs::remove(path);
  }
  EXPECT_THROW(read_site_file("/nonexistent/sites.txt", mesh), Error);
}

}  // namespace
}  // namespace geodual
