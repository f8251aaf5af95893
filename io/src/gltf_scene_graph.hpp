#pragma once
// Internal: which meshes a glTF file shows, and where. Walks the node tree of
// the default scene (else scene 0, else every root node; a file without nodes
// shows each mesh once, untransformed) and composes node transforms (matrix,
// or translation * rotation * scale) from the root down.
//
// Checked: node, mesh and scene indices; that no node has two parents and
// that scenes list only root nodes, each once (together these make every walk
// a tree walk, so loops cannot make it run forever); transforms: matrix XOR
// TRS, a non-zero rotation quaternion (normalized here), an affine matrix
// (bottom row 0 0 0 1), finite products.

#include "gltf_json.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <string>
#include <vector>

namespace geodual::io::detail::gltf {

struct MeshInstance {
  std::size_t mesh = 0;
  std::string node;  ///< e.g. "node 4 'Arm'", empty when the file has no nodes
  Eigen::Affine3d world = Eigen::Affine3d::Identity();
  bool identity = true;  ///< world is exactly the identity: coordinates are copied bit for bit
};

/// The mesh instances in depth-first node order. Adds remarks to `notes`
/// (e.g. which scene was chosen when the file names no default).
std::vector<MeshInstance> collect_mesh_instances(const Json& root, const std::string& where,
                                                 std::vector<std::string>& notes);

}  // namespace geodual::io::detail::gltf
