// texture_bench: how faithfully a remesh's baked textures show its input
// (issue 54, item 5), measured by a program independent of the baker.
//
//   build/bench/texture_bench TEXTURED.glb [SCAN] [--textured-sites 2000,5000] [--texture-sizes 1024,2048,4096]
//                             [--scan-cases 5000:2048,20000:4096] [--levels 1] [--cache-dir DIR]
//                             [--samples 100000] [--seed 1] [--no-normal-map] [--colour-only 5000:2048]
//
// TEXTURED.glb: a textured scan whose texture is procedural_texture.hpp's
// f (tests/data/textured/spot_procedural.glb, made by make_textured_scan).
// SCAN: a mesh (e.g. igea.ply, 268,686 faces) Loop-subdivided --levels times
// (subdivided_inputs.hpp; one step: 1,074,744 faces) and given per-vertex
// colours f(p) (uint8 sRGB), cached in --cache-dir (default
// /tmp/geodual_texture_bench) as <stem>_loop<levels>_procedural.ply.
//
// Cases: TEXTURED at each of --textured-sites x --texture-sizes, SCAN at each
// SITES:SIZE of --scan-cases; with --colour-only SITES:SIZE, the same case
// once more without the normal map (the base colour's own cost). Each case
// is a forked child (bench_support.hpp): geodual::pipeline::run_remesh_pipeline
// with the default options (statistics included: the default job), sites,
// texture_size and bake_normal_map. Then, over --samples points of the
// remesh (uniform by area, --seed), each point's corresponding input point
// is the input's nearest point, found with CGAL's AABB tree
// (closest_point_and_primitive; none of geodual's baking code), and:
//
//  - colour: the baked base colour sampled bilinearly at the point's UV
//    (barycentric in its atlas face; the texels decoded to linear light,
//    interpolated, encoded to sRGB again, as a GPU does with an sRGB
//    texture) against the input's colour at its point (TEXTURED: its own
//    texture sampled the same way at the interpolated input UV; SCAN: its
//    vertex colours interpolated in linear light), in sRGB 0-255 units, the
//    largest channel difference; "vertex" is today's result: the remesh's
//    vertex colours (RemeshPipelineResult::attributes.colors) interpolated
//    in linear light; "f" columns compare with f(input point) itself;
//  - normal (with the normal map): the shading normal a glTF viewer shows,
//    N, T interpolated and normalised, B = cross(N, T) w, the normal map's
//    bilinear texel (c / 255 * 2 - 1) taken in (T, B, N), against the
//    input's shading normal (the file's normals, else angle-weighted ones,
//    interpolated), in degrees; beside it flat shading (the remesh's face
//    normals) and smooth shading (the atlas vertices' normals interpolated);
//  - the correspondence: the distance from the point to its input point, in
//    % of the input's bounding-box diagonal (large where the nearest point
//    jumps to another part of the surface);
//  - time: the pipeline's seconds per stage, the texture stage against all
//    the others (the job without texture), and the peak RSS at the end of
//    the stage before the texture stage and at the end of the texture stage.
//
// Output: one JSON line per case as it is done, then one Markdown table.

#include "bench_support.hpp"
#include "procedural_texture.hpp"
#include "subdivided_inputs.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/mesh/texture_image.hpp"
#include "geodual/pipeline/remesh_pipeline.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace geodual::bench {
namespace {

constexpr const char* usage =
    "usage: texture_bench TEXTURED.glb [SCAN] [--textured-sites 2000,5000] [--texture-sizes 1024,2048,4096]\n"
    "                     [--scan-cases 5000:2048,20000:4096] [--levels 1] [--cache-dir DIR]\n"
    "                     [--samples 100000] [--seed 1] [--no-normal-map] [--colour-only SITES:SIZE,...]\n";

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct Case {
  std::string name;  ///< the input's file name
  std::filesystem::path path;
  std::int64_t sites = 0;
  int texture_size = 0;
  bool normal_map = true;
};

struct Spread {
  double mean = std::numeric_limits<double>::quiet_NaN();
  double p99 = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};

Spread spread(std::vector<double> values) {
  Spread s;
  if (values.empty()) return s;
  double sum = 0;
  for (const double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  std::sort(values.begin(), values.end());
  s.p99 = values[static_cast<std::size_t>(std::floor(0.99 * static_cast<double>(values.size() - 1)))];
  s.max = values.back();
  return s;
}

/// What one case measured (trivially copyable: sent back from its child).
struct Result {
  std::int64_t vertices = 0, faces = 0, input_faces = 0, charts = 0;
  double texture_used = 0;
  double seconds_texture = 0, seconds_other = 0, seconds_statistics = 0;
  std::int64_t peak_before_texture = 0, peak_after_texture = 0;
  bool textured_input = false, has_vertex_colors = false, has_normal_map = false;
  Spread color_baked, color_vertex, color_baked_f, color_vertex_f, color_input_f;
  Spread normal_map, normal_flat, normal_smooth;
  Spread distance_pct;
  double evaluation_seconds = 0;
};

// ---------------------------------------------------------------------------
// Texture sampling as a GPU does it

/// The texel (x, y) of `image`, channel k, decoded: sRGB -> linear where `srgb`.
double texel(const TextureImage& image, int x, int y, int k, bool srgb) {
  const double c = image.texels[image.offset(x, y) + static_cast<std::size_t>(k)] / 255.0;
  return srgb ? srgb_to_linear(c) : c;
}

/// Bilinear sample of the RGB channels at glTF texture coordinates (u, v)
/// ((0, 0) the top-left corner of the first texel), wrapped (REPEAT) or
/// clamped to the edge; in linear light where `srgb` (returned linear).
Eigen::Vector3d sample(const TextureImage& image, Eigen::Vector2d uv, bool srgb, bool repeat) {
  const double x = uv.x() * image.width - 0.5;
  const double y = uv.y() * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto wrap = [repeat](long long i, int n) {
    if (repeat) return static_cast<int>(((i % n) + n) % n);
    return static_cast<int>(std::clamp<long long>(i, 0, n - 1));
  };
  const auto ix = static_cast<long long>(fx), iy = static_cast<long long>(fy);
  const int x0 = wrap(ix, image.width), x1 = wrap(ix + 1, image.width);
  const int y0 = wrap(iy, image.height), y1 = wrap(iy + 1, image.height);
  Eigen::Vector3d out;
  for (int k = 0; k < 3; ++k) {
    const double top = (1 - ax) * texel(image, x0, y0, k, srgb) + ax * texel(image, x1, y0, k, srgb);
    const double bottom = (1 - ax) * texel(image, x0, y1, k, srgb) + ax * texel(image, x1, y1, k, srgb);
    out[k] = (1 - ay) * top + ay * bottom;
  }
  return out;
}

Eigen::Vector3d to_srgb(const Eigen::Vector3d& linear) {
  return {linear_to_srgb(linear[0]), linear_to_srgb(linear[1]), linear_to_srgb(linear[2])};
}

/// Per-vertex sRGB colours interpolated in linear light at barycentric `w` of `face`; sRGB.
Eigen::Vector3d interpolate_color(const ColorMatrix& colors, const Eigen::Vector3i& face, const Eigen::Vector3d& w) {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) linear[c] += w[k] * srgb_to_linear(static_cast<double>(colors(face[k], c)));
  }
  return to_srgb(linear);
}

/// The largest channel difference of two sRGB colours, in 0-255 units.
double color_error(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return 255 * (a - b).cwiseAbs().maxCoeff(); }

double angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi;
}

Eigen::Vector3d row3(const VertexMatrix& m, Index i) { return m.row(i).transpose(); }

// ---------------------------------------------------------------------------
// One case

Result measure(const Case& c, std::int64_t samples, std::uint64_t seed) {
  pipeline::RemeshPipelineOptions options;
  options.sites = c.sites;
  options.texture_size = c.texture_size;
  options.bake_normal_map = c.normal_map;
  const pipeline::RemeshPipelineResult run = pipeline::run_remesh_pipeline(c.path, options);
  if (!run.atlas) throw Error("the pipeline made no atlas");

  Result r;
  const TriangleMesh& input = run.input.mesh;
  const TriangleMesh& remesh = run.remesh.mesh;
  const remesh::TextureAtlas& atlas = *run.atlas;
  const remesh::BakedTextures& baked = run.textures;
  r.vertices = remesh.num_vertices();
  r.faces = remesh.num_faces();
  r.input_faces = input.num_faces();
  r.charts = atlas.charts;
  r.texture_used = atlas.texture_used;
  for (const auto& [stage, seconds] : pipeline::seconds_per_stage(run.timings)) {
    if (stage == pipeline::Stage::texture) {
      r.seconds_texture += seconds;
    } else {
      r.seconds_other += seconds;
    }
    if (stage == pipeline::Stage::statistics) r.seconds_statistics += seconds;
  }
  for (std::size_t i = 0; i < run.timings.size(); ++i) {
    if (run.timings[i].stage == pipeline::Stage::texture) {
      r.peak_after_texture = run.timings[i].peak_memory_bytes;
      if (i > 0) r.peak_before_texture = run.timings[i - 1].peak_memory_bytes;
    }
  }

  const auto start = Clock::now();
  // The input's nearest points: CGAL's AABB tree over its faces with area.
  std::vector<Triangle> triangles;
  std::vector<Index> face_of_triangle;
  auto point = [](const TriangleMesh& mesh, Index v) {
    return Kernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
  };
  for (Index f = 0; f < input.num_faces(); ++f) {
    const Triangle t(point(input, input.faces(f, 0)), point(input, input.faces(f, 1)), point(input, input.faces(f, 2)));
    if (t.is_degenerate()) continue;
    triangles.push_back(t);
    face_of_triangle.push_back(f);
  }
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  const double diagonal = (input.vertices.colwise().maxCoeff() - input.vertices.colwise().minCoeff()).norm();
  const ProceduralTexture f = ProceduralTexture::of(input);

  const SurfaceTexture& texture = run.input.texture;
  r.textured_input = !texture.empty();
  const ColorMatrix& input_colors = run.input.attributes.colors;
  if (!r.textured_input && input_colors.rows() != input.num_vertices()) throw Error("the input has no colour");
  const VertexMatrix input_normals = run.input.attributes.normals.rows() == input.num_vertices()
                                         ? run.input.attributes.normals
                                         : angle_weighted_normals(input);
  const ColorMatrix& vertex_colors = run.attributes.colors;
  r.has_vertex_colors = vertex_colors.rows() == remesh.num_vertices();
  r.has_normal_map = !baked.normal_map.empty();
  const bool has_base_color = !baked.base_color.empty();
  if (!has_base_color) throw Error("nothing baked");

  // Points uniform by area on the remesh.
  std::vector<double> cumulative(static_cast<std::size_t>(remesh.num_faces()));
  double total = 0;
  for (Index face = 0; face < remesh.num_faces(); ++face) {
    const Eigen::Vector3d a = row3(remesh.vertices, remesh.faces(face, 0));
    const Eigen::Vector3d b = row3(remesh.vertices, remesh.faces(face, 1));
    const Eigen::Vector3d cc = row3(remesh.vertices, remesh.faces(face, 2));
    total += 0.5 * (b - a).cross(cc - a).norm();
    cumulative[static_cast<std::size_t>(face)] = total;
  }
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  std::vector<double> e_baked, e_vertex, e_baked_f, e_vertex_f, e_input_f, n_map, n_flat, n_smooth, distance;
  for (std::int64_t s = 0; s < samples; ++s) {
    const double pick = uniform(random) * total;
    const auto face = static_cast<Index>(std::min<std::ptrdiff_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(), remesh.num_faces() - 1));
    const double r1 = std::sqrt(uniform(random)), r2 = uniform(random);
    const Eigen::Vector3d w(1 - r1, r1 * (1 - r2), r1 * r2);
    const Eigen::Vector3i corners = remesh.faces.row(face).transpose();
    const Eigen::Vector3i atlas_corners = atlas.faces.row(face).transpose();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) {
      p += w[k] * row3(remesh.vertices, corners[k]);
      uv += w[k] * atlas.uvs.row(atlas_corners[k]).transpose();
    }

    // The corresponding input point.
    const auto [nearest, primitive] = tree.closest_point_and_primitive(Kernel::Point_3(p.x(), p.y(), p.z()));
    const Index input_face = face_of_triangle[static_cast<std::size_t>(primitive - triangles.cbegin())];
    const Eigen::Vector3i input_corners = input.faces.row(input_face).transpose();
    const Eigen::Vector3d q(nearest.x(), nearest.y(), nearest.z());
    const Eigen::Vector3d b =
        barycentric(q, row3(input.vertices, input_corners[0]), row3(input.vertices, input_corners[1]),
                    row3(input.vertices, input_corners[2]));
    distance.push_back(100 * (q - p).norm() / diagonal);

    // Colours (sRGB).
    Eigen::Vector3d reference;
    if (r.textured_input) {
      Eigen::Vector2d input_uv = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) input_uv += b[k] * texture.corner_uvs.row(3 * input_face + k).transpose();
      reference = to_srgb(sample(texture.image_of(input_face), input_uv, true, true));
    } else {
      reference = interpolate_color(input_colors, input_corners, b);
    }
    const Eigen::Vector3d truth = f.color(q);
    const Eigen::Vector3d shown = to_srgb(sample(baked.base_color, uv, true, false));
    e_baked.push_back(color_error(shown, reference));
    e_baked_f.push_back(color_error(shown, truth));
    e_input_f.push_back(color_error(reference, truth));
    if (r.has_vertex_colors) {
      const Eigen::Vector3d today = interpolate_color(vertex_colors, corners, w);
      e_vertex.push_back(color_error(today, reference));
      e_vertex_f.push_back(color_error(today, truth));
    }

    // Normals.
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) expected += b[k] * row3(input_normals, input_corners[k]);
    expected.normalize();
    const Eigen::Vector3d a0 = row3(remesh.vertices, corners[0]);
    const Eigen::Vector3d flat =
        (row3(remesh.vertices, corners[1]) - a0).cross(row3(remesh.vertices, corners[2]) - a0).normalized();
    n_flat.push_back(angle_degrees(flat, expected));
    if (baked.normals.rows() == atlas.uvs.rows()) {
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) normal += w[k] * row3(baked.normals, atlas_corners[k]);
      normal.normalize();
      n_smooth.push_back(angle_degrees(normal, expected));
      if (r.has_normal_map && baked.tangents.rows() == atlas.uvs.rows()) {
        Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
        double handedness = 0;
        for (int k = 0; k < 3; ++k) {
          tangent += w[k] * baked.tangents.row(atlas_corners[k]).head<3>().transpose();
          handedness += w[k] * baked.tangents(atlas_corners[k], 3);
        }
        tangent.normalize();
        const Eigen::Vector3d bitangent = normal.cross(tangent) * (handedness < 0 ? -1.0 : 1.0);
        const Eigen::Vector3d t = sample(baked.normal_map, uv, false, false) * 2 - Eigen::Vector3d::Ones();
        const Eigen::Vector3d shading = (t.x() * tangent + t.y() * bitangent + t.z() * normal).normalized();
        n_map.push_back(angle_degrees(shading, expected));
      }
    }
  }
  r.color_baked = spread(std::move(e_baked));
  r.color_vertex = spread(std::move(e_vertex));
  r.color_baked_f = spread(std::move(e_baked_f));
  r.color_vertex_f = spread(std::move(e_vertex_f));
  r.color_input_f = spread(std::move(e_input_f));
  r.normal_map = spread(std::move(n_map));
  r.normal_flat = spread(std::move(n_flat));
  r.normal_smooth = spread(std::move(n_smooth));
  r.distance_pct = spread(std::move(distance));
  r.evaluation_seconds = seconds_since(start);
  return r;
}

// ---------------------------------------------------------------------------
// The coloured scan

std::filesystem::path ensure_colored_scan(const std::filesystem::path& scan, int levels,
                                          const std::filesystem::path& cache_folder) {
  const std::filesystem::path output =
      cache_folder / (scan.stem().string() + "_loop" + std::to_string(levels) + "_procedural.ply");
  if (std::filesystem::exists(output)) return output;
  const std::filesystem::path subdivided = ensure_subdivided(scan, levels, cache_folder);
  const io::LoadedMesh loaded = io::read_mesh(subdivided);
  const ProceduralTexture f = ProceduralTexture::of(loaded.mesh);
  VertexAttributes attributes;
  attributes.colors.resize(loaded.mesh.num_vertices(), 3);
  for (Index v = 0; v < loaded.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d color = f.color(row3(loaded.mesh.vertices, v));
    for (int k = 0; k < 3; ++k) attributes.colors(v, k) = static_cast<float>(std::round(color[k] * 255) / 255);
  }
  attributes.color_type = ValueType::uint8;
  io::write_ply(output, loaded.mesh, attributes);
  return output;
}

// ---------------------------------------------------------------------------
// Output

std::string json_spread(const char* name, const Spread& s) {
  auto number = [](double v) { return std::isnan(v) ? std::string("null") : fixed(v, 4); };
  return std::string("\"") + name + "\": {\"mean\": " + number(s.mean) + ", \"p99\": " + number(s.p99) +
         ", \"max\": " + number(s.max) + "}";
}

std::string json_line(const Case& c, const Result& r) {
  return "{\"input\": \"" + c.name + "\", \"sites\": " + std::to_string(c.sites) +
         ", \"texture_size\": " + std::to_string(c.texture_size) +
         ", \"normal_map\": " + (c.normal_map ? "true" : "false") + ", \"vertices\": " + std::to_string(r.vertices) +
         ", \"faces\": " + std::to_string(r.faces) + ", \"input_faces\": " + std::to_string(r.input_faces) +
         ", \"charts\": " + std::to_string(r.charts) + ", \"texture_used\": " + fixed(r.texture_used, 4) +
         ", \"seconds_texture\": " + fixed(r.seconds_texture, 3) + ", \"seconds_other\": " + fixed(r.seconds_other, 3) +
         ", \"seconds_statistics\": " + fixed(r.seconds_statistics, 3) +
         ", \"peak_before_texture\": " + std::to_string(r.peak_before_texture) +
         ", \"peak_after_texture\": " + std::to_string(r.peak_after_texture) + ", " +
         json_spread("color_baked", r.color_baked) + ", " + json_spread("color_vertex", r.color_vertex) + ", " +
         json_spread("color_baked_vs_f", r.color_baked_f) + ", " + json_spread("color_vertex_vs_f", r.color_vertex_f) +
         ", " + json_spread("color_input_vs_f", r.color_input_f) + ", " + json_spread("normal_map_deg", r.normal_map) +
         ", " + json_spread("normal_flat_deg", r.normal_flat) + ", " +
         json_spread("normal_smooth_deg", r.normal_smooth) + ", " + json_spread("distance_pct", r.distance_pct) +
         ", \"evaluation_seconds\": " + fixed(r.evaluation_seconds, 2) + "}";
}

std::string pair(const Spread& s, int digits) {
  if (std::isnan(s.mean)) return "-";
  return fixed(s.mean, digits) + " / " + fixed(s.p99, digits);
}

std::vector<std::pair<std::int64_t, int>> parse_cases(const std::string& option, const std::string& text) {
  std::vector<std::pair<std::int64_t, int>> cases;
  if (text.empty()) return cases;
  for (const std::string_view item : split_commas(text)) {
    const std::size_t colon = item.find(':');
    if (colon == std::string_view::npos)
      throw UsageError(option + ": expected SITES:SIZE, got '" + std::string(item) + "'");
    cases.emplace_back(parse_integer(option, std::string(item.substr(0, colon)), 4, 100'000'000),
                       static_cast<int>(parse_integer(option, std::string(item.substr(colon + 1)), 64, 16384)));
  }
  return cases;
}

int run(int argc, char** argv) {
  std::vector<std::int64_t> textured_sites = {2000, 5000};
  std::vector<std::int64_t> sizes = {1024, 2048, 4096};
  std::vector<std::pair<std::int64_t, int>> scan_cases = {{5000, 2048}, {20000, 4096}};
  std::vector<std::pair<std::int64_t, int>> colour_only;
  int levels = 1;
  std::filesystem::path cache = "/tmp/geodual_texture_bench";
  std::int64_t samples = 100'000;
  std::uint64_t seed = 1;
  bool normal_map = true;
  const std::vector<std::filesystem::path> paths =
      parse_command_line(argc, argv, usage, [&](const std::string& word, const NextValue& value) {
        if (word == "--textured-sites") {
          textured_sites = parse_integer_list(word, value(), 4, 100'000'000);
        } else if (word == "--texture-sizes") {
          sizes = parse_integer_list(word, value(), 64, 16384);
        } else if (word == "--scan-cases") {
          scan_cases = parse_cases(word, value());
        } else if (word == "--colour-only") {
          colour_only = parse_cases(word, value());
        } else if (word == "--levels") {
          levels = static_cast<int>(parse_integer(word, value(), 0, 3));
        } else if (word == "--cache-dir") {
          cache = value();
        } else if (word == "--samples") {
          samples = parse_integer(word, value(), 1, 100'000'000);
        } else if (word == "--seed") {
          seed = static_cast<std::uint64_t>(parse_integer(word, value(), 0, 1'000'000'000));
        } else if (word == "--no-normal-map") {
          normal_map = false;
        } else {
          return false;
        }
        return true;
      });
  if (paths.empty() || paths.size() > 2) throw UsageError(usage);

  std::vector<Case> cases;
  auto add = [&](const std::filesystem::path& path, std::int64_t sites, int size) {
    const std::string name = path.filename().string();
    cases.push_back({name, path, sites, size, normal_map});
    for (const auto& [s, z] : colour_only) {
      if (s == sites && z == size && normal_map) cases.push_back({name, path, sites, size, false});
    }
  };
  for (const std::int64_t sites : textured_sites) {
    for (const std::int64_t size : sizes) add(paths[0], sites, static_cast<int>(size));
  }
  if (paths.size() == 2) {
    std::cerr << "texture_bench: the coloured scan (" << paths[1].string() << ", " << levels << " Loop step(s))...\n";
    const std::filesystem::path scan = ensure_colored_scan(paths[1], levels, cache);
    for (const auto& [sites, size] : scan_cases) add(scan, sites, size);
  }

  std::cout << "texture_bench: " << cpu_model() << ", load " << load_average() << ", " << samples
            << " samples per case, seed " << seed << '\n';
  TextTable table({{"input", TextTable::Align::left},
                   {"V"},
                   {"tex"},
                   {"nmap"},
                   {"colour baked"},
                   {"colour vertex"},
                   {"baked vs f"},
                   {"vertex vs f"},
                   {"input vs f"},
                   {"normal map deg"},
                   {"flat deg"},
                   {"smooth deg"},
                   {"dist % p99/max"},
                   {"texture s"},
                   {"job s"},
                   {"stats s"},
                   {"peak MiB"}});
  int status = 0;
  for (const Case& c : cases) {
    const ChildOutcome outcome = run_in_child({}, [&] { return to_bytes(measure(c, samples, seed)); });
    std::vector<std::string> cells = {c.name, grouped(c.sites), std::to_string(c.texture_size),
                                      c.normal_map ? "yes" : "no"};
    if (outcome.status != ChildOutcome::Status::ok) {
      status = 1;
      cells.push_back("failed: " + outcome.message);
      std::cerr << "texture_bench: " << c.name << " " << c.sites << " " << c.texture_size << ": " << outcome.message
                << '\n';
      table.add_row(cells);
      continue;
    }
    const auto r = from_bytes<Result>(outcome.payload);
    std::cout << json_line(c, r) << std::endl;
    cells[1] = grouped(r.vertices);
    cells.insert(cells.end(),
                 {pair(r.color_baked, 2), pair(r.color_vertex, 2), pair(r.color_baked_f, 2), pair(r.color_vertex_f, 2),
                  pair(r.color_input_f, 2), pair(r.normal_map, 2), pair(r.normal_flat, 2), pair(r.normal_smooth, 2),
                  fixed(r.distance_pct.p99, 3) + " / " + fixed(r.distance_pct.max, 2), fixed(r.seconds_texture, 2),
                  fixed(r.seconds_other, 2), fixed(r.seconds_statistics, 2),
                  mebibytes(r.peak_before_texture) + " -> " + mebibytes(r.peak_after_texture)});
    table.add_row(cells);
  }
  std::cout << '\n';
  table.print(std::cout);
  return status;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main("texture_bench", [&] { return geodual::bench::run(argc, argv); });
}
