// geodual remesh --compress: on a real remesh, meshopt's .glb is at most 30 %
// of the uncompressed one; the same remesh (the statistics in the extras) in
// every form; the same bytes twice; refused for PLY and OBJ before any work;
// geodual's own reader names the extension it cannot read.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {
namespace fs = std::filesystem;

constexpr const char* scan = "tests/data/bunny.ply";

// asset.extras of a GLB: the remesh's statistics, the same whatever the compression.
nlohmann::json extras_of(const std::string& glb) {
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, json_length))["asset"]["extras"];
}

CliRun remesh(const std::string& compress, const fs::path& out) {
  return run_cli({"remesh", scan, "--sites", "4000", "--seed", "7", "--samples", "20000", "--compress", compress, "-o",
                  out.string(), "--json", "-q"});
}

TEST(Compress, MeshoptGlbIsAtMost30PercentOfTheUncompressedOneAndDracoSmallerStill) {
  ScratchFolder folder;
  std::vector<std::string> files;
  for (const char* compress : {"none", "meshopt", "draco"}) {
    const fs::path out = folder.path() / (std::string(compress) + ".glb");
    const CliRun run = remesh(compress, out);
    ASSERT_EQ(run.exit_status, 0) << run.err;
    EXPECT_EQ(nlohmann::json::parse(run.out)["compress"], compress);
    files.push_back(slurp(out));
  }
  const double meshopt = static_cast<double>(files[1].size()) / static_cast<double>(files[0].size());
  const double draco = static_cast<double>(files[2].size()) / static_cast<double>(files[0].size());
  std::cout << "bunny, 4,000 sites: " << files[0].size() << " bytes uncompressed, " << files[1].size() << " meshopt ("
            << 100 * meshopt << " %), " << files[2].size() << " draco (" << 100 * draco << " %)\n";
  EXPECT_LE(meshopt, 0.30);
  EXPECT_LT(files[2].size(), files[1].size());
  EXPECT_EQ(extras_of(files[1]), extras_of(files[0]));
  EXPECT_EQ(extras_of(files[2]), extras_of(files[0]));
}

TEST(Compress, SameInputAndOptionsGiveTheSameBytes) {
  ScratchFolder folder;
  for (const char* compress : {"meshopt", "draco"}) {
    std::vector<std::string> files;
    for (const char* name : {"a.gltf", "b.gltf"}) {
      const fs::path out = folder.path() / (std::string(compress) + name);
      const CliRun run = run_cli({"remesh", "tests/data/fertility.ply", "--sites", "400", "--seed", "3", "--samples",
                                  "5000", "--compress", compress, "-o", out.string(), "-q"});
      ASSERT_EQ(run.exit_status, 0) << run.err;
      files.push_back(slurp(out));
    }
    EXPECT_EQ(files[0], files[1]) << compress;
  }
}

TEST(Compress, RefusedForPlyAndObjBeforeAnyWork) {
  ScratchFolder folder;
  for (const char* extension : {".ply", ".obj"}) {
    const fs::path out = folder.path() / (std::string("remesh") + extension);
    const CliRun run = run_cli({"remesh", scan, "--sites", "4000", "--compress", "meshopt", "-o", out.string()});
    EXPECT_NE(run.exit_status, 0);
    EXPECT_NE(run.err.find("--compress meshopt"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(out.string()), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const CliRun batch = run_cli({"remesh", scan, "--sites", "4000", "--compress", "draco", "--output-dir",
                                (folder.path() / "out").string(), "--format", "ply"});
  EXPECT_NE(batch.exit_status, 0);
  EXPECT_NE(batch.err.find("--compress draco"), std::string::npos) << batch.err;
  const CliRun unknown = run_cli({"remesh", scan, "--compress", "zip", "-o", (folder.path() / "x.glb").string()});
  EXPECT_NE(unknown.exit_status, 0);
  EXPECT_NE(unknown.err.find("--compress"), std::string::npos) << unknown.err;
}

TEST(Compress, GeodualInfoNamesTheFileAndTheExtensionItCannotRead) {
  ScratchFolder folder;
  const fs::path out = folder.path() / "small.glb";
  ASSERT_EQ(run_cli({"remesh", "tests/data/fertility.ply", "--sites", "300", "--samples", "2000", "--compress",
                     "meshopt", "-o", out.string(), "-q"})
                .exit_status,
            0);
  const CliRun info = run_cli({"info", out.string()});
  EXPECT_NE(info.exit_status, 0);
  EXPECT_NE(info.err.find(out.string()), std::string::npos) << info.err;
  EXPECT_NE(info.err.find("EXT_meshopt_compression"), std::string::npos) << info.err;
}

}  // namespace
}  // namespace geodual::cli_test
