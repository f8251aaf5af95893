#pragma once
// Runs the built geodual tool (GEODUAL_CLI) as a child process and captures
// what it printed and how it ended; and shell commands, for the tests that
// drive it through other tools.

#include <string>
#include <utility>
#include <vector>

namespace geodual::cli_test {

struct CliRun {
  int exit_status = -1;  ///< the status passed to exit(), or -1 if killed by a signal
  int signal = 0;        ///< the signal that ended it, 0 if none
  std::string out;
  std::string err;

  /// Lines of stderr (without their newlines).
  std::vector<std::string> err_lines() const;
};

/// Runs `GEODUAL_CLI args...` with the test's working directory.
CliRun run_cli(const std::vector<std::string>& args);

/// Runs a shell command; returns its exit status (-1 if it did not exit) and
/// what it printed on stdout and stderr together.
std::pair<int, std::string> shell(const std::string& command);

}  // namespace geodual::cli_test
