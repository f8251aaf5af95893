#pragma once
// Outputs are written next to their target under a temporary name and renamed
// at the end, so that a failure never leaves a half-written file behind.

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <iosfwd>
#include <string>
#include <string_view>

namespace geodual::io {

/// The path's extension in lower case (".glb"); empty if it has none.
std::string lowercase_extension(const std::filesystem::path& path);

/// Checks an output before any work is done: throws geodual::Error, naming
/// the path, unless it ends in one of `extensions` (lower case, with the dot)
/// and names a file in an existing folder where a file can be created now.
/// `what` says what it is for, e.g. "a remesh".
void require_output_path(const std::filesystem::path& path, std::initializer_list<std::string_view> extensions,
                         std::string_view what);

/// Throws geodual::Error if `output` is (or links to) one of `inputs`.
void refuse_to_overwrite_inputs(const std::filesystem::path& output,
                                std::initializer_list<std::filesystem::path> inputs);

/// Calls `write` on a binary stream to a temporary file in output's folder,
/// flushes and checks it, then renames it over `output`. On any exception the
/// temporary file is removed and `output` is left untouched.
void write_file_atomically(const std::filesystem::path& output, const std::function<void(std::ostream&)>& write);

}  // namespace geodual::io
