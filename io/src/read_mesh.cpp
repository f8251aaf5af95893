// read_mesh: loads a file into memory with one read, hands it to the reader
// its extension names, then applies the checks every format shares.

#include "geodual/io/read_mesh.hpp"

#include "file_error.hpp"
#include "format_readers.hpp"
#include "mesh_checks.hpp"

#include <cerrno>
#include <cstddef>
#include <memory>
#include <new>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace geodual::io {
namespace {

namespace fs = std::filesystem;

/// Closes a POSIX file descriptor on scope exit.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) {
      ::close(fd_);
    }
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

/// A whole file's bytes, read without zero-filling the buffer first.
struct FileBytes {
  std::unique_ptr<std::byte[]> bytes;
  std::size_t size = 0;

  std::span<const std::byte> span() const { return {bytes.get(), size}; }
};

std::string errno_text(int error) { return std::generic_category().message(error); }

FileBytes read_whole_file(const fs::path& path) {
  // O_NONBLOCK: opening a FIFO must not hang; it is refused below as not a regular file.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  if (file.get() < 0) {
    const int error = errno;
    if (error == ENOENT) {
      detail::throw_file_error(path, "no such file");
    }
    detail::throw_file_error(path, "cannot open the file: ", errno_text(error));
  }
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) {
    detail::throw_file_error(path, "cannot query the file: ", errno_text(errno));
  }
  if (S_ISDIR(status.st_mode)) {
    detail::throw_file_error(path, "is a directory, expected a mesh file");
  }
  if (!S_ISREG(status.st_mode)) {
    detail::throw_file_error(path, "is not a regular file");
  }
  FileBytes contents;
  contents.size = static_cast<std::size_t>(status.st_size);
  try {
    contents.bytes = std::make_unique_for_overwrite<std::byte[]>(contents.size);
  } catch (const std::bad_alloc&) {
    detail::throw_file_error(path, "not enough memory to load the file (", contents.size, " bytes)");
  }
  std::size_t done = 0;
  while (done < contents.size) {  // one read, unless the kernel hands out less at a time
    const ::ssize_t got = ::read(file.get(), contents.bytes.get() + done, contents.size - done);
    if (got < 0 && errno == EINTR) {
      continue;
    }
    if (got < 0) {
      detail::throw_file_error(path, "read failed: ", errno_text(errno));
    }
    if (got == 0) {
      detail::throw_file_error(path, "the file shrank while being read (", done, " of ", contents.size, " bytes)");
    }
    done += static_cast<std::size_t>(got);
  }
  return contents;
}

LoadedMesh read_by_format(std::span<const std::byte> data, MeshFormat format, const fs::path& name) {
  switch (format) {
    case MeshFormat::ply: return detail::read_ply(data, name);
    case MeshFormat::obj: return detail::read_obj(data, name);
    case MeshFormat::off: return detail::read_off(data, name);
    case MeshFormat::stl: return detail::read_stl(data, name);
    case MeshFormat::gltf: return detail::read_gltf(data, false, name);
    case MeshFormat::glb: return detail::read_gltf(data, true, name);
  }
  detail::throw_file_error(name, "unknown mesh format");
}

}  // namespace

LoadedMesh read_mesh(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    // Say so before the extension check: a folder's "extension" means nothing.
    detail::throw_file_error(path, "is a directory, expected a mesh file");
  }
  const MeshFormat format = format_from_extension(path);
  const FileBytes contents = read_whole_file(path);
  return read_mesh_from_memory(contents.span(), format, path);
}

LoadedMesh read_mesh_from_memory(std::span<const std::byte> data, MeshFormat format, const fs::path& name) {
  if (data.empty()) {
    detail::throw_file_error(name, "the file is empty");
  }
  LoadedMesh loaded;
  try {
    loaded = read_by_format(data, format, name);
  } catch (const std::bad_alloc&) {
    detail::throw_file_error(name, "not enough memory to hold the mesh");
  }
  // info.format is the reader's: the glTF reader goes by content (a .glb
  // that holds JSON says gltf).
  loaded.info.file_bytes = data.size();

  const TriangleMesh& mesh = loaded.mesh;
  detail::check_counts_fit_index(name, mesh);
  if (format == MeshFormat::gltf || format == MeshFormat::glb) {
    // The PLY, OBJ, OFF and STL readers check every index as they decode it,
    // naming the face and line; glTF's is checked here once more.
    detail::check_face_indices(name, mesh);
  }
  if (mesh.faces.rows() == 0) {
    detail::throw_file_error(name, "the file holds no triangles (", mesh.vertices.rows(),
                             " vertices, 0 faces); geodual needs a triangle mesh");
  }
  detail::check_finite_coordinates(name, mesh);
  return loaded;
}

}  // namespace geodual::io
