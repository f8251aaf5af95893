// Every mesh of tests/data, and of the CAD corpus tests/data/cad (OpenSCAD
// renders, bench/render_cad_corpus.sh), loads with exactly the counts its
// folder's MANIFEST.tsv gives, and analyze_mesh finds exactly the defects
// listed there. The manifests are parsed here; no figure is copied into this
// file.

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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

/// A folder of test meshes with a MANIFEST.tsv, and the fewest rows it has.
struct MeshFolder {
  const char* name;  ///< for the test's name
  const char* path;  ///< under tests/data in the source tree
  std::size_t min_rows;
};

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

class Manifest : public testing::TestWithParam<MeshFolder> {
 protected:
  void SetUp() override {
    folder_ = fs::path(GEODUAL_SOURCE_DIR) / "tests" / "data" / GetParam().path;
    manifest_ = folder_ / "MANIFEST.tsv";
    ASSERT_TRUE(fs::exists(manifest_)) << manifest_ << " not found";
    rows_ = read_manifest(manifest_);
  }

  fs::path folder_;
  fs::path manifest_;
  std::vector<ManifestRow> rows_;
};

INSTANTIATE_TEST_SUITE_P(TestData, Manifest, testing::Values(MeshFolder{"scans", "", 14}, MeshFolder{"cad", "cad", 40}),
                         [](const testing::TestParamInfo<MeshFolder>& param_info) {
                           return std::string(param_info.param.name);
                         });

TEST_P(Manifest, HasTheColumnsThisTestChecks) {
  ASSERT_GE(rows_.size(), GetParam().min_rows) << manifest_;
  for (const char* column : {"file", "vertices", "faces", "components", "boundary_loops", "nonmanifold_edges",
                             "nonmanifold_vertices", "degenerate_faces", "duplicate_vertices", "unreferenced_vertices",
                             "duplicate_triangles", "euler_characteristic", "genus", "bbox_diag"}) {
    EXPECT_EQ(rows_.front().count(column), 1U) << "column " << column << " missing in " << manifest_;
  }
}

TEST_P(Manifest, EveryMeshHasExactlyTheListedCountsAndDefects) {
  for (const ManifestRow& row : rows_) {
    const fs::path path = folder_ / row.at("file");
    SCOPED_TRACE(path.string());
    if (row.count("bytes") == 1) {
      EXPECT_EQ(static_cast<std::int64_t>(fs::file_size(path)), integer(row, "bytes"));
    }
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

TEST_P(Manifest, ListsEveryMeshOfItsFolder) {
  std::vector<std::string> listed;
  for (const ManifestRow& row : rows_) listed.push_back(row.at("file"));
  for (const auto& entry : fs::directory_iterator(folder_)) {
    const std::string extension = entry.path().extension().string();
    if (!entry.is_regular_file() || (extension != ".ply" && extension != ".stl")) continue;
    EXPECT_NE(std::find(listed.begin(), listed.end(), entry.path().filename().string()), listed.end())
        << entry.path() << " is not in " << manifest_;
  }
}

}  // namespace
}  // namespace geodual
