#include "site_source.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/sites.hpp"
#include "option_checks.hpp"

#include <CLI/CLI.hpp>

namespace geodual::cli {

void SiteSource::add_to(CLI::App& command) {
  CLI::Option* sites = command.add_option("--sites", count_, "Number of sites to sample on the surface")
                           ->check(integer_between(1, max_sites));
  CLI::Option* file = command.add_option("--site-file", file_, "Read the sites from this file");
  sites->excludes(file);
  file->excludes(sites);
  command.add_option("--sampling", sampling_, "How to sample: random (by area), poisson (blue noise) or fps")
      ->capture_default_str()
      ->check(CLI::IsMember({"random", "poisson", "fps"}));
  command.add_option("--seed", seed_, "Seed for the sampling")->capture_default_str()->check(unsigned_integer());
}

void SiteSource::validate(const std::string& command_name) const {
  if (file_.empty() && count_ <= 0) {
    throw UsageError(command_name + ": give the sites: --sites N (sampled on the surface) or --site-file FILE");
  }
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
