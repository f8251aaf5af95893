// Builds the fuzzers' seed corpus: every mesh given on the command line is cut
// down to its first few faces and written in every variant the readers know,
// into <folder>/ply, <folder>/obj, <folder>/off and <folder>/stl, next to a
// few hand-written files for the rarer forms.
//
//   make_seed_corpus fuzz-corpus tests/data/woody.ply ...

#include "geodual/io/read_mesh.hpp"
#include "geodual/io/write_mesh.hpp"
#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace {

namespace fs = std::filesystem;
using geodual::Index;
using geodual::TriangleMesh;

constexpr Eigen::Index max_faces = 64;  // small seeds keep the fuzzers fast

/// The first `faces` triangles and the vertices they use, renumbered in order of use.
TriangleMesh first_faces(const TriangleMesh& mesh, Eigen::Index faces) {
  TriangleMesh part;
  part.faces.resize(std::min(faces, mesh.faces.rows()), 3);
  std::unordered_map<Index, Index> renumbered;
  std::vector<Index> used;
  for (Eigen::Index f = 0; f < part.faces.rows(); ++f) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      const Index old = mesh.faces(f, c);
      const auto [at, added] = renumbered.emplace(old, static_cast<Index>(used.size()));
      if (added) {
        used.push_back(old);
      }
      part.faces(f, c) = at->second;
    }
  }
  part.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t v = 0; v < used.size(); ++v) {
    part.vertices.row(static_cast<Eigen::Index>(v)) = mesh.vertices.row(used[v]);
  }
  return part;
}

std::string number(double value) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

void save(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    throw geodual::Error(path.string() + ": cannot write");
  }
}

template <class T>
void append(std::string& out, T value, std::endian order) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (order != std::endian::native) {
    std::reverse(bytes, bytes + sizeof(T));
  }
  out.append(bytes, sizeof(T));
}

/// ASCII PLY with a colour before x and an extra element after the faces.
std::string ascii_ply(const TriangleMesh& mesh) {
  std::string out = "ply\nformat ascii 1.0\ncomment seed\nelement vertex " + std::to_string(mesh.vertices.rows()) +
                    "\nproperty uchar red\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(mesh.faces.rows()) +
                    "\nproperty list uchar int vertex_indices\nelement edge 1\nproperty list int int ends\n"
                    "end_header\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out += "7 " + number(static_cast<float>(mesh.vertices(v, 0))) + " " +
           number(static_cast<float>(mesh.vertices(v, 1))) + " " + number(static_cast<float>(mesh.vertices(v, 2))) +
           "\n";
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    out += "3 " + std::to_string(mesh.faces(f, 0)) + " " + std::to_string(mesh.faces(f, 1)) + " " +
           std::to_string(mesh.faces(f, 2)) + "\n";
  }
  return out + "2 0 1\n";
}

/// Binary PLY in `order`, float32 coordinates, `list ushort uint` indices and
/// an extra face list, so the general (not the fast) decoding path runs.
std::string binary_ply(const TriangleMesh& mesh, std::endian order) {
  std::string out = std::string("ply\nformat ") +
                    (order == std::endian::little ? "binary_little_endian" : "binary_big_endian") +
                    " 1.0\nelement vertex " + std::to_string(mesh.vertices.rows()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty short label\nelement face " +
                    std::to_string(mesh.faces.rows()) +
                    "\nproperty list ushort uint vertex_indices\nproperty list uchar float texcoord\nend_header\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      append(out, static_cast<float>(mesh.vertices(v, c)), order);
    }
    append(out, static_cast<std::int16_t>(v), order);
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    append(out, std::uint16_t{3}, order);
    for (Eigen::Index c = 0; c < 3; ++c) {
      append(out, static_cast<std::uint32_t>(mesh.faces(f, c)), order);
    }
    append(out, std::uint8_t{2}, order);
    append(out, 0.5f, order);
    append(out, 0.25f, order);
  }
  return out;
}

/// OBJ with texture coordinates, normals, groups and every corner form.
std::string obj_with_forms(const TriangleMesh& mesh) {
  std::string out = "# seed\nmtllib seed.mtl\no seed\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out += "v " + number(mesh.vertices(v, 0)) + " " + number(mesh.vertices(v, 1)) + " " + number(mesh.vertices(v, 2)) +
           "\nvt 0.5 0.5\nvn 0 0 1\n";
  }
  out += "g part\nusemtl skin\ns 1\n";
  const auto rows = static_cast<Index>(mesh.vertices.rows());
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Index a = mesh.faces(f, 0) + 1;
    const Index b = mesh.faces(f, 1) + 1;
    const Index c = mesh.faces(f, 2) - rows;  // relative
    switch (f % 4) {
      case 0: out += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\r\n"; break;
      case 1: out += "f " + std::to_string(a) + "/1 " + std::to_string(b) + "/2 " + std::to_string(c) + "/3\n"; break;
      case 2:
        out += "f " + std::to_string(a) + "//1 " + std::to_string(b) + "//1 " + std::to_string(c) + "//1\n";
        break;
      default: out += "f " + std::to_string(a) + "/1/1 " + std::to_string(b) + "/2/1 " + std::to_string(c) + "/3/1\n";
    }
  }
  return out;
}

std::string off(const TriangleMesh& mesh, bool coloured) {
  std::string out = std::string(coloured ? "COFF" : "OFF") + "\n# seed\n" + std::to_string(mesh.vertices.rows()) + " " +
                    std::to_string(mesh.faces.rows()) + " 0\n";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out += number(mesh.vertices(v, 0)) + " " + number(mesh.vertices(v, 1)) + " " + number(mesh.vertices(v, 2)) +
           (coloured ? " 255 128 0 255\n" : "\n");
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    out += "3 " + std::to_string(mesh.faces(f, 0)) + " " + std::to_string(mesh.faces(f, 1)) + " " +
           std::to_string(mesh.faces(f, 2)) + (coloured ? " 0.5 0.5 0.5\n" : "\n");
  }
  return out;
}

std::string ascii_stl(const TriangleMesh& mesh) {
  std::string out = "solid seed\n";
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    out += "  facet normal 0 0 1\n    outer loop\n";
    for (Eigen::Index c = 0; c < 3; ++c) {
      const auto p = mesh.vertices.row(mesh.faces(f, c));
      out += "      vertex " + number(p(0)) + " " + number(p(1)) + " " + number(p(2)) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid seed\n";
}

std::string binary_stl(const TriangleMesh& mesh, std::string_view comment) {
  std::string out(comment);
  out.resize(80, ' ');
  append(out, static_cast<std::uint32_t>(mesh.faces.rows()), std::endian::little);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    for (const float n : {0.f, 0.f, 1.f}) {
      append(out, n, std::endian::little);
    }
    for (Eigen::Index c = 0; c < 3; ++c) {
      for (Eigen::Index axis = 0; axis < 3; ++axis) {
        append(out, static_cast<float>(mesh.vertices(mesh.faces(f, c), axis)), std::endian::little);
      }
    }
    append(out, std::uint16_t{0}, std::endian::little);
  }
  return out;
}

/// Small hand-written files for forms the converted meshes do not show.
void write_handmade(const fs::path& folder) {
  save(folder / "ply" / "polygons.ply",
       "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
       "element face 2\nproperty list uchar int vertex_index\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n5 5 5\n"
       "4 0 1 2 3\n3 2 1 0\n");
  save(folder / "obj" / "polygons.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -1 -2 -3\nl 1 2\n");
  save(folder / "off" / "polygons.off", "OFF 5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n5 5 5\n4 0 1 2 3\n3 4 1 0 1 0 0\n");
  save(folder / "off" / "nokeyword.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
}

void write_variants(const TriangleMesh& mesh, const std::string& stem, const fs::path& folder) {
  const fs::path ply = folder / "ply";
  geodual::VertexAttributes quality;
  quality.scalars.push_back({"quality", geodual::ValueType::float32,
                             std::vector<double>(static_cast<std::size_t>(mesh.vertices.rows()), 0.5)});
  geodual::io::write_ply(ply / (stem + "_le_double.ply"), mesh, quality);
  save(ply / (stem + "_ascii.ply"), ascii_ply(mesh));
  save(ply / (stem + "_le_float.ply"), binary_ply(mesh, std::endian::little));
  save(ply / (stem + "_be_float.ply"), binary_ply(mesh, std::endian::big));
  geodual::io::write_obj(folder / "obj" / (stem + ".obj"), mesh);
  save(folder / "obj" / (stem + "_forms.obj"), obj_with_forms(mesh));
  save(folder / "off" / (stem + ".off"), off(mesh, false));
  save(folder / "off" / (stem + "_colour.off"), off(mesh, true));
  save(folder / "stl" / (stem + "_ascii.stl"), ascii_stl(mesh));
  save(folder / "stl" / (stem + "_binary.stl"), binary_stl(mesh, "binary seed"));
  save(folder / "stl" / (stem + "_solid_binary.stl"), binary_stl(mesh, "solid but binary"));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: make_seed_corpus <folder> <mesh>...\n";
    return 2;
  }
  try {
    const fs::path folder = argv[1];
    for (const char* format : {"ply", "obj", "off", "stl"}) {
      fs::create_directories(folder / format);
    }
    write_handmade(folder);
    for (int i = 2; i < argc; ++i) {
      const fs::path input = argv[i];
      const TriangleMesh part = first_faces(geodual::io::read_mesh(input).mesh, max_faces);
      write_variants(part, input.stem().string(), folder);
    }
    std::cout << "seed corpus written to " << folder.string() << "/{ply,obj,off,stl}\n";
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "make_seed_corpus: " << error.what() << "\n";
    return 1;
  }
}
