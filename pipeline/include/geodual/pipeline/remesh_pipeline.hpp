#pragma once
// The remesh pipeline for C++ code: the stages the `geodual remesh` command
// runs, callable all at once or one at a time, with per-stage timings and
// peak memory, and a progress callback that can cancel.
//
//   geodual::pipeline::RemeshPipelineOptions options;   // 4000 sites, 10 Lloyd iterations
//   options.sites = 2000;
//   auto result = geodual::pipeline::run_remesh_pipeline("scan.ply", options);
//   geodual::io::write_mesh("remeshed.ply", result.remesh.mesh, result.attributes);
//
// Stage by stage (each takes plain data and returns plain data; these are
// the calls the pipeline makes):
//   auto loaded = geodual::io::read_mesh("scan.ply");
//   auto surface = geodual::remesh::cut_to_manifold(loaded.mesh).mesh;
//   auto sites = geodual::remesh::sample_sites_for_topology(surface, 2000).sites;
//   geodual::voronoi::GeodesicSurface geodesic(surface);  // prepared once for both stages
//   auto relaxed = geodual::remesh::lloyd_relax(geodesic, sites);
//   auto remeshed = geodual::remesh::dual_with_repair(geodesic, relaxed.sites, std::move(relaxed.diagram));
//   auto report = geodual::quality::compare_meshes(loaded.mesh, remeshed.mesh);

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/mesh_report.hpp"
#include "geodual/quality/quality_stats.hpp"
#include "geodual/remesh/angle_smoothing.hpp"
#include "geodual/remesh/deviation_fitting.hpp"
#include "geodual/remesh/feature_cut.hpp"
#include "geodual/remesh/features.hpp"
#include "geodual/remesh/follow_segments.hpp"
#include "geodual/remesh/manifold_cut.hpp"
#include "geodual/remesh/remesh.hpp"
#include "geodual/remesh/remesh_smoothing.hpp"
#include "geodual/remesh/sample_sites.hpp"
#include "geodual/remesh/texture_atlas.hpp"
#include "geodual/remesh/texture_bake.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geodual::pipeline {

enum class Stage { load, sample, relax, dual, statistics, texture };

/// "load", "sample", "relax" (Lloyd and its diagrams), "dual" (the dual and
/// its repair rounds), "statistics", "texture" (the atlas and the baking).
std::string_view stage_name(Stage stage);

/// Called now and then with the stage and its fraction done in [0, 1];
/// returning false cancels the run (geodual::Cancelled is thrown, nothing is
/// written).
using ProgressCallback = std::function<bool(Stage stage, double fraction)>;

struct RemeshPipelineOptions {
  std::int64_t sites = 4000;                             ///< sites sampled on the input (ignored if given_sites is set)
  std::optional<std::vector<SurfacePoint>> given_sites;  ///< use these sites instead of sampling
  /// Sizing instead of `sites` (0: unused): the site count is derived on the
  /// surface cut to a manifold for near-equilateral triangles of this side
  /// (remesh::sites_for_edge_length) or for about this many faces
  /// (remesh::sites_for_faces). At most one of edge_length, faces and
  /// given_sites may be set (geodual::UsageError otherwise).
  double edge_length = 0;
  std::int64_t faces = 0;
  /// Blue noise (Poisson disk), seed 1, sites on boundary loops: the relaxation
  /// converges from evenly spread sites in fewer steps than from random ones.
  remesh::SamplingOptions sampling;
  remesh::RemeshOptions remesh;  ///< 10 Lloyd iterations, up to 10 repair rounds
  /// Sharp features kept (creases at 60 degrees, continued at 30); none with
  /// given_sites. sampling.given_edges are edges of the input.
  remesh::FeatureRemeshOptions features;
  /// The last stage (with a relaxation): deviation fitting, then angle
  /// smoothing at 30 degrees. crease_tolerance 0: the feature recall's
  /// tolerance (quality.feature_tolerance_pct of the bounding-box diagonal).
  remesh::RemeshSmoothingOptions smoothing;
  /// Fail (geodual::Error, before the relaxation) when more than
  /// `max_dropped_area_pct` of the input's area is left out; false: report it only.
  bool strict = false;
  double max_dropped_area_pct = 0.1;
  /// Carry the input's vertex attributes (colours, normals, scalars) to the
  /// remesh's vertices (RemeshPipelineResult::attributes); false: drop them.
  bool attributes = true;
  bool statistics = true;           ///< compare the remesh with the input (quality, Hausdorff)
  quality::QualityOptions quality;  ///< 10^6 samples per side
  /// An error bound (0: none): the two-sided Hausdorff distance between the
  /// remesh and the input, in % of the input's bounding-box diagonal (the
  /// statistics' hausdorff_pct). Where a remesh strays farther, the next is
  /// made with more sites there (remesh::refine_density; without features
  /// it starts from the last one's sites, remesh::add_sites_at_deviations),
  /// until the bound holds, after at most max_error_rounds remeshes, or once
  /// one had max_sites sites (0: 8 times the first's). Needs statistics; not
  /// with given_sites.
  double max_error_pct = 0;
  std::int64_t max_sites = 0;
  int max_error_rounds = 8;
  /// Where a remesh under the bound starts from the last one's sites, only
  /// the sites within two spacings of those added move
  /// (remesh::sites_away_from_added), on the restricted diagram alone
  /// (LloydOptions::warm_start_alone), and the rest of the remesh stays as
  /// it was; false: every site is relaxed again, as in the first remesh.
  bool refine_locally = true;
  /// With max_error_pct: called before each remesh with its number (from 1)
  /// and the sites it asks for (0 where the first is sized by edge length or
  /// faces), so that a progress display can say which remesh it shows.
  std::function<void(int round, std::int64_t sites)> on_error_round;
  /// The last stage: a texture atlas for the remesh (texture_size texels a
  /// side; 0: none), with seams along the remesh's edges that turn by at
  /// least features.sampling.sharp_angle (60 degrees where that is 0), and
  /// the input's base colour (its texture, else its vertex colours) baked
  /// onto it (remesh::make_texture_atlas, remesh::bake_textures)...
  int texture_size = 0;
  /// ... and a tangent-space normal map of the input's shading normals.
  bool bake_normal_map = false;
  ProgressCallback progress;
};

/// One remesh made under an error bound.
struct ErrorRound {
  std::int64_t sites = 0;  ///< asked (sites added for topology or by repair aside)
  double hausdorff_pct = 0;
};

struct StageTiming {
  Stage stage = Stage::load;
  double seconds = 0;
  std::int64_t peak_memory_bytes = 0;  ///< the process's peak resident memory at the stage's end
};

/// Each stage's seconds summed over `timings` (a run with max_error_pct
/// makes several remeshes), in the order the stages first ran.
std::vector<std::pair<Stage, double>> seconds_per_stage(const std::vector<StageTiming>& timings);

/// The input's faces the remesh leaves out: scraps and flaps the cut to a
/// manifold disabled (manifold_cut.hpp), duplicate faces (counted in `faces`,
/// not in the area: the face they copy is kept), and faces with a repeated
/// corner.
struct DroppedSurface {
  std::int64_t faces = 0;
  double area = 0;
  double area_pct = 0;  ///< of the input's total area, copies of kept faces aside
};

/// The faces of `input` that `cut` (its cut to a manifold) leaves out.
DroppedSurface dropped_surface(const TriangleMesh& input, const remesh::ManifoldCut& cut);

/// A stretch of sharp edges that the remesh does not keep as a chain of its
/// edges, because the remesh that kept it failed near it: the edges left
/// out, joined where they share a vertex.
struct FeatureLeftOut {
  std::int64_t edges = 0;
  double length = 0;
  Eigen::Vector3d place = Eigen::Vector3d::Zero();  ///< the stretch's vertex nearest its centroid
};

struct RemeshPipelineResult {
  io::LoadedMesh input;
  MeshReport input_report;
  /// The surface remeshed: the input cut apart at non-manifold vertices.
  remesh::ManifoldCut surface;
  DroppedSurface dropped;  ///< what the cut left out
  /// The sharp features kept (options.features; none with given
  /// sites), and the surface cut open along them, which the relaxation and
  /// the dual work on (empty when there are none).
  remesh::FeatureSet features;
  remesh::FeatureCut feature_cut;
  std::int64_t feature_sites = 0;  ///< distinct points of the remesh placed on the features
  /// Of those, the points added where a crease bends too much for chords
  /// 3/4 of a spacing long (FeatureSampling::points_tightened).
  std::int64_t feature_sites_tightened = 0;
  /// The chains whose points lie at their own vertices where they bend
  /// (remesh::FeatureSites::chains_split_at_bends).
  std::int64_t feature_chains_split_at_bends = 0;
  /// Sites added beside the features where their sites are closer than the
  /// spacing (FeatureSites::dense_points), so that the triangles there keep their shape.
  std::int64_t sites_added_near_features = 0;
  /// Sites pinned on the short creases (FeatureSet::short_creases), within
  /// the site count, and the remesh's edges along them (crease_pins.hpp).
  std::int64_t crease_pins = 0;
  std::int64_t first_crease_pin = 0;  ///< the pins are initial_sites[first_crease_pin, + crease_pins)
  remesh::FollowedSegments crease_segments;
  /// The smoothing of the remesh's worst triangles (RemeshPipelineOptions::smoothing):
  /// the vertices it moved (with their sites) and the smallest angle before and after.
  remesh::AngleSmoothingResult smoothing;
  /// The fitting of the vertices that answer for the surface's points
  /// farthest from the remesh (RemeshSmoothingOptions::fit_deviations), before the
  /// smoothing: the vertices it moved and the largest distance before and after.
  remesh::DeviationFittingResult fitting;
  /// Why the short creases were not pinned, where they were asked for (empty otherwise).
  std::string crease_pins_reason;
  /// Of initial_sites, the second (third...) copies of a feature point, one
  /// per further side of its chain: initial_sites.size() - site_twins points.
  std::int64_t site_twins = 0;
  /// Why the features were not kept, where the remesh that keeps them
  /// failed and the remesh was made without them (empty otherwise).
  std::string features_dropped_reason;
  /// Where the remesh that keeps all the features failed at places and was
  /// made without the creases within two spacings of them: those places,
  /// and why the first try failed (empty otherwise).
  std::vector<Eigen::Vector3d> features_dropped_near;
  std::string features_partly_dropped_reason;
  /// The creases left out by either fallback above, by stretch, longest first.
  std::vector<FeatureLeftOut> features_left_out;
  /// The surface remeshed (the input cut to a manifold at its non-manifold
  /// edges and vertices): its Euler characteristic and boundary loops, which
  /// differ from input_report's where the cut changed the part's topology.
  std::int64_t surface_euler_characteristic = 0;
  std::int64_t surface_boundary_loops = 0;
  std::vector<SurfacePoint> initial_sites;
  /// The site count derived from options.edge_length or options.faces, used
  /// instead of options.sites (0 when neither is set).
  std::int64_t sites_for_sizing = 0;
  /// Sites sampled beyond options.sites (or sites_for_sizing) because the surface's pieces and
  /// boundary loops need them (remesh::sample_sites_for_topology), and why.
  std::int64_t sites_added_for_topology = 0;
  std::string sites_added_reason;
  /// Sites added because the count asked for could not carry the creases:
  /// no try kept them with it, one with more sites did
  /// (remesh::FeatureRemeshOptions::max_site_doublings), and why.
  std::int64_t sites_added_for_creases = 0;
  std::string sites_added_for_creases_reason;
  /// The relax stage: relaxed sites, energy history (its diagram moved on to `remesh`).
  remesh::LloydResult relaxation;
  remesh::RepairedDual remesh;  ///< the dual stage: the remeshed mesh, final sites and diagram
  /// The input's attributes at the remesh's vertices, one row per vertex of
  /// remesh.mesh (interpolate_attributes at the points of the input they are);
  /// empty when the input has none or options.attributes is false.
  VertexAttributes attributes;
  std::optional<quality::QualityReport> statistics;
  /// With options.max_error_pct: every remesh made, in order, and whether
  /// the one returned (the last if it meets the bound, else the closest)
  /// meets it.
  std::vector<ErrorRound> error_rounds;
  bool error_bound_met = true;
  std::vector<StageTiming> timings;  ///< of every remesh made, in order
  /// With options.texture_size: the remesh's atlas and the textures baked
  /// onto it (on the atlas's vertices, copies of the remesh's).
  std::optional<remesh::TextureAtlas> atlas;
  remesh::BakedTextures textures;
};

/// Where `input` has a texture (LoadedMesh::texture): its vertices at
/// exactly the same position welded into one, the first copy keeping its
/// attributes, the faces in their order and the texture's corner coordinates
/// with them, and a note in input.info. glTF splits vertices along a
/// texture's seams, which would otherwise be boundaries of the remesh.
/// Returns, per vertex of the input as given, its welded vertex; empty where
/// nothing was welded. run_remesh_pipeline calls it first (not with given sites).
std::vector<Index> weld_texture_seams(io::LoadedMesh& input);

/// The seams of the remesh's atlas: its edges whose faces' normals turn by
/// at least `angle_degrees`, as vertex pairs (AtlasOptions::seams).
std::vector<std::array<Index, 2>> atlas_seams(const TriangleMesh& remesh, double angle_degrees);

/// Each vertex of `result.remesh.mesh` as a point of the input mesh (the cuts
/// keep the input's faces and their corner order, and split vertices into copies).
std::vector<SurfacePoint> remesh_vertices_on_input(const RemeshPipelineResult& result);

/// Per pin on the short creases (RemeshPipelineResult::crease_pins), its
/// vertex of result.remesh.mesh (-1: the repair left it out).
std::vector<Index> crease_pin_vertices(const RemeshPipelineResult& result);

/// Runs every stage on a file.
RemeshPipelineResult run_remesh_pipeline(const std::filesystem::path& input, const RemeshPipelineOptions& options = {});
/// Runs every stage after `load` on a mesh already read, a textured input
/// welded first (weld_texture_seams; not with given sites, which name its vertices).
RemeshPipelineResult run_remesh_pipeline(io::LoadedMesh input, const RemeshPipelineOptions& options = {});

}  // namespace geodual::pipeline
