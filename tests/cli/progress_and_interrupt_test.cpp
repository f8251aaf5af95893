// The progress line appears on a terminal and nowhere else, --threads does
// not change the result, and Ctrl-C (SIGINT) stops every command with exit
// status 3 and "cancelled", leaving no file. No test here asserts how long
// that takes (a loaded machine must not turn the suite red): a run that
// ignored the signal would finish with status 0 and its result, or be killed
// by the safety net (status 137), and each assertion below tells those apart.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/triangle_mesh.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace geodual::cli_test {
namespace {

constexpr const char* scan = "examples/data/bunny.ply";

/// A wavy n x n grid of 2 (n - 1)^2 faces, `phase` shifting its waves.
TriangleMesh wavy_grid(int n, double phase) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = static_cast<double>(i) / (n - 1), y = static_cast<double>(j) / (n - 1);
      mesh.vertices.row(i * n + j) << x, y, 0.05 * std::sin(20 * x + phase) * std::cos(17 * y);
    }
  }
  mesh.faces.resize(2 * static_cast<Eigen::Index>(n - 1) * (n - 1), 3);
  Eigen::Index f = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const Index a = i * n + j, b = a + n;
      mesh.faces.row(f++) << a, b, b + 1;
      mesh.faces.row(f++) << a, b + 1, a + 1;
    }
  }
  return mesh;
}

struct InterruptedRun {
  int status = 0;
  std::string output;
};

/// Seconds after SIGINT at which a run still going is killed (SIGKILL, status
/// 137): a guard against a hang, not a bound the tests hold the run to.
constexpr int kKillAfter = 60;

/// Runs the tool with `arguments` and sends SIGINT after `delay` seconds.
InterruptedRun interrupt_after(double delay, const std::string& arguments) {
  const auto [status, output] = shell("timeout --preserve-status -k " + std::to_string(kKillAfter) + " -s INT " +
                                      std::to_string(delay) + " " + std::string(GEODUAL_CLI) + " " + arguments);
  return {status, output};
}

/// Runs the CLI with `arguments` in the background and interrupts it
/// (SIGINT, as Ctrl-C) `delay` seconds after `file` appears, or at once if
/// it ends before: a point in a batch that does not depend on how busy the
/// machine is. The program installs its own handler, so the signal reaches
/// it even as a background job of a shell that ignores SIGINT there.
InterruptedRun interrupt_after_file(const std::filesystem::path& file, double delay, const std::string& arguments) {
  const std::string script = std::string(GEODUAL_CLI) + " " + arguments + " & pid=$!; while [ ! -e '" + file.string() +
                             "' ] && kill -0 $pid 2>/dev/null; do sleep 0.02; done; sleep " + std::to_string(delay) +
                             "; kill -INT $pid 2>/dev/null; (sleep " + std::to_string(kKillAfter) +
                             "; kill -KILL $pid 2>/dev/null) >/dev/null 2>&1 & guard=$!; wait $pid; status=$?; "
                             "kill $guard 2>/dev/null; exit $status";
  const auto [status, output] = shell("sh -c '" + script + "'");
  return {status, output};
}

/// Meshes written once for all the tests here: a large one of a million
/// faces, and two of 125,000 faces whose distances take long with many samples.
class LargeMeshes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new ScratchFolder;
    io::write_ply(large(), wavy_grid(708, 0.0));
    io::write_ply(reference(), wavy_grid(251, 0.0));
    io::write_ply(candidate(), wavy_grid(250, 0.3));
  }
  static void TearDownTestSuite() {
    delete folder_;
    folder_ = nullptr;
  }
  static std::string large() { return (folder_->path() / "large.ply").string(); }
  static std::string reference() { return (folder_->path() / "reference.ply").string(); }
  static std::string candidate() { return (folder_->path() / "candidate.ply").string(); }

  ScratchFolder output_folder_;

 private:
  static ScratchFolder* folder_;
};

ScratchFolder* LargeMeshes::folder_ = nullptr;

TEST_F(LargeMeshes, CtrlCStopsStats) {
  // 1.5 s in, while it measures the 2 x 10^8 sample distances (minutes).
  const InterruptedRun run =
      interrupt_after(1.5, "stats " + reference() + " " + candidate() + " --samples 100000000 --json");
  EXPECT_EQ(run.status, 3) << run.output;
  EXPECT_NE(run.output.find("cancelled"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("hausdorff"), std::string::npos) << run.output;  // no result printed
}

TEST_F(LargeMeshes, CtrlCStopsInfo) {
  const auto preview = output_folder_.path() / "preview.png";
  // 0.3 s in, while it reads or analyses the mesh (each takes longer), before
  // the preview.
  const InterruptedRun run = interrupt_after(0.3, "info " + large() + " --json --preview " + preview.string());
  EXPECT_EQ(run.status, 3) << run.output;
  EXPECT_EQ(run.output.find("faces"), std::string::npos) << run.output;  // no result printed
  EXPECT_FALSE(std::filesystem::exists(preview));
}

TEST_F(LargeMeshes, CtrlCStopsABatchKeepingTheFinishedScansOnly) {
  // A small scan (well under a second), then the million-face one (about 8 s
  // to remesh), interrupted 1 s after the small one's output appears.
  const std::string small = "tests/data/woody.ply";
  const auto folder = output_folder_.path();
  const std::string options = " --sites 300 --lloyd 0 --samples -1 --output-dir " + folder.string();
  const InterruptedRun run =
      interrupt_after_file(folder / "woody.glb", 1.0, "remesh " + small + " " + large() + options);
  EXPECT_EQ(run.status, 3) << run.output;
  EXPECT_NE(run.output.find("cancelled"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("scans remeshed"), std::string::npos) << run.output;  // no summary
  // The finished scan's output and nothing else (no temporary file either).
  EXPECT_TRUE(std::filesystem::exists(folder / "woody.glb"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()), 1);
}

TEST(Interrupt, CtrlCStopsTheStatisticsStageOfRemesh) {
  ScratchFolder folder;
  const auto out = folder.path() / "out.ply";
  const std::string remesh = std::string("remesh ") + scan + " --sites 300 --lloyd 0 -o " + out.string();
  // How long the stages before the statistics take; then a run whose
  // statistics take minutes, interrupted one second into them.
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(shell(std::string(GEODUAL_CLI) + " " + remesh + " --samples -1").first, 0);
  const double before_statistics = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::filesystem::remove(out);
  const InterruptedRun run = interrupt_after(before_statistics + 1, remesh + " --samples 1000000000");
  EXPECT_EQ(run.status, 3) << run.output;
  EXPECT_NE(run.output.find("statistics cancelled"), std::string::npos) << run.output;
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

TEST(Progress, OnATerminalOnlyAndNotWithQuiet) {
  ScratchFolder folder;
  const std::string out = (folder.path() / "a.ply").string();
  // Piped: nothing on stderr.
  const CliRun piped = run_cli({"remesh", scan, "--sites", "300", "--lloyd", "2", "--samples", "-1", "-o", out});
  ASSERT_EQ(piped.exit_status, 0) << piped.err;
  EXPECT_EQ(piped.err, "");
  // On a pseudo-terminal (script(1) gives the command one): the stage line.
  const std::string command = std::string(GEODUAL_CLI) + " remesh " + scan + " --sites 300 --lloyd 2 --samples -1 -o " +
                              (folder.path() / "b.ply").string();
  const auto [status, terminal] = shell("script -qec '" + command + "' /dev/null");
  ASSERT_EQ(status, 0) << terminal;
  EXPECT_NE(terminal.find("geodual: relax"), std::string::npos) << terminal;
  EXPECT_NE(terminal.find('%'), std::string::npos);
  const auto [quiet_status, quiet] = shell("script -qec '" + command + " --quiet' /dev/null");
  ASSERT_EQ(quiet_status, 0) << quiet;
  EXPECT_EQ(quiet.find("geodual: relax"), std::string::npos) << quiet;
}

TEST(Threads, OneThreadGivesTheSameBytes) {
  ScratchFolder folder;
  const auto a = folder.path() / "a.ply", b = folder.path() / "b.ply";
  ASSERT_EQ(
      run_cli({"remesh", scan, "--sites", "400", "--lloyd", "2", "--samples", "-1", "-o", a.string()}).exit_status, 0);
  ASSERT_EQ(
      run_cli({"--threads", "1", "remesh", scan, "--sites", "400", "--lloyd", "2", "--samples", "-1", "-o", b.string()})
          .exit_status,
      0);
  EXPECT_EQ(slurp(a), slurp(b));
}

TEST(Threads, OneThreadGivesTheSameBytesWithSitesBesideRoundCreases) {
  // fandisk at 2,000 sites: its round creases get closer sites and sites
  // beside them (sites_added_near_features), placed and relaxed the same on
  // any number of threads.
  ScratchFolder folder;
  const auto a = folder.path() / "a.ply", b = folder.path() / "b.ply";
  const CliRun two = run_cli({"--threads", "2", "remesh", "tests/data/fandisk.ply", "--sites", "2000", "--samples",
                              "-1", "--json", "-o", a.string()});
  ASSERT_EQ(two.exit_status, 0) << two.err;
  EXPECT_NE(two.out.find("\"sites_added_near_features\": "), std::string::npos) << two.out;
  EXPECT_EQ(two.out.find("\"sites_added_near_features\": 0,"), std::string::npos) << two.out;
  const CliRun one = run_cli(
      {"--threads", "1", "remesh", "tests/data/fandisk.ply", "--sites", "2000", "--samples", "-1", "-o", b.string()});
  ASSERT_EQ(one.exit_status, 0) << one.err;
  EXPECT_EQ(slurp(a), slurp(b));
}

TEST(Interrupt, CtrlCExitsThreeAndWritesNothing) {
  ScratchFolder folder;
  const auto out = folder.path() / "out.glb";
  // SIGINT one second in, while the relaxation runs (it takes several).
  const auto [status, output] = shell("timeout --preserve-status -s INT 1 " + std::string(GEODUAL_CLI) + " remesh " +
                                      scan + " --sites 4000 --lloyd 20 -o " + out.string());
  EXPECT_EQ(status, 3) << output;
  EXPECT_NE(output.find("cancelled"), std::string::npos) << output;
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

}  // namespace
}  // namespace geodual::cli_test
