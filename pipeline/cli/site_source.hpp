#pragma once
// Where the geodesic, voronoi and remesh commands take their sites from:
// --sites N [--sampling random|poisson|fps] [--seed S], or --site-file F;
// for remesh also --edge-length L[%] or --faces N (add_sizing_to), which the
// pipeline turns into a site count. --sites N samples the surface the same
// way in every command.

#include "geodual/mesh/surface_point.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/remesh/sample_sites.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace geodual::cli {

class SiteSource {
 public:
  /// The most sites --sites accepts (each costs memory in every stage).
  static constexpr std::int64_t max_sites = 100'000'000;

  /// `default_sampling`: what --sampling is when not given.
  explicit SiteSource(std::string default_sampling = "poisson") : sampling_(std::move(default_sampling)) {}
  /// Adds --sites, --site-file, --sampling and --seed to `command`.
  void add_to(CLI::App& command);
  /// Adds --edge-length and --faces as further sources (after add_to).
  void add_sizing_to(CLI::App& command);
  /// Throws geodual::UsageError unless exactly one source was given.
  void validate(const std::string& command_name) const;
  std::vector<SurfacePoint> sites(const TriangleMesh& mesh) const;
  remesh::SamplingOptions sampling_options() const;

  /// --edge-length: the length asked for, or 0 when not given; a
  /// percentage is of the bounding-box diagonal of the vertices `mesh`'s
  /// faces use.
  double edge_length(const TriangleMesh& mesh) const;
  /// --edge-length as given ("" when not given).
  const std::string& edge_length_text() const { return edge_length_; }
  /// --faces, or 0 when not given.
  std::int64_t faces() const { return faces_; }

  const std::string& file() const { return file_; }
  std::int64_t count() const { return count_; }
  std::string sampling() const { return sampling_; }
  std::uint64_t seed() const { return seed_; }

 private:
  std::int64_t count_ = 0;
  std::string file_;
  std::string edge_length_;
  std::int64_t faces_ = 0;
  bool sizing_ = false;
  CLI::Option* count_option_ = nullptr;
  CLI::Option* file_option_ = nullptr;
  std::string sampling_;
  std::uint64_t seed_ = 1;
};

}  // namespace geodual::cli
