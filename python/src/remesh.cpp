// remesh: the whole pipeline (sample, Lloyd relaxation, dual with repair,
// statistics) on numpy arrays, through pipeline::run_remesh_pipeline.

#include "arrays.hpp"
#include "bindings.hpp"
#include "cancellation.hpp"
#include "json_to_python.hpp"

#include "geodual/mesh/coordinate_range.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"
#include "geodual/pipeline/report_json.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

namespace geodual::python {
namespace {

/// What remesh() returns: plain Python objects, read-only attributes.
struct RemeshResult {
  py::object vertices;
  py::object faces;
  py::object colors;
  py::object stats;
  py::object report;
  std::int64_t sites = 0;
  std::int64_t sites_added_for_topology = 0;
  std::int64_t sites_added_for_creases = 0;
  std::int64_t sites_added_near_features = 0;
  std::int64_t crease_pins = 0;
  std::int64_t feature_chains = 0;
  py::object features_dropped_reason;
  py::object features_dropped_near;
  py::list features_left_out;
  std::int64_t cracks_closed = 0;
  py::object narrowest_corner;
  std::int64_t sites_added = 0;
  std::int64_t sites_left_out = 0;
  std::int64_t vertices_smoothed = 0;
  std::int64_t vertices_fitted = 0;
  py::object error_bound_met;
  py::object error_rounds;
  py::object timings;
  // With texture_size: the atlas (its vertices are copies of the remesh's) and the baked images.
  py::object uvs = py::none();
  py::object uv_faces = py::none();
  py::object uv_vertices = py::none();
  py::object tangents = py::none();
  py::object base_color_texture = py::none();
  py::object normal_texture = py::none();
};

std::int64_t positive_count(const py::handle& value, const char* name) {
  if (!is_integer(value)) throw py::type_error(std::string(name) + " must be an integer");
  const auto count = value.cast<long long>();
  if (count < 1) throw py::value_error(std::string(name) + " must be at least 1, got " + std::to_string(count));
  return count;
}

/// Vertex pairs from a k x 2 integer array (or anything numpy makes one of).
std::vector<std::array<Index, 2>> edges_from_object(const py::object& object) {
  const py::array array = py::array::ensure(object);
  if (array && array.size() == 0) return {};
  const bool integers = array && (array.dtype().kind() == 'i' || array.dtype().kind() == 'u');
  if (!integers || array.ndim() != 2 || array.shape(1) != 2) {
    throw py::type_error("feature_edges must be a k x 2 array of vertex indices, got " + std::string(py::repr(object)));
  }
  const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> pairs(array);
  std::vector<std::array<Index, 2>> edges(static_cast<std::size_t>(pairs.size() / 2));
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (int k = 0; k < 2; ++k) {
      const std::int64_t v = pairs.data()[2 * i + static_cast<std::size_t>(k)];
      if (v < 0 || v > std::numeric_limits<Index>::max()) {
        throw py::value_error("feature_edges: vertex " + std::to_string(v) + " is out of range");
      }
      edges[i][static_cast<std::size_t>(k)] = static_cast<Index>(v);
    }
  }
  return edges;
}

RemeshResult remesh(const py::handle& vertices, const py::handle& faces, const py::object& sites,
                    const py::object& edge_length, const py::object& face_count, int lloyd, std::int64_t seed,
                    const py::object& colors, double sharp_angle, double continuation_angle, bool pin_creases,
                    const py::object& feature_edges, double smoothing_angle, bool fit_deviations,
                    const py::object& progress, bool statistics, const py::object& max_error,
                    const py::object& max_sites, int texture_size, bool bake_normal) {
  const int sizings = !sites.is_none() + !edge_length.is_none() + !face_count.is_none();
  if (sizings > 1) {
    throw py::value_error("give at most one of sites, edge_length and faces (got " + std::to_string(sizings) + ")");
  }
  io::LoadedMesh input;
  input.mesh = mesh_from_arrays(vertices, faces);
  if (!colors.is_none()) input.attributes.colors = colors_from_array(colors, input.mesh.num_vertices());

  pipeline::RemeshPipelineOptions options;
  if (!sites.is_none()) {
    if (is_integer(sites)) {
      options.sites = positive_count(sites, "sites");
    } else if (!py::isinstance<py::sequence>(sites) && !py::isinstance<py::array>(sites)) {
      throw py::type_error("sites must be a count or a sequence of vertex indices and (face, u, v, w) tuples, got " +
                           std::string(py::repr(sites)));
    } else {
      options.given_sites = sites_from_object(sites, input.mesh);
    }
  }
  if (!edge_length.is_none()) {
    options.edge_length = edge_length.cast<double>();
    if (!std::isfinite(options.edge_length) || options.edge_length <= 0) {
      throw py::value_error("edge_length must be a finite number > 0, got " + std::string(py::repr(edge_length)));
    }
  }
  if (!face_count.is_none()) options.faces = positive_count(face_count, "faces");
  if (lloyd < 0) throw py::value_error("lloyd must be >= 0 (iterations), got " + std::to_string(lloyd));
  if (seed < 0) throw py::value_error("seed must be >= 0, got " + std::to_string(seed));
  // The feature and smoothing options are checked by the pipeline (geodual.UsageError, a ValueError).
  options.remesh.lloyd.iterations = lloyd;
  options.sampling.seed = static_cast<std::uint64_t>(seed);
  options.features.sampling.sharp_angle = sharp_angle;
  options.features.sampling.continuation_angle = continuation_angle;
  options.features.pin_short_creases = pin_creases;
  options.smoothing.smoothing_angle = smoothing_angle;
  options.smoothing.fit_deviations = fit_deviations;
  if (!feature_edges.is_none()) options.features.sampling.given_edges = edges_from_object(feature_edges);
  options.statistics = statistics;
  if (!max_error.is_none()) {
    options.max_error_pct = max_error.cast<double>();
    if (!(options.max_error_pct > 0 && options.max_error_pct <= 100)) {
      throw py::value_error("max_error must be in (0, 100] (% of the bounding-box diagonal), got " +
                            std::string(py::repr(max_error)));
    }
  }
  if (!max_sites.is_none()) {
    if (max_error.is_none()) throw py::value_error("max_sites needs max_error");
    options.max_sites = positive_count(max_sites, "max_sites");
  }
  if (texture_size != 0 && (texture_size < 64 || texture_size > 16384)) {
    throw py::value_error("texture_size must be 0 (none) or in [64, 16384], got " + std::to_string(texture_size));
  }
  if (bake_normal && texture_size == 0) throw py::value_error("bake_normal needs texture_size");
  options.texture_size = texture_size;
  options.bake_normal_map = bake_normal;
  ProgressBridge bridge(progress);
  options.progress = [&bridge](pipeline::Stage stage, double fraction) {
    return bridge(pipeline::stage_name(stage), fraction);
  };

  const pipeline::RemeshPipelineResult run = bridge.run([&] {
    require_computable_range(input.mesh, "V");
    return pipeline::run_remesh_pipeline(std::move(input), options);
  });

  RemeshResult result;
  const TriangleMesh& mesh = run.remesh.mesh;
  result.vertices = vertices_to_array(mesh.vertices);
  result.faces = faces_to_array(mesh.faces);
  result.colors = run.attributes.colors.rows() > 0 ? py::object(colors_to_array(run.attributes.colors)) : py::none();
  if (run.atlas) {
    result.uvs = matrix_to_array(run.atlas->uvs);
    result.uv_faces = faces_to_array(run.atlas->faces);
    result.uv_vertices = vector_to_array<Index>(run.atlas->source_vertex);
    if (run.textures.tangents.rows() > 0) result.tangents = matrix_to_array(run.textures.tangents);
    result.base_color_texture = image_to_array(run.textures.base_color);
    result.normal_texture = image_to_array(run.textures.normal_map);
  }
  result.stats = json_to_python(run.statistics ? pipeline::quality_report_json(*run.statistics, options.quality)
                                               : pipeline::triangle_quality_json(quality::triangle_quality(mesh)));
  // The counts from the one report the CLI writes too (pipeline::remesh_report_json).
  const nlohmann::ordered_json report = pipeline::remesh_report_json(run, options);
  result.report = json_to_python(report);
  result.sites = report["sites"].get<std::int64_t>();
  result.sites_added_for_topology = report["sites_added_for_topology"].get<std::int64_t>();
  result.sites_added_for_creases = report["sites_added_for_creases"].get<std::int64_t>();
  result.sites_added_near_features = report["sites_added_near_features"].get<std::int64_t>();
  result.crease_pins = report["crease_pins"].get<std::int64_t>();
  result.feature_chains = report["feature_chains"].get<std::int64_t>();
  result.features_dropped_reason = json_to_python(report["features_dropped_reason"]);
  result.features_dropped_near = points_to_array(run.features_dropped_near);
  for (const nlohmann::ordered_json& stretch : report["features_left_out"]) {
    py::dict entry;
    entry["edges"] = stretch["edges"].get<std::int64_t>();
    entry["length"] = stretch["length"].get<double>();
    entry["place"] = py::make_tuple(stretch["place"][0].get<double>(), stretch["place"][1].get<double>(),
                                    stretch["place"][2].get<double>());
    result.features_left_out.append(entry);
  }
  result.cracks_closed = report["cracks_closed"].get<std::int64_t>();
  result.narrowest_corner = json_to_python(report["feature_narrowest_corner_deg"]);
  result.sites_added = report["sites_added"].get<std::int64_t>();
  result.sites_left_out = report["sites_left_out"].get<std::int64_t>();
  result.vertices_smoothed = report["vertices_smoothed"].get<std::int64_t>();
  result.vertices_fitted = report["vertices_fitted"].get<std::int64_t>();
  result.error_bound_met = py::none();
  result.error_rounds = py::list();
  if (options.max_error_pct > 0) {
    result.error_bound_met = py::bool_(run.error_bound_met);
    py::list rounds;
    for (const pipeline::ErrorRound& round : run.error_rounds)
      rounds.append(py::make_tuple(round.sites, round.hausdorff_pct));
    result.error_rounds = std::move(rounds);
  }
  py::dict timings;
  for (const auto& [stage, seconds] : pipeline::seconds_per_stage(run.timings)) {
    timings[py::str(std::string(pipeline::stage_name(stage)))] = seconds;
  }
  result.timings = std::move(timings);
  return result;
}

}  // namespace

void add_remesh(py::module_& module) {
  py::class_<RemeshResult>(module, "RemeshResult", "What geodual.remesh() returns.")
      .def_readonly("vertices", &RemeshResult::vertices, "float64 n x 3: the remesh's vertex positions")
      .def_readonly("faces", &RemeshResult::faces, "int32 m x 3: its triangles, oriented like the input")
      .def_readonly("colors", &RemeshResult::colors,
                    "float32 n x 3 / n x 4: the input's colours interpolated at the remesh's vertices, or None")
      .def_readonly("stats", &RemeshResult::stats,
                    "dict: with statistics=True the keys of `geodual stats --json` (the remesh's quality "
                    "figures, Hausdorff/RMS distance to the input, reference_quality...); otherwise the remesh's "
                    "quality figures only")
      .def_readonly("report", &RemeshResult::report,
                    "dict: what the remesh is, under the keys of `geodual remesh --json` less the paths, times and "
                    "memory (docs/formats.md)")
      .def_readonly("sites", &RemeshResult::sites, "the sites sampled (or given), before repair")
      .def_readonly("sites_added_for_topology", &RemeshResult::sites_added_for_topology,
                    "sites sampled beyond the count asked because the surface's pieces and boundary loops need "
                    "them (included in `sites`)")
      .def_readonly("sites_added_for_creases", &RemeshResult::sites_added_for_creases,
                    "sites beyond the count asked because no try kept the creases with it and one with twice or "
                    "four times as many did (included in `sites`)")
      .def_readonly("sites_added_near_features", &RemeshResult::sites_added_near_features,
                    "sites added beside the stretches of a sharp chain whose sites are closer than the spacing "
                    "(included in `sites`)")
      .def_readonly("crease_pins", &RemeshResult::crease_pins,
                    "with pin_creases: the sites pinned on short creases (included in `sites`)")
      .def_readonly("feature_chains", &RemeshResult::feature_chains,
                    "the sharp chains kept as chains of edges (sharp_angle, feature_edges)")
      .def_readonly("features_dropped_reason", &RemeshResult::features_dropped_reason,
                    "why the remesh went without any feature, where the one that kept them failed; else None")
      .def_readonly("features_dropped_near", &RemeshResult::features_dropped_near,
                    "float64 k x 3: the places where the remesh that kept all the features failed, near which "
                    "creases were left out (0 x 3 where none was)")
      .def_readonly("features_left_out", &RemeshResult::features_left_out,
                    "the creases left out where the remesh that kept them failed, by stretch, longest first: "
                    "dicts with 'edges', 'length' and 'place' (x, y, z), the stretch's vertex nearest its middle")
      .def_readonly("cracks_closed", &RemeshResult::cracks_closed,
                    "cracks of the weld along the features that no site move closed, closed with triangles on "
                    "their own vertices")
      .def_readonly("narrowest_corner", &RemeshResult::narrowest_corner,
                    "the narrowest angle in degrees between two kept features at a corner, which bounds the "
                    "remesh's smallest angle there; None where no corner joins two")
      .def_readonly("sites_added", &RemeshResult::sites_added,
                    "sites the repair added where the dual was not a valid remesh")
      .def_readonly("sites_left_out", &RemeshResult::sites_left_out,
                    "given sites the repair left out (each cut a corner off a neighbour's cell)")
      .def_readonly("vertices_smoothed", &RemeshResult::vertices_smoothed,
                    "vertices moved off their sites to mend triangles with an angle below smoothing_angle")
      .def_readonly("vertices_fitted", &RemeshResult::vertices_fitted,
                    "vertices moved off their sites towards the input's points farthest from the remesh "
                    "(fit_deviations)")
      .def_readonly("error_bound_met", &RemeshResult::error_bound_met,
                    "with max_error: whether the remesh returned keeps within it (else it is the closest one "
                    "made); None without max_error")
      .def_readonly("error_rounds", &RemeshResult::error_rounds,
                    "with max_error: (sites, hausdorff_pct) of every remesh made, in order; empty without it")
      .def_readonly("timings", &RemeshResult::timings,
                    "dict: seconds per stage (sample, relax, dual, statistics, texture), summed over the remeshes made")
      .def_readonly("uvs", &RemeshResult::uvs,
                    "with texture_size: float64 k x 2, glTF texture coordinates (v down) of the atlas's vertices; "
                    "None otherwise")
      .def_readonly("uv_faces", &RemeshResult::uv_faces,
                    "with texture_size: int32 m x 3, the triangles (in the order of faces) on the atlas's vertices")
      .def_readonly("uv_vertices", &RemeshResult::uv_vertices,
                    "with texture_size: int32 k, per atlas vertex the remesh vertex it copies (seams copy vertices)")
      .def_readonly("tangents", &RemeshResult::tangents,
                    "with bake_normal: float64 k x 4, glTF TANGENT per atlas vertex (the normal map's frame)")
      .def_readonly("base_color_texture", &RemeshResult::base_color_texture,
                    "with texture_size: uint8 N x N x 3 (or 4), the baked base colour, sRGB, rows top first; None "
                    "where the input has no colour")
      .def_readonly("normal_texture", &RemeshResult::normal_texture,
                    "with bake_normal: uint8 N x N x 3, the tangent-space normal map ((n + 1) / 2)")
      .def("__repr__", [](const RemeshResult& result) {
        return "<geodual.RemeshResult: " + std::to_string(py::len(result.vertices)) + " vertices, " +
               std::to_string(py::len(result.faces)) + " faces>";
      });

  module.def(
      "remesh", &remesh, py::arg("V"), py::arg("F"), py::arg("sites") = py::none(), py::arg("edge_length") = py::none(),
      py::arg("faces") = py::none(), py::arg("lloyd") = 10, py::arg("seed") = 1, py::arg("colors") = py::none(),
      py::arg("sharp_angle") = remesh::FeatureSamplingOptions{}.sharp_angle,
      py::arg("continuation_angle") = remesh::FeatureSamplingOptions{}.continuation_angle,
      py::arg("pin_creases") = remesh::FeatureRemeshOptions{}.pin_short_creases, py::arg("feature_edges") = py::none(),
      py::arg("smoothing_angle") = remesh::RemeshSmoothingOptions{}.smoothing_angle,
      py::arg("fit_deviations") = remesh::RemeshSmoothingOptions{}.fit_deviations, py::arg("progress") = py::none(),
      py::arg("statistics") = true, py::arg("max_error") = py::none(), py::arg("max_sites") = py::none(),
      py::arg("texture_size") = 0, py::arg("bake_normal") = false,
      R"(Remesh a triangle mesh through the dual of its exact geodesic Voronoi diagram.

The same pipeline as `geodual remesh`: the surface is cut to a manifold, sites
are sampled (blue noise), relaxed towards a geodesic centroidal Voronoi
tessellation by Lloyd iterations, and the dual of their Voronoi diagram is the
remesh (one vertex per site); where it is not a valid remesh, sites are added
there and the diagram recomputed.

V, F: the input (n x 3 positions, m x 3 triangles).
Sizing, at most one of (default: sites=4000):
  sites        the number of vertices wanted, or the sites themselves as a
               sequence of vertex indices and (face, u, v, w) tuples
  edge_length  the edge length wanted, in the mesh's units
  faces        about this many triangles
The remesh has exactly `sites` vertices unless the surface's pieces and
boundary loops need more sites (result.sites_added_for_topology) or the repair
adds some (result.sites_added) or leaves some out (result.sites_left_out):
len(result.vertices) == result.sites + result.sites_added - result.sites_left_out.
lloyd: Lloyd iterations (0: none). seed: the sampling's seed; the same input,
options and seed give the same result.
colors: None or the input's per-vertex colours (n x 3 / n x 4, floats in
[0, 1] or uint8), interpolated to the remesh's vertices (result.colors).
sharp_angle: keep sharp creases where the normals turn by at least this many
degrees (0: none; 60 by default).
continuation_angle: continue those creases through edges where the normals
turn by at least this many degrees and both sides are smooth at the remesh's
scale (a machined crease whose angle fades; 0, or not below sharp_angle: off;
30 by default).
pin_creases: also follow the creases at sharp_angle too short to cut along (a
fillet's coarse edges, a crease that fades within a spacing): sites pinned on
their vertices, the sites round them about as close (more sites than asked,
result.sites_added_near_features), edges flipped onto them (False by default).
feature_edges: None or a k x 2 integer array of vertex pairs, edges of F kept
as features too whatever their angle (sharp_angle 0: only these); a pair that
is no edge of F raises geodual.UsageError.
smoothing_angle: last, the corners of triangles with an angle below this many
degrees move along the surface to where the smallest angle round them is
largest (result.vertices_smoothed; chain, corner, boundary and pinned
vertices stay; 0, or lloyd=0: none, every vertex at its site; 30 by default).
fit_deviations: before that, the vertices that answer for the input's points
farthest from the remesh (a crease or a scan's rim the dual cuts off) move
along the surface to where that distance is least, never below 30 degrees
or the remesh's worst Q (result.vertices_fitted; True by default; none with
lloyd=0).
progress: None or progress(stage, fraction) with stage one of "sample",
"relax", "dual", "statistics", "texture"; return False to cancel (geodual.Cancelled).
Ctrl-C raises KeyboardInterrupt.
statistics: compare the remesh with the input (Hausdorff and RMS distance
with 10^6 samples per side); result.stats then has the keys of
`geodual stats --json`.
max_error: None or a bound on the Hausdorff distance in % of the bounding-box
diagonal (result.stats["hausdorff_pct"]): the remesh is made again with more
sites where it strays furthest until it holds, or until max_sites (default 8
times the first count) or 8 remeshes; then the closest remesh is returned
with result.error_bound_met False, as `geodual remesh --max-error` writes it
and exits with 4. Needs statistics=True and a site count, not given sites.
texture_size: 0 (none) or N in [64, 16384]: a texture atlas of N x N texels
for the remesh, with the input's colours baked onto it (result.uvs on the
atlas's vertices result.uv_vertices and triangles result.uv_faces,
result.base_color_texture as an N x N x 3 uint8 array), as `geodual remesh
--texture-size N`. bake_normal: also a tangent-space normal map of the
input's shading normals (result.normal_texture, result.tangents).

Returns a RemeshResult: .vertices, .faces, .colors, .stats, .timings, and the
site counts above. Raises ValueError/TypeError for bad arguments,
geodual.Error where the remesh is impossible (the message says why).

Example:
    V, F = geodual.read_mesh("scan.ply")
    result = geodual.remesh(V, F, sites=2000)
    print(len(result.vertices), result.stats["q_avg"], result.stats["hausdorff_pct"])
)");
}

}  // namespace geodual::python
