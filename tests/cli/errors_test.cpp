// Failures of the geodual tool: every one is a single line on stderr,
// "geodual: error: ...", naming the file where there is one, with exit status
// 2 for a bad command line and 1 for bad input; never a crash.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace geodual::cli_test {
namespace {

constexpr int exit_failure = 1;
constexpr int exit_usage = 2;

/// Checks the run ended with `status`, nothing on stdout, and one error line
/// on stderr that contains `mention`.
void expect_error(const CliRun& run, int status, const std::string& mention) {
  EXPECT_EQ(run.signal, 0) << "killed by signal " << run.signal << "; stderr: " << run.err;
  EXPECT_EQ(run.exit_status, status) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  const std::vector<std::string> lines = run.err_lines();
  ASSERT_EQ(lines.size(), 1U) << run.err;
  EXPECT_EQ(lines[0].rfind("geodual: error: ", 0), 0U) << lines[0];
  EXPECT_NE(lines[0].find(mention), std::string::npos) << "'" << mention << "' not in: " << lines[0];
}

std::string random_bytes(std::size_t count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string bytes(count, '\0');
  for (char& c : bytes) c = static_cast<char>(byte(generator));
  return bytes;
}

std::string file_contents(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

/// `git describe --always --dirty` of the source, "" where it is not a git
/// checkout or git cannot run.
std::string describe_source() {
  if (!std::filesystem::exists(std::filesystem::path(GEODUAL_SOURCE_DIR) / ".git")) return "";
  auto [status, out] = shell("git -C '" GEODUAL_SOURCE_DIR "' describe --always --dirty");
  if (status != 0) return "";
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

TEST(CliUsage, VersionNamesTheCommitOfTheSourceBuilt) {
  // Read at build time: after a commit, an incremental build names the new
  // one (it used to keep the commit of the last configure). "-dirty" is left
  // out on both sides: a file edited since the build is no stale commit.
  auto without_dirty = [](std::string text) {
    for (std::size_t at; (at = text.find("-dirty")) != std::string::npos;) text.erase(at, 6);
    return text;
  };
  const std::string describe = without_dirty(describe_source());
  const std::string expected =
      "geodual " GEODUAL_PROJECT_VERSION + (describe.empty() ? std::string() : " (" + describe + ")") + "\n";
  EXPECT_EQ(without_dirty(run_cli({"--version"}).out), expected);
}

TEST(CliUsage, VersionAndHelpSucceed) {
  const CliRun version = run_cli({"--version"});
  EXPECT_EQ(version.exit_status, 0);
  // project(VERSION), then the commit where the build had git.
  EXPECT_EQ(version.out.rfind("geodual " GEODUAL_PROJECT_VERSION, 0), 0U) << version.out;
  const CliRun help = run_cli({"--help"});
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.out.find("info"), std::string::npos) << help.out;
  const CliRun info_help = run_cli({"info", "--help"});
  EXPECT_EQ(info_help.exit_status, 0);
  EXPECT_NE(info_help.out.find("--json"), std::string::npos) << info_help.out;
}

TEST(CliUsage, NoArgumentsIsAUsageError) { expect_error(run_cli({}), exit_usage, "--help"); }

TEST(CliUsage, UnknownOptionIsAUsageError) {
  expect_error(run_cli({"--frobnicate"}), exit_usage, "--frobnicate");
  expect_error(run_cli({"info", "examples/data/bunny.ply", "--frobnicate"}), exit_usage, "--frobnicate");
}

TEST(CliUsage, UnknownCommandIsAUsageError) {
  expect_error(run_cli({"frobnicate", "x.ply"}), exit_usage, "frobnicate");
}

TEST(CliUsage, MissingFileArgumentIsAUsageError) { expect_error(run_cli({"info"}), exit_usage, "FILE"); }

TEST(CliUsage, ExtraArgumentIsAUsageError) { expect_error(run_cli({"info", "a.ply", "b.ply"}), exit_usage, "b.ply"); }

class CliBadInput : public ::testing::Test {
 protected:
  /// Runs `geodual info path` and expects exit 1 with one line naming path.
  void expect_rejected(const std::filesystem::path& path) {
    SCOPED_TRACE(path.string());
    expect_error(run_cli({"info", path.string()}), exit_failure, path.string());
    expect_error(run_cli({"info", path.string(), "--json"}), exit_failure, path.string());
  }

  ScratchFolder folder_;
};

TEST_F(CliBadInput, MissingFile) { expect_rejected(folder_.path() / "no-such-mesh.ply"); }

TEST_F(CliBadInput, Directory) {
  std::filesystem::create_directory(folder_.path() / "folder.ply");
  expect_rejected(folder_.path() / "folder.ply");
  expect_rejected(folder_.path());
}

TEST_F(CliBadInput, UnknownExtension) { expect_rejected(folder_.write("mesh.xyz", "v 0 0 0\n")); }

TEST_F(CliBadInput, EmptyFiles) {
  for (const char* name : {"empty.ply", "empty.obj", "empty.off", "empty.stl", "empty.glb", "empty.gltf"}) {
    expect_rejected(folder_.write(name, ""));
  }
}

TEST_F(CliBadInput, TruncatedBinaryPly) {
  const std::string whole = file_contents("examples/data/bunny.ply");
  ASSERT_GT(whole.size(), 100000U);
  expect_rejected(folder_.write("truncated.ply", whole.substr(0, whole.size() / 2)));
  expect_rejected(folder_.write("header-only.ply", whole.substr(0, whole.find("end_header") + 11)));
  expect_rejected(folder_.write("cut-header.ply", whole.substr(0, 60)));
}

TEST_F(CliBadInput, RandomBytes) {
  unsigned seed = 1;
  for (const char* extension : {".ply", ".obj", ".off", ".stl", ".glb", ".gltf"}) {
    for (const std::size_t size : {17U, 1000U, 65536U}) {
      expect_rejected(folder_.write("random-" + std::to_string(size) + extension, random_bytes(size, seed++)));
    }
  }
}

TEST_F(CliBadInput, NanCoordinates) {
  expect_rejected(folder_.write("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n"));
  expect_rejected(folder_.write("nan.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 1\n"
                                "property list uchar int vertex_indices\nend_header\n"
                                "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n"));
}

TEST_F(CliBadInput, CoordinatesBeyondWhatDoublesComputeWith) {
  // Finite, but their squared areas overflow (or vanish): info printed inf and nan.
  const auto huge = folder_.write("huge.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1e300 0\nf 1 2 3\n");
  const auto tiny = folder_.write("tiny.obj", "v 0 0 0\nv 1e-300 0 0\nv 0 1e-300 0\nf 1 2 3\n");
  for (const auto& path : {huge, tiny}) {
    expect_rejected(path);
    expect_error(run_cli({"stats", path.string(), "tests/data/woody.ply"}), exit_failure, path.string());
    expect_error(run_cli({"remesh", path.string(), "--sites", "10", "-o", (folder_.path() / "out.ply").string()}),
                 exit_failure, path.string());
  }
  // A mesh far from the origin but within range is fine.
  const auto far = folder_.write("far.obj", "v 1e60 0 0\nv 1e60 1e59 0\nv 1e60 0 1e59\nf 1 2 3\n");
  EXPECT_EQ(run_cli({"info", far.string()}).exit_status, 0);
}

TEST_F(CliBadInput, FeatureFileLinesThatAreNoEdgesOfTheMesh) {
  // Line 1 of the first file is an edge of woody.ply's first face.
  const auto out = folder_.path() / "out.ply";
  for (const auto& [text, mention] :
       std::vector<std::pair<std::string, std::string>>{{"166 96\n7 banana\n", ":2: expected vertex indices"},
                                                        {"0 99999999\n", ":1: vertex 99999999 is out of range"},
                                                        {"# one vertex\n5\n", ":2: a polyline needs two vertices"}}) {
    const auto features = folder_.write("features.txt", text);
    expect_error(run_cli({"remesh", "tests/data/woody.ply", "--sites", "50", "--feature-file", features.string(), "-o",
                          out.string()}),
                 exit_failure, features.string() + mention);
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const auto missing = folder_.path() / "no-such-features.txt";
  expect_error(run_cli({"remesh", "tests/data/woody.ply", "--sites", "50", "--feature-file", missing.string(), "-o",
                        out.string()}),
               exit_failure, missing.string());
}

TEST_F(CliBadInput, FaceIndexOutOfRange) {
  expect_rejected(folder_.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"));
  expect_rejected(folder_.write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
  expect_rejected(folder_.write("negative.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 1\n"
                                "property list uchar int vertex_indices\nend_header\n"
                                "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n"));
}

}  // namespace
}  // namespace geodual::cli_test
