#include "site_source.hpp"

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/sites.hpp"
#include "option_checks.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace geodual::cli {

void SiteSource::add_to(CLI::App& command) {
  count_option_ = command.add_option("--sites", count_, "Number of sites to sample on the surface")
                      ->check(integer_between(1, max_sites));
  file_option_ = command.add_option("--site-file", file_, "Read the sites from this file");
  count_option_->excludes(file_option_);
  file_option_->excludes(count_option_);
  command.add_option("--sampling", sampling_, "How to sample: random (by area), poisson (blue noise) or fps")
      ->capture_default_str()
      ->check(CLI::IsMember({"random", "poisson", "fps"}));
  command.add_option("--seed", seed_, "Seed for the sampling")->capture_default_str()->check(unsigned_integer());
}

void SiteSource::add_sizing_to(CLI::App& command) {
  sizing_ = true;
  CLI::Option* length =
      command
          .add_option("--edge-length", edge_length_,
                      "Sites for near-equilateral triangles of this side: a length, or L% of the bounding-box "
                      "diagonal")
          ->check(length_or_percentage());
  CLI::Option* faces = command.add_option("--faces", faces_, "Sites for a remesh of about this many faces")
                           ->check(integer_between(1, 2 * max_sites));
  for (CLI::Option* option : {count_option_, file_option_, length, faces}) {
    for (CLI::Option* other : {count_option_, file_option_, length, faces}) {
      if (other != option) option->excludes(other);
    }
  }
}

void SiteSource::validate(const std::string& command_name) const {
  if (file_.empty() && count_ <= 0 && edge_length_.empty() && faces_ <= 0) {
    throw UsageError(command_name + ": give the sites: --sites N (sampled on the surface) or --site-file FILE" +
                     (sizing_ ? ", or the size of the remesh: --edge-length L (or L% of the bounding-box diagonal) "
                                "or --faces N"
                              : ""));
  }
}

double SiteSource::edge_length(const TriangleMesh& mesh) const {
  if (edge_length_.empty()) return 0;
  const bool percentage = edge_length_.back() == '%';
  const double value = std::stod(percentage ? edge_length_.substr(0, edge_length_.size() - 1) : edge_length_);
  if (!percentage) return value;
  const double diagonal = mesh.num_faces() > 0 ? referenced_bounding_box(mesh).diagonal() : 0;
  if (!(diagonal > 0)) {
    throw UsageError("--edge-length " + edge_length_ + ": the input's bounding box has no diagonal to take it of");
  }
  return value / 100 * diagonal;
}

std::vector<SurfacePoint> SiteSource::sites(const TriangleMesh& mesh) const {
  if (!file_.empty()) return read_site_file(file_, mesh);
  return remesh::sample_sites(mesh, count_, sampling_options());
}

remesh::SamplingOptions SiteSource::sampling_options() const {
  remesh::SamplingOptions options;
  options.strategy = remesh::parse_sampling_strategy(sampling_);
  options.seed = seed_;
  return options;
}

}  // namespace geodual::cli
