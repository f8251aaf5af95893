// Every mesh of tests/data loads with exactly the counts its
// MANIFEST.tsv gives, and analyze_mesh finds exactly the defects listed there.
// The manifest is parsed here; no figure is copied into this file.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace geodual {
namespace {

namespace fs = std::filesystem;

/// The test meshes (tests/data in the source tree).
fs::path mesh_folder() { return fs::path(GEODUAL_SOURCE_DIR) / "tests" / "data"; }

/// One row of MANIFEST.tsv, by column name.
using ManifestRow = std::map<std::string, std::string>;

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream stream(line);
  std::string field;
  while (std::getline(stream, field, '\t')) fields.push_back(field);
  return fields;
}

std::vector<ManifestRow> read_manifest(const fs::path& path) {
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  const std::vector<std::string> columns = split_tabs(line);
  std::vector<ManifestRow> rows;
  while (std::getline(file, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_tabs(line);
    ManifestRow row;
    for (std::size_t i = 0; i < columns.size() && i < fields.size(); ++i) row[columns[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

std::int64_t integer(const ManifestRow& row, const std::string& column) { return std::stoll(row.at(column)); }

class Manifest : public testing::Test {
 protected:
  void SetUp() override {
    manifest_ = mesh_folder() / "MANIFEST.tsv";
    ASSERT_TRUE(fs::exists(manifest_)) << manifest_ << " not found";
    rows_ = read_manifest(manifest_);
  }

  fs::path manifest_;
  std::vector<ManifestRow> rows_;
};

TEST_F(Manifest, HasTheColumnsThisTestChecks) {
  ASSERT_GE(rows_.size(), 14U) << manifest_;
  for (const char* column : {"file", "vertices", "faces", "components", "boundary_loops", "nonmanifold_edges",
                             "nonmanifold_vertices", "degenerate_faces", "duplicate_vertices", "unreferenced_vertices",
                             "duplicate_triangles", "euler_characteristic", "genus", "bbox_diag"}) {
    EXPECT_EQ(rows_.front().count(column), 1U) << "column " << column << " missing in " << manifest_;
  }
}

TEST_F(Manifest, EveryMeshHasExactlyTheListedCountsAndDefects) {
  for (const ManifestRow& row : rows_) {
    const fs::path path = mesh_folder() / row.at("file");
    SCOPED_TRACE(path.string());
    const io::LoadedMesh loaded = io::read_mesh(path);
    EXPECT_EQ(loaded.mesh.num_vertices(), integer(row, "vertices"));
    EXPECT_EQ(loaded.mesh.num_faces(), integer(row, "faces"));

    const MeshReport report = analyze_mesh(loaded.mesh);
    EXPECT_EQ(report.vertices, integer(row, "vertices"));
    EXPECT_EQ(report.faces, integer(row, "faces"));
    EXPECT_EQ(report.components, integer(row, "components"));
    EXPECT_EQ(report.boundary_loops, integer(row, "boundary_loops"));
    EXPECT_EQ(report.nonmanifold_edges, integer(row, "nonmanifold_edges"));
    EXPECT_EQ(report.nonmanifold_vertices, integer(row, "nonmanifold_vertices"));
    EXPECT_EQ(report.degenerate_faces, integer(row, "degenerate_faces"));
    EXPECT_EQ(report.duplicate_vertices, integer(row, "duplicate_vertices"));
    EXPECT_EQ(report.unreferenced_vertices, integer(row, "unreferenced_vertices"));
    EXPECT_EQ(report.duplicate_faces, integer(row, "duplicate_triangles"));
    EXPECT_EQ(report.euler_characteristic, integer(row, "euler_characteristic"));

    // A '*' marks a genus that is not meaningful (non-manifold): we report none.
    const std::string& genus = row.at("genus");
    if (genus.find('*') != std::string::npos) {
      EXPECT_FALSE(report.genus.has_value()) << "manifest genus " << genus;
    } else {
      ASSERT_TRUE(report.genus.has_value()) << "manifest genus " << genus;
      EXPECT_EQ(*report.genus, std::stod(genus));
    }

    // Within half a unit of the 4th significant digit.
    const double diagonal = std::stod(row.at("bbox_diag"));
    const double unit = std::pow(10.0, std::floor(std::log10(diagonal)) - 3);
    EXPECT_NEAR(report.bbox_diagonal, diagonal, 0.5 * unit);
  }
}

}  // namespace
}  // namespace geodual
