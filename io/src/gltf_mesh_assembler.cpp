#include "gltf_mesh_assembler.hpp"

#include "gltf_triangulate.hpp"

#include <array>
#include <limits>
#include <numeric>
#include <utility>

namespace geodual::io::detail::gltf {
namespace {

constexpr auto max_elements = static_cast<std::size_t>(std::numeric_limits<Index>::max());

constexpr std::array<std::string_view, 4> non_triangle_modes = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};

// The most triangles `n` vertices make in `mode` (strips and fans may drop degenerates later).
std::size_t max_triangles(PrimitiveMode mode, std::size_t n) {
  if (mode == PrimitiveMode::triangles) return n / 3;
  return n >= 3 ? n - 2 : 0;
}

std::string counted(std::size_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

}  // namespace

MeshAssembler::MeshAssembler(const Json& root, BufferStore& buffers, TextureStore& textures, bool allow_quantized,
                             std::string where)
    : root_(root),
      buffers_(buffers),
      allow_quantized_(allow_quantized),
      where_(std::move(where)),
      attributes_(root, buffers, textures, allow_quantized, where_) {}

TriangleMesh MeshAssembler::assemble(const std::vector<MeshInstance>& instances) {
  std::size_t total_vertices = 0;
  std::size_t total_triangles = 0;
  for (const MeshInstance& instance : instances) {
    const std::string where = where_ + ": " + (instance.node.empty() ? "" : instance.node + ": ") +
                              describe("mesh", instance.mesh, array_member(root_, "meshes", where_)[instance.mesh]);
    const MeshPlan& plan = plan_mesh(instance.mesh, where);
    // Checked after every instance, and each plan's counts are bounded by buffer
    // sizes (< 2^53): the 64-bit sums cannot overflow.
    total_vertices += plan.vertices;
    total_triangles += plan.triangles;
    if (total_vertices > max_elements || total_triangles > max_elements) {
      fail(where,
           "the scene expands to more than 2^31 - 1 vertices or triangles (counting every instance of "
           "every mesh), more than a geodual mesh holds");
    }
  }

  std::vector<const PrimitiveAttributes*> planned;
  for (const auto& [mesh, plan] : plans_) {
    for (const PrimitivePlan& primitive : plan.primitives) planned.push_back(&primitive.attributes);
  }
  attributes_.choose(planned, total_vertices);

  vertices_.reserve(3 * total_vertices);
  faces_.reserve(3 * total_triangles);
  for (const MeshInstance& instance : instances) read_instance(plans_.at(instance.mesh), instance);

  TriangleMesh mesh;
  mesh.vertices = Eigen::Map<const VertexMatrix>(vertices_.data(), static_cast<Eigen::Index>(vertices_.size() / 3), 3);
  mesh.faces = Eigen::Map<const FaceMatrix>(faces_.data(), static_cast<Eigen::Index>(faces_.size() / 3), 3);
  vertices_ = {};
  faces_ = {};
  return mesh;
}

const MeshAssembler::MeshPlan& MeshAssembler::plan_mesh(std::size_t mesh_index, const std::string& where) {
  if (const auto found = plans_.find(mesh_index); found != plans_.end()) return found->second;

  const Json& mesh = array_member(root_, "meshes", where_)[mesh_index];
  if (!mesh.is_object()) fail(where, "must be a JSON object");
  MeshPlan plan;
  std::map<std::size_t, std::size_t> position_counts;  // POSITION accessor -> vertices, each counted once
  const Json& primitives = array_member(mesh, "primitives", where);
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    std::optional<PrimitivePlan> primitive = plan_primitive(primitives[p], where + " primitive " + std::to_string(p));
    if (!primitive) continue;
    position_counts.emplace(primitive->position_accessor, primitive->positions.count);
    const std::size_t drawn = primitive->indices ? primitive->indices->count : primitive->positions.count;
    // Each term is below 2^53 / 4 (it counts buffer elements), so the sums stay far from overflow.
    plan.triangles += max_triangles(primitive->mode, drawn);
    plan.primitives.push_back(std::move(*primitive));
  }
  for (const auto& [accessor, count] : position_counts) plan.vertices += count;
  return plans_.emplace(mesh_index, std::move(plan)).first->second;
}

std::optional<MeshAssembler::PrimitivePlan> MeshAssembler::plan_primitive(const Json& primitive, std::string where) {
  if (!primitive.is_object()) fail(where, "must be a JSON object");
  const std::uint64_t mode = optional_uint(primitive, "mode", where).value_or(4);
  if (mode > 6) fail(where, "invalid 'mode' " + std::to_string(mode));
  if (mode < non_triangle_modes.size()) {
    ++skipped_by_mode_[std::string(non_triangle_modes[mode])];
    return std::nullopt;
  }

  const Json* attributes = optional_object(primitive, "attributes", where);
  if (attributes == nullptr) fail(where, "required 'attributes' is missing");
  const std::size_t accessor_count = array_member(root_, "accessors", where).size();
  const std::optional<std::size_t> position =
      optional_index(*attributes, "POSITION", accessor_count, "accessor", where + ": POSITION");
  if (!position) {
    ++without_position_;
    return std::nullopt;
  }

  PrimitivePlan plan;
  plan.mode = static_cast<PrimitiveMode>(mode);
  plan.position_accessor = *position;
  plan.positions = view_accessor(root_, buffers_, *position, AccessorShape::vec3, where + ": POSITION");
  if (plan.positions.count > max_elements) fail(plan.positions.where, "has more than 2^31 - 1 elements");
  if (const auto indices = optional_index(primitive, "indices", accessor_count, "accessor", where + ": indices")) {
    plan.indices = view_accessor(root_, buffers_, *indices, AccessorShape::scalar, where + ": indices");
  }
  plan.attributes = attributes_.plan(primitive, *attributes, plan.positions.count, where);
  plan.where = std::move(where);
  return plan;
}

void MeshAssembler::read_instance(const MeshPlan& plan, const MeshInstance& instance) {
  ++instances_;
  if (!instance.identity) ++transformed_instances_;
  const bool flip = instance.world.linear().determinant() < 0;
  if (flip) ++mirrored_instances_;

  // POSITION accessor -> its first vertex in this instance and the primitive that appended it
  std::map<std::size_t, std::pair<std::size_t, const PrimitivePlan*>> first_vertex;
  for (const PrimitivePlan& primitive : plan.primitives) {
    auto found = first_vertex.find(primitive.position_accessor);
    if (found == first_vertex.end()) {
      const std::size_t first = append_positions(primitive, instance);
      found = first_vertex.emplace(primitive.position_accessor, std::pair(first, &primitive)).first;
    } else if (found->second.second->attributes.sources != primitive.attributes.sources) {
      ++attribute_conflicts_;
    }
    append_triangles(primitive, found->second.first, flip);
  }
}

VertexAttributes MeshAssembler::take_attributes() { return attributes_.take(); }

std::size_t MeshAssembler::append_positions(const PrimitivePlan& primitive, const MeshInstance& instance) {
  const AccessorView& positions = primitive.positions;
  attributes_.append(primitive.attributes, positions.count, instance);
  const std::size_t first = vertices_.size() / 3;
  gltf::append_positions(positions, allow_quantized_, vertices_);
  if (!instance.identity) {
    for (std::size_t v = first; v < first + positions.count; ++v) {
      Eigen::Map<Eigen::Vector3d> p(vertices_.data() + 3 * v);
      p = instance.world * p;
    }
  }
  return first;
}

void MeshAssembler::append_triangles(const PrimitivePlan& primitive, std::size_t first_vertex, bool flip) {
  const std::size_t vertex_count = primitive.positions.count;
  std::vector<std::uint32_t> corners;
  if (primitive.indices) {
    corners = read_indices(*primitive.indices);
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (corners[i] >= vertex_count) {
        fail(primitive.indices->where, "element " + std::to_string(i) + " is vertex index " +
                                           std::to_string(corners[i]) + ", but POSITION accessor " +
                                           std::to_string(primitive.position_accessor) + " has only " +
                                           std::to_string(vertex_count) + " vertices");
      }
    }
  } else {
    corners.resize(vertex_count);  // non-indexed: the vertices are drawn in order
    std::iota(corners.begin(), corners.end(), std::uint32_t{0});
  }

  const Triangulation triangles = triangulate(primitive.mode, std::move(corners));
  if (primitive.mode != PrimitiveMode::triangles) ++strips_and_fans_;
  degenerate_dropped_ += triangles.degenerate_dropped;
  trailing_ignored_ += triangles.trailing_ignored;

  // Planned totals keep every index below 2^31.
  const auto base = static_cast<Index>(first_vertex);
  if (const std::int32_t image = attributes_.kept_image(primitive.attributes); image >= 0) {
    face_image_.insert(face_image_.end(), triangles.corners.size() / 3, image);
  }
  for (std::size_t t = 0; t < triangles.corners.size(); t += 3) {
    const Index a = base + static_cast<Index>(triangles.corners[t]);
    const Index b = base + static_cast<Index>(triangles.corners[t + 1]);
    const Index c = base + static_cast<Index>(triangles.corners[t + 2]);
    faces_.insert(faces_.end(), {a, flip ? c : b, flip ? b : c});
  }
}

std::vector<std::string> MeshAssembler::notes() const {
  std::vector<std::string> notes;
  if (transformed_instances_ > 0) {
    notes.push_back("node transforms applied to " + counted(transformed_instances_, "mesh instance", "mesh instances") +
                    " of " + std::to_string(instances_));
  }
  if (mirrored_instances_ > 0) {
    notes.push_back("triangle winding flipped in " +
                    counted(mirrored_instances_, "mirrored mesh instance", "mirrored mesh instances"));
  }
  if (!skipped_by_mode_.empty()) {
    std::string kinds;
    std::size_t total = 0;
    for (const auto& [mode, n] : skipped_by_mode_) {
      kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + mode;
      total += n;
    }
    notes.push_back("skipped " + counted(total, "non-triangle primitive", "non-triangle primitives") + " (" + kinds +
                    ")");
  }
  if (without_position_ > 0) {
    notes.push_back("skipped " + counted(without_position_, "primitive", "primitives") + " without POSITION");
  }
  if (strips_and_fans_ > 0) {
    notes.push_back("converted " + counted(strips_and_fans_, "triangle strip or fan", "triangle strips and fans") +
                    " to triangles");
  }
  if (degenerate_dropped_ > 0) {
    notes.push_back("dropped " +
                    counted(degenerate_dropped_, "degenerate strip/fan triangle", "degenerate strip/fan triangles") +
                    " (repeated vertex)");
  }
  if (trailing_ignored_ > 0) {
    notes.push_back("ignored " + counted(trailing_ignored_, "index", "indices") +
                    " after the last whole triangle of TRIANGLES primitives");
  }
  if (attribute_conflicts_ > 0) {
    notes.push_back(counted(attribute_conflicts_, "primitive shares", "primitives share") +
                    " its POSITION accessor with an earlier primitive of the mesh but has other vertex attributes "
                    "or another material; the shared vertices keep the earlier primitive's");
  }
  for (std::string& note : attributes_.notes()) notes.push_back(std::move(note));
  return notes;
}

}  // namespace geodual::io::detail::gltf
