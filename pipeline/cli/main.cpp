// geodual: the command line tool. Parses the command line, runs the chosen
// subcommand and reports every failure as one line on stderr:
//   geodual: error: <message>
// Exit status: 0 success, 1 bad input or failure, 2 bad command line,
// 3 cancelled (Ctrl-C; nothing is written).

#include "command.hpp"
#include "progress_bar.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/heap.hpp"
#include "geodual/pipeline/version.hpp"

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geodual::cli {

// The subcommands. Adding one is a new <name>_command.cpp that defines
// make_<name>_command(), declared here, and its entry in command_factories
// below (the order `geodual --help` lists them in).
CommandFactory make_info_command;
CommandFactory make_geodesic_command;
CommandFactory make_voronoi_command;
CommandFactory make_remesh_command;
CommandFactory make_stats_command;

void report_error(std::string_view message) {
  std::cerr << "geodual: error: ";
  for (const char c : message) std::cerr.put(c == '\n' || c == '\r' ? ' ' : c);
  std::cerr << std::endl;
}

namespace {

constexpr CommandFactory* command_factories[] = {
    &make_info_command, &make_geodesic_command, &make_voronoi_command, &make_remesh_command, &make_stats_command,
};

constexpr int exit_failure = 1;
constexpr int exit_usage = 2;
constexpr int exit_cancelled = 3;

int run(int argc, char** argv) {
  CLI::App app{
      "geodual: remeshing of dense triangle-mesh scans through exact geodesic "
      "Voronoi diagrams",
      "geodual"};
  app.set_version_flag("--version", "geodual " + std::string(build_version()), "Print the version and exit");
  app.require_subcommand(1);
  app.fallthrough();  // --threads may come after the subcommand too
  int threads = 0;
  app.add_option("--threads", threads, "Worker threads (default: all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);

  std::vector<std::pair<CLI::App*, std::unique_ptr<Command>>> commands;
  for (CommandFactory* factory : command_factories) {
    std::unique_ptr<Command> command = factory();
    CLI::App& subcommand = command->add_to(app);
    commands.emplace_back(&subcommand, std::move(command));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) {
      return app.exit(error);  // --help or --version: printed on stdout
    }
    // Without a known subcommand, CLI11 only says that one is required; name
    // the word it did not know instead.
    const std::vector<std::string> unknown = app.remaining();
    const std::string message = app.get_subcommands().empty() && !unknown.empty()
                                    ? "unknown command or option '" + unknown.front() + "'"
                                    : std::string(error.what());
    report_error(message + " (run 'geodual --help' for usage)");
    return exit_usage;
  }

  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }
  catch_interrupts();
  for (auto& [subcommand, command] : commands) {
    if (subcommand->parsed()) {
      const int status = command->run();
      std::cout.flush();
      if (!std::cout) {
        throw Error("cannot write to standard output");
      }
      return status;
    }
  }
  return exit_usage;  // unreachable: require_subcommand(1)
}

}  // namespace
}  // namespace geodual::cli

int main(int argc, char** argv) {
  geodual::pipeline::keep_freed_memory_in_heap();
  try {
    return geodual::cli::run(argc, argv);
  } catch (const geodual::UsageError& error) {
    geodual::cli::report_error(error.what());
    return geodual::cli::exit_usage;
  } catch (const geodual::Cancelled& error) {
    geodual::cli::report_error(error.what());
    return geodual::cli::exit_cancelled;
  } catch (const geodual::Error& error) {
    geodual::cli::report_error(error.what());
  } catch (const std::bad_alloc&) {
    geodual::cli::report_error("out of memory");
  } catch (const std::exception& error) {
    geodual::cli::report_error(error.what());
  } catch (...) {
    geodual::cli::report_error("unexpected failure");
  }
  return geodual::cli::exit_failure;
}
