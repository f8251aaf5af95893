#pragma once
// A subcommand of the geodual tool. Each lives in its own <name>_command.cpp,
// which defines make_<name>_command(); main.cpp lists them, parses the command
// line, runs the chosen one and turns its exceptions into exit statuses.

#include <memory>
#include <string_view>

namespace CLI {
class App;
}

namespace geodual::cli {

class Command {
 public:
  virtual ~Command() = default;

  /// Adds the subcommand, its options and their help to `app`; returns it.
  virtual CLI::App& add_to(CLI::App& app) = 0;

  /// Runs the subcommand once the command line parsed; returns the exit
  /// status. Failures are thrown: geodual::UsageError for bad options (exit
  /// 2), geodual::Error for bad input (exit 1).
  virtual int run() = 0;
};

/// Prints "geodual: error: <message>" on stderr as one line, without
/// allocating (it also reports running out of memory).
void report_error(std::string_view message);

using CommandFactory = std::unique_ptr<Command>();

}  // namespace geodual::cli
