#pragma once
// The geodesic engine's options, the same flags on every command that
// computes geodesics (geodesic, voronoi, remesh): --no-rwr, --window-memory,
// --site-groups.

#include "geodual/voronoi/geodesic_field.hpp"

#include <cstdint>

namespace CLI {
class App;
}

namespace geodual::cli {

class GeodesicFlags {
 public:
  /// Adds --no-rwr (GeodesicOptions::remove_redundant_windows = false),
  /// --window-memory MIB (window_memory_limit_bytes) and --site-groups N
  /// (site_groups) to `command`.
  void add_to(CLI::App& command);
  /// Sets those fields of `options`; the others are left as they are.
  void apply(voronoi::GeodesicOptions& options) const;

  bool remove_redundant_windows() const { return !no_rwr_; }
  std::int64_t window_memory_mib() const { return window_memory_mib_; }
  int site_groups() const { return site_groups_; }

 private:
  bool no_rwr_ = false;
  std::int64_t window_memory_mib_ =
      static_cast<std::int64_t>(voronoi::GeodesicOptions{}.window_memory_limit_bytes >> 20);
  int site_groups_ = voronoi::GeodesicOptions{}.site_groups;
};

}  // namespace geodual::cli
