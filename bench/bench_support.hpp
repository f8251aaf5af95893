#pragma once
// Small helpers shared by the benchmark programs in bench/: timers, medians,
// process memory (peak RSS through /proc), running one measurement in a
// forked child under a memory and time limit, byte streams for sending its
// results back, plain-text tables, reproducible random vertex sites, and the
// quality figures of one remesh as the remesh benchmarks report them.
//
// Linux only (it reads /proc and forks); header-only so that every bench/*.cpp
// stays one executable.

#include "geodual/mesh/error.hpp"
#include "geodual/mesh/face_area.hpp"
#include "geodual/mesh/triangle_mesh.hpp"
#include "geodual/pipeline/sites.hpp"
#include "geodual/quality/quality_stats.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <new>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_set>
#include <utility>
#include <vector>

#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <csignal>

namespace geodual::bench {

// ---------------------------------------------------------------------------
// main()

/// Runs a benchmark's body and turns its failures into one line on stderr
/// and an exit status: 2 for a bad command line, 1 for anything else.
inline int run_main(std::string_view program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return 1;
  }
}

// ---------------------------------------------------------------------------
// Time

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// CPU time (user + system) of the whole process, all threads, in seconds.
/// On a machine shared with other jobs this is the steadier measure of work
/// done; wall time also counts the time the process waited for a core.
inline double process_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The median of `values` (the mean of the two middle ones for an even count);
/// NaN for none.
inline double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return (lower + upper) / 2;
}

/// The position of the median run among `values`: for an even count, the
/// lower of the two middle runs. Used to report the split of that very run.
inline std::size_t median_index(std::span<const double> values) {
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  return order.empty() ? 0 : order[(order.size() - 1) / 2];
}

// ---------------------------------------------------------------------------
// Process memory (Linux /proc)

/// A "Key:   value kB" field of /proc/self/status in bytes, or nullopt.
inline std::optional<std::int64_t> proc_status_bytes(std::string_view key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() > key.size() && line.compare(0, key.size(), key) == 0 && line[key.size()] == ':') {
      std::istringstream fields(line.substr(key.size() + 1));
      std::int64_t kib = 0;
      if (fields >> kib) return kib * 1024;
    }
  }
  return std::nullopt;
}

/// Resident set size now.
inline std::optional<std::int64_t> current_rss_bytes() { return proc_status_bytes("VmRSS"); }

/// High-water mark of the resident set size (since start or the last reset).
inline std::optional<std::int64_t> peak_rss_bytes() { return proc_status_bytes("VmHWM"); }

/// Resets the RSS high-water mark to the current RSS (writes "5" to
/// /proc/self/clear_refs, Linux >= 4.0). Returns false where that failed.
inline bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

/// "MemAvailable" of /proc/meminfo in bytes, or nullopt.
inline std::optional<std::int64_t> memory_available_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::int64_t kib = 0;
  std::string unit;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

/// "a,b,c" -> {"a", "b", "c"} (a list option's items; views into text).
inline std::vector<std::string_view> split_commas(std::string_view text) {
  std::vector<std::string_view> parts;
  while (true) {
    const std::size_t comma = text.find(',');
    parts.push_back(text.substr(0, comma));
    if (comma == std::string_view::npos) return parts;
    text.remove_prefix(comma + 1);
  }
}

/// A finite number given to `option`, or a UsageError naming it.
inline double parse_number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(value)) throw std::invalid_argument(text);
    return value;
  } catch (const std::exception&) {
    throw UsageError(option + ": not a number: '" + text + "'");
  }
}

/// An integer in [low, high] given to `option`, or a UsageError naming it.
inline std::int64_t parse_integer(const std::string& option, const std::string& text, std::int64_t low,
                                  std::int64_t high) {
  const double value = parse_number(option, text);
  if (value != std::floor(value) || value < static_cast<double>(low) || value > static_cast<double>(high)) {
    throw UsageError(option + ": expected an integer in [" + std::to_string(low) + ", " + std::to_string(high) +
                     "], got '" + text + "'");
  }
  return static_cast<std::int64_t>(value);
}

/// "a,b,c", each an integer in [low, high] (parse_integer).
inline std::vector<std::int64_t> parse_integer_list(const std::string& option, const std::string& text,
                                                    std::int64_t low, std::int64_t high) {
  std::vector<std::int64_t> values;
  for (const std::string_view item : split_commas(text))
    values.push_back(parse_integer(option, std::string(item), low, high));
  return values;
}

/// Reads an option's value: the next word, or a UsageError naming the option.
using NextValue = std::function<std::string()>;

/// The benchmarks' command line: each word that starts with '-' goes to
/// `option(word, value)`, which returns false for a word it does not know (a
/// UsageError showing `usage`); --help and -h print `usage` and exit; the
/// other words are returned, in order (the meshes).
inline std::vector<std::filesystem::path> parse_command_line(
    int argc, char** argv, std::string_view usage,
    const std::function<bool(const std::string& word, const NextValue& value)>& option) {
  std::vector<std::filesystem::path> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const NextValue value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::cout << usage;
      std::exit(0);
    }
    if (arg.empty() || arg[0] != '-') {
      paths.emplace_back(arg);
    } else if (!option(arg, value)) {
      throw UsageError("unknown option " + arg + "\n" + std::string(usage));
    }
  }
  return paths;
}

/// The 1, 5 and 15 minute load averages as /proc/loadavg prints them.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

/// "model name" of the first processor in /proc/cpuinfo.
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(std::min(line.size(), colon + 2));
    }
  }
  return "unknown CPU";
}

// ---------------------------------------------------------------------------
// Byte streams (results sent from a child process back to its parent)

/// Appends trivially copyable values and arrays to a byte buffer.
class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::byte*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_span(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(values.size()));
    const auto* p = reinterpret_cast<const std::byte*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size_bytes());
  }
  void put_string(std::string_view text) { put_span(std::span<const char>(text.data(), text.size())); }

  const std::vector<std::byte>& bytes() const { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

/// Reads back what a ByteWriter wrote, in the same order; throws
/// std::runtime_error on a short buffer.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> get_vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto count = get<std::uint64_t>();
    if (count > bytes_.size() / sizeof(T)) throw std::runtime_error("ByteReader: array longer than the buffer");
    std::vector<T> values(static_cast<std::size_t>(count));
    const std::span<const std::byte> raw = take(values.size() * sizeof(T));
    if (!raw.empty()) std::memcpy(values.data(), raw.data(), raw.size());
    return values;
  }
  std::string get_string() {
    const std::vector<char> chars = get_vector<char>();
    return {chars.begin(), chars.end()};
  }

 private:
  std::span<const std::byte> take(std::size_t count) {
    if (count > bytes_.size() - position_) throw std::runtime_error("ByteReader: unexpected end of data");
    const std::span<const std::byte> part = bytes_.subspan(position_, count);
    position_ += count;
    return part;
  }

  std::span<const std::byte> bytes_;
  std::size_t position_ = 0;
};

/// A trivially copyable value as bytes, and back (a child's whole result).
template <class T>
std::vector<std::byte> to_bytes(const T& value) {
  ByteWriter out;
  out.put(value);
  return out.bytes();
}

template <class T>
T from_bytes(std::span<const std::byte> bytes) {
  ByteReader in(bytes);
  return in.get<T>();
}

// ---------------------------------------------------------------------------
// One measurement in a forked child process

struct ChildLimits {
  /// RLIMIT_AS of the child in bytes; 0 for none.
  std::int64_t address_space_bytes = 0;
  /// Wall-clock limit in seconds (SIGALRM); 0 for none.
  unsigned time_limit_seconds = 0;
};

struct ChildOutcome {
  enum class Status { ok, out_of_memory, time_limit, failed };
  Status status = Status::failed;
  /// Why it did not succeed, in words (empty when ok).
  std::string message;
  /// What the child's work function returned (ok only).
  std::vector<std::byte> payload;
  /// The child's own peak RSS as the kernel kept it (wait4's ru_maxrss): also
  /// known when the child was killed. It includes the memory the child
  /// inherited from the parent.
  std::int64_t child_max_rss_bytes = 0;
};

namespace detail {

inline bool write_all(int fd, std::span<const std::byte> data) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data = data.subspan(static_cast<std::size_t>(n));
  }
  return true;
}

/// Child to parent message: one status byte, then the payload or a message.
enum class ChildMessage : std::uint8_t { ok = 0, out_of_memory = 1, failed = 2 };

}  // namespace detail

/// Runs `work` in a forked child process under `limits` and returns what it
/// returned (its bytes), or why it did not: std::bad_alloc (or being killed
/// by SIGKILL, most likely the kernel's OOM killer) is reported as
/// out_of_memory, SIGALRM as time_limit, anything else as failed with the
/// exception's message or the signal. The parent's memory is not touched by
/// the child's allocations, so every measurement starts from the same state.
/// Flushes stdout and stderr first (the child must not flush them twice).
inline ChildOutcome run_in_child(const ChildLimits& limits, const std::function<std::vector<std::byte>()>& work) {
  std::fflush(stdout);
  std::fflush(stderr);
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // The child: never returns into the caller's code.
    ::close(fds[0]);
    if (limits.address_space_bytes > 0) {
      const auto bytes = static_cast<rlim_t>(limits.address_space_bytes);
      const rlimit limit{bytes, bytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    if (limits.time_limit_seconds > 0) ::alarm(limits.time_limit_seconds);
    std::vector<std::byte> message;
    auto fail = [&](detail::ChildMessage kind, std::string_view text) {
      message.assign(1, static_cast<std::byte>(kind));
      const auto* p = reinterpret_cast<const std::byte*>(text.data());
      message.insert(message.end(), p, p + text.size());
    };
    try {
      std::vector<std::byte> payload = work();
      message.reserve(payload.size() + 1);
      message.push_back(static_cast<std::byte>(detail::ChildMessage::ok));
      message.insert(message.end(), payload.begin(), payload.end());
    } catch (const std::bad_alloc&) {
      fail(detail::ChildMessage::out_of_memory, "std::bad_alloc");
    } catch (const std::exception& e) {
      fail(detail::ChildMessage::failed, e.what());
    } catch (...) {
      fail(detail::ChildMessage::failed, "unknown exception");
    }
    const bool written = detail::write_all(fds[1], message);
    ::close(fds[1]);
    ::_exit(written ? 0 : 1);
  }

  // The parent: read everything, then reap the child.
  ::close(fds[1]);
  std::vector<std::byte> received;
  std::byte buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    received.insert(received.end(), buffer, buffer + n);
  }
  ::close(fds[0]);
  int wait_status = 0;
  rusage usage{};
  while (::wait4(pid, &wait_status, 0, &usage) < 0 && errno == EINTR) {
  }

  ChildOutcome outcome;
  outcome.child_max_rss_bytes = static_cast<std::int64_t>(usage.ru_maxrss) * 1024;
  if (WIFSIGNALED(wait_status)) {
    const int signal = WTERMSIG(wait_status);
    if (signal == SIGALRM) {
      outcome.status = ChildOutcome::Status::time_limit;
      outcome.message = "time limit of " + std::to_string(limits.time_limit_seconds) + " s";
    } else if (signal == SIGKILL) {
      outcome.status = ChildOutcome::Status::out_of_memory;
      outcome.message = "killed by SIGKILL (most likely the kernel's OOM killer)";
    } else {
      outcome.status = ChildOutcome::Status::failed;
      outcome.message = std::string("killed by signal ") + std::to_string(signal) + " (" + strsignal(signal) + ")";
    }
    return outcome;
  }
  if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0 || received.empty()) {
    outcome.status = ChildOutcome::Status::failed;
    outcome.message = "child exited without a result";
    return outcome;
  }
  const auto kind = static_cast<detail::ChildMessage>(received.front());
  const std::span<const std::byte> rest = std::span<const std::byte>(received).subspan(1);
  if (kind == detail::ChildMessage::ok) {
    outcome.status = ChildOutcome::Status::ok;
    outcome.payload.assign(rest.begin(), rest.end());
    return outcome;
  }
  outcome.status =
      kind == detail::ChildMessage::out_of_memory ? ChildOutcome::Status::out_of_memory : ChildOutcome::Status::failed;
  outcome.message.assign(reinterpret_cast<const char*>(rest.data()), rest.size());
  if (outcome.status == ChildOutcome::Status::out_of_memory) {
    outcome.message = "out of memory (" + outcome.message + ")";
  }
  return outcome;
}

// ---------------------------------------------------------------------------
// Formatting and tables

/// `value` with `digits` digits after the point.
inline std::string fixed(double value, int digits) {
  if (std::isnan(value)) return "-";
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

/// `value` in scientific notation with `digits` significant digits after the point.
inline std::string scientific(double value, int digits = 1) {
  if (std::isnan(value)) return "-";
  std::ostringstream out;
  out << std::scientific << std::setprecision(digits) << value;
  return out.str();
}

/// An integer with thousands separators: 1234567 -> "1,234,567".
inline std::string grouped(std::int64_t value) {
  const std::string digits = std::to_string(value < 0 ? -value : value);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return value < 0 ? "-" + out : out;
}

/// Bytes in MiB with one decimal.
inline std::string mebibytes(std::int64_t bytes) { return fixed(static_cast<double>(bytes) / (1 << 20), 1); }

/// A ratio a/b as "12.3x" (two significant decimals below 10), "-" when undefined.
inline std::string ratio(double numerator, double denominator) {
  if (!(denominator > 0) || std::isnan(numerator)) return "-";
  const double r = numerator / denominator;
  return fixed(r, r < 10 ? 2 : 1) + "x";
}

/// A plain-text table printed as Markdown (pipes, a header rule, columns
/// padded to a common width), so the same text reads well in a terminal and
/// pastes into a README or an issue.
class TextTable {
 public:
  enum class Align { left, right };

  struct Column {
    std::string title;
    Align align = Align::right;
  };

  explicit TextTable(std::vector<Column> columns) : columns_(std::move(columns)) {}

  void add_row(std::vector<std::string> cells) {
    cells.resize(columns_.size());
    rows_.push_back(std::move(cells));
  }

  void print(std::ostream& out) const {
    std::vector<std::size_t> width(columns_.size(), 3);
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      width[c] = std::max(width[c], columns_[c].title.size());
      for (const auto& row : rows_) width[c] = std::max(width[c], row[c].size());
    }
    auto print_row = [&](const std::vector<std::string>& cells) {
      out << '|';
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        const std::string pad(width[c] - cells[c].size(), ' ');
        out << ' ' << (columns_[c].align == Align::right ? pad + cells[c] : cells[c] + pad) << " |";
      }
      out << '\n';
    };
    std::vector<std::string> titles;
    for (const auto& column : columns_) titles.push_back(column.title);
    print_row(titles);
    out << '|';
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      out << ' ' << std::string(width[c] - 1, '-') << (columns_[c].align == Align::right ? ':' : '-') << " |";
    }
    out << '\n';
    for (const auto& row : rows_) print_row(row);
  }

 private:
  std::vector<Column> columns_;
  std::vector<std::vector<std::string>> rows_;
};

// ---------------------------------------------------------------------------
// Reproducible random sites

/// True for a face whose three corners are distinct (faces with a repeated
/// vertex take no part in any surface computation).
inline bool is_proper_face(const TriangleMesh& mesh, Index f) { return !has_repeated_corner(mesh, f); }

/// The vertices of geodual::random_vertex_sites (the CLI's --sites), as indices.
inline std::vector<Index> random_vertex_sites(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
  std::vector<Index> vertices;
  for (const SurfacePoint& site : geodual::random_vertex_sites(mesh, static_cast<std::int64_t>(count), seed)) {
    vertices.push_back(site.element);
  }
  return vertices;
}

// ---------------------------------------------------------------------------
// The figures of one remesh (trivially copyable: sent back from a child)

/// One mesh's figures of shared/DESIGN.md; the distances are to the input
/// (NaN for the input itself).
struct QualityFigures {
  std::int64_t vertices = 0, faces = 0, euler_characteristic = 0, boundary_loops = 0, nonmanifold_edges = 0;
  double q_min = 0, q_avg = 0, theta_min_deg = 0, theta_min_avg_deg = 0, pct_angles_lt30 = 0, p30 = 0;
  double pct_valence6 = std::numeric_limits<double>::quiet_NaN();
  double hausdorff_pct = std::numeric_limits<double>::quiet_NaN();
  double rms_pct = std::numeric_limits<double>::quiet_NaN();
};

inline QualityFigures figures_of(const quality::TriangleQuality& q) {
  QualityFigures f;
  f.vertices = q.vertices;
  f.faces = q.faces;
  f.euler_characteristic = q.euler_characteristic;
  f.boundary_loops = q.boundary_loops;
  f.nonmanifold_edges = q.nonmanifold_edges;
  f.q_min = q.q_min;
  f.q_avg = q.q_avg;
  f.theta_min_deg = q.theta_min_deg;
  f.theta_min_avg_deg = q.theta_min_avg_deg;
  f.pct_angles_lt30 = q.pct_angles_lt30;
  f.p30 = q.p30;
  if (q.pct_valence6) f.pct_valence6 = *q.pct_valence6;
  return f;
}

/// What one remesh run reports: its vertex count and cost, and (when
/// measured) the quality of its output and of the input.
struct RemeshRun {
  std::int64_t vertices = 0;  ///< of the output
  double seconds = 0, cpu_seconds = 0;
  std::int64_t peak_rss = 0;
  std::int64_t sites_added = 0;
  int lloyd_iterations = 0;
  int warm_start_iterations = 0;
  int error_rounds = 0;          ///< remeshes made under an error bound (0: none)
  bool error_bound_met = false;  ///< and whether the last met it
  double bound_checked_pct = 0;  ///< the Hausdorff distance the pipeline's own statistics gave it
  bool has_figures = false;
  QualityFigures output;
  QualityFigures input;  ///< the reference side of compare_meshes, distances NaN
};

/// Fills run.output and run.input from quality::compare_meshes(input, output)
/// with `samples` points per side.
inline void add_figures(RemeshRun& run, const TriangleMesh& input, const TriangleMesh& output, std::int64_t samples) {
  quality::QualityOptions quality;
  quality.samples_per_side = samples;
  const quality::QualityReport report = quality::compare_meshes(input, output, quality);
  run.output = figures_of(report.candidate);
  run.output.hausdorff_pct = report.hausdorff_pct;
  run.output.rms_pct = report.rms_pct;
  run.input = figures_of(report.reference);
  run.has_figures = true;
}

}  // namespace geodual::bench
