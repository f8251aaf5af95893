// The progress line appears on a terminal and nowhere else, --threads does
// not change the result, and Ctrl-C (SIGINT) exits 3 leaving no file.

#include "cli_runner.hpp"
#include "scratch_folder.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>

namespace geodual::cli_test {
namespace {

constexpr const char* scan = "examples/data/bunny.ply";

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs a shell command; returns its exit status and what it printed.
std::pair<int, std::string> shell(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, output};
  std::array<char, 4096> buffer{};
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(Progress, OnATerminalOnlyAndNotWithQuiet) {
  ScratchFolder folder;
  const std::string out = (folder.path() / "a.ply").string();
  // Piped: nothing on stderr.
  const CliRun piped = run_cli({"remesh", scan, "--sites", "300", "--lloyd", "2", "--samples", "-1", "-o", out});
  ASSERT_EQ(piped.exit_status, 0) << piped.err;
  EXPECT_EQ(piped.err, "");
  // On a pseudo-terminal (script(1) gives the command one): the stage line.
  const std::string command = std::string(GEODUAL_CLI) + " remesh " + scan +
                              " --sites 300 --lloyd 2 --samples -1 -o " + (folder.path() / "b.ply").string();
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
  ASSERT_EQ(run_cli({"remesh", scan, "--sites", "400", "--lloyd", "2", "--samples", "-1", "-o", a.string()}).exit_status, 0);
  ASSERT_EQ(run_cli({"--threads", "1", "remesh", scan, "--sites", "400", "--lloyd", "2", "--samples", "-1", "-o",
                     b.string()})
                .exit_status,
            0);
  EXPECT_EQ(slurp(a), slurp(b));
}

TEST(Interrupt, CtrlCExitsThreeAndWritesNothing) {
  ScratchFolder folder;
  const auto out = folder.path() / "out.glb";
  // SIGINT one second in, while the relaxation runs (it takes several).
  const auto [status, output] = shell("timeout --preserve-status -s INT 1 " + std::string(GEODUAL_CLI) +
                                      " remesh " + scan + " --sites 4000 --lloyd 20 -o " + out.string());
  EXPECT_EQ(status, 3) << output;
  EXPECT_NE(output.find("cancelled"), std::string::npos) << output;
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

}  // namespace
}  // namespace geodual::cli_test
