#include "geodesic_flags.hpp"

#include "option_checks.hpp"

#include <CLI/CLI.hpp>

#include <cstddef>

namespace geodual::cli {

void GeodesicFlags::add_to(CLI::App& command) {
  command.add_flag("--no-rwr", no_rwr_, "Keep every window (no Redundant Window Removal), as MMP does");
  command.add_option("--window-memory", window_memory_mib_, "Stop with an error beyond this many MiB of windows")
      ->capture_default_str()
      ->check(integer_between(1, std::int64_t{1} << 30));
}

void GeodesicFlags::apply(voronoi::GeodesicOptions& options) const {
  options.remove_redundant_windows = !no_rwr_;
  options.window_memory_limit_bytes = static_cast<std::size_t>(window_memory_mib_) << 20;
}

}  // namespace geodual::cli
