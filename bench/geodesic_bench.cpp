// geodesic_bench: the exact geodesic engine side by side with CGAL and with
// the Dijkstra floor, on the same sites, in one process per mesh.
//
//   geodesic_bench [options] MESH...
//
// For every mesh, N random vertex sites (fixed seed) are drawn once; then each
// method runs R times and the median is reported:
//   ours RWR      geodual::voronoi::compute_geodesic_field, RWR on (default)
//   ours no-RWR   the same with remove_redundant_windows = false
//   CGAL SMSP     CGAL::Surface_mesh_shortest_path (Xin-Wang exact geodesics):
//                 Surface_mesh construction, add the sources, build the
//                 sequence tree, query the distance at every vertex
//   Dijkstra      multi-source Dijkstra on the edge graph (distance + label
//                 per vertex): an upper bound, and the floor for the time
// Each method runs in its own forked child process under an address-space
// and a time limit, so that a method that runs out of memory is reported as
// such instead of ending the benchmark, and so that each method's peak RSS is
// its own. The answers are checked: ours with and without RWR must agree
// exactly, CGAL must agree with ours to a tolerance (relative to the bounding
// box diagonal), and no exact distance may exceed the Dijkstra path length.
// The exit status is 1 when a check fails.

#include "bench_support.hpp"
#include "subdivided_inputs.hpp"

#include "geodual/io/read_mesh.hpp"
#include "geodual/mesh/error.hpp"
#include "geodual/voronoi/geodesic_field.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <queue>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace geodual::bench {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::int64_t kGiB = std::int64_t{1} << 30;

// ---------------------------------------------------------------------------
// Command line

enum class Method { ours_rwr, ours_no_rwr, cgal, dijkstra };

constexpr Method kAllMethods[] = {Method::ours_rwr, Method::ours_no_rwr, Method::cgal, Method::dijkstra};

std::string_view method_key(Method method) {
  switch (method) {
    case Method::ours_rwr: return "rwr";
    case Method::ours_no_rwr: return "no-rwr";
    case Method::cgal: return "cgal";
    case Method::dijkstra: return "dijkstra";
  }
  return "?";
}

std::string_view method_title(Method method) {
  switch (method) {
    case Method::ours_rwr: return "ours RWR";
    case Method::ours_no_rwr: return "ours no-RWR";
    case Method::cgal: return "CGAL SMSP";
    case Method::dijkstra: return "Dijkstra edges";
  }
  return "?";
}

struct Options {
  std::vector<std::filesystem::path> meshes;
  std::size_t sites = 30;
  std::uint64_t seed = 1;
  int repeat = 3;
  std::optional<int> cgal_repeat;  ///< default: repeat
  std::vector<Method> methods{std::begin(kAllMethods), std::end(kAllMethods)};
  std::int64_t max_faces_cgal = 400'000;
  std::optional<double> memory_limit_gib;  ///< default: min(20 GiB, 80% of MemAvailable)
  unsigned time_limit_seconds = 1800;
  double window_limit_gib = 8;
  double tolerance = 1e-6;
  std::vector<int> subdivided_levels;
  std::optional<std::filesystem::path> subdivided_input;  ///< default: see subdivision_input()
  std::optional<std::filesystem::path> subdivided_cache;  ///< default: <executable's folder>/subdivided
};

constexpr std::string_view kUsage = R"(usage: geodesic_bench [options] MESH...

Runs exact multi-source geodesics on each mesh with the same random vertex
sites: ours with and without Redundant Window Removal, CGAL's
Surface_mesh_shortest_path and a Dijkstra-on-edges floor; prints one table.

options:
  --sites N              random vertex sites per mesh (default 30)
  --seed S               seed of the site choice (default 1)
  --repeat R             runs per method; the median is reported (default 3)
  --cgal-repeat R        runs of CGAL, which is 10-100x slower (default: R)
  --methods LIST         comma-separated subset of rwr,no-rwr,cgal,dijkstra
                         (default: all four)
  --skip-cgal            leave CGAL out
  --max-faces-cgal F     skip CGAL on meshes with more than F faces (default 400000)
  --memory-limit-gib G   address-space limit of each method's child process
                         (default: 20, or 80% of MemAvailable if less)
  --time-limit S         wall-clock limit of each method's child in seconds
                         (ours stops then and says how far it got; the others
                         are killed a minute later), 0 for none (default 1800)
  --window-limit-gib G   GeodesicOptions::window_memory_limit_bytes (default 8)
  --tolerance T          allowed max |ours - CGAL| / bbox diagonal (default 1e-6)
  --subdivided LEVELS    also run the Loop-subdivided igea, comma-separated
                         levels (1: 1,074,744 faces, 2: 4,298,976 faces),
                         generated once into the cache folder if missing
  --subdivided-input P   the mesh to subdivide (default: igea.ply among the
                         meshes given, else examples/data/bunny.ply)
  --subdivided-cache D   where subdivided meshes are kept (default: the
                         folder 'subdivided' next to this executable)
  -h, --help             this text
)";

template <class T>
T parse_number(std::string_view option, std::string_view text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) {
    throw UsageError(std::string(option) + ": '" + std::string(text) + "' is not a valid number");
  }
  return value;
}

Options parse_options(int argc, char** argv) {
  Options options;
  const std::vector<std::string_view> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view arg = args[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= args.size()) throw UsageError(std::string(arg) + " needs a value");
      return args[++i];
    };
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "--sites") {
      options.sites = parse_number<std::size_t>(arg, value());
      if (options.sites == 0) throw UsageError("--sites must be at least 1");
    } else if (arg == "--seed") {
      options.seed = parse_number<std::uint64_t>(arg, value());
    } else if (arg == "--repeat") {
      options.repeat = parse_number<int>(arg, value());
      if (options.repeat < 1) throw UsageError("--repeat must be at least 1");
    } else if (arg == "--cgal-repeat") {
      options.cgal_repeat = parse_number<int>(arg, value());
      if (*options.cgal_repeat < 1) throw UsageError("--cgal-repeat must be at least 1");
    } else if (arg == "--methods") {
      options.methods.clear();
      for (const std::string_view name : split_commas(value())) {
        const auto* found = std::find_if(std::begin(kAllMethods), std::end(kAllMethods),
                                         [&](Method m) { return method_key(m) == name; });
        if (found == std::end(kAllMethods)) {
          throw UsageError("--methods: unknown method '" + std::string(name) + "' (rwr, no-rwr, cgal, dijkstra)");
        }
        if (std::find(options.methods.begin(), options.methods.end(), *found) == options.methods.end()) {
          options.methods.push_back(*found);
        }
      }
      // Always in the canonical order: the reference (ours RWR) first.
      std::sort(options.methods.begin(), options.methods.end());
    } else if (arg == "--skip-cgal") {
      std::erase(options.methods, Method::cgal);
    } else if (arg == "--max-faces-cgal") {
      options.max_faces_cgal = parse_number<std::int64_t>(arg, value());
    } else if (arg == "--memory-limit-gib") {
      options.memory_limit_gib = parse_number<double>(arg, value());
    } else if (arg == "--time-limit") {
      options.time_limit_seconds = parse_number<unsigned>(arg, value());
    } else if (arg == "--window-limit-gib") {
      options.window_limit_gib = parse_number<double>(arg, value());
    } else if (arg == "--tolerance") {
      options.tolerance = parse_number<double>(arg, value());
    } else if (arg == "--subdivided") {
      for (const std::string_view level : split_commas(value())) {
        const int l = parse_number<int>("--subdivided", level);
        if (l < 1 || l > 2) throw UsageError("--subdivided: levels are 1 and 2");
        options.subdivided_levels.push_back(l);
      }
    } else if (arg == "--subdivided-input") {
      options.subdivided_input = std::filesystem::path(value());
    } else if (arg == "--subdivided-cache") {
      options.subdivided_cache = std::filesystem::path(value());
    } else if (arg.starts_with("-")) {
      throw UsageError("unknown option " + std::string(arg) + " (see --help)");
    } else {
      options.meshes.emplace_back(arg);
    }
  }
  if (options.meshes.empty() && options.subdivided_levels.empty()) {
    throw UsageError("no mesh given (see --help)");
  }
  if (options.methods.empty()) throw UsageError("no method left to run");
  return options;
}

// ---------------------------------------------------------------------------
// What one run of a method produces

struct Answer {
  std::vector<double> distance;  ///< per vertex, +inf where unreachable
  std::vector<Index> label;      ///< per vertex, site index or -1
  double setup_seconds = 0;
  double solve_seconds = 0;
  voronoi::GeodesicStats stats;  ///< ours only
};

// ---- ours ------------------------------------------------------------------

/// When a method's child must give up: `at`, `seconds` after it started.
struct Deadline {
  Clock::time_point at;
  unsigned seconds = 0;
};

/// Ours. With a deadline it stops through the progress callback and says how
/// far it got (a SIGALRM would end the child without a word).
Answer run_ours(const TriangleMesh& mesh, std::span<const SurfacePoint> sites, bool rwr, double window_limit_gib,
                const std::optional<Deadline>& deadline) {
  voronoi::GeodesicOptions options;
  options.remove_redundant_windows = rwr;
  options.window_memory_limit_bytes = static_cast<std::size_t>(window_limit_gib * static_cast<double>(kGiB));
  double reached = 0;
  if (deadline) {
    options.progress = [&](double fraction) {
      reached = fraction;
      return Clock::now() < deadline->at;
    };
  }
  voronoi::GeodesicField field;
  try {
    field = voronoi::compute_geodesic_field(mesh, sites, options);
  } catch (const Cancelled&) {
    throw Error("time limit of " + std::to_string(deadline->seconds) + " s: stopped with " + fixed(100 * reached, 1) +
                "% of the faces reached");
  }
  Answer answer;
  answer.stats = field.stats;
  answer.setup_seconds = field.stats.setup_seconds;
  answer.solve_seconds = field.stats.propagation_seconds;
  answer.distance = std::move(field.distance);
  answer.label = std::move(field.nearest_site);
  return answer;
}

// ---- CGAL ------------------------------------------------------------------

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using CgalTraits = CGAL::Surface_mesh_shortest_path_traits<Kernel, CgalMesh>;
using CgalShortestPath = CGAL::Surface_mesh_shortest_path<CgalTraits>;
using CgalVertex = CgalMesh::Vertex_index;

CgalVertex cgal_vertex(Index i) { return CgalVertex(static_cast<CgalMesh::size_type>(i)); }

/// Our mesh as a CGAL Surface_mesh: only the vertices used by proper faces
/// (SMSP expects no isolated vertices), renumbered; `from_cgal` maps back.
/// Throws geodual::Error where a face is refused (not a manifold mesh).
CgalMesh to_cgal_mesh(const TriangleMesh& mesh, std::vector<Index>& to_cgal, std::vector<Index>& from_cgal) {
  to_cgal.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
  from_cgal.clear();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.faces(f, c);
      if (to_cgal[v] < 0) {
        to_cgal[v] = static_cast<Index>(from_cgal.size());
        from_cgal.push_back(v);
      }
    }
  }
  CgalMesh sm;
  sm.reserve(static_cast<CgalMesh::size_type>(from_cgal.size()),
             static_cast<CgalMesh::size_type>(3 * mesh.num_faces() / 2 + 3),
             static_cast<CgalMesh::size_type>(mesh.num_faces()));
  for (const Index v : from_cgal) {
    sm.add_vertex(Kernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    if (sm.add_face(cgal_vertex(to_cgal[mesh.faces(f, 0)]), cgal_vertex(to_cgal[mesh.faces(f, 1)]),
                    cgal_vertex(to_cgal[mesh.faces(f, 2)])) == CgalMesh::null_face()) {
      throw Error("CGAL Surface_mesh refuses face " + std::to_string(f) +
                  " (non-manifold or inconsistently oriented); SMSP needs a clean manifold mesh");
    }
  }
  return sm;
}

Answer run_cgal(const TriangleMesh& mesh, std::span<const Index> site_vertices) {
  Answer answer;
  const auto start = Clock::now();
  std::vector<Index> to_cgal, from_cgal;
  const CgalMesh sm = to_cgal_mesh(mesh, to_cgal, from_cgal);
  answer.setup_seconds = seconds_since(start);

  const auto solve_start = Clock::now();
  CgalShortestPath solver(sm);
  // Source points live in a std::list inside the solver: their addresses
  // identify them.
  std::unordered_map<const void*, Index> site_of;
  for (std::size_t i = 0; i < site_vertices.size(); ++i) {
    const auto source = solver.add_source_point(cgal_vertex(to_cgal[site_vertices[i]]));
    site_of.emplace(static_cast<const void*>(&*source), static_cast<Index>(i));
  }
  solver.build_sequence_tree();
  answer.distance.assign(static_cast<std::size_t>(mesh.num_vertices()), kInfinity);
  answer.label.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
  for (std::size_t i = 0; i < from_cgal.size(); ++i) {
    const auto [distance, source] = solver.shortest_distance_to_source_points(cgal_vertex(static_cast<Index>(i)));
    if (distance < 0 || source == solver.source_points_end()) continue;  // not reachable
    answer.distance[from_cgal[i]] = distance;
    answer.label[from_cgal[i]] = site_of.at(static_cast<const void*>(&*source));
  }
  answer.solve_seconds = seconds_since(solve_start);
  return answer;
}

// ---- Dijkstra on the edge graph ---------------------------------------------

/// The vertex graph of the mesh's edges in compressed rows: the neighbours of
/// v are neighbour[offset[v] .. offset[v + 1]), with the edges' lengths.
struct EdgeGraph {
  std::vector<std::int64_t> offset;
  std::vector<Index> neighbour;
  std::vector<double> length;
};

EdgeGraph build_edge_graph(const TriangleMesh& mesh) {
  const auto nv = static_cast<std::size_t>(mesh.num_vertices());
  EdgeGraph graph;
  graph.offset.assign(nv + 1, 0);
  // Each proper face offers both directions of its three edges; an interior
  // edge thus appears twice per row and is deduplicated below.
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      ++graph.offset[static_cast<std::size_t>(mesh.faces(f, k)) + 1];
      ++graph.offset[static_cast<std::size_t>(mesh.faces(f, (k + 1) % 3)) + 1];
    }
  }
  for (std::size_t v = 0; v < nv; ++v) graph.offset[v + 1] += graph.offset[v];
  graph.neighbour.resize(static_cast<std::size_t>(graph.offset[nv]));
  std::vector<std::int64_t> fill(graph.offset.begin(), graph.offset.end() - 1);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      graph.neighbour[static_cast<std::size_t>(fill[a]++)] = b;
      graph.neighbour[static_cast<std::size_t>(fill[b]++)] = a;
    }
  }
  // Sort and deduplicate each row, compacting in place.
  std::int64_t out = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const auto row_begin = graph.neighbour.begin() + graph.offset[v];
    const auto row_end = graph.neighbour.begin() + graph.offset[v + 1];
    std::sort(row_begin, row_end);
    const auto unique_end = std::unique(row_begin, row_end);
    graph.offset[v] = out;
    out = std::copy(row_begin, unique_end, graph.neighbour.begin() + out) - graph.neighbour.begin();
  }
  graph.offset[nv] = out;
  graph.neighbour.resize(static_cast<std::size_t>(out));
  graph.neighbour.shrink_to_fit();
  graph.length.resize(graph.neighbour.size());
  for (std::size_t v = 0; v < nv; ++v) {
    for (auto e = graph.offset[v]; e < graph.offset[v + 1]; ++e) {
      const auto i = static_cast<std::size_t>(e);
      graph.length[i] = (mesh.vertices.row(static_cast<Index>(v)) - mesh.vertices.row(graph.neighbour[i])).norm();
    }
  }
  return graph;
}

Answer run_dijkstra(const TriangleMesh& mesh, std::span<const Index> site_vertices) {
  Answer answer;
  const auto start = Clock::now();
  const EdgeGraph graph = build_edge_graph(mesh);
  answer.setup_seconds = seconds_since(start);

  const auto solve_start = Clock::now();
  std::vector<double>& distance = answer.distance;
  std::vector<Index>& label = answer.label;
  distance.assign(static_cast<std::size_t>(mesh.num_vertices()), kInfinity);
  label.assign(static_cast<std::size_t>(mesh.num_vertices()), -1);
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t i = 0; i < site_vertices.size(); ++i) {
    distance[site_vertices[i]] = 0;
    label[site_vertices[i]] = static_cast<Index>(i);
    queue.emplace(0.0, site_vertices[i]);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;  // a stale entry
    for (auto e = graph.offset[v]; e < graph.offset[v + 1]; ++e) {
      const auto i = static_cast<std::size_t>(e);
      const Index u = graph.neighbour[i];
      const double candidate = d + graph.length[i];
      if (candidate < distance[u]) {
        distance[u] = candidate;
        label[u] = label[v];
        queue.emplace(candidate, u);
      }
    }
  }
  answer.solve_seconds = seconds_since(solve_start);
  return answer;
}

// ---------------------------------------------------------------------------
// One method: R runs in a forked child

/// What the child sends back for one method.
struct MethodReport {
  std::vector<double> total_seconds;  ///< per run, wall clock
  std::vector<double> cpu_seconds;    ///< per run, process CPU time
  std::vector<double> setup_seconds;
  std::vector<double> solve_seconds;
  voronoi::GeodesicStats stats;       ///< of the last run (deterministic)
  std::int64_t rss_before_bytes = 0;  ///< the child's RSS before the first run
  std::int64_t peak_rss_bytes = 0;    ///< max over runs of VmHWM, reset before each
  bool peak_reset = false;            ///< clear_refs worked (else VmHWM is the child's lifetime peak)
  std::vector<double> distance;       ///< of the last run
  std::vector<Index> label;
};

std::vector<std::byte> encode(const MethodReport& r) {
  ByteWriter out;
  out.put_span<double>(r.total_seconds);
  out.put_span<double>(r.cpu_seconds);
  out.put_span<double>(r.setup_seconds);
  out.put_span<double>(r.solve_seconds);
  out.put(r.stats);
  out.put(r.rss_before_bytes);
  out.put(r.peak_rss_bytes);
  out.put(r.peak_reset);
  out.put_span<double>(r.distance);
  out.put_span<Index>(r.label);
  return out.bytes();
}

MethodReport decode(std::span<const std::byte> bytes) {
  ByteReader in(bytes);
  MethodReport r;
  r.total_seconds = in.get_vector<double>();
  r.cpu_seconds = in.get_vector<double>();
  r.setup_seconds = in.get_vector<double>();
  r.solve_seconds = in.get_vector<double>();
  r.stats = in.get<voronoi::GeodesicStats>();
  r.rss_before_bytes = in.get<std::int64_t>();
  r.peak_rss_bytes = in.get<std::int64_t>();
  r.peak_reset = in.get<bool>();
  r.distance = in.get_vector<double>();
  r.label = in.get_vector<Index>();
  return r;
}

/// Runs in the child: `repeat` runs of `run`, each from a reset RSS
/// high-water mark, keeping only the last run's answer.
MethodReport measure(const std::function<Answer()>& run, int repeat) {
  MethodReport report;
  report.rss_before_bytes = current_rss_bytes().value_or(0);
  for (int r = 0; r < repeat; ++r) {
    // Drop the previous run's answer first so that it does not count.
    report.distance = {};
    report.label = {};
    report.peak_reset = reset_peak_rss();
    const double cpu_start = process_cpu_seconds();
    const auto start = Clock::now();
    Answer answer = run();
    report.total_seconds.push_back(seconds_since(start));
    report.cpu_seconds.push_back(process_cpu_seconds() - cpu_start);
    report.peak_rss_bytes = std::max(report.peak_rss_bytes, peak_rss_bytes().value_or(0));
    report.setup_seconds.push_back(answer.setup_seconds);
    report.solve_seconds.push_back(answer.solve_seconds);
    report.stats = answer.stats;
    report.distance = std::move(answer.distance);
    report.label = std::move(answer.label);
  }
  return report;
}

// ---------------------------------------------------------------------------
// Checks

/// How an answer compares with the reference (ours with RWR).
struct Agreement {
  double max_abs_diff = 0;         ///< over vertices finite in both
  double max_excess = -kInfinity;  ///< max (reference - other): > 0 where the reference is longer
  std::int64_t reachability_differs = 0;
  std::int64_t distance_differs = 0;  ///< bitwise
  std::int64_t label_differs = 0;
};

Agreement compare(std::span<const double> reference, std::span<const Index> reference_label,
                  std::span<const double> other, std::span<const Index> other_label) {
  Agreement a;
  for (std::size_t v = 0; v < reference.size(); ++v) {
    const bool finite_ref = std::isfinite(reference[v]), finite_other = std::isfinite(other[v]);
    if (finite_ref != finite_other) ++a.reachability_differs;
    if (finite_ref && finite_other) {
      a.max_abs_diff = std::max(a.max_abs_diff, std::abs(reference[v] - other[v]));
      a.max_excess = std::max(a.max_excess, reference[v] - other[v]);
    }
    if (std::memcmp(&reference[v], &other[v], sizeof(double)) != 0) ++a.distance_differs;
    if (reference_label[v] != other_label[v]) ++a.label_differs;
  }
  return a;
}

/// Bounding box diagonal of the vertices used by proper faces.
double bbox_diagonal(const TriangleMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity), hi = Eigen::Vector3d::Constant(-kInfinity);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (!is_proper_face(mesh, f)) continue;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = mesh.vertices.row(mesh.faces(f, c)).transpose();
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return (hi - lo).norm();
}

// ---------------------------------------------------------------------------
// The benchmark of one mesh

struct MethodResult {
  Method method{};
  ChildOutcome::Status status = ChildOutcome::Status::failed;
  std::string note;  ///< why skipped or failed, or what the checks found
  std::optional<MethodReport> report;
  std::int64_t child_max_rss_bytes = 0;
  std::optional<double> diff_over_diagonal;  ///< max |this - ours RWR| / diagonal
  bool identical_to_reference = false;
  bool check_failed = false;
};

struct MeshResult {
  std::string name;
  std::int64_t faces = 0;
  std::int64_t vertices = 0;
  std::size_t sites = 0;
  std::vector<MethodResult> methods;

  const MethodResult* find(Method m) const {
    for (const auto& r : methods) {
      if (r.method == m) return &r;
    }
    return nullptr;
  }
};

double median_cpu(const MethodResult* r) {
  return r && r->report ? median(r->report->cpu_seconds) : std::numeric_limits<double>::quiet_NaN();
}

/// Records in `r` how its answer compares with ours with RWR, and whether
/// that is acceptable for its method.
void judge(MethodResult& r, const Agreement& a, double diagonal, double tolerance) {
  r.diff_over_diagonal = a.max_abs_diff / diagonal;
  if (a.reachability_differs > 0) {
    r.check_failed = true;
    r.note = "CHECK FAILED: reachability differs at " + grouped(a.reachability_differs) + " vertices; ";
  }
  switch (r.method) {
    case Method::ours_no_rwr:
      r.identical_to_reference = a.distance_differs == 0 && a.label_differs == 0;
      if (r.identical_to_reference) {
        r.note += "distances and labels identical to RWR on";
      } else {
        r.check_failed = true;
        r.note += "CHECK FAILED: differs from RWR on at " + grouped(a.distance_differs) + " distances, " +
                  grouped(a.label_differs) + " labels";
      }
      break;
    case Method::cgal:
      if (*r.diff_over_diagonal > tolerance) {
        r.check_failed = true;
        r.note += "CHECK FAILED: max |diff| above --tolerance " + scientific(tolerance) + "; ";
      }
      r.note += "labels differ at " + grouped(a.label_differs) + " vertices";
      break;
    case Method::dijkstra:
      // An exact geodesic is never longer than a path along edges.
      if (a.max_excess > tolerance * diagonal) {
        r.check_failed = true;
        r.note +=
            "CHECK FAILED: ours exceeds the edge path by " + scientific(a.max_excess / diagonal) + " of the diagonal; ";
      }
      r.note += "upper bound; labels differ at " + grouped(a.label_differs) + " vertices";
      break;
    case Method::ours_rwr: break;
  }
}

MeshResult bench_mesh(const std::filesystem::path& path, const Options& options, std::int64_t memory_limit_bytes) {
  const auto load_start = Clock::now();
  io::LoadedMesh loaded = io::read_mesh(path);
  const TriangleMesh& mesh = loaded.mesh;
  MeshResult result;
  result.name = path.filename().string();
  result.faces = mesh.num_faces();
  result.vertices = mesh.num_vertices();
  result.sites = options.sites;
  const double diagonal = bbox_diagonal(mesh);
  std::cerr << "\n== " << result.name << ": " << grouped(result.vertices) << " vertices, " << grouped(result.faces)
            << " faces, bbox diagonal " << diagonal << ", read in " << fixed(seconds_since(load_start), 2) << " s\n";

  const std::vector<Index> site_vertices = random_vertex_sites(mesh, options.sites, options.seed);
  std::vector<SurfacePoint> sites;
  for (const Index v : site_vertices) sites.push_back(SurfacePoint::at_vertex(v));
  std::cerr << "   sites (vertex ids):";
  for (std::size_t i = 0; i < site_vertices.size(); ++i)
    std::cerr << (i % 15 == 0 ? "\n     " : " ") << site_vertices[i];
  std::cerr << '\n';

  // Ours stops itself at the time limit; SIGALRM, a minute later, is the
  // backstop for every method.
  constexpr unsigned kAlarmGraceSeconds = 60;
  const ChildLimits limits{memory_limit_bytes,
                           options.time_limit_seconds > 0 ? options.time_limit_seconds + kAlarmGraceSeconds : 0};
  std::optional<Deadline> deadline;  // set in each child as it starts
  // The answer of ours with RWR, which every other method is checked against.
  std::optional<std::pair<std::vector<double>, std::vector<Index>>> reference;
  for (const Method method : options.methods) {
    MethodResult& r = result.methods.emplace_back();
    r.method = method;
    if (method == Method::cgal && result.faces > options.max_faces_cgal) {
      r.note = "skipped: " + grouped(result.faces) + " faces > --max-faces-cgal " + grouped(options.max_faces_cgal);
      std::cerr << "   " << method_title(method) << ": " << r.note << '\n';
      continue;
    }
    std::function<Answer()> run;
    switch (method) {
      case Method::ours_rwr:
      case Method::ours_no_rwr: {
        const bool rwr = method == Method::ours_rwr;
        run = [&, rwr] { return run_ours(mesh, sites, rwr, options.window_limit_gib, deadline); };
        break;
      }
      case Method::cgal: run = [&] { return run_cgal(mesh, site_vertices); }; break;
      case Method::dijkstra: run = [&] { return run_dijkstra(mesh, site_vertices); }; break;
    }
    const int repeat = method == Method::cgal ? options.cgal_repeat.value_or(options.repeat) : options.repeat;
    std::cerr << "   " << method_title(method) << ": " << repeat << " run(s) ... " << std::flush;
    const ChildOutcome outcome = run_in_child(limits, [&] {
      if (options.time_limit_seconds > 0) {
        deadline =
            Deadline{Clock::now() + std::chrono::seconds(options.time_limit_seconds), options.time_limit_seconds};
      }
      return encode(measure(run, repeat));
    });
    r.status = outcome.status;
    r.child_max_rss_bytes = outcome.child_max_rss_bytes;
    if (outcome.status != ChildOutcome::Status::ok) {
      r.note = outcome.message;
      std::cerr << r.note << '\n';
      continue;
    }
    r.report = decode(outcome.payload);
    std::cerr << "median " << fixed(median(r.report->total_seconds), 3) << " s (CPU "
              << fixed(median(r.report->cpu_seconds), 3) << " s)\n";

    // Checks against the reference, ours with RWR. The answers are dropped
    // once checked, so that the parent (whose memory the next child inherits)
    // stays small.
    std::vector<double> distance = std::exchange(r.report->distance, {});
    std::vector<Index> label = std::exchange(r.report->label, {});
    if (method == Method::ours_rwr) {
      reference.emplace(std::move(distance), std::move(label));
      continue;
    }
    if (!reference) {
      r.note = "not checked (no reference: ours RWR did not run)";
      continue;
    }
    judge(r, compare(reference->first, reference->second, distance, label), diagonal, options.tolerance);
  }
  return result;
}

// ---------------------------------------------------------------------------
// Output

constexpr std::string_view kTable1Legend = R"(Every method runs in its own forked child process.
  time     wall-clock median over the runs of the whole call; CPU: process CPU time, median
  setup    (wall, of the median run) ours: GeodesicStats::setup_seconds; CGAL: Surface_mesh build;
           Dijkstra: edge graph
  solve    (wall, of the median run) ours: GeodesicStats::propagation_seconds; CGAL: add sources +
           build_sequence_tree + a distance query at every vertex; Dijkstra: the search
  peak RSS the child's VmHWM, reset through /proc/self/clear_refs before each run, max over the runs;
           it includes the mesh and all the child inherited from the parent, shown as 'RSS before';
           '>= x' for a child that did not finish: its lifetime peak (wait4's ru_maxrss)
  max|diff|/diag  max over vertices of |d - d(ours RWR)| / bounding box diagonal)";

void print_tables(std::span<const MeshResult> results, const Options& options) {
  using Align = TextTable::Align;
  TextTable table({{"mesh", Align::left},
                   {"faces"},
                   {"sites"},
                   {"method", Align::left},
                   {"runs"},
                   {"time s"},
                   {"CPU s"},
                   {"setup s"},
                   {"solve s"},
                   {"peak window MiB"},
                   {"windows stored"},
                   {"windows created"},
                   {"RSS before MiB"},
                   {"peak RSS MiB"},
                   {"max|diff|/diag"},
                   {"note", Align::left}});
  for (const MeshResult& mesh : results) {
    for (const MethodResult& m : mesh.methods) {
      const bool ours = m.method == Method::ours_rwr || m.method == Method::ours_no_rwr;
      std::vector<std::string> row{mesh.name, grouped(mesh.faces), std::to_string(mesh.sites),
                                   std::string(method_title(m.method))};
      if (m.report) {
        const MethodReport& r = *m.report;
        const std::size_t mid = median_index(r.total_seconds);
        row.push_back(std::to_string(r.total_seconds.size()));
        row.push_back(fixed(median(r.total_seconds), 3));
        row.push_back(fixed(median(r.cpu_seconds), 3));
        row.push_back(fixed(r.setup_seconds[mid], 3));
        row.push_back(fixed(r.solve_seconds[mid], 3));
        row.push_back(ours ? mebibytes(r.stats.peak_window_bytes) : "-");
        row.push_back(ours ? grouped(r.stats.windows_stored) : "-");
        row.push_back(ours ? grouped(r.stats.windows_created) : "-");
        row.push_back(mebibytes(r.rss_before_bytes));
        row.push_back(mebibytes(r.peak_rss_bytes) + (r.peak_reset ? "" : " (lifetime)"));
        row.push_back(m.method == Method::ours_rwr ? "reference"
                      : m.identical_to_reference   ? "0 (identical)"
                      : m.diff_over_diagonal       ? scientific(*m.diff_over_diagonal)
                                                   : "-");
      } else {
        row.insert(row.end(), {"0", "-", "-", "-", "-", "-", "-", "-", "-",
                               m.child_max_rss_bytes > 0 ? ">= " + mebibytes(m.child_max_rss_bytes) : "-", "-"});
      }
      row.push_back(m.note);
      table.add_row(std::move(row));
    }
  }
  std::cout << "\nTable 1. Exact multi-source geodesics, " << options.sites << " random vertex sites (seed "
            << options.seed << ").\n"
            << kTable1Legend << "\n\n";
  table.print(std::cout);

  TextTable ratios({{"mesh", Align::left},
                    {"faces"},
                    {"CGAL / ours-RWR CPU time"},
                    {"no-RWR / RWR windows stored"},
                    {"no-RWR / RWR peak window bytes"},
                    {"ours-RWR / Dijkstra CPU time"},
                    {"ours vs CGAL max|diff|/diag"},
                    {"RWR on = off"}});
  for (const MeshResult& mesh : results) {
    const MethodResult* rwr = mesh.find(Method::ours_rwr);
    const MethodResult* no_rwr = mesh.find(Method::ours_no_rwr);
    const MethodResult* cgal = mesh.find(Method::cgal);
    const MethodResult* dijkstra = mesh.find(Method::dijkstra);
    const bool both_ours = rwr && rwr->report && no_rwr && no_rwr->report;
    ratios.add_row({mesh.name, grouped(mesh.faces), ratio(median_cpu(cgal), median_cpu(rwr)),
                    both_ours ? ratio(static_cast<double>(no_rwr->report->stats.windows_stored),
                                      static_cast<double>(rwr->report->stats.windows_stored))
                              : "-",
                    both_ours ? ratio(static_cast<double>(no_rwr->report->stats.peak_window_bytes),
                                      static_cast<double>(rwr->report->stats.peak_window_bytes))
                              : "-",
                    ratio(median_cpu(rwr), median_cpu(dijkstra)),
                    cgal && cgal->diff_over_diagonal ? scientific(*cgal->diff_over_diagonal) : "-",
                    both_ours ? (no_rwr->identical_to_reference ? "identical" : "DIFFERENT") : "-"});
  }
  std::cout << "\nTable 2. Ratios of the medians in Table 1; times are compared by CPU time, which a loaded\n"
               "machine disturbs less than wall time.\n\n";
  ratios.print(std::cout);
}

// ---------------------------------------------------------------------------
// The Loop-subdivided inputs (bench/subdivided_inputs.hpp)

std::filesystem::path subdivision_input(const Options& options) {
  if (options.subdivided_input) return *options.subdivided_input;
  for (const auto& mesh : options.meshes) {
    if (mesh.filename() == "igea.ply") return mesh;
  }
  return std::filesystem::path("examples") / "data" / "bunny.ply";
}

std::filesystem::path subdivision_cache(const Options& options) {
  if (options.subdivided_cache) return *options.subdivided_cache;
  return std::filesystem::read_symlink("/proc/self/exe").parent_path() / "subdivided";
}

/// The subdivided mesh's path, made first if it is not in the cache. The
/// subdivision runs in a child process so that its memory (OpenMesh) never
/// inflates the parent, whose pages every measurement inherits.
std::filesystem::path subdivided_mesh(const Options& options, int levels) {
  const std::filesystem::path input = subdivision_input(options);
  const std::filesystem::path cache = subdivision_cache(options);
  const std::filesystem::path path = subdivided_path(input, levels, cache);
  if (std::filesystem::exists(path)) return path;
  std::cerr << "making " << path.string() << " (" << input.string() << ", " << levels << " Loop step(s)) ... "
            << std::flush;
  const auto start = Clock::now();
  const ChildOutcome outcome = run_in_child({}, [&] {
    ensure_subdivided(input, levels, cache);
    return std::vector<std::byte>{};
  });
  if (outcome.status != ChildOutcome::Status::ok) {
    throw Error("cannot make " + path.string() + ": " + outcome.message);
  }
  std::cerr << fixed(seconds_since(start), 1) << " s\n";
  return path;
}

int run_benchmark(const Options& options) {
  const std::int64_t available = memory_available_bytes().value_or(20 * kGiB);
  const std::int64_t memory_limit =
      options.memory_limit_gib ? static_cast<std::int64_t>(*options.memory_limit_gib * static_cast<double>(kGiB))
                               : std::min(20 * kGiB, available / 10 * 8);
  std::cout << "geodesic_bench: " << cpu_model() << ", " << ::sysconf(_SC_NPROCESSORS_ONLN) << " CPUs online, "
            << "load average " << load_average() << " at start, MemAvailable " << mebibytes(available) << " MiB\n"
            << "per-method child limits: address space " << mebibytes(memory_limit) << " MiB, time "
            << (options.time_limit_seconds > 0 ? std::to_string(options.time_limit_seconds) + " s" : "none")
            << "; ours: window memory limit " << fixed(options.window_limit_gib, 1) << " GiB\n";

  std::vector<std::filesystem::path> meshes = options.meshes;
  for (const int level : options.subdivided_levels) {
    meshes.push_back(subdivided_mesh(options, level));
  }
  std::vector<MeshResult> results;
  for (const auto& path : meshes) results.push_back(bench_mesh(path, options, memory_limit));

  print_tables(results, options);
  std::cout << "\nload average " << load_average() << " at the end\n";
  bool failed = false;
  for (const MeshResult& mesh : results) {
    for (const MethodResult& m : mesh.methods) {
      if (m.check_failed) {
        std::cout << "CHECK FAILED: " << mesh.name << ", " << method_title(m.method) << ": " << m.note << '\n';
        failed = true;
      }
    }
  }
  std::cout << (failed ? "some checks FAILED\n" : "all checks passed\n");
  return failed ? 1 : 0;
}

}  // namespace
}  // namespace geodual::bench

int main(int argc, char** argv) {
  return geodual::bench::run_main(
      "geodesic_bench", [&] { return geodual::bench::run_benchmark(geodual::bench::parse_options(argc, argv)); });
}
