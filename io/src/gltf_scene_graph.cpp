#include "gltf_scene_graph.hpp"

#include <cmath>
#include <optional>
#include <utility>

namespace geodual::io::detail::gltf {
namespace {

constexpr double affine_tolerance = 1e-6;

Eigen::Affine3d local_transform(const Json& node, const std::string& where) {
  const auto matrix = optional_numbers<16>(node, "matrix", where);
  const auto translation = optional_numbers<3>(node, "translation", where);
  const auto rotation = optional_numbers<4>(node, "rotation", where);
  const auto scale = optional_numbers<3>(node, "scale", where);

  Eigen::Affine3d transform = Eigen::Affine3d::Identity();
  if (matrix) {
    if (translation || rotation || scale) {
      fail(where, "has both 'matrix' and translation/rotation/scale; glTF allows one or the other");
    }
    const Eigen::Map<const Eigen::Matrix4d> m(matrix->data());  // glTF matrices are column-major, as Eigen's
    if (m.row(3).head<3>().cwiseAbs().maxCoeff() > affine_tolerance || std::abs(m(3, 3) - 1.0) > affine_tolerance) {
      fail(where, "'matrix' is not affine (its last row must be 0 0 0 1)");
    }
    transform.matrix().topRows<3>() = m.topRows<3>();
    return transform;
  }
  if (translation) transform.translate(Eigen::Vector3d(translation->data()));
  if (rotation) {
    // glTF stores x, y, z, w.
    Eigen::Quaterniond q((*rotation)[3], (*rotation)[0], (*rotation)[1], (*rotation)[2]);
    const double norm = q.norm();
    if (!(norm > 1e-12) || !std::isfinite(norm)) fail(where, "'rotation' quaternion has zero length");
    transform.rotate(Eigen::Quaterniond(q.coeffs() / norm));
  }
  if (scale) transform.scale(Eigen::Vector3d(scale->data()));
  return transform;
}

struct NodeGraph {
  std::vector<std::optional<std::size_t>> parent;
  std::vector<std::vector<std::size_t>> children;
};

NodeGraph link_nodes(const Json& nodes, const std::string& where) {
  NodeGraph graph;
  graph.parent.resize(nodes.size());
  graph.children.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string node_where = where + ": " + describe("node", i, nodes[i]);
    if (!nodes[i].is_object()) fail(node_where, "must be a JSON object");
    for (const Json& child_value : array_member(nodes[i], "children", node_where)) {
      const std::size_t child = index_value(child_value, nodes.size(), "node", node_where);
      if (child == i) fail(node_where, "lists itself as a child");
      if (graph.parent[child]) {
        fail(node_where, "lists node " + std::to_string(child) + " as a child, but node " +
                             std::to_string(*graph.parent[child]) + " does too; a glTF node has at most one parent");
      }
      graph.parent[child] = i;
      graph.children[i].push_back(child);
    }
  }
  return graph;
}

// The nodes a walk starts from, and a note saying why those.
std::vector<std::size_t> choose_roots(const Json& root, const Json& nodes, const NodeGraph& graph,
                                      const std::string& where, std::vector<std::string>& notes) {
  const Json& scenes = array_member(root, "scenes", where);
  const std::optional<std::size_t> default_scene = optional_index(root, "scene", scenes.size(), "scene", where);
  if (!scenes.empty()) {
    const std::size_t s = default_scene.value_or(0);
    if (!default_scene && scenes.size() > 1) {
      notes.push_back("no default scene; read scene 0 of " + std::to_string(scenes.size()));
    }
    const std::string scene_where = where + ": " + describe("scene", s, scenes[s]);
    if (!scenes[s].is_object()) fail(scene_where, "must be a JSON object");
    std::vector<std::size_t> roots;
    std::vector<bool> listed(nodes.size(), false);
    for (const Json& value : array_member(scenes[s], "nodes", scene_where)) {
      const std::size_t n = index_value(value, nodes.size(), "node", scene_where);
      if (listed[n]) fail(scene_where, "lists node " + std::to_string(n) + " twice");
      if (graph.parent[n]) {
        fail(scene_where, "lists node " + std::to_string(n) + ", which is a child of node " +
                              std::to_string(*graph.parent[n]) + "; scenes may list only root nodes");
      }
      listed[n] = true;
      roots.push_back(n);
    }
    return roots;
  }
  std::vector<std::size_t> roots;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (!graph.parent[n]) roots.push_back(n);
  }
  notes.push_back("no scenes; read all " + std::to_string(roots.size()) + " root nodes");
  return roots;
}

}  // namespace

std::vector<MeshInstance> collect_mesh_instances(const Json& root, const std::string& where,
                                                 std::vector<std::string>& notes) {
  const Json& meshes = array_member(root, "meshes", where);
  const Json& nodes = array_member(root, "nodes", where);
  std::vector<MeshInstance> instances;

  if (nodes.empty() && array_member(root, "scenes", where).empty()) {
    if (!meshes.empty()) notes.push_back("no nodes; read every mesh once, untransformed");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      MeshInstance instance;
      instance.mesh = m;
      instances.push_back(std::move(instance));
    }
    return instances;
  }

  const NodeGraph graph = link_nodes(nodes, where);
  const std::vector<std::size_t> roots = choose_roots(root, nodes, graph, where, notes);

  // Depth-first, children in file order, with an explicit stack: node chains
  // can be deeper than the call stack.
  std::vector<std::pair<std::size_t, Eigen::Affine3d>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, Eigen::Affine3d::Identity());
  while (!stack.empty()) {
    const auto [n, parent_world] = stack.back();
    stack.pop_back();
    const Json& node = nodes[n];
    const std::string node_where = where + ": " + describe("node", n, node);
    const Eigen::Affine3d world = parent_world * local_transform(node, node_where);
    if (!world.matrix().allFinite()) fail(node_where, "transform overflows (non-finite values)");

    if (const auto mesh = optional_index(node, "mesh", meshes.size(), "mesh", node_where)) {
      instances.push_back({.mesh = *mesh,
                           .node = describe("node", n, node),
                           .world = world,
                           .identity = world.matrix() == Eigen::Matrix4d::Identity()});
    }
    const std::vector<std::size_t>& children = graph.children[n];
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, world);
  }
  return instances;
}

}  // namespace geodual::io::detail::gltf
