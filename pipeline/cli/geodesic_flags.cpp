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
  command
      .add_option("--site-groups", site_groups_,
                  "Propagate the sites in this many groups, in parallel (0: one per 256 sites, 2 to 16); the result "
                  "is exact for any and the same on any number of threads; 1 holds the fewest windows")
      ->capture_default_str()
      ->check(integer_between(0, 100'000'000));
}

void GeodesicFlags::apply(voronoi::GeodesicOptions& options) const {
  options.remove_redundant_windows = !no_rwr_;
  options.window_memory_limit_bytes = static_cast<std::size_t>(window_memory_mib_) << 20;
  options.site_groups = site_groups_;
}

}  // namespace geodual::cli
