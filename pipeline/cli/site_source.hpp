#pragma once
// Where the geodesic, voronoi and remesh commands take their sites from:
// --sites N [--sampling random|poisson|fps] [--seed S], or --site-file F.
// --sites N samples the surface the same way in every command.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace geodual::cli {

class SiteSource {
 public:
  /// The most sites --sites accepts (each costs memory in every stage).
  static constexpr std::int64_t max_sites = 100'000'000;

  /// `default_sampling`: what --sampling is when not given.
  explicit SiteSource(std::string default_sampling = "random") : sampling_(std::move(default_sampling)) {}
  /// Adds --sites, --site-file, --sampling and --seed to `command`.
  void add_to(CLI::App& command);
  /// Throws geodual::UsageError unless exactly one source was given.
  void validate(const std::string& command_name) const;
  std::vector<SurfacePoint> sites(const TriangleMesh& mesh) const;
  remesh::SamplingOptions sampling_options() const;

  const std::string& file() const { return file_; }
  std::int64_t count() const { return count_; }
  std::string sampling() const { return sampling_; }
  std::uint64_t seed() const { return seed_; }

 private:
  std::int64_t count_ = 0;
  std::string file_;
  std::string sampling_;
  std::uint64_t seed_ = 1;
};

}  // namespace geodual::cli
