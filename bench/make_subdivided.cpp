// make_subdivided INPUT LEVELS OUTPUT.ply
//
// Writes INPUT Loop-subdivided LEVELS times as binary PLY (float64), e.g.
//   build/bench/make_subdivided path/to/igea.ply 1 igea_1M.ply
// gives the 1,074,744-face igea, 2 levels the 4,298,976-face one.

#include "subdivided_inputs.hpp"

#include "bench_support.hpp"

#include <charconv>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string_view>

namespace {

constexpr int max_levels = 4;  // 4^4 = 256 times the faces: beyond that, memory runs out

int parse_levels(std::string_view text) {
  int levels = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), levels);
  if (error != std::errc() || end != text.data() + text.size() || levels < 0 || levels > max_levels) {
    throw geodual::UsageError("LEVELS must be an integer from 0 to " + std::to_string(max_levels) + ", not '" +
                              std::string(text) + "'");
  }
  return levels;
}

int run(int argc, char** argv) {
  if (argc != 4) {
    throw geodual::UsageError("usage: make_subdivided INPUT LEVELS OUTPUT.ply");
  }
  const std::filesystem::path input = argv[1];
  const int levels = parse_levels(argv[2]);
  const std::filesystem::path output = argv[3];

  const auto start = geodual::bench::Clock::now();
  const geodual::TriangleMesh mesh = geodual::bench::write_subdivided(input, levels, output);
  std::printf("%s: %d Loop step(s): %d vertices, %d faces -> %s (%ju bytes, %.2f s)\n", input.string().c_str(), levels,
              mesh.num_vertices(), mesh.num_faces(), output.string().c_str(), std::filesystem::file_size(output),
              geodual::bench::seconds_since(start));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const geodual::UsageError& error) {
    std::cerr << "make_subdivided: error: " << error.what() << '\n';
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "make_subdivided: error: out of memory\n";
  } catch (const std::exception& error) {
    std::cerr << "make_subdivided: error: " << error.what() << '\n';
  }
  return 1;
}
