#include "geodual/io/atomic_file.hpp"

#include "geodual/mesh/error.hpp"

#include <algorithm>
#include <atomic>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace geodual::io {
namespace fs = std::filesystem;

namespace {

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (!fs::exists(a, ec) || !fs::exists(b, ec)) {
    // Not both on disk: compare the normalised absolute spellings.
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
  }
  return fs::equivalent(a, b, ec);
}

fs::path temporary_sibling(const fs::path& output) {
  static std::atomic<unsigned> counter{0};
  fs::path tmp = output;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}

}  // namespace

void refuse_to_overwrite_inputs(const fs::path& output, std::initializer_list<fs::path> inputs) {
  for (const fs::path& input : inputs) {
    if (same_file(output, input)) {
      throw Error(output.string() + ": refusing to overwrite the input file; choose another output path");
    }
  }
}

void write_file_atomically(const fs::path& output, const std::function<void(std::ostream&)>& write) {
  std::error_code ec;
  if (fs::is_directory(output, ec)) {
    throw Error(output.string() + ": is a directory, expected an output file path");
  }
  const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) {
    throw Error(output.string() + ": output folder '" + parent.string() + "' does not exist");
  }
  const fs::path tmp = temporary_sibling(output);
  try {
    {
      std::ofstream stream(tmp, std::ios::binary | std::ios::trunc);
      if (!stream) {
        throw Error(output.string() + ": cannot create a file in '" + parent.string() +
                    "' (permission denied or read-only?)");
      }
      write(stream);
      stream.flush();
      if (!stream) {
        throw Error(output.string() + ": write failed (disk full?)");
      }
    }
    fs::rename(tmp, output, ec);
    if (ec) {
      throw Error(output.string() + ": cannot replace the file: " + ec.message());
    }
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

std::string lowercase_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; });
  return extension;
}

void require_output_path(const fs::path& path, std::initializer_list<std::string_view> extensions,
                         std::string_view what) {
  const std::string extension = lowercase_extension(path);
  if (!path.has_filename() || std::find(extensions.begin(), extensions.end(), extension) == extensions.end()) {
    std::string expected;
    for (const std::string_view e : extensions) expected += (expected.empty() ? "" : ", ") + std::string(e);
    throw Error(path.string() + ": " + std::string(what) + " is written as " + expected);
  }
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw Error(path.string() + ": folder " + folder.string() + " does not exist");
  if (fs::is_directory(path, error)) throw Error(path.string() + ": is a directory");
  // The folder must take a new file now, not only after the work is done.
  const fs::path probe = temporary_sibling(path);
  if (!std::ofstream(probe, std::ios::binary)) {
    throw Error(path.string() + ": cannot create a file in '" + folder.string() +
                "' (permission denied or read-only?)");
  }
  fs::remove(probe, error);
}

}  // namespace geodual::io
