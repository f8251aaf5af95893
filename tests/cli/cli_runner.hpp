#pragma once
// Runs the built geodual tool (GEODUAL_CLI) as a child process and captures
// what it printed and how it ended.

#include <string>
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

}  // namespace geodual::cli_test
