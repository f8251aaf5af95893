#include "geodual/pipeline/remesh_pipeline.hpp"

#include "geodual/mesh/error.hpp"
#include "geodual/pipeline/diagram_output.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

namespace geodual::pipeline {
namespace {

class StageClock {
 public:
  StageClock(std::vector<StageTiming>& timings, Stage stage) : timings_(timings), stage_(stage) {}
  void stop() {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    timings_.push_back({stage_, seconds, peak_memory_bytes()});
  }

 private:
  std::vector<StageTiming>& timings_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

void report(const ProgressCallback& progress, Stage stage, double fraction) {
  if (progress && !progress(stage, fraction)) {
    throw Cancelled(std::string(stage_name(stage)) + " cancelled");
  }
}

}  // namespace

std::string_view stage_name(Stage stage) {
  switch (stage) {
    case Stage::load: return "load";
    case Stage::sample: return "sample";
    case Stage::relax: return "relax";
    case Stage::dual: return "dual";
    case Stage::statistics: return "statistics";
  }
  return "?";
}

RemeshPipelineResult run_remesh_pipeline(const std::filesystem::path& input, const RemeshPipelineOptions& options) {
  std::vector<StageTiming> timings;
  report(options.progress, Stage::load, 0.0);
  StageClock clock(timings, Stage::load);
  io::LoadedMesh loaded = io::read_mesh(input);
  clock.stop();
  report(options.progress, Stage::load, 1.0);
  RemeshPipelineResult result = run_remesh_pipeline(std::move(loaded), options);
  result.timings.insert(result.timings.begin(), timings.front());
  return result;
}

RemeshPipelineResult run_remesh_pipeline(io::LoadedMesh input, const RemeshPipelineOptions& options) {
  RemeshPipelineResult result;
  result.input = std::move(input);
  result.input_report = analyze_mesh(result.input.mesh);

  report(options.progress, Stage::sample, 0.0);
  StageClock sample_clock(result.timings, Stage::sample);
  result.surface = remesh::cut_to_manifold(result.input.mesh);
  result.initial_sites = options.given_sites ? *options.given_sites
                                             : remesh::sample_sites(result.surface.mesh, options.sites, options.sampling);
  sample_clock.stop();
  report(options.progress, Stage::sample, 1.0);

  // Relaxation and dual: the geodesic engine reports the fraction of faces
  // reached in each diagram; Lloyd's accepted iterations split the relax
  // stage, and the diagrams after the relaxation are the dual's repair rounds.
  remesh::RemeshOptions remesh_options = options.remesh;
  const int diagrams = remesh_options.lloyd.iterations + 1;
  int diagrams_done = 0;  // the first diagram, then one per accepted iteration
  bool relaxing = true;
  double relaxed = 0;     // the relax stage's fraction reported last
  if (options.progress) {
    remesh_options.lloyd.on_iteration = [&](int iterations_done, bool finished) {
      diagrams_done = iterations_done + 1;
      relaxing = !finished;
    };
    remesh_options.lloyd.voronoi.geodesic.progress = [&](double fraction) {
      if (!relaxing) return options.progress(Stage::dual, 0.5);
      // Never backwards: a rejected step's diagram holds the fraction where it is.
      relaxed = std::max(relaxed, std::min(1.0, (diagrams_done + std::min(fraction, 1.0)) / diagrams));
      return options.progress(Stage::relax, relaxed);
    };
  }
  report(options.progress, Stage::relax, 0.0);
  StageClock relax_clock(result.timings, Stage::relax);
  result.remesh = remesh::remesh_from_sites(result.surface.mesh, result.initial_sites, remesh_options);
  relax_clock.stop();
  report(options.progress, Stage::dual, 1.0);
  // remesh_from_sites runs the relaxation and the dual together; split the
  // measured time between the two stages by its own accounting.
  StageTiming& combined = result.timings.back();
  const double dual_seconds = std::min(combined.seconds, result.remesh.dual_seconds);
  combined.seconds -= dual_seconds;
  result.timings.push_back({Stage::dual, dual_seconds, combined.peak_memory_bytes});

  if (options.statistics) {
    report(options.progress, Stage::statistics, 0.0);
    StageClock statistics_clock(result.timings, Stage::statistics);
    result.statistics = remesh::compare_meshes(result.input.mesh, result.remesh.mesh, options.quality);
    statistics_clock.stop();
    report(options.progress, Stage::statistics, 1.0);
  }
  return result;
}

}  // namespace geodual::pipeline
