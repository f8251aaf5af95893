// Outputs appear whole or not at all: a write that fails midway leaves
// neither the file nor its temporary, and an existing file stays as it was.
// The input is never chosen as the output, however the path is spelled.

#include "io_test_files.hpp"

#include "geodual/io/atomic_file.hpp"
#include "geodual/io/write_mesh.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace geodual::test {
namespace {

using io::write_file_atomically;

/// Writes a megabyte, then fails the way a writer can: with a geodual::Error.
void write_then_fail(std::ostream& out) {
  const std::string block(1 << 20, 'x');
  out.write(block.data(), static_cast<std::streamsize>(block.size()));
  throw Error("failed midway");
}

TEST(AtomicWrite, FailureMidwayLeavesNoFileAndNoTemporary) {
  TempDir dir;
  EXPECT_THROW(write_file_atomically(dir / "out.ply", write_then_fail), Error);
  EXPECT_TRUE(dir.entries().empty());
  // Any exception type, not only geodual::Error.
  EXPECT_THROW(write_file_atomically(dir / "out.ply",
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw std::runtime_error("boom");
                                     }),
               std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicWrite, FailureLeavesAnExistingOutputUntouched) {
  TempDir dir;
  write_file(dir / "out.obj", "the previous result\n");
  EXPECT_THROW(write_file_atomically(dir / "out.obj", write_then_fail), Error);
  EXPECT_EQ(read_file(dir / "out.obj"), "the previous result\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.obj"});
}

TEST(AtomicWrite, SuccessReplacesTheFileAndLeavesNoTemporary) {
  TempDir dir;
  write_file(dir / "out.obj", "old");
  write_file_atomically(dir / "out.obj", [](std::ostream& out) { out << "new content"; });
  EXPECT_EQ(read_file(dir / "out.obj"), "new content");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.obj"});
}

TEST(AtomicWrite, MeshWritersUseIt) {
  TempDir dir;
  TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;
  write_file(dir / "keep.ply", "previous");
  // A property of the wrong length makes write_ply fail before it writes: the old file stays.
  VertexAttributes bad;
  bad.scalars.push_back({"bad", ValueType::float32, std::vector<double>(2)});
  EXPECT_THROW(io::write_ply(dir / "keep.ply", mesh, bad), Error);
  EXPECT_EQ(read_file(dir / "keep.ply"), "previous");
  // A missing output folder: an error naming the path, nothing created.
  const std::string message = error_message([&] { io::write_obj(dir / "missing" / "out.obj", mesh); });
  EXPECT_TRUE(message.starts_with((dir / "missing" / "out.obj").string() + ": ")) << message;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.ply"});
  io::write_ply(dir / "keep.ply", mesh);
  EXPECT_TRUE(read_file(dir / "keep.ply").starts_with("ply\n"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.ply"});
}

TEST(RefuseToOverwriteInputs, SameFileUnderAnySpelling) {
  TempDir dir;
  fs::create_directory(dir / "x");
  const fs::path input = write_file(dir / "x" / "scan.ply", "data");
  const std::string message = error_message([&] { io::refuse_to_overwrite_inputs(input, {input}); });
  EXPECT_EQ(message, input.string() + ": refusing to overwrite the input file; choose another output path");
  const fs::path respelled = dir.path() / "." / "x" / ".." / "x" / "scan.ply";
  EXPECT_THROW(io::refuse_to_overwrite_inputs(respelled, {input}), Error);
  EXPECT_THROW(io::refuse_to_overwrite_inputs(input, {respelled}), Error);
  fs::create_symlink(input, dir / "link.ply");
  EXPECT_THROW(io::refuse_to_overwrite_inputs(dir / "link.ply", {input}), Error);
  // Relative to the current directory, as users type it.
  const fs::path relative = fs::relative(input, fs::current_path());
  EXPECT_THROW(io::refuse_to_overwrite_inputs(relative, {input}), Error);
}

TEST(RefuseToOverwriteInputs, OtherFilesAreFine) {
  TempDir dir;
  const fs::path input = write_file(dir / "scan.ply", "data");
  const fs::path other = write_file(dir / "other.ply", "data");
  EXPECT_NO_THROW(io::refuse_to_overwrite_inputs(other, {input}));
  EXPECT_NO_THROW(io::refuse_to_overwrite_inputs(dir / "new.glb", {input, other}));
  EXPECT_THROW(io::refuse_to_overwrite_inputs(other, {input, other}), Error);
  EXPECT_EQ(read_file(input), "data");
}

}  // namespace
}  // namespace geodual::test
