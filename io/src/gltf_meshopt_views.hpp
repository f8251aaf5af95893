#pragma once
// Internal: the EXT_meshopt_compression objects of the buffer views, added to
// the file tinygltf wrote, because tinygltf 2.7 writes no extensions of buffer
// views or buffers. Each compressed view then refers to a fallback buffer:
// buffer 1, without data or "uri", marked {"fallback": true}; its compressed
// bytes stay in buffer 0 (the GLB BIN chunk or the data URI), where the
// view's extension points. The extension is required: a reader without it
// has no data (as the extension's specification allows).

#include <cstddef>
#include <span>
#include <string>

namespace geodual::io::detail::gltf {

/// A buffer view holding meshopt-encoded bytes in buffer 0.
struct MeshoptView {
  int view = 0;                 ///< its index in bufferViews
  std::size_t byte_stride = 0;  ///< decoded bytes per element
  std::size_t count = 0;        ///< decoded elements
  bool triangles = false;       ///< mode TRIANGLES (an index buffer) or ATTRIBUTES
  std::string filter = "NONE";  ///< "NONE" (left out of the file) or "OCTAHEDRAL"
};

/// Rewrites `file` (GLB when `glb`, otherwise .gltf JSON, as tinygltf wrote
/// it) with each view's extension object and the fallback buffer.
void add_meshopt_views(std::string& file, bool glb, std::span<const MeshoptView> views);

}  // namespace geodual::io::detail::gltf
